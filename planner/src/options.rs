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

/// Options of a plan. Default: about [`DEFAULT_TILES`] tiles, [`Turns::Auto`].
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PlanOptions {
    /// About this many tiles (the tile size is searched to come near it). Ignored when
    /// `tile_size` is set.
    pub tiles: Option<usize>,
    /// The tile width (across flats) in SVG user units.
    pub tile_size: Option<f64>,
    /// The turn style.
    pub turns: Turns,
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

    /// The turn style.
    pub fn with_turns(mut self, turns: Turns) -> PlanOptions {
        self.turns = turns;
        self
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
