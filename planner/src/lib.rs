//! # foldchain-planner
//!
//! Plans a self-folding tile chain that fills a target shape drawn in SVG (thesis section
//! 5.5, SPEC section 5). The shape is read with `usvg` (all shapes, paths, transforms,
//! viewBox and units) and flattened to polygons; it is filled with serpentine rows of
//! straight tiles joined by U-turns that alternate in direction, along a direction in which
//! the shape is monotone, or, where it splits into monotone cells, with one serpentine per
//! cell joined by turns. Row lengths, orientation and start corner are chosen by dynamic
//! programming to minimise an area-true fit error plus a price per turn, the tile size so
//! that the chain holds about the asked number of tiles (or is a width in mm). No plan
//! leaves a part of the shape empty. Every plan is checked by sequential folding with the
//! self-intersection check before it is returned.
//!
//! ```
//! use foldchain_planner::{plan_svg_str, PlanOptions, Turns};
//! let square = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
//!     <rect x="10" y="10" width="80" height="80"/></svg>"#;
//! let opts = PlanOptions::default().with_tiles(60).with_turns(Turns::Tight);
//! let plan = plan_svg_str(square, "square.svg", &opts)?;
//! assert_eq!(plan.poses.len(), plan.tiles);
//! assert_eq!(plan.fold_word()?.tiles(), plan.tiles);
//! println!("{}\n{}", plan.tile_list, plan.summary());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! How the parts fit: [`plan_svg_file`] and [`plan_svg_str`] read a [`Shape`] (`drawing`)
//! and hand it to the top level (`plan_shape`), which checks the [`PlanOptions`] and asks two
//! planners: one serpentine over the whole shape (`serpentine`) and routes through monotone
//! cells (`cells`, `route`, `cell_plan`). Both solve rows with one dynamic programme
//! (`rows`), search the tile width the same way (`sizing`), map between frames with kurbo
//! affines (`frame`) and turn a checked fold word into a [`Plan`] (`assembly`) whose fit is
//! measured as exact areas of the tiles' union inside and outside the shape (`fit`,
//! `coverage`). [`preview_svg`] draws a plan over its
//! shape.

mod assembly;
mod cap_plan;
mod caps;
mod cell_plan;
mod centre_grid;
mod check;
mod clip;
mod coverage;
mod drawing;
mod empty;
mod error;
mod fit;
mod flatten;
mod frame;
mod lobes;
mod narrow;
mod near_widths;
mod options;
mod parts;
mod pieces;
mod plan;
mod plan_shape;
mod pockets;
mod preview;
mod rank;
mod refusal;
mod route;
mod row_chain;
mod rows;
mod serpentine;
mod shape;
mod simplify;
mod sizing;
mod slabs;
mod units;
mod walk;

/// kurbo, whose [`kurbo::Point`], [`kurbo::Rect`] and [`kurbo::Affine`] the [`Shape`] API
/// takes and returns (re-exported so that callers use the same version).
pub use kurbo;

pub use drawing::FLATTEN_TOLERANCE;
pub use empty::EmptyPart;
pub use error::{PlanError, PlanOption, Rejected};
pub use options::{
    ParseTurnsError, PlanOptions, Turns, DEFAULT_TILES, DEFAULT_TILES_TOLERANCE, DEFAULT_TURN_COST,
    MAX_DRAWING_BYTES, MAX_OUTLINE_POINTS, MAX_PLAN_TILES,
};
pub use plan::{Metrics, Plan, PlanPose};
pub use preview::{preview_svg, preview_svg_file, preview_svg_rejected};
pub use shape::{Ring, Shape};

/// A progress callback: `(stage, done, total)`, called now and then while a plan is made
/// (from the planner's worker threads, hence `Sync`). The library never prints; a binary
/// shows these as it likes.
pub type Progress<'a> = &'a (dyn Fn(&str, u64, u64) + Sync);

/// Plans the shape in an SVG file; the file's name (as given) names it in errors and in the
/// plan's `source`.
pub fn plan_svg_file(path: &std::path::Path, opts: &PlanOptions) -> Result<Plan, PlanError> {
    plan_svg_file_reporting(path, opts, &|_, _, _| {})
}

/// [`plan_svg_file`], reporting progress to `progress`.
pub fn plan_svg_file_reporting(
    path: &std::path::Path,
    opts: &PlanOptions,
    progress: Progress<'_>,
) -> Result<Plan, PlanError> {
    let text = read_drawing_file(path)?;
    plan_svg_data(&text, &path.display().to_string(), opts, progress)
}

/// The bytes of the drawing in `path`, read up to [`MAX_DRAWING_BYTES`].
pub(crate) fn read_drawing_file(path: &std::path::Path) -> Result<Vec<u8>, PlanError> {
    read_file_at_most(path, MAX_DRAWING_BYTES).map_err(|source| PlanError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// Plans the shape in SVG text; `name` names it in errors and in the plan's `source`.
pub fn plan_svg_str(svg: &str, name: &str, opts: &PlanOptions) -> Result<Plan, PlanError> {
    plan_svg_data(svg.as_bytes(), name, opts, &|_, _, _| {})
}

fn plan_svg_data(
    data: &[u8],
    name: &str,
    opts: &PlanOptions,
    progress: Progress<'_>,
) -> Result<Plan, PlanError> {
    progress("reading the drawing", 0, 1);
    let (shape, mm_per_unit) = drawing::read_drawing(data, name)?;
    let mut plan = plan_shape::plan_shape(
        &shape,
        &opts.resolved(mm_per_unit),
        name,
        mm_per_unit,
        true,
        progress,
    )
    .map_err(|mut e| {
        if let PlanError::Unplannable {
            rejected: Some(r), ..
        } = &mut e
        {
            r.plan.set_scale(mm_per_unit);
        }
        e
    })?;
    plan.set_scale(mm_per_unit);
    Ok(plan)
}

/// Reads a whole file of at most `limit` bytes: a larger file, or a device or pipe that
/// does not end (`/dev/zero`), is refused with an `InvalidData` error once `limit` bytes
/// are read, so that reading an input never takes unbounded memory or time. The tools read
/// every input file (drawings, plans, designs, reports) through it.
pub fn read_file_at_most(path: &std::path::Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than {} MiB, the most read from one input file",
                limit >> 20
            ),
        ));
    }
    Ok(bytes)
}
