//! How plans that break a rule rank against each other: when no plan both holds the asked
//! count (within the tolerance) and leaves no part of the shape larger than
//! [`crate::empty::REFUSE_EMPTY_TILES`] tile areas empty, the plan returned is the one
//! that falls least short of the asked chain, the count's miss and the part left empty
//! priced together in one unit: tiles of the asked chain (issue 26).
//!
//! The one price: a tile by which the count misses beyond the tolerance weighs as much as a
//! tile the asked chain would lay on the part left empty. The part left empty is measured
//! as a share of the shape's area times the asked count (the tiles a full plan of the asked
//! count lays over it), not in the plan's own tile areas: a plan of 13 tiles where 100 were
//! asked has tiles 2.8 times as wide, and its 45 tile areas empty are 346 tiles of the
//! asked chain. Ranking rejected plans by their empty part in their own tile areas (as
//! before) made the plan with the fewest, widest tiles win (narrowb-at: 13 tiles for 100
//! asked, xlight-O 23, mdi-anchor 202 for 300).

use crate::error::Rejected;
use crate::options::{PlanOptions, DEFAULT_TILES};
use crate::plan::Plan;

/// The asked chain, as the ranking of plans that break a rule needs it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Asked {
    /// The asked count (or the count the asked width gives).
    target: usize,
    /// Tiles by which a count may miss `target` without a warning (0 when a width was asked:
    /// then no count misses).
    tolerance: usize,
    /// A tile width was asked: counts do not miss.
    by_width: bool,
    /// The shape's area, user units squared (0: empty parts compare in tile areas).
    area: f64,
}

impl Asked {
    /// The asked chain of `opts` over a shape of area `area`; `tiles_est` is the count the
    /// asked width gives when a width was asked.
    pub(crate) fn new(opts: &PlanOptions, area: f64, tiles_est: usize) -> Asked {
        let by_width = opts.tile_size.is_some();
        let target = if by_width {
            tiles_est
        } else {
            opts.tiles.unwrap_or(DEFAULT_TILES)
        };
        Asked {
            target,
            tolerance: (opts.tiles_tolerance * target as f64) as usize,
            by_width,
            area,
        }
    }

    /// Tiles by which `tiles` misses the asked count beyond the tolerance.
    pub(crate) fn miss(&self, tiles: usize) -> usize {
        if self.by_width {
            0
        } else {
            tiles.abs_diff(self.target).saturating_sub(self.tolerance)
        }
    }

    /// How far a plan of `tiles` tiles of width `w` leaving `empty` of its own tile areas
    /// empty falls short of the asked chain, in tiles of it: the tiles the asked chain
    /// lays over the part left empty plus the count's miss (see the module documentation).
    pub(crate) fn shortfall(&self, tiles: usize, w: f64, empty: f64) -> f64 {
        let empty = if self.area > 0.0 && self.target > 0 {
            empty * w * w / self.area * self.target as f64
        } else {
            empty
        };
        empty + self.miss(tiles) as f64
    }

    /// [`Asked::shortfall`] of a plan (its largest part left empty as measured).
    pub(crate) fn plan_shortfall(&self, p: &Plan) -> f64 {
        self.shortfall(p.tiles, p.tile_size, p.metrics.largest_empty_tiles)
    }

    /// [`Asked::shortfall`] of a plan rejected for the part it leaves empty.
    pub(crate) fn rejected_shortfall(&self, r: &Rejected) -> f64 {
        self.shortfall(r.plan.tiles, r.plan.tile_size, r.empty.tiles)
    }

    /// Whether rejected plan `r` falls less short of the asked chain than `kept` (none kept:
    /// yes). Rejected plans rank by this alone.
    pub(crate) fn before(&self, r: &Rejected, kept: Option<&Rejected>) -> bool {
        kept.is_none_or(|k| self.rejected_shortfall(r) < self.rejected_shortfall(k))
    }

    /// Whether rejected plan `r` is returned in place of `best`, a plan that passed the
    /// empty-part check but misses the asked count: when it holds the count more nearly
    /// and falls less short of the asked chain. A plan within the tolerance is never
    /// replaced.
    pub(crate) fn prefers_rejected(&self, r: &Rejected, best: &Plan) -> bool {
        let m = self.miss(best.tiles);
        m > 0
            && self.miss(r.plan.tiles) < m
            && self.rejected_shortfall(r) < self.plan_shortfall(best)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn asked(tiles: usize) -> Asked {
        Asked::new(&PlanOptions::default().with_tiles(tiles), 10_000.0, 0)
    }

    /// A plan of few wide tiles leaving few of its own tile areas empty falls shorter than
    /// one within the count leaving more: its empty part is larger in tiles of the asked
    /// chain, and its count misses.
    #[test]
    fn few_wide_tiles_fall_short_of_the_asked_chain() {
        let a = asked(100);
        // 13 tiles of width 20 (400 units^2 a tile area), 45 tile areas empty: 180 tiles
        // of the asked chain empty, 84 missing beyond the 3 of the tolerance
        let far = a.shortfall(13, 20.0, 45.0);
        assert!((far - (180.0 + 84.0)).abs() < 1e-9, "{far}");
        // 100 tiles of width 8 (64 units^2), 60 tile areas empty: 38.4 tiles
        let near = a.shortfall(100, 8.0, 60.0);
        assert!((near - 38.4).abs() < 1e-9, "{near}");
        assert!(near < far);
        // within the tolerance no count misses
        assert_eq!(a.miss(97), 0);
        assert_eq!(a.miss(103), 0);
        assert_eq!(a.miss(96), 1);
    }

    /// A width asked: counts never miss, and empty parts compare by their area.
    #[test]
    fn with_a_width_asked_only_the_empty_part_counts() {
        let opts = PlanOptions {
            tile_size: Some(5.0),
            ..PlanOptions::default()
        };
        let a = Asked::new(&opts, 10_000.0, 283);
        assert_eq!(a.miss(10), 0);
        assert!(a.shortfall(10, 5.0, 3.0) < a.shortfall(500, 5.0, 4.0));
    }
}
