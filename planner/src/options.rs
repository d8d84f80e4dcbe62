//! Planning options: scale and turn style, with documented defaults, and the limits a plan
//! must keep.

use crate::error::{PlanError, PlanOption};
use crate::shape::Shape;

/// How the serpentine rows are joined.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Turns {
    /// One LL or RR tile per U-turn: row pitch sqrt2 * w.
    Tight,
    /// Fold, one straight tile, fold: no LL/RR tiles, row pitch (1 + sqrt2) * w.
    Loose,
    /// Both are planned and the better fit is kept (the default).
    #[default]
    Auto,
}

/// A turn style that is not `tight`, `loose` or `auto`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("bad turns '{0}': expected tight, loose or auto")]
#[non_exhaustive]
pub struct ParseTurnsError(pub String);

impl std::str::FromStr for Turns {
    type Err = ParseTurnsError;
    fn from_str(s: &str) -> Result<Turns, ParseTurnsError> {
        match s.to_ascii_lowercase().as_str() {
            "tight" => Ok(Turns::Tight),
            "loose" => Ok(Turns::Loose),
            "auto" => Ok(Turns::Auto),
            _ => Err(ParseTurnsError(s.to_string())),
        }
    }
}

impl std::fmt::Display for Turns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Turns::Tight => "tight",
            Turns::Loose => "loose",
            Turns::Auto => "auto",
        })
    }
}

/// Default number of tiles when neither `tiles` nor `tile_size` is given.
pub const DEFAULT_TILES: usize = 200;

/// The most tiles a plan may hold: two million, twice the largest plan benchmarked (a million
/// tiles in about 15 s); larger requests are refused up front instead of running for minutes.
pub const MAX_PLAN_TILES: usize = 2_000_000;

/// The most outline points a drawing may hold (after curves are flattened): ten million,
/// ten times the largest outline benchmarked (a million points read and simplified in
/// about a second); larger drawings are refused up front.
pub const MAX_OUTLINE_POINTS: usize = 10_000_000;

/// The largest drawing file read: 256 MiB, room for [`MAX_OUTLINE_POINTS`] written out as
/// path data (about 20 bytes a point); a larger file, or a device that never ends, is refused
/// after reading that much instead of filling the memory.
pub const MAX_DRAWING_BYTES: u64 = 256 << 20;

/// Default of [`PlanOptions::tiles_tolerance`]: the count may float by 3% when that
/// buys fit (a whole row of a 200-tile square is about 7%, so the nearest counts either side
/// of a row step are both within reach).
pub const DEFAULT_TILES_TOLERANCE: f64 = 0.03;

/// Default of [`PlanOptions::turn_cost`]: a U-turn or a quarter turn is worth one tile's
/// area of misfit. An estimate, not a measurement: a turn folds joints where a straight
/// run does not, and folding time and the risk of a failed fold grow with the number of
/// folds (thesis section 7.2); the price keeps the planner from buying a sliver of fit
/// with extra turns (the key's shaft in two long rows, not in 2-tile columns).
pub const DEFAULT_TURN_COST: f64 = 1.0;

/// Options of a plan. Default: about [`DEFAULT_TILES`] tiles within
/// [`DEFAULT_TILES_TOLERANCE`], [`Turns::Auto`], turns priced at [`DEFAULT_TURN_COST`].
#[derive(Clone, Debug, PartialEq)]
pub struct PlanOptions {
    /// About this many tiles (the tile size is searched to come near it). Ignored when
    /// `tile_size` or `tile_mm` is set.
    pub tiles: Option<usize>,
    /// The tile width (across flats) in SVG user units.
    pub tile_size: Option<f64>,
    /// The tile width (across flats) in millimetres: the drawing's size in physical units
    /// (its `width` and `height` with their units, and its viewBox) sets the scale. A
    /// drawing without physical units is taken at the CSS 96 user units per inch.
    pub tile_mm: Option<f64>,
    /// The share by which the tile count may miss `tiles` when that buys a better fit
    /// (0: as near to `tiles` as the widths allow).
    pub tiles_tolerance: f64,
    /// The price of one U-turn or quarter turn, in tile areas of misfit (uncovered shape
    /// or chain outside it), when plans are ranked.
    pub turn_cost: f64,
    /// The turn style.
    pub turns: Turns,
}

impl Default for PlanOptions {
    fn default() -> PlanOptions {
        PlanOptions {
            tiles: None,
            tile_size: None,
            tile_mm: None,
            tiles_tolerance: DEFAULT_TILES_TOLERANCE,
            turn_cost: DEFAULT_TURN_COST,
            turns: Turns::Auto,
        }
    }
}

impl PlanOptions {
    /// About `n` tiles.
    pub fn with_tiles(mut self, n: usize) -> PlanOptions {
        self.tiles = Some(n);
        self
    }

    /// Tiles of width `w` in SVG user units.
    pub fn with_tile_size(mut self, w: f64) -> PlanOptions {
        self.tile_size = Some(w);
        self
    }

    /// Tiles of width `mm` millimetres.
    pub fn with_tile_mm(mut self, mm: f64) -> PlanOptions {
        self.tile_mm = Some(mm);
        self
    }

    /// The share by which the count may miss the asked one.
    pub fn with_tiles_tolerance(mut self, share: f64) -> PlanOptions {
        self.tiles_tolerance = share;
        self
    }

    /// The price of a turn in tile areas.
    pub fn with_turn_cost(mut self, cost: f64) -> PlanOptions {
        self.turn_cost = cost;
        self
    }

    /// The turn style.
    pub fn with_turns(mut self, turns: Turns) -> PlanOptions {
        self.turns = turns;
        self
    }

    /// The options with the tile width in user units: `tile_mm` converted by the drawing's
    /// millimetres per user unit.
    pub(crate) fn resolved(&self, mm_per_unit: f64) -> PlanOptions {
        let mut o = self.clone();
        if let Some(mm) = self.tile_mm {
            o.tile_size = Some(mm / mm_per_unit);
        }
        o
    }
}

impl PlanOptions {
    /// Checks the options against `shape`: a positive
    /// finite tile size, at least one tile, and at most [`MAX_PLAN_TILES`] tiles asked for
    /// or implied by the tile size (no run could finish, or allocate, more).
    pub(crate) fn check(&self, shape: &Shape) -> Result<(), PlanError> {
        let bad = |option, value: String, reason: String| {
            Err(PlanError::BadOption {
                option,
                value,
                reason,
            })
        };
        if let Some(w) = self.tile_size {
            if !(w.is_finite() && w > 0.0) {
                return bad(
                    PlanOption::TileSize,
                    w.to_string(),
                    "expected a positive number of SVG user units".into(),
                );
            }
        }
        if let Some(w) = self.tile_mm {
            if !(w.is_finite() && w > 0.0) {
                return bad(
                    PlanOption::TileMm,
                    w.to_string(),
                    "expected a positive number of millimetres".into(),
                );
            }
        }
        if !(self.tiles_tolerance.is_finite() && (0.0..=0.5).contains(&self.tiles_tolerance)) {
            return bad(
                PlanOption::TilesTolerance,
                self.tiles_tolerance.to_string(),
                "expected a share from 0 to 0.5".into(),
            );
        }
        if !(self.turn_cost.is_finite() && self.turn_cost >= 0.0) {
            return bad(
                PlanOption::TurnCost,
                self.turn_cost.to_string(),
                "expected a number of tile areas >= 0".into(),
            );
        }
        match self.tiles {
            Some(0) => return bad(PlanOption::Tiles, "0".into(), "expected at least 1".into()),
            Some(n) if n > MAX_PLAN_TILES => {
                return bad(
                    PlanOption::Tiles,
                    n.to_string(),
                    format!("expected at most {MAX_PLAN_TILES}"),
                )
            }
            _ => {}
        }
        if let Some(w) = self.tile_size {
            // a tile covers w^2 (sqrt2 - 1) * 2 of area: about w^2 / 1.2; the estimate only
            // has to be right to a small factor
            let implied = shape.area() / (0.8 * w * w);
            if implied > MAX_PLAN_TILES as f64 {
                return bad(
                    PlanOption::TileSize,
                    w.to_string(),
                    format!(
                        "the shape would take about {implied:.3e} tiles of that size, more than the {MAX_PLAN_TILES} a plan may hold"
                    ),
                );
            }
        }
        Ok(())
    }
}
