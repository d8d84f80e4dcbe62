//! Reading what a user names on the command line, and guarding their files: a chain given
//! inline or as a file (with a clear message when it is neither), a chain from fold-plan's
//! JSON and the outline of the shape it was planned for, and the refusal to write an output
//! over an input.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context};
use foldchain::engine::{SValue, TileDesigns};
use foldchain::Chain;
use foldchain_planner::{plan_svg_file_reporting, Plan, PlanOptions, Shape, Turns};

use crate::progress::Progress;
use crate::run_name::{inline_name, stem};

/// Reads a chain argument: a fold word, a tile list, JSON, or a file holding one (or a plan
/// that `fold-plan --out` wrote: its word, checked as [`read_plan_file`] does). A name that
/// looks like a file (it has an extension or a directory) but is not there gets "no such
/// file, and not a fold word", with a pointer to `fold-plan`/`fold-run` for SVG shapes.
pub fn read_chain(arg: &str) -> anyhow::Result<Chain> {
    match crate::chain_arg::read_chain_arg(arg) {
        Ok(chain) => Ok(chain),
        Err(e) => {
            let path = Path::new(arg.trim());
            if path.is_file() {
                match read_plan_file(path) {
                    Ok((chain, _)) => return Ok(chain),
                    // a damaged plan is reported as a plan, not as chain JSON with an
                    // unknown field `source`
                    Err(plan_error) if looks_like_a_plan(path) => return Err(plan_error),
                    Err(_) => {}
                }
            }
            let looks_like_a_file = path.extension().is_some() || arg.contains(['/', '\\']);
            let svg = path
                .extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("svg"));
            if svg && path.is_file() {
                bail!(
                    "{arg}: an SVG shape is not a chain; plan it with `fold-plan {arg}` or fold it with `fold-run {arg}`"
                );
            }
            if looks_like_a_file && !path.exists() {
                let hint = if svg {
                    " (an SVG shape goes to fold-plan or fold-run)"
                } else {
                    ""
                };
                bail!("{arg}: no such file, and not a fold word or tile list{hint}");
            }
            Err(e.into())
        }
    }
}

/// The path as it will be once written: the canonical form of an existing file, or of its
/// directory joined with its name (links resolved) when it does not exist yet.
fn resolved(p: &Path) -> PathBuf {
    if let Ok(c) = p.canonicalize() {
        return c;
    }
    let dir = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    match (dir.canonicalize(), p.file_name()) {
        (Ok(d), Some(name)) => d.join(name),
        _ => p.to_path_buf(),
    }
}

/// Does the file at `path` start as `fold-plan --json` writes a plan: a JSON object whose
/// first 4 KiB name its `source` drawing?
fn looks_like_a_plan(path: &Path) -> bool {
    use std::io::Read;
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .unwrap_or(0);
    let text = String::from_utf8_lossy(&head[..n]);
    text.trim_start().starts_with('{') && text.contains("\"source\"")
}

/// Refuses (before any work) an output that is one of the inputs, after resolving links:
/// `what` names the output's flag.
pub fn refuse_overwrite(inputs: &[&Path], output: &Path, what: &str) -> anyhow::Result<()> {
    let out = resolved(output);
    for input in inputs {
        if resolved(input) == out {
            bail!(
                "{what} {}: is the input file {}; refusing to overwrite it (choose another output)",
                output.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// Refuses (before any work) to replace an existing file that this tool did not write:
/// `ours(head, tail)` recognises its own output from the file's first and last 4 KiB. A
/// missing or empty file, or one of ours, may be written; anything else (a user's notes, a
/// drawing) is refused, naming the file and what to do.
pub fn refuse_foreign(
    path: &Path,
    what: &str,
    kind: &str,
    ours: impl Fn(&str, &str) -> bool,
) -> anyhow::Result<()> {
    use anyhow::Context;
    use std::io::{Read, Seek, SeekFrom};
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(());
    };
    if !meta.is_file() || meta.len() == 0 {
        return Ok(());
    }
    let mut f = std::fs::File::open(path)
        .with_context(|| format!("{what} {}: cannot read the existing file", path.display()))?;
    let mut head = vec![0u8; 4096];
    let n = f.read(&mut head)?;
    head.truncate(n);
    let mut tail = Vec::new();
    f.seek(SeekFrom::Start(meta.len().saturating_sub(4096)))?;
    f.read_to_end(&mut tail)?;
    if ours(
        &String::from_utf8_lossy(&head),
        &String::from_utf8_lossy(&tail),
    ) {
        return Ok(());
    }
    anyhow::bail!(
        "{what} {}: the file exists and is not {kind}; refusing to overwrite it (remove it first, or choose another name)",
        path.display()
    )
}

/// Refuses an output directory that would replace one of the inputs: an input that lies in
/// `dir` under one of the names `is_output` claims.
pub fn refuse_overwrite_in(
    inputs: &[&Path],
    dir: &Path,
    is_output: &dyn Fn(&str) -> bool,
    what: &str,
) -> anyhow::Result<()> {
    let dir = resolved(dir);
    for input in inputs {
        let r = resolved(input);
        let inside = r.parent() == Some(dir.as_path());
        let named = r
            .file_name()
            .is_some_and(|n| is_output(&n.to_string_lossy()));
        if inside && named {
            bail!(
                "{what} {}: would overwrite the input file {}; refusing (choose another output directory)",
                dir.display(),
                input.display()
            );
        }
    }
    Ok(())
}

/// The largest plan file read: 512 MiB, room for a plan of the most tiles the planner makes
/// (2,000,000, about 100 bytes each with their poses) with a margin.
pub const MAX_PLAN_FILE_BYTES: u64 = 512 << 20;

/// Reads the chain designed by a plan file (`fold-plan --out` or `--json`), and the plan.
pub fn read_plan_file(path: &Path) -> anyhow::Result<(Chain, Plan)> {
    let bytes = foldchain_planner::read_file_at_most(path, MAX_PLAN_FILE_BYTES)
        .with_context(|| format!("cannot read plan file {}", path.display()))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        anyhow!(
            "{}: not a fold-plan JSON file: not UTF-8 text ({e})",
            path.display()
        )
    })?;
    let plan = Plan::from_json(&text).map_err(|e| {
        anyhow!(
            "{}: not a fold-plan JSON file: {e} (expected the object `fold-plan --json` writes)",
            path.display()
        )
    })?;
    let word = plan
        .fold_word()
        .with_context(|| format!("{}: bad fold word in the plan", path.display()))?;
    let chain = word.to_chain();
    if chain.to_tile_list() != plan.tile_list.trim() || chain.len() != plan.tiles {
        bail!(
            "{}: the plan's word ({} tiles) and its tile_list/tiles ({} tiles) disagree: the file was edited by hand or is damaged",
            path.display(),
            chain.len(),
            plan.tiles
        );
    }
    Ok((chain, plan))
}

/// The outline of the shape in `shape_path` in the chain's own frame, in tile widths (tile
/// 0 at the origin heading +x, y up): the plan's `chain_to_svg` map inverted. `None` when
/// the file cannot be read again or the map is singular.
pub fn target_outline(plan: &Plan, shape_path: &Path) -> Option<Vec<Vec<(f64, f64)>>> {
    let data =
        foldchain_planner::read_file_at_most(shape_path, foldchain_planner::MAX_DRAWING_BYTES)
            .ok()?;
    let shape = Shape::from_svg_data(&data, &shape_path.display().to_string()).ok()?;
    let [a, b, c, d, e, f] = plan.chain_to_svg;
    let det = a * d - b * c;
    if !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    // the shape's rings are y up; SVG user units are y down
    let to_chain = |(x, y): (f64, f64)| {
        let (sx, sy) = (x - e, -y - f);
        ((d * sx - c * sy) / det, (a * sy - b * sx) / det)
    };
    Some(
        shape
            .rings()
            .map(|r| r.points.iter().map(|p| to_chain((p.x, p.y))).collect())
            .collect(),
    )
}

/// The arguments naming a chain and its designs that `fold-run` and `fold-print` share
/// (`#[command(flatten)]`): `CHAIN`, `--plan`, `--design`.
#[derive(clap::Args, Clone, Debug)]
pub struct ChainInput {
    /// The chain: a tile list (`SS SL LS`), a fold word (`SLLS`), a file holding one, or a
    /// target shape `SHAPE.svg` to plan first.
    pub chain: Option<String>,
    /// Read the chain from fold-plan's JSON.
    #[arg(long, value_name = "PLAN.json")]
    pub plan: Option<PathBuf>,
    /// Tile design JSON (a design object, or {"global": ..., "tiles": [...]}); default: the
    /// thesis design.
    #[arg(long, value_name = "DESIGN.json")]
    pub design: Option<PathBuf>,
}

impl ChainInput {
    /// The designs `--design` names (the thesis design without it).
    pub fn designs(&self) -> anyhow::Result<TileDesigns> {
        read_designs(self.design.as_deref(), None)
    }
}

/// The tile designs of a design file (the thesis design without one), with `--s` (a
/// distance or a fraction of e, [`SValue::parse`]) for every tile when given, checked.
pub fn read_designs(design: Option<&Path>, s: Option<&str>) -> anyhow::Result<TileDesigns> {
    let mut designs = match design {
        Some(p) => TileDesigns::from_file(p)?,
        None => TileDesigns::default(),
    };
    if let Some(s) = s {
        designs = designs.with_s(SValue::parse(s)?);
        designs.check_ranges("--s")?;
    }
    Ok(designs)
}

/// The planner's options with `--tiles`, `--tile-size` and `--turns` where given (the
/// planner's defaults elsewhere).
pub fn plan_options(
    tiles: Option<usize>,
    tile_size: Option<f64>,
    turns: Option<Turns>,
) -> PlanOptions {
    let mut po = PlanOptions::default();
    if let Some(n) = tiles {
        po = po.with_tiles(n);
    }
    if let Some(w) = tile_size {
        po = po.with_tile_size(w);
    }
    if let Some(t) = turns {
        po = po.with_turns(t);
    }
    po
}

/// A chain as a tool's arguments name it: `CHAIN` (a fold word, a tile list, a file holding
/// one, or a `SHAPE.svg` to plan), or `--plan PLAN.json`, with the planner's options for a
/// shape.
#[derive(Clone, Copy, Debug, Default)]
pub struct ChainArgs<'a> {
    /// The positional `CHAIN`.
    pub chain: Option<&'a str>,
    /// `--plan`.
    pub plan: Option<&'a Path>,
    /// `--tiles` (a shape only).
    pub tiles: Option<usize>,
    /// `--tile-size` (a shape only).
    pub tile_size: Option<f64>,
    /// `--turns` (a shape only).
    pub turns: Option<Turns>,
}

/// The chain a tool works on, with its name, the outline it was planned for (if any) and
/// the input files it came from.
#[derive(Clone, Debug)]
pub struct ResolvedChain {
    /// The chain.
    pub chain: Chain,
    /// Its name: the file's stem, or the word itself when short.
    pub name: String,
    /// The target outline in the chain's frame, in tile widths (empty when none).
    pub target: Vec<Vec<(f64, f64)>>,
    /// The files read (an output must not replace them).
    pub files: Vec<PathBuf>,
}

/// Reads the chain `args` name; a shape is planned (progress to `progress`), a shape that
/// cannot be planned is the planner's error (exit 1). Options that apply only to a shape are
/// refused for anything else.
pub fn resolve_chain(args: &ChainArgs<'_>, progress: &Progress) -> anyhow::Result<ResolvedChain> {
    let shape_opts = args.tiles.is_some() || args.tile_size.is_some() || args.turns.is_some();
    let is_svg = |a: &str| a.to_ascii_lowercase().ends_with(".svg");
    if shape_opts && !args.chain.is_some_and(is_svg) {
        bail!("--tiles, --tile-size and --turns apply only to a SHAPE.svg (a plan or a chain has its tiles already)");
    }
    match (args.chain, args.plan) {
        (Some(_), Some(_)) => bail!("give either CHAIN or --plan, not both"),
        (None, None) => bail!(
            "no chain: give CHAIN (a tile list, fold word, file or SHAPE.svg) or --plan PLAN.json"
        ),
        (None, Some(plan_path)) => {
            let (chain, plan) = read_plan_file(plan_path)?;
            // the plan names its shape file; drawn when it is still there
            let shape = Path::new(&plan.source);
            let target = if shape.is_file() {
                target_outline(&plan, shape).unwrap_or_default()
            } else {
                Vec::new()
            };
            Ok(ResolvedChain {
                chain,
                name: stem(plan_path),
                target,
                files: vec![plan_path.to_path_buf()],
            })
        }
        (Some(arg), None) if is_svg(arg) => {
            let path = Path::new(arg);
            let po = plan_options(args.tiles, args.tile_size, args.turns);
            progress.stage("planning the shape");
            let report = |stage: &str, done: u64, total: u64| {
                progress.update_in(&format!("planning: {stage}"), "steps", done, total)
            };
            let plan = plan_svg_file_reporting(path, &po, &report)?;
            let word = plan
                .fold_word()
                .with_context(|| format!("plan of {}", path.display()))?;
            Ok(ResolvedChain {
                chain: word.to_chain(),
                name: stem(path),
                target: target_outline(&plan, path).unwrap_or_default(),
                files: vec![path.to_path_buf()],
            })
        }
        (Some(arg), None) => {
            let chain = read_chain(arg)?;
            let file = Path::new(arg).is_file();
            Ok(ResolvedChain {
                name: if file {
                    stem(Path::new(arg))
                } else {
                    inline_name(arg, &chain)
                },
                chain,
                target: Vec::new(),
                files: if file {
                    vec![PathBuf::from(arg)]
                } else {
                    Vec::new()
                },
            })
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn a_missing_file_is_not_read_as_a_fold_word() {
        let e = read_chain("nope.txt").unwrap_err().to_string();
        assert!(e.contains("no such file, and not a fold word"), "{e}");
        let e = read_chain("dir/sq.svg").unwrap_err().to_string();
        assert!(e.contains("fold-plan or fold-run"), "{e}");
        // a word is still a word
        assert_eq!(read_chain("SLLS").unwrap().len(), 5);
    }

    #[test]
    fn an_output_equal_to_an_input_is_refused_through_links() {
        let dir = crate::output::scratch("inputs");
        let f = dir.join("sq.svg");
        std::fs::write(&f, "x").unwrap();
        let dotted = dir.join(".").join("sq.svg");
        assert!(refuse_overwrite(&[&f], &dotted, "--preview").is_err());
        assert!(refuse_overwrite(&[&f], &dir.join("other.svg"), "--preview").is_ok());
        #[cfg(unix)]
        {
            let link = dir.join("link.svg");
            let _ = std::fs::remove_file(&link);
            std::os::unix::fs::symlink(&f, &link).unwrap();
            assert!(refuse_overwrite(&[&f], &link, "--out").is_err());
        }
        let ours = |n: &str| n == "summary.json";
        let s = dir.join("summary.json");
        std::fs::write(&s, "{}").unwrap();
        assert!(refuse_overwrite_in(&[&s], &dir, &ours, "--out").is_err());
        assert!(refuse_overwrite_in(&[&f], &dir, &ours, "--out").is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
