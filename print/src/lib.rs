//! # foldchain-print
//!
//! From a chain (or a plan, or a shape) to files a maker prints: one part per tile type the
//! chain uses, built from the same [`foldchain::Design`] and
//! [`foldchain::magnet_path::MagnetPath`] the engine simulates (the octagon plate, a floor,
//! open channels that follow each magnet path as wide as the magnet plus the printer's
//! clearance, an engraved mark naming the type and the reaction initiator's side), as closed,
//! consistently oriented meshes in mm, written as 3MF or STL.
//!
//! ```
//! use foldchain::{Design, Tile};
//! use foldchain_print::{PartOptions, TilePart};
//!
//! let part = TilePart::new("SL".parse::<Tile>()?, &Design::thesis(), &PartOptions::default())?;
//! assert!(part.mesh.topology().is_sound());
//! let (lo, hi) = part.mesh.bounds();
//! assert!((hi[0] - lo[0] - 30.0).abs() < 1e-9 && (hi[2] - 7.5).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod assembly;
mod channel;
mod error;
mod job;
mod mark;
mod mesh;
mod options;
mod picture;
mod plate;
pub mod region;
mod solid;
mod stl;
mod threemf;
mod tile_part;

pub use assembly::{assembly_svg, SheetTile, SHEET_COLUMNS};
pub use channel::Channel;
pub use error::PrintError;
pub use job::{
    estimate_basis, is_job_file, print_job, Magnets, OutputFile, PartEntry, PartsReport,
    PlateEntry, PrintJob, Source, FDM_RATE_MM3_PER_S, MAX_PRINT_TILES, RESIN_LAYER_MM,
    RESIN_SECONDS_PER_LAYER,
};
pub use mesh::{Mesh, MeshBuilder, Pt3, Topology};
pub use options::{
    default_clearance, Bed, Format, PartOptions, PrintOptions, DEFAULT_ARC_TOLERANCE,
    DEFAULT_FLOOR, DEFAULT_MARK_DEPTH, DEFAULT_MARK_HEIGHT, DEFAULT_MARK_STROKE, DEFAULT_MIN_WALL,
    THESIS_HEIGHT,
};
pub use picture::{mesh_png, mesh_svg, View};
pub use plate::{grid, lay_out, Placement};
pub use solid::{prism_with_pockets, triangulate, FaceError, Pocket};
pub use stl::{from_stl, to_stl};
pub use threemf::{model_xml, read_3mf, to_3mf, Item, Model, Object};
pub use tile_part::{TilePart, Wall, MIN_MARK_HEIGHT};
