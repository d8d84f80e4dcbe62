//! The plan: the chain that fills a shape, its poses in the drawing and its fit.

use std::collections::BTreeMap;

use crate::options::Turns;

/// One tile centre of the folded chain, in the SVG's user units.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PlanPose {
    /// Centre x, SVG user units.
    pub x: f64,
    /// Centre y, SVG user units (SVG y points down the page).
    pub y: f64,
    /// The direction the chain runs through the tile, degrees in `[0, 360)` measured in SVG
    /// coordinates from +x towards +y (so 90 points down the page).
    pub heading_deg: f64,
}

/// Fit measures of a plan, each a share in `[0, 1]`.
///
/// Both are areas, computed exactly (not on sample points): each tile is its regular
/// octagon of width w, the shape its filled area (every filled path by its own fill rule,
/// clip paths and masks applied). Tiles wholly inside or wholly outside the shape count
/// whole; the tiles the outline crosses (and any that overlap another tile, which a plan
/// that folds never has) are united and clipped against the shape by polygon boolean
/// operations (`i_overlay`, on an integer grid of about 2^-29 of the drawing's extent), so
/// both shares are good to 1e-6. Tight rows `sqrt2 w` apart cover `2 - sqrt2 = 0.586` of
/// the band they fill; a shape whose outline lies flush on the outer rows' faces can be
/// covered a little more (five rows flush in a rectangle: 0.62).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Metrics {
    /// The area of the union of the tiles inside the shape over the shape's area.
    pub covered_share: f64,
    /// The area of the union of the tiles outside the shape over the area of their union
    /// (for a plan that folds, whose tiles do not overlap: the chain's area).
    pub outside_share: f64,
    /// The shape's area, SVG user units squared.
    pub shape_area: f64,
    /// The chain's area (tiles times the octagon area), SVG user units squared.
    pub chain_area: f64,
    /// The largest part of the shape the plan leaves empty, in tile areas: a connected
    /// region at least half a tile inside the outline and farther than 0.95 tile widths
    /// from every tile centre ([`crate::EmptyPart`]); 0 when there is none larger than two
    /// tile areas.
    #[serde(default)]
    pub largest_empty_tiles: f64,
}

impl Metrics {
    /// One number for comparisons (lower is better): the share of the shape left uncovered
    /// plus the share of the chain outside it.
    pub fn fit_error(&self) -> f64 {
        (1.0 - self.covered_share) + self.outside_share
    }
}

/// A planned chain: what `fold-plan --json` prints and `fold-run --plan` reads.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Plan {
    /// The SVG file planned (as given), or `<string>`.
    pub source: String,
    /// Number of tiles.
    pub tiles: usize,
    /// The chain as a run-length tile list (`SS*12 SL LL ...`).
    pub tile_list: String,
    /// The fold word, one letter per joint (`S*11 L L ...`; `FoldWord::parse` reads it).
    pub word: String,
    /// The direction (degrees, SVG coordinates, in `[0, 180)`) along which the rows are
    /// stacked: the axis the shape is monotone to. Rows run orthogonal to it.
    pub axis_deg: f64,
    /// The tile width (across flats), SVG user units.
    pub tile_size: f64,
    /// Millimetres per SVG user unit: from the drawing's width and height with their units
    /// and its viewBox, or 96 user units per inch when it states no physical size.
    #[serde(default)]
    pub mm_per_unit: f64,
    /// The tile width (across flats), millimetres.
    #[serde(default)]
    pub tile_mm: f64,
    /// The folded chain's size in millimetres, `[width, height]` across the drawing: the
    /// bounding box of the tile centres plus one tile width.
    #[serde(default)]
    pub extent_mm: [f64; 2],
    /// The turn style used (tight or loose).
    pub turns: Turns,
    /// Number of 180 degree U-turns.
    pub u_turns: usize,
    /// Number of single 90 degree turns (joins between cells).
    pub quarter_turns: usize,
    /// Number of monotone cells the shape was split into (1 for a monotone shape).
    pub cells: usize,
    /// Count per physical part (SS, RS, SR, RR, ...).
    pub bom: BTreeMap<String, usize>,
    /// Fit measures.
    pub metrics: Metrics,
    /// The affine map from the chain's own frame (tile 0 at the origin heading +x, in units
    /// of the tile width, as `foldchain::kinematics` computes it with w = 1) to SVG user
    /// units, as an SVG matrix `[a, b, c, d, e, f]`: `x' = a x + c y + e`,
    /// `y' = b x + d y + f`. Its determinant is negative: the drawing is seen from above with
    /// y pointing down, so L folds appear as left turns on the page.
    pub chain_to_svg: [f64; 6],
    /// One pose per tile centre, SVG user units.
    pub poses: Vec<PlanPose>,
    /// What the plan falls short in (a part of the shape left empty, a tile count outside
    /// the asked tolerance), one sentence each; empty for a plan that meets every aim.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// Millimetres to three significant digits or to 0.1 mm, whichever is coarser.
pub(crate) fn mm(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(0.005..1e6).contains(&a) {
        // a drawing a billionth of a millimetre or a million kilometres across
        format!("{v:.3e}")
    } else if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

impl Plan {
    /// The plan as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// A plan read back from its JSON.
    pub fn from_json(text: &str) -> Result<Plan, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The fold word, parsed.
    pub fn fold_word(&self) -> Result<foldchain::FoldWord, foldchain::ChainError> {
        foldchain::FoldWord::parse(&self.word)
    }

    /// Sets the physical scale (millimetres per user unit) and the sizes that follow.
    pub(crate) fn set_scale(&mut self, mm_per_unit: f64) {
        self.mm_per_unit = mm_per_unit;
        self.tile_mm = self.tile_size * mm_per_unit;
        let (mut x0, mut y0, mut x1, mut y1) = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for p in &self.poses {
            (x0, y0, x1, y1) = (x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y));
        }
        self.extent_mm = if self.poses.is_empty() {
            [0.0, 0.0]
        } else {
            [
                (x1 - x0 + self.tile_size) * mm_per_unit,
                (y1 - y0 + self.tile_size) * mm_per_unit,
            ]
        };
    }

    /// The one-line summary `fold-plan` prints.
    pub fn summary(&self) -> String {
        format!(
            "{}, {}, {}, {}, axis {:.1} deg, tile {} units = {} mm, folded {} x {} mm; fit: {:.1}% of the shape covered, {:.1}% of the chain outside it",
            plural(self.tiles, "tile", "tiles"),
            plural(self.u_turns, &format!("{} U-turn", self.turns), &format!("{} U-turns", self.turns)),
            plural(self.quarter_turns, "90-degree turn", "90-degree turns"),
            plural(self.cells, "cell", "cells"),
            self.axis_deg,
            crate::units::figure(self.tile_size),
            mm(self.tile_mm),
            mm(self.extent_mm[0]),
            mm(self.extent_mm[1]),
            100.0 * self.metrics.covered_share,
            100.0 * self.metrics.outside_share
        )
    }
}

/// `n` and the noun in the number it takes: `1 cell`, `2 cells`.
pub(crate) fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}
