//! Outline simplification. Every ring is first cleaned ([`clean`]): repeated points,
//! zero-width spikes (an outline that runs out and back along one line, as font outlines
//! and boolean operations leave them; invisible when drawn) and slivers narrower than
//! [`SLIVER`] of the drawing are removed, so that they are not taken for self-intersections.
//! A ring with many more points than the planner can resolve (a drawing program may write a
//! circle as a million points) is then thinned by Douglas-Peucker to the flattening
//! tolerance ([`crate::FLATTEN_TOLERANCE`]), so that the cost of planning depends on the
//! shape, not on how many points describe it. Every dropped point lies within the tolerance
//! of the simplified outline.

use kurbo::Point;

use crate::shape::{FilledPath, Ring};

/// Rings with more points than this are simplified; smaller ones are kept as they are (a
/// flattened curve already has about as many points as its tolerance needs).
pub(crate) const SIMPLIFY_ABOVE: usize = 256;

/// The most outline points (all rings together) the planner plans from: eight times the
/// most any drawing of the corpus keeps (Italy's 503 on 2026-11-28). The planner's work
/// grows faster than the points (an outline of 4,000 points of detail it cannot thin plans
/// at 300 tiles in about 0.6 s of CPU, 12,000 in 3.6 s, 50,000 in over a minute and 200,000
/// took 5 GB of memory), so a drawing of more is thinned further, by [`thin_to_budget`].
pub(crate) const OUTLINE_BUDGET: usize = 5_000;

/// The coarsest tolerance [`thin_to_budget`] thins to, as a share of the drawing's larger
/// side: ten times the flattening tolerance, a tenth of a tile at 100 tiles and about two
/// thirds of one at 3,000 tiles of a square drawing. A drawing still over the budget at this
/// tolerance is refused (`PlanError::TooDetailed`).
pub(crate) const THIN_AT_MOST: f64 = 1e-2;

/// Width below which a corner is a spike or sliver, as a share of the drawing's larger side:
/// a vertex whose triangle with its two neighbours is narrower than this (its least
/// height) is removed. 1e-6 is about 16 steps of the `f32` coordinates usvg computes in,
/// and under 1/700 of a tile even at the planner's largest tile count (2,000,000 tiles of a
/// square drawing are about 1/1400 of its side wide), so no visible feature is touched.
pub(crate) const SLIVER: f64 = 1e-6;

/// The ring without repeated points, zero-width spikes and slivers narrower than `eps`
/// (drawing units): a point within `eps` of the one before it is dropped, and so is a vertex
/// where the outline turns back (its edges run out and back along one line, the triangle
/// they make no higher than `eps`). Points on a straight run are kept: the ring's geometry
/// changes only where it had no width. Returns fewer than three points when nothing with
/// area is left.
pub(crate) fn clean(ring: &Ring, eps: f64) -> Ring {
    let mut pts: Vec<Point> = Vec::with_capacity(ring.points.len());
    for &p in &ring.points {
        if pts.last().is_none_or(|&q| (p - q).hypot() > eps) {
            pts.push(p);
        }
    }
    // the vertex b between a and c turns back along the line it came (or the three points
    // lie within eps of each other)
    let spike = |a: Point, b: Point, c: Point| {
        let longest = (b - a).hypot().max((c - b).hypot()).max((c - a).hypot());
        longest <= eps || ((b - a).dot(c - b) < 0.0 && (b - a).cross(c - a).abs() <= eps * longest)
    };
    loop {
        // a stack walk: a vertex is tested against the last one kept and the next one, and
        // a removal re-tests the one kept before it, so a spike of several points folds away
        let n = pts.len();
        if n < 3 {
            break;
        }
        let mut kept: Vec<Point> = Vec::with_capacity(n);
        for i in 0..n {
            let b = pts[i];
            while kept.len() >= 2 && spike(kept[kept.len() - 2], kept[kept.len() - 1], b) {
                kept.pop();
            }
            let c = pts[(i + 1) % n];
            match kept.last() {
                Some(&a) if spike(a, b, c) || (b - a).hypot() <= eps => {}
                _ => kept.push(b),
            }
        }
        // the joint where the ring closes
        while kept.len() >= 3 && spike(kept[kept.len() - 1], kept[0], kept[1]) {
            kept.remove(0);
        }
        while kept.len() >= 3 && {
            let m = kept.len();
            spike(kept[m - 2], kept[m - 1], kept[0]) || (kept[m - 1] - kept[0]).hypot() <= eps
        } {
            kept.pop();
        }
        let done = kept.len() == n;
        pts = kept;
        if done {
            break;
        }
    }
    Ring { points: pts }
}

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

/// Distance evaluations [`mark`] spends per point of its polyline, at least
/// [`DP_WORK_FLOOR`], splitting at the farthest point (Douglas-Peucker); beyond, a split at a
/// farthest point outside the middle half of its span is made at the middle instead. Plain
/// Douglas-Peucker is quadratic where every split peels off a point or two (a zigzag
/// coarser than the tolerance: 1.3 million points took over 60 s of CPU); with the middle
/// splits every level of the recursion costs at most the points and there are at most
/// `log_{4/3} n` levels, so the work is O(n log n). A smooth outline (a circle of a million
/// points: about 20 evaluations a point) never reaches the budget, so it thins as before.
const DP_WORK_PER_POINT: usize = 64;
/// The least budget of distance evaluations [`mark`] has before it balances its splits: a
/// drawing's outline of a few thousand points is thinned by plain Douglas-Peucker.
const DP_WORK_FLOOR: usize = 1_000_000;

/// The points of the open polyline `pts` that Douglas-Peucker keeps at tolerance `tol`
/// (the ends always), marked in `keep`; iterative, so a million points need no deep stack.
/// Every point not kept lies within `tol` of the segment between the kept points around it.
/// The work is bounded (see [`DP_WORK_PER_POINT`]); returns the distance evaluations spent.
fn mark(pts: &[Point], tol: f64, keep: &mut [bool]) -> usize {
    let n = pts.len();
    if n < 2 {
        return 0;
    }
    keep[0] = true;
    keep[n - 1] = true;
    let budget = DP_WORK_PER_POINT.saturating_mul(n).max(DP_WORK_FLOOR);
    let mut work = 0usize;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        let (mut far, mut at) = (0.0, i);
        for (k, &p) in pts.iter().enumerate().take(j).skip(i + 1) {
            let d = distance_to_segment(p, pts[i], pts[j]);
            if d > far {
                (far, at) = (d, k);
            }
        }
        work += j - i - 1;
        if far > tol {
            // past the budget, a split near an end (a quarter of the span or less) is
            // made in the middle: each part then has at most three quarters of the points
            let quarter = (j - i) / 4;
            if work > budget && (at < i + quarter || at > j - quarter) {
                at = i + (j - i) / 2;
            }
            keep[at] = true;
            stack.push((i, at));
            stack.push((at, j));
        }
    }
    work
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

/// Thins the rings of `paths` while they hold more than `budget` points together: each
/// round doubles the tolerance (from `tol` up to `max_tol`, drawing units) and simplifies
/// every ring of more than [`SIMPLIFY_ABOVE`] points; a thinned ring that `crosses` itself
/// (thinning may bring two close edges across each other) keeps its points. Returns the
/// points left. Drawings within the budget are not touched.
pub(crate) fn thin_to_budget(
    paths: &mut [FilledPath],
    tol: f64,
    max_tol: f64,
    budget: usize,
    crosses: impl Fn(&Ring) -> bool,
) -> usize {
    let total = |paths: &[FilledPath]| -> usize {
        paths
            .iter()
            .flat_map(|p| p.rings.iter())
            .map(|r| r.points.len())
            .sum()
    };
    let mut tol = tol;
    while total(paths) > budget && tol < max_tol {
        tol = (2.0 * tol).min(max_tol);
        for ring in paths.iter_mut().flat_map(|p| p.rings.iter_mut()) {
            if ring.points.len() > SIMPLIFY_ABOVE {
                let thin = simplify(ring, tol);
                if thin.points.len() >= 3 && !crosses(&thin) {
                    *ring = thin;
                }
            }
        }
    }
    total(paths)
}

/// The ring simplified to tolerance `tol`, and while it keeps more than `budget` points, to
/// twice that tolerance, up to `max_tol` (each time from the full ring): a ring of more
/// detail than the planner can use is thinned before anything else looks at its points.
pub(crate) fn thin_ring(ring: &Ring, tol: f64, max_tol: f64, budget: usize) -> Ring {
    let mut thin = simplify(ring, tol);
    let mut tol = tol;
    while thin.points.len() > budget && tol < max_tol {
        tol = (2.0 * tol).min(max_tol);
        thin = simplify(ring, tol);
    }
    thin
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn ring(pts: &[(f64, f64)]) -> Ring {
        Ring {
            points: pts.iter().map(|&(x, y)| Point::new(x, y)).collect(),
        }
    }

    /// A square with a zero-width spike on its top (out to y = 15 and back along the same
    /// line) and a repeated point: the square is what is left, with the point on its
    /// straight side kept.
    #[test]
    fn spikes_and_repeats_are_removed() {
        let r = ring(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 0.0),
            (10.0, 5.0),
            (10.0, 10.0),
            (5.0, 10.0),
            (5.0, 15.0),
            (5.0, 10.0),
            (0.0, 10.0),
        ]);
        let c = clean(&r, 1e-9);
        assert_eq!(
            c,
            ring(&[
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 5.0),
                (10.0, 10.0),
                (5.0, 10.0),
                (0.0, 10.0)
            ]),
            "{c:?}"
        );
    }

    /// A spike whose return misses its way out by less than the width (a sliver), and one
    /// of two points out and back: both go; a corner wider than the width stays.
    #[test]
    fn slivers_go_and_corners_stay() {
        let r = ring(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 10.0),
            (6.0, 10.0),
            (6.0, 14.0),
            (6.0, 18.0),
            (6.0 + 1e-7, 10.0),
            (2.0, 10.0),
            (0.0, 10.0),
        ]);
        let c = clean(&r, 1e-6);
        assert!(c.points.iter().all(|p| p.y <= 10.0), "{c:?}");
        assert!((c.signed_area() - 100.0).abs() < 1e-5);
        let notch = ring(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 10.0),
            (5.0, 9.0),
            (0.0, 10.0),
        ]);
        assert_eq!(clean(&notch, 1e-6), notch);
    }

    /// A ring that is all spike (a line out and back) has nothing left; a spike at the
    /// joint where the ring closes goes too.
    #[test]
    fn a_ring_without_area_is_emptied() {
        let r = ring(&[(0.0, 0.0), (5.0, 0.0), (10.0, 0.0), (5.0, 0.0)]);
        assert!(clean(&r, 1e-9).points.len() < 3);
        let r = ring(&[
            (0.0, 5.0),
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 10.0),
            (0.0, 10.0),
            (0.0, 20.0),
        ]);
        let c = clean(&r, 1e-9);
        assert!(c.points.iter().all(|p| p.y <= 10.0), "{c:?}");
        assert!((c.signed_area() - 100.0).abs() < 1e-9, "{c:?}");
    }

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

    /// A disc of radius 40 whose outline zigzags out to `40 + amp` at every other one of its
    /// `n` points, as an open polyline from angle 0 to half a turn.
    fn zigzag_arc(n: usize, amp: f64) -> Vec<Point> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::PI * k as f64 / n as f64;
                let r = 40.0 + amp * (k % 2) as f64;
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    /// Douglas-Peucker's worst case, a zigzag coarser than the tolerance (plain
    /// Douglas-Peucker peels off a few points a split: 845 million distance evaluations for
    /// these 200,000 points, 4,200 a point; 1.3 million points took over 60 s), is thinned
    /// with work bounded by O(n log n) evaluations, and every point dropped still lies
    /// within the tolerance of the segment between the points kept around it.
    #[test]
    fn a_zigzag_thins_with_bounded_work() {
        let n = 200_000;
        let pts = zigzag_arc(n, 0.5);
        let mut keep = vec![false; n];
        let work = mark(&pts, 0.1, &mut keep);
        let levels = (n as f64).ln() / (4.0f64 / 3.0).ln();
        let bound = (DP_WORK_PER_POINT as f64 + levels.ceil()) * n as f64;
        assert!(work as f64 <= bound, "{work} evaluations, bound {bound}");
        let kept: Vec<usize> = (0..n).filter(|&i| keep[i]).collect();
        for w in kept.windows(2) {
            for k in w[0] + 1..w[1] {
                let d = distance_to_segment(pts[k], pts[w[0]], pts[w[1]]);
                assert!(d <= 0.1, "point {k} is {d} from its segment");
            }
        }
        // coarser than the zigzag: a few dozen points, at less work
        let mut coarse = vec![false; n];
        let light = mark(&pts, 1.0, &mut coarse);
        assert!(coarse.iter().filter(|&&k| k).count() < 200);
        assert!(light <= 40 * n, "{light}");
    }
}
