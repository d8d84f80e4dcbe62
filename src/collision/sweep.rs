//! Exact first contact of an octagon turning about a fixed point with a static one.
//!
//! Two convex polygons that are disjoint at the start of a rotation can only come to overlap
//! after their boundaries meet, and boundaries first meet with a vertex of one on an edge of
//! the other. A vertex turning about the pivot follows a circular arc, so the first contact
//! is the smallest angle at which one of these arcs crosses an edge: a quadratic per
//! (vertex, edge) pair, solved in closed form. No sampling: a graze between two samples cannot
//! be missed. Vertices of the static polygon are followed in the moving polygon's frame (the
//! same arcs turned the other way).
//!
//! Points and vectors are [`kurbo`]'s; every product and sum is the one the closed form
//! needs, in the same order, so the answers are exact up to the rounding of those operations.

use kurbo::{Point, Rect, Vec2};

/// The points (relative to `pivot`) where the circle about `pivot` through `v` crosses the
/// segment `a`-`b`: none, one or two, from the quadratic in the segment parameter.
#[inline]
fn circle_crossings(v: Point, pivot: Point, a: Point, b: Point) -> [Option<Vec2>; 2] {
    let r2 = (v - pivot).hypot2();
    let d = b - a;
    let ac = a - pivot;
    let qa = d.hypot2();
    if qa == 0.0 {
        return [None, None];
    }
    let qb = 2.0 * d.dot(ac);
    let qc = ac.hypot2() - r2;
    let disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        return [None, None];
    }
    // numerically stable roots
    let q = -0.5 * (qb + qb.signum() * disc.sqrt());
    let (t1, t2) = if q != 0.0 {
        (q / qa, qc / q)
    } else {
        (-qb / (2.0 * qa), -qb / (2.0 * qa))
    };
    [t1, t2].map(|t| (0.0..=1.0).contains(&t).then_some(ac + t * d))
}

/// The smallest angle in `(0, |theta|]`, turning the way `theta`'s sign says (positive =
/// counter-clockwise), at which `v`, turning about `pivot`, lies on the segment `a`-`b`.
#[inline]
fn arc_hits_segment(v: Point, pivot: Point, theta: f64, a: Point, b: Point) -> Option<f64> {
    let pv = v - pivot;
    let mut best: Option<f64> = None;
    for x in circle_crossings(v, pivot, a, b).into_iter().flatten() {
        let mut phi = pv.cross(x).atan2(pv.dot(x));
        if theta >= 0.0 {
            if phi < 0.0 {
                phi += std::f64::consts::TAU;
            }
        } else {
            if phi > 0.0 {
                phi -= std::f64::consts::TAU;
            }
            phi = -phi;
        }
        if phi <= theta.abs() && best.is_none_or(|b| phi < b) {
            best = Some(phi);
        }
    }
    best
}

/// Whether `v`, turning a quarter turn about `pivot` (counter-clockwise when `left`), lies
/// on the segment `a`-`b` at some moment: [`arc_hits_segment`] with `theta = +-pi/2`, without
/// computing the angle (a crossing point is within the quarter turn exactly when it is on the
/// turning side of the start direction and not behind the pivot).
#[inline]
fn quarter_arc_hits_segment(v: Point, pivot: Point, left: bool, a: Point, b: Point) -> bool {
    let pv = v - pivot;
    circle_crossings(v, pivot, a, b)
        .into_iter()
        .flatten()
        .any(|x| {
            let c = pv.cross(x);
            pv.dot(x) >= 0.0 && if left { c >= 0.0 } else { c <= 0.0 }
        })
}

/// Two octagons (vertices counter-clockwise), each within `r` of its centre: `moving` turns
/// about `pivot`, `fixed` stays. Its sweep tests skip the vertices whose arc stays outside
/// the annulus about `pivot` that holds the other octagon, which leaves their results
/// unchanged and saves most of the work.
#[derive(Clone, Copy)]
pub(crate) struct TurningPair<'a> {
    moving: &'a [Point; 8],
    moving_centre: Point,
    fixed: &'a [Point; 8],
    fixed_centre: Point,
    r: f64,
    pivot: Point,
}

impl<'a> TurningPair<'a> {
    /// `moving` (centred at `moving_centre`) turning about `pivot` against `fixed` (centred
    /// at `fixed_centre`), both within `r` of their centres.
    pub(crate) fn new(
        moving: &'a [Point; 8],
        moving_centre: Point,
        fixed: &'a [Point; 8],
        fixed_centre: Point,
        r: f64,
        pivot: Point,
    ) -> TurningPair<'a> {
        TurningPair {
            moving,
            moving_centre,
            fixed,
            fixed_centre,
            r,
            pivot,
        }
    }

    /// Calls `hit(vertex, edge start, edge end, turns_forward)` for every (vertex, edge)
    /// pair whose vertex arc can reach the other octagon's annulus about the pivot;
    /// `turns_forward` is true for the moving octagon's vertices (the fixed octagon's turn
    /// the other way in the moving frame). Stops when `hit` returns true.
    fn for_each_reachable(&self, mut hit: impl FnMut(Point, Point, Point, bool) -> bool) {
        let (pivot, r) = (self.pivot, self.r);
        let ring = |c: Point| {
            let d = (c - pivot).hypot2().sqrt();
            let lo = (d - r).max(0.0);
            (lo * lo * (1.0 - 1e-12), (d + r) * (d + r) * (1.0 + 1e-12))
        };
        let sides = [
            (self.moving, self.fixed, ring(self.fixed_centre), true),
            (self.fixed, self.moving, ring(self.moving_centre), false),
        ];
        for (verts, edges, (lo, hi), forward) in sides {
            for &v in verts {
                let rho = (v - pivot).hypot2();
                if rho < lo || rho > hi {
                    continue;
                }
                for e in 0..8 {
                    if hit(v, edges[e], edges[(e + 1) % 8], forward) {
                        return;
                    }
                }
            }
        }
    }

    /// Whether the two meet while `moving` turns a quarter turn (counter-clockwise when
    /// `left`), assuming they are apart at the start: the yes/no form of
    /// [`TurningPair::first_contact`] for full folds.
    pub(crate) fn quarter_contact(&self, left: bool) -> bool {
        let mut found = false;
        self.for_each_reachable(|v, p, q, fwd| {
            found = quarter_arc_hits_segment(v, self.pivot, left == fwd, p, q);
            found
        });
        found
    }

    /// The first angle (absolute, radians) in `(0, |theta|]` at which `moving`, turned by up
    /// to `theta` (signed, positive = counter-clockwise), touches `fixed`, assuming the two
    /// are disjoint at the start; `None` when they never meet.
    pub(crate) fn first_contact(&self, theta: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        self.for_each_reachable(|v, p, q, fwd| {
            let turn = if fwd { theta } else { -theta };
            if let Some(phi) = arc_hits_segment(v, self.pivot, turn, p, q) {
                if best.is_none_or(|b| phi < b) {
                    best = Some(phi);
                }
            }
            false
        });
        best
    }
}

/// Where to look for the placed tiles a straight tail may meet while its joint turns by
/// `theta` about `pivot`: the box of the sector its centres sweep (from `first`, the tail's
/// first centre, to `last`, its last and farthest one), inflated by two circumradii `r`
/// (a placed centre farther from every swept centre cannot touch).
pub(crate) fn swept_query(pivot: Point, first: Point, last: Point, theta: f64, r: f64) -> Rect {
    let base = (last - pivot).atan2();
    let mut a_first = (first - pivot).atan2();
    // keep the two angles on the same branch
    while a_first - base > std::f64::consts::PI {
        a_first -= std::f64::consts::TAU;
    }
    while base - a_first > std::f64::consts::PI {
        a_first += std::f64::consts::TAU;
    }
    let (mut a0, mut a1) = (base.min(a_first), base.max(a_first));
    if theta >= 0.0 {
        a1 += theta;
    } else {
        a0 += theta;
    }
    let far = (last - pivot).hypot2().sqrt();
    sector_box(pivot, far, a0, a1).inflate(2.0 * r, 2.0 * r)
}

/// The axis-aligned box of the sector swept by points within `radius` of `pivot` at angles
/// in `[a0, a1]` (radians, `a0 <= a1`).
pub(crate) fn sector_box(pivot: Point, radius: f64, a0: f64, a1: f64) -> Rect {
    let mut bounds = Rect::from_points(pivot, pivot);
    let mut add = |a: f64| {
        let p = Point::new(pivot.x + radius * a.cos(), pivot.y + radius * a.sin());
        bounds = bounds.union_pt(p);
    };
    add(a0);
    add(a1);
    let mut k = (a0 / std::f64::consts::FRAC_PI_2).ceil();
    while k * std::f64::consts::FRAC_PI_2 <= a1 {
        add(k * std::f64::consts::FRAC_PI_2);
        k += 1.0;
    }
    bounds
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_6};

    use super::*;

    /// The first contact of two convex polygons of any size, every (vertex, edge) pair tried:
    /// the plain form that [`TurningPair::first_contact`] must agree with.
    fn first_contact(moving: &[Point], fixed: &[Point], pivot: Point, theta: f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        for (verts, edges, turn) in [(moving, fixed, theta), (fixed, moving, -theta)] {
            for &v in verts {
                for e in 0..edges.len() {
                    let hit =
                        arc_hits_segment(v, pivot, turn, edges[e], edges[(e + 1) % edges.len()]);
                    if let Some(p) = hit {
                        if best.is_none_or(|b| p < b) {
                            best = Some(p);
                        }
                    }
                }
            }
        }
        best
    }

    fn square(cx: f64, cy: f64, h: f64) -> Vec<Point> {
        vec![
            Point::new(cx - h, cy - h),
            Point::new(cx + h, cy - h),
            Point::new(cx + h, cy + h),
            Point::new(cx - h, cy + h),
        ]
    }

    /// A regular octagon of across-flats width 1 centred at `c` (vertices counter-clockwise).
    fn octagon(c: Point) -> [Point; 8] {
        crate::Octagon::new(1.0)
            .vertices()
            .map(|(x, y)| c + Vec2::new(x, y))
    }

    const O: Point = Point::ORIGIN;

    #[test]
    fn vertex_arc_meets_edge() {
        // (1, 0) turning about the origin crosses y = 0.5 at 30 and 150 degrees
        let (a, b) = (Point::new(-1.0, 0.5), Point::new(1.0, 0.5));
        let v = Point::new(1.0, 0.0);
        let hit = arc_hits_segment(v, O, 2.0, a, b).unwrap();
        assert!((hit - FRAC_PI_6).abs() < 1e-12, "{hit}");
        assert!(arc_hits_segment(v, O, 0.5, a, b).is_none());
        // turning clockwise it goes the long way round: not within 2 rad
        assert!(arc_hits_segment(v, O, -2.0, a, b).is_none());
        let below = (Point::new(-1.0, -0.5), Point::new(1.0, -0.5));
        let cw = arc_hits_segment(v, O, -2.0, below.0, below.1).unwrap();
        assert!((cw - FRAC_PI_6).abs() < 1e-12, "{cw}");
    }

    #[test]
    fn swinging_square_hits_neighbour() {
        // a square at (3, 0) swinging counter-clockwise about the origin hits one at (0, 3)
        // before a quarter turn; with the other one further out it misses.
        let m = square(3.0, 0.0, 0.5);
        let hit = first_contact(&m, &square(0.0, 3.0, 0.5), O, FRAC_PI_2).unwrap();
        assert!(hit > 0.5 && hit < FRAC_PI_2, "{hit}");
        assert!(first_contact(&m, &square(0.0, 5.0, 0.5), O, FRAC_PI_2).is_none());
        // turning clockwise it meets nothing above
        assert!(first_contact(&m, &square(0.0, 3.0, 0.5), O, -FRAC_PI_2).is_none());
    }

    #[test]
    fn graze_between_samples_is_found() {
        // a small target just inside / just outside the circle the leading corner follows,
        // met over a tiny range of angle only: the closed form agrees with dense sampling.
        let m = square(10.0, 0.0, 0.5);
        let theta = 0.3;
        let (s, c) = (0.15f64).sin_cos();
        let corner_r = (10.5f64 * 10.5 + 0.25).sqrt();
        for (gap, expect) in [(-1e-6, true), (1e-6, false)] {
            let d = corner_r + 0.01 + gap;
            // the target turned to face the pivot, its near face 0.01 inside its centre
            let target: Vec<Point> = square(d, 0.0, 0.01)
                .iter()
                .map(|p| Point::new(c * p.x - s * p.y, s * p.x + c * p.y))
                .collect();
            assert_eq!(
                first_contact(&m, &target, O, theta).is_some(),
                expect,
                "gap {gap}"
            );
        }
    }

    /// A small xorshift generator of numbers in `[-3, 3)`.
    fn numbers(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
        }
    }

    #[test]
    fn quarter_predicate_agrees_with_angles() {
        let mut rnd = numbers(12345);
        let mut point = || Point::new(rnd(), rnd());
        for _ in 0..20_000 {
            let (v, p, a, b) = (point(), point(), point(), point());
            for left in [true, false] {
                let theta = if left { FRAC_PI_2 } else { -FRAC_PI_2 };
                assert_eq!(
                    quarter_arc_hits_segment(v, p, left, a, b),
                    arc_hits_segment(v, p, theta, a, b).is_some(),
                    "{v:?} {p:?} {a:?} {b:?} {left}"
                );
            }
        }
    }

    #[test]
    fn skipping_far_vertices_changes_nothing() {
        // octagons at random places, turning about random pivots: the annulus filter of
        // TurningPair::first_contact and quarter_contact gives the plain answer
        let mut rnd = numbers(987_654_321);
        let r = crate::Octagon::new(1.0).circumradius();
        let mut met = 0;
        for _ in 0..5_000 {
            let (mc, fc) = (Point::new(rnd(), rnd()), Point::new(rnd(), rnd()));
            if (mc - fc).hypot2().sqrt() < 2.0 * r {
                continue; // may overlap at the start
            }
            let pivot = Point::new(rnd(), rnd());
            let theta = rnd();
            let (m, f) = (octagon(mc), octagon(fc));
            let plain = first_contact(&m, &f, pivot, theta);
            let pair = TurningPair::new(&m, mc, &f, fc, r, pivot);
            assert_eq!(pair.first_contact(theta), plain);
            let quarter = first_contact(&m, &f, pivot, FRAC_PI_2);
            assert_eq!(pair.quarter_contact(true), quarter.is_some());
            met += usize::from(plain.is_some());
        }
        assert!(met > 100, "{met}");
    }

    #[test]
    fn sector_box_covers_quadrant() {
        let b = sector_box(O, 2.0, -0.1, FRAC_PI_2 + 0.1);
        assert!(b.x0 <= -0.19 && b.y0 <= -0.19);
        assert!((b.x1 - 2.0).abs() < 1e-12 && (b.y1 - 2.0).abs() < 1e-12);
    }
}
