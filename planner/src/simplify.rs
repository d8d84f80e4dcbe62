//! Outline simplification: a ring with many more points than the planner can resolve (a
//! drawing program may write a circle as a million points) is thinned by Douglas-Peucker to
//! the flattening tolerance ([`crate::FLATTEN_TOLERANCE`]), so that the cost of planning
//! depends on the shape, not on how many points describe it. Every dropped point lies within
//! the tolerance of the simplified outline.

use kurbo::Point;

use crate::shape::Ring;

/// Rings with more points than this are simplified; smaller ones are kept as they are (a
/// flattened curve already has about as many points as its tolerance needs).
pub(crate) const SIMPLIFY_ABOVE: usize = 256;

/// Distance from `p` to the segment `ab`.
fn distance_to_segment(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.hypot2();
    if len2 <= 0.0 {
        return (p - a).hypot();
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).hypot()
}

/// The points of the open polyline `pts` that Douglas-Peucker keeps at tolerance `tol`
/// (the ends always), marked in `keep`; iterative, so a million points need no deep stack.
fn mark(pts: &[Point], tol: f64, keep: &mut [bool]) {
    let n = pts.len();
    if n < 2 {
        return;
    }
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        let (mut far, mut at) = (0.0, i);
        for (k, &p) in pts.iter().enumerate().take(j).skip(i + 1) {
            let d = distance_to_segment(p, pts[i], pts[j]);
            if d > far {
                (far, at) = (d, k);
            }
        }
        if far > tol {
            keep[at] = true;
            stack.push((i, at));
            stack.push((at, j));
        }
    }
}

/// The ring simplified to tolerance `tol`: split at its first point and the point farthest
/// from it, each half thinned by Douglas-Peucker.
pub(crate) fn simplify(ring: &Ring, tol: f64) -> Ring {
    let pts = &ring.points;
    let n = pts.len();
    if n <= 3 {
        return ring.clone();
    }
    let far = (1..n)
        .max_by(|&a, &b| {
            (pts[a] - pts[0])
                .hypot2()
                .total_cmp(&(pts[b] - pts[0]).hypot2())
        })
        .unwrap_or(n / 2);
    let mut keep = vec![false; n + 1];
    mark(&pts[..=far], tol, &mut keep[..=far]);
    let mut closed: Vec<Point> = pts[far..].to_vec();
    closed.push(pts[0]);
    mark(&closed, tol, &mut keep[far..]);
    let points: Vec<Point> = (0..n).filter(|&i| keep[i]).map(|i| pts[i]).collect();
    if points.len() < 3 {
        return ring.clone();
    }
    Ring { points }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A circle of 100,000 points thinned to 1e-3 of its diameter keeps a few dozen, every
    /// original point within the tolerance of the thinned outline, the area within 0.5%.
    #[test]
    fn a_dense_circle_thins_within_the_tolerance() {
        let n = 100_000;
        let ring = Ring {
            points: (0..n)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / n as f64;
                    Point::new(50.0 * a.cos(), 50.0 * a.sin())
                })
                .collect(),
        };
        let tol = 0.1;
        let s = simplify(&ring, tol);
        assert!(
            s.points.len() > 20 && s.points.len() < 200,
            "{}",
            s.points.len()
        );
        let m = s.points.len();
        for &p in ring.points.iter().step_by(97) {
            let d = (0..m)
                .map(|i| distance_to_segment(p, s.points[i], s.points[(i + 1) % m]))
                .fold(f64::INFINITY, f64::min);
            assert!(d <= tol + 1e-12, "{p:?} is {d} from the outline");
        }
        let rel = (s.signed_area() - ring.signed_area()).abs() / ring.signed_area();
        assert!(rel < 5e-3, "{rel}");
    }
}
