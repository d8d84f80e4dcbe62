//! # foldchain-planner
//!
//! Plans a self-folding tile chain that fills a target shape drawn in SVG (thesis section
//! 5.5, SPEC section 5): the shape is read with `usvg` (all shapes, paths, transforms,
//! viewBox and units), flattened to polygons, and filled with serpentine rows of straight
//! tiles joined by U-turns that alternate in direction, along a direction in which the shape
//! is monotone. Row lengths, orientation and start corner are chosen by dynamic programming
//! to minimise the fit error. Every plan is checked by sequential folding with the
//! self-intersection check before it is returned.
//!
//! ```no_run
//! use foldchain_planner::{plan_svg_file, PlanOptions, Turns};
//! let opts = PlanOptions::default().with_tiles(107).with_turns(Turns::Tight);
//! let plan = plan_svg_file(std::path::Path::new("shapes/square.svg"), &opts).unwrap();
//! println!("{}\n{}", plan.tile_list, plan.summary());
//! ```

mod cells;
mod check;
mod error;
mod options;
mod plan;
mod planner;
pub mod preview;
mod route;
mod rows;
mod shape;

pub use error::PlanError;
pub use options::{PlanOptions, Turns, DEFAULT_TILES};
pub use plan::{Metrics, Plan, PlanPose};
pub use planner::MAX_PLAN_TILES;
pub use shape::{Ring, Shape, FLATTEN_TOLERANCE};

/// Plans the shape in an SVG file.
pub fn plan_svg_file(path: &std::path::Path, opts: &PlanOptions) -> Result<Plan, PlanError> {
    let text = std::fs::read(path).map_err(|source| PlanError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let name = path.display().to_string();
    let shape = Shape::from_svg_data(&text, &name)?;
    planner::plan_shape(&shape, opts, &name)
}

/// Plans the shape in SVG text; `name` names it in errors and in the plan's `source`.
pub fn plan_svg_str(svg: &str, name: &str, opts: &PlanOptions) -> Result<Plan, PlanError> {
    let shape = Shape::from_svg_data(svg.as_bytes(), name)?;
    planner::plan_shape(&shape, opts, name)
}
