//! Whether a tile fits anywhere in a shape (issue 26: a drawing is refused only when one
//! chain cannot do it: separate parts, or no part wide enough for a tile). A tile of width
//! w fits around a point at least w/2 inside the outline: the test of the caps' raster and
//! of the empty-part measure ([`crate::empty::DeepLine`]: the chords of a disc of radius
//! w/2 on five lines across it lie inside the shape), here made exact along each line (the
//! deep points of a line are an intersection of intervals, not samples) and run on lines a
//! quarter tile apart. A drawing no tile fits in is refused at once, with the tile count (or
//! width) at which one does, instead of searching widths at which every row sticks out.

use crate::empty::EDGE;
use crate::shape::Shape;

/// Lines scanned per tile width.
const LINES_PER_TILE: f64 = 4.0;
/// At most this many lines are scanned (a shape many thousand tiles tall is scanned more
/// coarsely; the answer then errs towards "fits", the planner's own search deciding).
const MAX_LINES: usize = 200_000;

/// The sorted, disjoint intervals common to `a` and `b` (each sorted and disjoint).
fn intersect(a: &[(f64, f64)], b: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let (mut i, mut j) = (0, 0);
    let mut out = Vec::new();
    while i < a.len() && j < b.len() {
        let (lo, hi) = (a[i].0.max(b[j].0), a[i].1.min(b[j].1));
        if lo <= hi {
            out.push((lo, hi));
        }
        if a[i].1 < b[j].1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    out
}

/// True if some point on the line at height `y` of `work` (tile widths) lies at least
/// [`EDGE`] inside the outline: for each of five chords of the disc of radius [`EDGE`]
/// about it (at heights `y + f EDGE`, half width `EDGE sqrt(1 - f^2)`), the point's
/// abscissa lies in an interval of the shape shrunk by the chord's half width.
fn deep_on_line(work: &Shape, y: f64) -> bool {
    let mut deep: Option<Vec<(f64, f64)>> = None;
    for f in [0.0f64, -1.0, 1.0, -0.5, 0.5] {
        let hw = EDGE * (1.0 - f * f).sqrt();
        let shrunk: Vec<(f64, f64)> = work
            .intervals_at(y + f * EDGE)
            .into_iter()
            .filter_map(|(a, e)| (a + hw <= e - hw).then_some((a + hw, e - hw)))
            .collect();
        let now = match deep {
            None => shrunk,
            Some(d) => intersect(&d, &shrunk),
        };
        if now.is_empty() {
            return false;
        }
        deep = Some(now);
    }
    true
}

/// True if a tile of width 1 fits somewhere in `work` (a shape scaled to tile widths): a
/// point at least half a tile inside its outline, looked for on lines a quarter tile apart
/// (at most [`MAX_LINES`] lines).
pub(crate) fn fits_a_tile(work: &Shape) -> bool {
    let b = work.bbox();
    let h = b.height() - 2.0 * EDGE;
    if !(h >= 0.0 && b.width() >= 2.0 * EDGE) {
        return false;
    }
    let n = ((h * LINES_PER_TILE).ceil() as usize).clamp(1, MAX_LINES);
    let step = h / n as f64;
    (0..=n).any(|k| deep_on_line(work, b.y0 + EDGE + k as f64 * step))
}

/// The tile widths tried for a shape no tile of width `w` fits in: `w` divided by sqrt2 at
/// each step (twice the tiles), at most this many steps (2^24 times the tiles).
const HALVINGS: u32 = 48;

/// The first width of `w / sqrt2^k` (k = 1, 2, ..., [`HALVINGS`]) at which a tile fits in
/// `shape`, with its `k`; `None` when none does (the width falls below `min_w` first).
pub(crate) fn fitting_width(shape: &Shape, w: f64, min_w: f64) -> Option<(u32, f64)> {
    (1..=HALVINGS)
        .map(|k| (k, w / std::f64::consts::SQRT_2.powi(k as i32)))
        .take_while(|&(_, v)| v >= min_w)
        .find(|&(_, v)| fits_a_tile(&shape.scaled(1.0 / v)))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    fn rect(w: f64, h: f64) -> Shape {
        Shape::from_rings(vec![Ring::rect(0.0, 0.0, w, h)])
    }

    /// A strip fits a tile when it is at least a tile wide, whichever way it lies.
    #[test]
    fn a_strip_fits_a_tile_when_a_tile_wide() {
        for (w, h) in [(40.0, 1.02), (1.02, 40.0), (3.0, 3.0)] {
            assert!(fits_a_tile(&rect(w, h)), "{w} x {h}");
        }
        for (w, h) in [(40.0, 0.9), (0.9, 40.0), (0.5, 0.5), (1000.0, 0.01)] {
            assert!(!fits_a_tile(&rect(w, h)), "{w} x {h}");
        }
    }

    /// A thin strip with one round bulge a tile fits in; a ring whose band is thinner than a
    /// tile (the deep points of a line are found between its two crossings).
    #[test]
    fn a_bulge_fits_and_a_thin_ring_does_not() {
        let circle = |r: f64, ccw: bool| {
            let mut pts: Vec<kurbo::Point> = (0..256)
                .map(|i| {
                    let t = i as f64 / 256.0 * std::f64::consts::TAU;
                    kurbo::Point::new(20.0 + r * t.cos(), 20.0 + r * t.sin())
                })
                .collect();
            if !ccw {
                pts.reverse();
            }
            Ring { points: pts }
        };
        let thin_ring = Shape::from_rings(vec![circle(10.0, true), circle(9.2, false)]);
        assert!(!fits_a_tile(&thin_ring));
        let wide_ring = Shape::from_rings(vec![circle(10.0, true), circle(8.8, false)]);
        assert!(fits_a_tile(&wide_ring));
        let bulge = Shape::from_rings(vec![Ring::rect(0.0, 19.8, 40.0, 20.2), circle(0.7, true)]);
        assert!(fits_a_tile(&bulge));
    }

    /// The fitting width halves the tile area until a tile fits; none below the least width.
    #[test]
    fn the_fitting_width_is_found_by_halving_the_tile_area() {
        let strip = rect(100.0, 0.6);
        let (k, v) = fitting_width(&strip, 2.0, 1e-3).unwrap();
        assert_eq!(k, 4, "{v}");
        assert!((v - 0.5).abs() < 1e-12, "{v}");
        assert_eq!(fitting_width(&strip, 2.0, 0.6), None);
    }
}
