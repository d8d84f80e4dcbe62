//! A print job: from a chain, a plan or a shape to every file a maker needs, as names and
//! bytes (the caller writes them): one part file per part the chain uses (`parts/RS.3mf`)
//! with a picture of it (`parts/RS.png`), the plates laying the bill of materials out on the
//! bed (`plates/plate-1.3mf`, ...), the assembly sheet (`assembly.svg`) and `parts.json`
//! (counts, volumes, printing time estimates and their basis).

use std::collections::BTreeMap;
use std::path::PathBuf;

use foldchain::timeline::TileDesigns;
use foldchain::tolerance::Printer;
use foldchain::{Chain, Design, FoldWord, Part, PathKind, Tile};
use foldchain_planner::{plan_svg_file, Plan, PlanOptions};

use crate::assembly::{assembly_svg, SheetTile};
use crate::options::{Format, PrintOptions};
use crate::plate::lay_out;
use crate::threemf::{to_3mf, Item, Object};
use crate::{mesh_png, to_stl, Mesh, PrintError, TilePart, View};

/// Where the chain comes from.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum Source {
    /// A chain, and a name for it.
    Chain {
        /// The chain.
        chain: Chain,
        /// Its name (titles, parts.json).
        name: String,
    },
    /// A plan `fold-plan` made.
    Plan {
        /// The plan.
        plan: Box<Plan>,
        /// Its name.
        name: String,
    },
    /// A shape to plan first.
    Shape {
        /// The SVG file.
        path: PathBuf,
        /// How to plan it.
        options: PlanOptions,
    },
}

/// A file of the job: its path relative to the output directory, and its bytes.
#[derive(Clone, Debug)]
pub struct OutputFile {
    /// Relative path, `/`-separated (e.g. `plates/plate-1.3mf`).
    pub path: String,
    /// The contents.
    pub bytes: Vec<u8>,
}

/// An FDM printer's volumetric rate the time estimate assumes, mm^3/s: a 0.4 mm nozzle laying
/// 0.2 mm layers at 50 mm/s, a common speed for outer perimeters (a tile is mostly walls).
pub const FDM_RATE_MM3_PER_S: f64 = 4.0;

/// A resin printer's layer, mm, and time per layer, s (about 2.5 s exposure and 5 s for the
/// lift and return of a typical MSLA printer): a plate takes its height's layers whatever it
/// holds.
pub const RESIN_LAYER_MM: f64 = 0.05;
/// See [`RESIN_LAYER_MM`].
pub const RESIN_SECONDS_PER_LAYER: f64 = 7.5;

/// What the estimates rest on, written into parts.json.
pub fn estimate_basis(printer: Printer) -> String {
    match printer {
        Printer::Fdm => format!(
            "FDM: the part's solid volume (from its mesh) at {FDM_RATE_MM3_PER_S} mm3/s, a 0.4 mm nozzle laying 0.2 mm layers at 50 mm/s; no travel, heating or infill saving counted, so a slicer's estimate differs (docs/printing.md compares PrusaSlicer's)"
        ),
        Printer::Resin => format!(
            "resin: a plate takes its height in {RESIN_LAYER_MM} mm layers at {RESIN_SECONDS_PER_LAYER} s each whatever it holds; the volume gives the resin used (1 ml = 1000 mm3, no supports)"
        ),
    }
}

/// One part of the bill of materials.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PartEntry {
    /// Its label and file stem (`RS`, or `RS-d1` for the second design of a chain).
    pub label: String,
    /// The part's name, as `foldchain` names it.
    pub part: Part,
    /// The tile types it is: as built and turned by 180 degrees (`RS`, `SL`).
    pub reads: [String; 2],
    /// How many the chain needs.
    pub count: usize,
    /// The part's file.
    pub file: String,
    /// Its picture.
    pub picture: String,
    /// The solid volume of one, mm^3.
    pub volume_mm3: f64,
    /// Triangles in its mesh.
    pub triangles: usize,
    /// Its thinnest wall, mm.
    pub thinnest_wall_mm: f64,
    /// Where that wall is.
    pub thinnest_wall: String,
    /// The engraved capitals' height, mm (0: no room for a mark).
    pub mark_height_mm: f64,
    /// The estimated printing time of one, minutes (FDM; resin: see the plates).
    pub print_minutes: f64,
    /// The design it is built to.
    pub design: Design,
}

/// One plate.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PlateEntry {
    /// Its file.
    pub file: String,
    /// Tiles on it.
    pub tiles: usize,
    /// Tiles of each part.
    pub parts: BTreeMap<String, usize>,
    /// Its solid volume, mm^3.
    pub volume_mm3: f64,
    /// Its estimated printing time, minutes.
    pub print_minutes: f64,
}

/// parts.json.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PartsReport {
    /// The chain's name.
    pub name: String,
    /// Where it came from (a shape or plan file), when not given inline.
    pub source: Option<String>,
    /// Tiles in the chain.
    pub tiles: usize,
    /// The chain's tile list.
    pub tile_list: String,
    /// The printer.
    pub printer: Printer,
    /// Channel width minus magnet diameter, mm.
    pub clearance_mm: f64,
    /// Tile height, mm.
    pub height_mm: f64,
    /// Floor under the channels, mm.
    pub floor_mm: f64,
    /// The parts' file format.
    pub format: Format,
    /// The parts.
    pub parts: Vec<PartEntry>,
    /// The plates.
    pub plates: Vec<PlateEntry>,
    /// Magnets to buy: count, and size in mm.
    pub magnets: Magnets,
    /// Total solid volume, mm^3.
    pub total_volume_mm3: f64,
    /// Total estimated printing time, minutes.
    pub total_print_minutes: f64,
    /// What the estimates rest on.
    pub estimate_basis: String,
    /// Inequalities of thesis chapter 6 that a design breaks or only just meets (the chain
    /// may then not fold as planned).
    pub design_warnings: Vec<String>,
    /// The warnings of the plan the chain comes from (a shape planned here, or a plan file):
    /// a tile count off the request, a part of the shape left empty. Absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub plan_warnings: Vec<String>,
}

/// The magnets a chain needs.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Magnets {
    /// How many (two per tile).
    pub count: usize,
    /// Diameter, mm (of the global design).
    pub diameter_mm: f64,
    /// Height, mm.
    pub height_mm: f64,
}

/// A finished job.
#[derive(Clone, Debug)]
pub struct PrintJob {
    /// The chain printed.
    pub chain: Chain,
    /// The files, in the order to write them.
    pub files: Vec<OutputFile>,
    /// What parts.json says.
    pub report: PartsReport,
}

/// Whether `name` (relative to an output directory) is one of the names a job writes: the
/// caller may replace these, and only these.
pub fn is_job_file(name: &str) -> bool {
    let plate = |n: &str| {
        n.strip_prefix("plate-")
            .and_then(|r| r.strip_suffix(".3mf").or_else(|| r.strip_suffix(".stl")))
            .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
    };
    match name.split_once('/') {
        None => name == "assembly.svg" || name == "parts.json",
        Some(("plates", rest)) => plate(rest),
        Some(("parts", rest)) => {
            let stem = rest
                .strip_suffix(".3mf")
                .or_else(|| rest.strip_suffix(".stl"))
                .or_else(|| rest.strip_suffix(".png"));
            stem.is_some_and(|s| {
                let (part, design) = s.split_once("-d").unwrap_or((s, "1"));
                ["SS", "RS", "SR", "RR", "LR", "RL"].contains(&part)
                    && !design.is_empty()
                    && design.bytes().all(|b| b.is_ascii_digit())
            })
        }
        _ => false,
    }
}

/// The tile a part is built as (its name read as a tile).
fn part_tile(part: Part) -> Tile {
    use PathKind::*;
    match part {
        Part::SS => Tile::new(S, S),
        Part::RS => Tile::new(R, S),
        Part::SR => Tile::new(S, R),
        Part::RR => Tile::new(R, R),
        Part::LR => Tile::new(L, R),
        Part::RL => Tile::new(R, L),
    }
}

/// The longest chain `print_job` builds: 100,000 tiles, far beyond what one prints by hand
/// (about 36,000 hours of printing for straight tiles), and what bounds the work and the
/// output of a small input (`S*5000000` would write about 16 GB).
pub const MAX_PRINT_TILES: usize = 100_000;

/// Makes every file for `source` built to `designs` with `opts`.
pub fn print_job(
    source: &Source,
    designs: &TileDesigns,
    opts: &PrintOptions,
) -> Result<PrintJob, PrintError> {
    opts.part.validate()?;
    opts.bed.validate()?;
    let (chain, name, origin, word, plan_warnings) = read_source(source)?;
    let n = chain.len();
    if n > MAX_PRINT_TILES {
        return Err(PrintError::BadOption {
            name: "the chain",
            value: format!("{n} tiles"),
            expected: "at most 100,000 tiles (the assembly sheet draws every tile, about 3 KB \
                       each: 100,000 tiles write 380 MB in over a minute)"
                .into(),
        });
    }
    let (list, index) = designs.resolve(n);
    let design_of = |i: usize| index.get(i).map_or(0, |&k| k as usize);
    // the parts: (part, design) in the bill of materials' order
    let mut keys: BTreeMap<(Part, usize), usize> = BTreeMap::new();
    for (i, t) in chain.tiles().iter().enumerate() {
        *keys.entry((t.part(), design_of(i))).or_insert(0) += 1;
    }
    let parts = part_entries(&keys, &list, opts)?;
    let mut files = part_files(&parts, opts)?;
    let plates = plate_files(&parts, &name, opts, &mut files)?;
    // the assembly sheet
    let sheet_tiles: Vec<SheetTile<'_>> = chain
        .tiles()
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let key = (t.part(), design_of(i));
            let pos = keys.keys().position(|k| *k == key).unwrap_or(0);
            SheetTile {
                tile: t,
                part_label: &parts[pos].0.label,
                part: &parts[pos].1,
            }
        })
        .collect();
    files.push(assembly_file(&name, &sheet_tiles, word.as_ref()));
    let design_warnings = design_warnings(&list);
    let global = designs.global_design();
    let total_volume: f64 = plates.iter().map(|p| p.volume_mm3).sum();
    let report = PartsReport {
        name,
        source: origin,
        tiles: n,
        tile_list: chain.to_tile_list(),
        printer: opts.part.printer,
        clearance_mm: opts.part.clearance,
        height_mm: opts.part.height,
        floor_mm: opts.part.floor,
        format: opts.format,
        total_print_minutes: plates.iter().map(|p| p.print_minutes).sum(),
        parts: parts.into_iter().map(|(e, _)| e).collect(),
        plates,
        magnets: Magnets {
            count: 2 * n,
            diameter_mm: global.magnet_diameter,
            height_mm: global.magnet_height,
        },
        total_volume_mm3: total_volume,
        estimate_basis: estimate_basis(opts.part.printer),
        design_warnings,
        plan_warnings,
    };
    let json = serde_json::to_string_pretty(&report).map_err(|e| PrintError::Format {
        name: "parts.json".into(),
        reason: e.to_string(),
    })?;
    files.push(OutputFile {
        path: "parts.json".into(),
        bytes: (json + "\n").into_bytes(),
    });
    Ok(PrintJob {
        chain,
        files,
        report,
    })
}

/// The chain of `source` (planned, for a plan's or a shape's), its name, where it came from,
/// its fold word when it has one and the plan's warnings.
#[allow(clippy::type_complexity)]
fn read_source(
    source: &Source,
) -> Result<(Chain, String, Option<String>, Option<FoldWord>, Vec<String>), PrintError> {
    Ok(match source {
        Source::Chain { chain, name } => (
            chain.clone(),
            name.clone(),
            None,
            chain.to_word().ok(),
            Vec::new(),
        ),
        Source::Plan { plan, name } => {
            let word = plan.fold_word()?;
            (
                word.to_chain(),
                name.clone(),
                Some(plan.source.clone()),
                Some(word),
                plan.warnings.clone(),
            )
        }
        Source::Shape { path, options } => {
            let plan = plan_svg_file(path, options)?;
            let word = plan.fold_word()?;
            let name = path
                .file_stem()
                .map_or("shape".into(), |s| s.to_string_lossy().into_owned());
            (
                word.to_chain(),
                name,
                Some(path.display().to_string()),
                Some(word),
                plan.warnings,
            )
        }
    })
}

/// One entry and its part for each `(part, design)` of `keys` (with its count of tiles),
/// in the bill of materials' order.
fn part_entries(
    keys: &BTreeMap<(Part, usize), usize>,
    list: &[Design],
    opts: &PrintOptions,
) -> Result<Vec<(PartEntry, TilePart)>, PrintError> {
    let several_designs = keys.keys().any(|&(_, d)| d > 0);
    let ext = opts.format.extension();
    let mut parts: Vec<(PartEntry, TilePart)> = Vec::new();
    for (&(part, d), &count) in keys {
        let design = list.get(d).copied().unwrap_or_default();
        let tp = TilePart::new(part_tile(part), &design, &opts.part)?;
        let label = if several_designs {
            format!("{part}-d{}", d + 1)
        } else {
            part.to_string()
        };
        let tile = part_tile(part);
        let volume = tp.volume();
        parts.push((
            PartEntry {
                file: format!("parts/{label}.{ext}"),
                picture: format!("parts/{label}.png"),
                label,
                part,
                reads: [tile.to_string(), tile.turned().to_string()],
                count,
                volume_mm3: volume,
                triangles: tp.mesh.triangles.len(),
                thinnest_wall_mm: tp.thinnest_wall.thickness,
                thinnest_wall: tp.thinnest_wall.place.clone(),
                mark_height_mm: tp.mark_height,
                print_minutes: fdm_minutes(volume, opts.part.printer),
                design,
            },
            tp,
        ));
    }
    Ok(parts)
}

/// Each part's mesh file and picture.
fn part_files(
    parts: &[(PartEntry, TilePart)],
    opts: &PrintOptions,
) -> Result<Vec<OutputFile>, PrintError> {
    let mut files = Vec::new();
    for (e, tp) in parts {
        let title = format!("{} (reads {} or {})", e.label, e.reads[0], e.reads[1]);
        files.push(OutputFile {
            path: e.file.clone(),
            bytes: mesh_file(
                opts.format,
                &e.file,
                &title,
                &[(e.label.clone(), &tp.mesh)],
                &[Item {
                    object: 0,
                    angle: 0.0,
                    x: 0.0,
                    y: 0.0,
                }],
            )?,
        });
        let png = mesh_png(&tp.mesh, &View::default()).ok_or_else(|| PrintError::Format {
            name: e.picture.clone(),
            reason: "the PNG encoder failed".into(),
        })?;
        files.push(OutputFile {
            path: e.picture.clone(),
            bytes: png,
        });
    }
    Ok(files)
}

/// The build plates of `parts` (each part's count of tiles laid out on the bed), their files
/// added to `files`.
fn plate_files(
    parts: &[(PartEntry, TilePart)],
    name: &str,
    opts: &PrintOptions,
    files: &mut Vec<OutputFile>,
) -> Result<Vec<PlateEntry>, PrintError> {
    let ext = opts.format.extension();
    let size = parts
        .iter()
        .map(|(_, tp)| tp.design.tile_width)
        .fold(0.0, f64::max);
    let counts: Vec<usize> = parts.iter().map(|(e, _)| e.count).collect();
    let layout = lay_out(&counts, size, &opts.bed)?;
    let mut plates = Vec::new();
    for (k, placed) in layout.iter().enumerate() {
        let file = format!("plates/plate-{}.{ext}", k + 1);
        let mut used: Vec<usize> = placed.iter().map(|p| p.part).collect();
        used.dedup();
        let objects: Vec<(String, &Mesh)> = used
            .iter()
            .map(|&i| (parts[i].0.label.clone(), &parts[i].1.mesh))
            .collect();
        let items: Vec<Item> = placed
            .iter()
            .map(|p| Item {
                object: used.iter().position(|&u| u == p.part).unwrap_or(0),
                angle: 0.0,
                x: p.x,
                y: p.y,
            })
            .collect();
        let mut per_part = BTreeMap::new();
        let mut volume = 0.0;
        for p in placed {
            *per_part.entry(parts[p.part].0.label.clone()).or_insert(0) += 1;
            volume += parts[p.part].0.volume_mm3;
        }
        let title = format!("{name}: plate {} of {}", k + 1, layout.len());
        files.push(OutputFile {
            path: file.clone(),
            bytes: mesh_file(opts.format, &file, &title, &objects, &items)?,
        });
        plates.push(PlateEntry {
            file,
            tiles: placed.len(),
            parts: per_part,
            volume_mm3: volume,
            print_minutes: plate_minutes(volume, opts.part.height, opts.part.printer),
        });
    }
    Ok(plates)
}

/// The assembly sheet of `tiles`, with the fold letters of `word` when the chain has one.
fn assembly_file(name: &str, tiles: &[SheetTile<'_>], word: Option<&FoldWord>) -> OutputFile {
    let letters: Option<Vec<PathKind>> = word.map(|w| {
        w.to_string()
            .chars()
            .filter_map(PathKind::from_char)
            .collect()
    });
    let sheet = assembly_svg(
        &format!("{name}: assembly, {} tiles", tiles.len()),
        tiles,
        letters.as_deref(),
    );
    OutputFile {
        path: "assembly.svg".into(),
        bytes: sheet.into_bytes(),
    }
}

/// A line for each inequality a design of `list` does not hold with room.
fn design_warnings(list: &[Design]) -> Vec<String> {
    let mut design_warnings = Vec::new();
    for (i, d) in list.iter().enumerate() {
        for c in d.report() {
            if c.standing != foldchain::Standing::Holds {
                design_warnings.push(format!(
                    "design {}: ({}) {} is {:?}: {} = {:.4} mm, {} = {:.4} mm",
                    i + 1,
                    c.id,
                    c.statement,
                    c.standing,
                    c.lhs_name,
                    c.lhs,
                    c.rhs_name,
                    c.rhs
                ));
            }
        }
    }
    design_warnings
}

/// The minutes an FDM printer takes for `volume` mm^3 (0 for resin: see the plates).
fn fdm_minutes(volume: f64, printer: Printer) -> f64 {
    match printer {
        Printer::Fdm => volume / FDM_RATE_MM3_PER_S / 60.0,
        Printer::Resin => 0.0,
    }
}

/// The minutes a plate of `volume` mm^3 and `height` mm takes.
fn plate_minutes(volume: f64, height: f64, printer: Printer) -> f64 {
    match printer {
        Printer::Fdm => fdm_minutes(volume, printer),
        Printer::Resin => (height / RESIN_LAYER_MM).ceil() * RESIN_SECONDS_PER_LAYER / 60.0,
    }
}

/// A file of `objects` placed by `items`: 3MF, or one binary STL of every item's mesh.
fn mesh_file(
    format: Format,
    name: &str,
    title: &str,
    objects: &[(String, &Mesh)],
    items: &[Item],
) -> Result<Vec<u8>, PrintError> {
    match format {
        Format::ThreeMf => {
            let objs: Vec<Object<'_>> = objects
                .iter()
                .map(|(n, m)| Object {
                    name: n.clone(),
                    mesh: m,
                })
                .collect();
            to_3mf(name, title, &objs, items)
        }
        Format::Stl => {
            let mut all = Mesh::default();
            for it in items {
                let Some((_, m)) = objects.get(it.object) else {
                    continue;
                };
                let placed = m.rotated_z(it.angle);
                let base = all.vertices.len() as u32;
                all.vertices.extend(
                    placed
                        .vertices
                        .iter()
                        .map(|v| [v[0] + it.x, v[1] + it.y, v[2]]),
                );
                all.triangles
                    .extend(placed.triangles.iter().map(|t| t.map(|i| i + base)));
            }
            Ok(to_stl(&all, title))
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::BillOfMaterials;

    #[test]
    fn job_file_names_are_recognised() {
        for n in [
            "parts.json",
            "assembly.svg",
            "plates/plate-12.3mf",
            "plates/plate-1.stl",
            "parts/RS.3mf",
            "parts/RR-d2.png",
        ] {
            assert!(is_job_file(n), "{n}");
        }
        for n in [
            "notes.txt",
            "plates/plate-.3mf",
            "parts/XX.3mf",
            "plates/mine.3mf",
        ] {
            assert!(!is_job_file(n), "{n}");
        }
    }

    #[test]
    fn a_u_turn_prints_its_bill_of_materials() {
        let chain = Chain::parse("SLLS").unwrap();
        let job = print_job(
            &Source::Chain {
                chain: chain.clone(),
                name: "u".into(),
            },
            &TileDesigns::default(),
            &PrintOptions::default(),
        )
        .unwrap();
        let bom = BillOfMaterials::from_chain(&chain);
        for e in &job.report.parts {
            assert_eq!(e.count, bom.count(e.part));
        }
        let on_plates: usize = job.report.plates.iter().map(|p| p.tiles).sum();
        assert_eq!(on_plates, chain.len());
        assert!(job.files.iter().all(|f| is_job_file(&f.path)));
    }
}
