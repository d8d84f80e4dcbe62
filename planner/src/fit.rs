//! The fit measures of a plan (see [`Metrics`]): how much of the shape the tiles cover and
//! how much of the chain lies outside it, as exact areas ([`crate::coverage`]).

use kurbo::Point;

use crate::coverage::areas;
use crate::plan::{Metrics, Plan};
use crate::rows::{tile_area, Style};
use crate::shape::Shape;

/// The fit measures of tiles centred at `centres` over `work` (both in the work frame, unit
/// tiles), areas scaled by `w^2` to user units.
pub(crate) fn measure(work: &Shape, centres: &[Point], w: f64) -> Metrics {
    let a = areas(work, centres);
    let share = |part: f64, whole: f64| {
        if whole > 0.0 {
            (part / whole).clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    Metrics {
        covered_share: share(a.covered, a.shape),
        outside_share: share(a.outside, a.tiles),
        shape_area: a.shape * w * w,
        chain_area: centres.len() as f64 * crate::coverage::OCTAGON_AREA * w * w,
        largest_empty_tiles: 0.0,
    }
}

/// The rank of a chain from its row programme cost (see [`crate::rows::solve_rows`]):
/// its estimated fit error (the share of the shape left uncovered plus the share of the
/// chain outside it, [`Metrics::fit_error`]) plus the price of its U-turns as a share of the
/// shape's area. `area` is the shape's area and `cost` the programme's cost, in tile units.
pub(crate) fn estimate(area: f64, tiles: usize, u_turns: usize, cost: f64, style: Style) -> f64 {
    let a = tile_area();
    let k = style.outside_weight();
    let price = style.turn_price * u_turns as f64;
    // cost = sum over tiles of (k (a - covered) - covered) + price
    let covered = (k * tiles as f64 * a - (cost - price)) / (1.0 + k);
    let chain = tiles as f64 * a;
    let uncovered = if area > 0.0 {
        1.0 - covered / area
    } else {
        1.0
    };
    let outside = if chain > 0.0 {
        1.0 - covered / chain
    } else {
        0.0
    };
    uncovered + outside + if area > 0.0 { price / area } else { 0.0 }
}

/// The rank of a finished plan (lower is better): its measured fit error plus its turns
/// (U-turns and quarter turns) priced at `turn_cost` tile areas each, as a share of the
/// shape's area.
pub(crate) fn plan_score(plan: &Plan, turn_cost: f64) -> f64 {
    let area_tiles = plan.metrics.shape_area / (plan.tile_size * plan.tile_size);
    let turns = (plan.u_turns + plan.quarter_turns) as f64;
    plan.metrics.fit_error()
        + if area_tiles > 0.0 {
            turn_cost * turns / area_tiles
        } else {
            0.0
        }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    /// A row of touching tiles along the middle of a strip one tile high: every tile lies
    /// inside (nothing outside), and they cover exactly the octagon's share of the strip
    /// (areas scaled by w^2).
    #[test]
    fn a_row_of_tiles_in_a_strip() {
        let strip = Shape::from_rings(vec![Ring {
            points: vec![
                Point::new(-0.5, -0.5),
                Point::new(19.5, -0.5),
                Point::new(19.5, 0.5),
                Point::new(-0.5, 0.5),
            ],
        }]);
        let centres: Vec<Point> = (0..20).map(|i| Point::new(i as f64, 0.0)).collect();
        let m = measure(&strip, &centres, 2.0);
        let octagon = 2.0 * (std::f64::consts::SQRT_2 - 1.0);
        // exact to the 1e-6 i_overlay's integer grid allows
        assert!(m.outside_share.abs() < 1e-6, "{m:?}");
        assert!((m.covered_share - octagon).abs() < 1e-6, "{m:?}");
        assert!((m.shape_area - 80.0).abs() < 1e-6 * 80.0, "{m:?}");
        assert!((m.chain_area - 80.0 * octagon).abs() < 1e-9, "{m:?}");
    }
}
