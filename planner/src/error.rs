//! Why a shape could not be planned: bad input (exit 2) or a shape the chain cannot fill
//! (exit 1).

use std::path::PathBuf;

/// An error of [`crate::plan_svg_file`] or [`crate::plan_svg_str`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlanError {
    /// The file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not a readable SVG document.
    #[error("{name}: not a readable SVG file: {reason}; save the drawing as SVG (e.g. Inkscape: Save As > Plain SVG) and plan that file")]
    BadSvg {
        /// The file name (or `<string>`).
        name: String,
        /// What the XML or SVG parser said.
        reason: String,
    },
    /// The drawing holds no filled area to plan.
    #[error("{name}: no filled area: {reason}; draw the shape as a filled area (an outline drawn as a stroke: Inkscape's Path > Stroke to Path)")]
    NoFilledArea {
        /// The file name (or `<string>`).
        name: String,
        /// What was found instead.
        reason: String,
    },
    /// An outline crosses itself.
    #[error("{name}: self-intersecting outline in {element}: edge {first} crosses edge {second} near ({x:.3}, {y:.3}); draw the outline without crossings (use separate shapes or a hole instead)")]
    SelfIntersecting {
        /// The file name (or `<string>`).
        name: String,
        /// The element (its id, or its index).
        element: String,
        /// One edge of the flattened outline.
        first: usize,
        /// The edge it crosses.
        second: usize,
        /// Where, in user units.
        x: f64,
        /// Where, in user units.
        y: f64,
    },
    /// A number in the drawing's geometry is not finite (NaN, an infinity, or beyond the
    /// about 3.4e38 that SVG renderers hold).
    #[error("{name}: {element} has {attribute}=\"...{value}...\": {value} is not a finite number within the about 3.4e38 an SVG renderer holds; give the element's coordinates as ordinary numbers")]
    BadNumber {
        /// The file name (or `<string>`).
        name: String,
        /// The element (its tag and id, or its tag and index among elements of that tag).
        element: String,
        /// The attribute holding the value.
        attribute: String,
        /// The value as written.
        value: String,
    },
    /// The root `<svg>` element's viewBox has a zero or negative width or height: SVG
    /// renders nothing for a zero one, and a negative one is an error (a renderer stops or
    /// ignores the viewBox), so the drawing's size is not known.
    #[error("{name}: <svg> has viewBox=\"{value}\": {reason}; give the viewBox a positive width and height (its third and fourth numbers), or remove it, and plan that file")]
    BadViewBox {
        /// The file name (or `<string>`).
        name: String,
        /// The attribute's value as written.
        value: String,
        /// What is wrong with it.
        reason: String,
    },
    /// An element's own transform scales it by so little that the SVG reader (32-bit
    /// numbers) drops it, with what it holds: the plan would miss a part a browser draws.
    #[error("{name}: {element} has transform=\"{value}\", which scales it by {scale:.3e}: the SVG reader (32-bit numbers) drops an element scaled by {limit:.2e} or less, so it would not be planned; give the element larger coordinates and a transform nearer scale(1) (e.g. Inkscape: Object > Transform, or Preferences > Behavior > Transforms > Optimized) and plan that file", limit = f32::EPSILON)]
    TinyTransform {
        /// The file name (or `<string>`).
        name: String,
        /// The element (its tag and id, or its tag and index among elements of that tag).
        element: String,
        /// The attribute's value as written.
        value: String,
        /// The smaller of its scales along its two axes.
        scale: f64,
    },
    /// The drawing holds text, which the planner does not read (it loads no fonts): planned
    /// without it, the chain would fill another shape than the one drawn.
    #[error("{name}: {element} holds text (\"{content}\"), which the planner does not read; convert the text to paths (Inkscape: Path > Object to Path) and plan that file")]
    Text {
        /// The file name (or `<string>`).
        name: String,
        /// The element (its id, or its index among the text elements).
        element: String,
        /// The start of its text.
        content: String,
    },
    /// The drawing holds more outline points than the planner reads.
    #[error("{name}: the outlines have {points} points, more than the {limit} the planner reads; simplify the drawing (e.g. Inkscape: Path > Simplify)")]
    TooManyPoints {
        /// The file name (or `<string>`).
        name: String,
        /// Points found (so far).
        points: usize,
        /// The limit ([`crate::MAX_OUTLINE_POINTS`]).
        limit: usize,
    },
    /// The outlines hold more detail than the planner plans from in seconds, even thinned
    /// to a coarser tolerance.
    #[error("{name}: the outlines keep {points} points when thinned to {pct}% of the drawing's size, more than the {limit} the planner plans from; simplify the drawing (e.g. Inkscape: Path > Simplify) or plan a smoother version of it", pct = share * 100.0)]
    TooDetailed {
        /// The file name (or `<string>`).
        name: String,
        /// Points left after thinning.
        points: usize,
        /// The most points planned from.
        limit: usize,
        /// The coarsest thinning tolerance, as a share of the drawing's larger side.
        share: f64,
    },
    /// An option value that cannot be used.
    #[error("bad {option} {value}: {reason}")]
    BadOption {
        /// The option.
        option: PlanOption,
        /// The value given.
        value: String,
        /// What was expected.
        reason: String,
    },
    /// The shape is valid but no collision-free chain was found that fills it.
    #[error("{name}: cannot plan this shape: {reason}")]
    Unplannable {
        /// The file name (or `<string>`).
        name: String,
        /// What is wrong, where (in drawing units and mm) and what to change: a sentence
        /// or two, what the error shows.
        reason: String,
        /// What each planner tried and why it failed, one line each (for a verbose
        /// report; empty when the reason says all).
        detail: Vec<String>,
        /// The best plan found that folds but was rejected because it leaves a part of the
        /// shape empty: for a preview that shows where ([`crate::preview_svg_rejected`]).
        rejected: Option<Box<Rejected>>,
    },
}

/// A plan that folds without collision but was not returned: it leaves a part of the shape
/// empty.
#[derive(Clone, Debug, PartialEq)]
pub struct Rejected {
    /// The plan.
    pub plan: crate::Plan,
    /// The part it leaves empty.
    pub empty: crate::EmptyPart,
}

/// An option of [`crate::PlanOptions`], as errors name it (a command line maps it to its
/// flag).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PlanOption {
    /// [`crate::PlanOptions::tiles`].
    Tiles,
    /// [`crate::PlanOptions::tile_size`].
    TileSize,
    /// [`crate::PlanOptions::tile_mm`].
    TileMm,
    /// [`crate::PlanOptions::tiles_tolerance`].
    TilesTolerance,
    /// [`crate::PlanOptions::turn_cost`].
    TurnCost,
}

impl std::fmt::Display for PlanOption {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            PlanOption::Tiles => "tile count",
            PlanOption::TileSize => "tile size",
            PlanOption::TileMm => "tile width in mm",
            PlanOption::TilesTolerance => "tile count tolerance",
            PlanOption::TurnCost => "turn cost",
        })
    }
}

impl PlanError {
    /// True for errors in the input (file, SVG, options): exit code 2. False for a valid
    /// shape the planner cannot fill: exit code 1.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, PlanError::Unplannable { .. })
    }

    /// The exit code a binary should use: 2 for bad input, 1 for an unplannable shape.
    pub fn exit_code(&self) -> i32 {
        if self.is_bad_input() {
            2
        } else {
            1
        }
    }
}
