//! The fit measures of a plan (see [`Metrics`]): how much of the shape the tiles cover and
//! how much of the chain lies outside it, estimated on sample points in the work frame.

use std::collections::HashMap;
use std::f64::consts::{FRAC_1_SQRT_2, SQRT_2};

use kurbo::Point;
use rayon::prelude::*;

use crate::centre_grid::CentreGrid;
use crate::plan::{Metrics, Plan};
use crate::rows::{tile_area, Style};
use crate::shape::Shape;

/// Octagon of across-flats width 1 centred at the origin: |x|, |y| <= 1/2 and
/// |x| + |y| <= 1/sqrt2 (its faces are axis-aligned and diagonal at every heading the
/// chain takes).
fn in_octagon(dx: f64, dy: f64) -> bool {
    dx.abs() <= 0.5 && dy.abs() <= 0.5 && dx.abs() + dy.abs() <= FRAC_1_SQRT_2
}

/// The fit measures of tiles centred at `centres` over `work` (both in the work frame, unit
/// tiles), areas scaled by `w^2` to user units.
pub(crate) fn measure(work: &Shape, centres: &[Point], w: f64) -> Metrics {
    let (total, out) = outside_samples(work, centres);
    let (in_shape, covered) = covered_samples(work, centres);
    let share = |part: usize, whole: usize| {
        if whole > 0 {
            part as f64 / whole as f64
        } else {
            0.0
        }
    };
    let oct_area = 2.0 * (SQRT_2 - 1.0);
    Metrics {
        covered_share: share(covered, in_shape),
        outside_share: share(out, total),
        shape_area: work.area() * w * w,
        chain_area: centres.len() as f64 * oct_area * w * w,
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

/// Samples over the tiles: 25 per tile (a 5 x 5 grid over its square, kept where inside the
/// octagon), and how many of them lie outside the shape.
fn outside_samples(work: &Shape, centres: &[Point]) -> (usize, usize) {
    let offs = [-0.4, -0.2, 0.0, 0.2, 0.4];
    // chunks of consecutive tiles share rows, so each chunk caches the lines it asks for
    centres
        .par_chunks(4096)
        .map(|chunk| {
            let mut cache: HashMap<i64, Vec<(f64, f64)>> = HashMap::new();
            let (mut total, mut out) = (0usize, 0usize);
            for c in chunk {
                for dy in offs {
                    let yy = c.y + dy;
                    let key = (yy * 1e7).round() as i64;
                    let iv = cache.entry(key).or_insert_with(|| work.intervals_at(yy));
                    for dx in offs {
                        if in_octagon(dx, dy) {
                            total += 1;
                            let xx = c.x + dx;
                            if !iv.iter().any(|&(a, b)| a <= xx && xx <= b) {
                                out += 1;
                            }
                        }
                    }
                }
            }
            (total, out)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// Samples over the shape: a square grid of about 250,000 points over its bounding box,
/// kept where inside it, and how many of them some tile covers.
fn covered_samples(work: &Shape, centres: &[Point]) -> (usize, usize) {
    let grid = CentreGrid::new(centres);
    let b = work.bbox();
    let step = (b.width() * b.height() / 250_000.0).sqrt().max(1e-9);
    let lines = (b.height() / step - 0.5).ceil().max(0.0) as usize;
    (0..lines)
        .into_par_iter()
        .map(|i| {
            let y = b.y0 + (i as f64 + 0.5) * step;
            let (mut in_shape, mut covered) = (0usize, 0usize);
            for (a, e) in work.intervals_at(y) {
                let mut x = b.x0 + ((a - b.x0) / step).ceil() * step + 0.5 * step;
                while x <= e {
                    in_shape += 1;
                    let p = Point::new(x, y);
                    if grid.any_near(p, |t| in_octagon(x - centres[t].x, y - centres[t].y)) {
                        covered += 1;
                    }
                    x += step;
                }
            }
            (in_shape, covered)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    /// A row of touching tiles along the middle of a strip one tile high: every tile lies
    /// inside (nothing outside), and they cover the octagon's share of the strip.
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
        assert_eq!(m.outside_share, 0.0);
        let octagon = 2.0 * (SQRT_2 - 1.0);
        assert!((m.covered_share - octagon).abs() < 0.01, "{m:?}");
        assert!((m.shape_area - 80.0).abs() < 1e-9 && (m.chain_area - 80.0 * octagon).abs() < 1e-9);
    }
}
