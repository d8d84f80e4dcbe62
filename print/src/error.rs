//! Why a part, a plate or a print job could not be made.

use foldchain::magnet_path::PathError;
use foldchain::{DesignError, Tile};

/// Why printable files could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PrintError {
    /// An option out of range.
    #[error("{name} = {value}: expected {expected}")]
    BadOption {
        /// The option's name (as the command line spells it).
        name: &'static str,
        /// The value given.
        value: String,
        /// What was expected.
        expected: String,
    },
    /// The design's parameters are out of range.
    #[error("design: {0}")]
    Design(#[from] DesignError),
    /// A curved path cannot be built for the design.
    #[error("tile {tile}: {source}")]
    Path {
        /// The tile type.
        tile: Tile,
        /// Why.
        source: PathError,
    },
    /// A printed feature does not fit in the tile: a wall too thin to print, or features
    /// that meet.
    #[error(
        "tile {tile}: {what} is {thickness:.3} mm thick; at least {min:.3} mm is needed ({hint})"
    )]
    ThinWall {
        /// The tile type.
        tile: Tile,
        /// Which wall.
        what: String,
        /// Its thickness, mm (0 or less where the features meet).
        thickness: f64,
        /// The least thickness allowed, mm.
        min: f64,
        /// What to change.
        hint: &'static str,
    },
    /// The magnet does not sit low enough in its channel.
    #[error("tile {tile}: the magnet's centre of mass sits {centre:.3} mm above the bed, not below the wall top at {top:.3} mm: use a thinner floor, a taller tile or a shorter magnet")]
    MagnetTooTall {
        /// The tile type.
        tile: Tile,
        /// The magnet centre's height, mm.
        centre: f64,
        /// The wall top, mm.
        top: f64,
    },
    /// A face could not be triangulated (a geometry the part builder should have refused).
    #[error("tile {tile}: the {face} face cannot be triangulated: {reason}")]
    Triangulation {
        /// The tile type.
        tile: Tile,
        /// Which face.
        face: &'static str,
        /// Why.
        reason: String,
    },
    /// A part larger than the bed.
    #[error("a {part} tile ({w:.1} x {h:.1} mm) does not fit on the {bed_w} x {bed_h} mm bed")]
    PartTooLarge {
        /// The part.
        part: String,
        /// Its footprint, mm.
        w: f64,
        /// Its footprint, mm.
        h: f64,
        /// The bed, mm.
        bed_w: f64,
        /// The bed, mm.
        bed_h: f64,
    },
    /// The shape could not be planned.
    #[error(transparent)]
    Plan(#[from] foldchain_planner::PlanError),
    /// A plan whose word does not make a chain.
    #[error("the plan's fold word: {0}")]
    Chain(#[from] foldchain::ChainError),
    /// A file format could not be written (the zip container of a 3MF file).
    #[error("writing {name}: {reason}")]
    Format {
        /// The file.
        name: String,
        /// Why.
        reason: String,
    },
}
