//! The cell planner's search budget and its memo of routed widths.
//!
//! Routing one width costs about (route searches) x (cells x beam x joins) row programmes of
//! the cell's size, each O(tiles), and a fold check of the route so far, also O(tiles): the
//! work per route search grows linearly with the tile count, and the size search may route a
//! score of widths when every route leaves a part of the shape empty. Two bounds keep the
//! whole linear in the tiles with a small constant, never exponential, and deterministic
//! (counted in units of work, never in time):
//! - [`route_searches`]: route searches (decomposition x cell order) per axis and width, at
//!   most [`ROUTE_SEARCH_TILES`] over the tile count times the axes: small chains search
//!   every decomposition and order as before, long ones only the first (the pinwheels
//!   first, then the fewest merged branches), so a route may fit a little worse;
//! - [`CELL_WORK_BUDGET`]: once the widths routed for one turn style have spent that many
//!   units ([`crate::check::CheckMemo::spend`]), no further width is routed; the best plan
//!   found so far is kept, and a shape with none says that the budget ran out.
//!
//! Both passes of the cell planner (the second retries widths around rejected ones) share a
//! [`CellSearch`], so a width is routed once.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use crate::route::Routed;

/// Reasons why axes gave no route (each an axis's message), each with the axes it holds
/// for (SVG degrees).
pub(crate) type Reasons = Vec<(String, Vec<String>)>;

/// Route searches per width (over all axes) times the tile count: 96 searches per axis (8
/// decompositions x 12 orders, the most any shape gets) up to 625 tiles with two axes and
/// 208 with six (a letter O), 30 at 2000 tiles with two axes. A route search's work grows
/// with the tiles, so this keeps a width's work about constant beyond.
pub(crate) const ROUTE_SEARCH_TILES: usize = 120_000;

/// The fewest route searches per axis and width.
const MIN_ROUTE_SEARCHES: usize = 2;

/// Units of work (lattice tiles priced by row programmes plus folds checked, see
/// [`crate::check::CheckMemo::spend`]) after which no further width is routed for one turn
/// style: the dozen widths a frame of 200 tiles routes (about 1e7 units each), or some 30
/// to 60 seconds of one core (about 3e6 units a second) at worst, whatever the tiles. A
/// shape whose every route leaves a part empty (two holes from 300 tiles) spends all of
/// it and says so.
pub(crate) const CELL_WORK_BUDGET: u64 = 120_000_000;

/// The route searches per axis, over `axes` axes, at a width where a serpentine holds about
/// `tiles` tiles.
pub(crate) fn route_searches(tiles: usize, axes: usize) -> usize {
    (ROUTE_SEARCH_TILES / (tiles.max(1) * axes.max(1))).max(MIN_ROUTE_SEARCHES)
}

/// The routes of one width: with their axis, cheapest first, why the other axes gave none,
/// and the work they cost.
pub(crate) struct RoutedWidth {
    pub routes: Vec<(f64, Arc<Routed>)>,
    pub why: Reasons,
    pub work: u64,
}

/// The state of one turn style's cell search: the widths routed so far (by the bits of the
/// width) and the work spent.
#[derive(Default)]
pub(crate) struct CellSearch {
    widths: Mutex<HashMap<u64, Arc<RoutedWidth>>>,
    /// Work spent, and the most one width cost.
    spent: Mutex<(u64, u64)>,
}

impl CellSearch {
    /// The routes at width `w`: remembered, or made by `route` if the budget allows (else
    /// `None`).
    pub(crate) fn routes_at(
        &self,
        w: f64,
        route: impl FnOnce() -> RoutedWidth,
    ) -> Option<Arc<RoutedWidth>> {
        let known = self
            .widths
            .lock()
            .ok()
            .and_then(|m| m.get(&w.to_bits()).cloned());
        if known.is_some() {
            return known;
        }
        if self.exhausted() {
            return None;
        }
        let r = Arc::new(route());
        if let Ok(mut s) = self.spent.lock() {
            s.0 += r.work;
            s.1 = s.1.max(r.work);
        }
        if let Ok(mut m) = self.widths.lock() {
            m.insert(w.to_bits(), Arc::clone(&r));
        }
        Some(r)
    }

    /// The units of work spent so far.
    pub(crate) fn spent(&self) -> u64 {
        self.spent.lock().map_or(0, |s| s.0)
    }

    /// True once the budget stops further widths: another width as costly as the costliest
    /// so far would overrun it.
    pub(crate) fn exhausted(&self) -> bool {
        self.spent
            .lock()
            .map_or(true, |s| s.0 > 0 && s.0 + s.1 > CELL_WORK_BUDGET)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn width(work: u64) -> RoutedWidth {
        RoutedWidth {
            routes: Vec::new(),
            why: Vec::new(),
            work,
        }
    }

    /// New widths are routed while another as costly as the costliest so far fits in the
    /// budget; a width routed before is answered from memory whatever the budget.
    #[test]
    fn budget_stops_new_widths_not_known_ones() {
        let s = CellSearch::default();
        assert!(s.routes_at(1.0, || width(CELL_WORK_BUDGET / 2)).is_some());
        assert!(!s.exhausted());
        assert!(s.routes_at(2.0, || width(CELL_WORK_BUDGET / 4)).is_some());
        assert!(s.exhausted());
        let mut routed = false;
        assert!(s
            .routes_at(3.0, || {
                routed = true;
                width(1)
            })
            .is_none());
        assert!(!routed);
        let known = s.routes_at(1.0, || width(0)).unwrap();
        assert_eq!(known.work, CELL_WORK_BUDGET / 2);
        assert_eq!(s.spent(), CELL_WORK_BUDGET / 2 + CELL_WORK_BUDGET / 4);
    }

    /// The searches per axis fall with the tiles, so their product stays bounded.
    #[test]
    fn route_searches_times_tiles_is_bounded() {
        assert!(route_searches(600, 2) >= 96);
        assert!(route_searches(200, 6) >= 96);
        for axes in [1, 2, 6] {
            for n in [100, 300, 1000, 2000, 5000, 20_000] {
                let r = route_searches(n, axes);
                assert!(r >= MIN_ROUTE_SEARCHES);
                assert!(
                    r * n * axes <= ROUTE_SEARCH_TILES.max(MIN_ROUTE_SEARCHES * n * axes),
                    "{r} at {n} over {axes} axes"
                );
            }
        }
    }
}
