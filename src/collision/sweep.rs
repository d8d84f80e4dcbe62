//! Exact first contact of a convex polygon turning about a fixed point with a static one.
//!
//! Two convex polygons that are disjoint at the start of a rotation can only come to overlap
//! after their boundaries meet, and boundaries first meet with a vertex of one on an edge of
//! the other. A vertex turning about the pivot follows a circular arc, so the first contact
//! is the smallest angle at which one of these arcs crosses an edge: a quadratic per
//! (vertex, edge) pair, solved in closed form. No sampling: a graze between two samples cannot
//! be missed. Vertices of the static polygon are followed in the moving polygon's frame (the
//! same arcs turned the other way).

/// A point or vector in the plane.
pub type V2 = (f64, f64);

#[inline]
fn sub(a: V2, b: V2) -> V2 {
    (a.0 - b.0, a.1 - b.1)
}
#[inline]
fn dot(a: V2, b: V2) -> f64 {
    a.0 * b.0 + a.1 * b.1
}
#[inline]
fn cross(a: V2, b: V2) -> f64 {
    a.0 * b.1 - a.1 * b.0
}

/// The points (relative to `pivot`) where the circle about `pivot` through `v` crosses the
/// segment `a`-`b`: none, one or two, from the quadratic in the segment parameter.
#[inline]
fn circle_crossings(v: V2, pivot: V2, a: V2, b: V2) -> [Option<V2>; 2] {
    let pv = sub(v, pivot);
    let r2 = dot(pv, pv);
    let d = sub(b, a);
    let ac = sub(a, pivot);
    let qa = dot(d, d);
    if qa == 0.0 {
        return [None, None];
    }
    let qb = 2.0 * dot(d, ac);
    let qc = dot(ac, ac) - r2;
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
    [t1, t2].map(|t| {
        (0.0..=1.0)
            .contains(&t)
            .then_some((ac.0 + t * d.0, ac.1 + t * d.1))
    })
}

/// The smallest angle in `(0, |theta|]`, turning the way `theta`'s sign says (positive =
/// counter-clockwise), at which `v`, turning about `pivot`, lies on the segment `a`-`b`.
#[inline]
pub fn arc_hits_segment(v: V2, pivot: V2, theta: f64, a: V2, b: V2) -> Option<f64> {
    let pv = sub(v, pivot);
    let mut best: Option<f64> = None;
    for x in circle_crossings(v, pivot, a, b).into_iter().flatten() {
        let mut phi = cross(pv, x).atan2(dot(pv, x));
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

/// The first angle (absolute, radians) in `(0, |theta|]` at which the convex polygon
/// `moving`, turned about `pivot` by up to `theta` (signed), touches the convex polygon
/// `fixed`, assuming the two are disjoint at the start. `None` when they never meet.
pub fn first_contact(moving: &[V2], fixed: &[V2], pivot: V2, theta: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    let mut consider = |phi: Option<f64>| {
        if let Some(p) = phi {
            if best.is_none_or(|b| p < b) {
                best = Some(p);
            }
        }
    };
    let n = fixed.len();
    for &v in moving {
        for e in 0..n {
            consider(arc_hits_segment(
                v,
                pivot,
                theta,
                fixed[e],
                fixed[(e + 1) % n],
            ));
        }
    }
    let m = moving.len();
    for &v in fixed {
        for e in 0..m {
            consider(arc_hits_segment(
                v,
                pivot,
                -theta,
                moving[e],
                moving[(e + 1) % m],
            ));
        }
    }
    best
}

/// Whether `v`, turning a quarter turn about `pivot` (counter-clockwise when `left`), lies
/// on the segment `a`-`b` at some moment: [`arc_hits_segment`] with `theta = +-pi/2`, without
/// computing the angle (a crossing point is within the quarter turn exactly when it is on the
/// turning side of the start direction and not behind the pivot).
#[inline]
pub fn quarter_arc_hits_segment(v: V2, pivot: V2, left: bool, a: V2, b: V2) -> bool {
    let pv = sub(v, pivot);
    circle_crossings(v, pivot, a, b)
        .into_iter()
        .flatten()
        .any(|x| {
            let c = cross(pv, x);
            dot(pv, x) >= 0.0 && if left { c >= 0.0 } else { c <= 0.0 }
        })
}

/// Calls `hit(vertex, edge start, edge end, turns_forward)` for every (vertex, edge) pair of
/// two polygons within `r` of their centres whose vertex arc can reach the other polygon's
/// annulus about `pivot`; `turns_forward` is true for the moving polygon's vertices (the
/// fixed polygon's turn the other way in the moving frame). Stops when `hit` returns true.
fn for_each_reachable_pair(
    moving: &[V2; 8],
    moving_centre: V2,
    fixed: &[V2; 8],
    fixed_centre: V2,
    r: f64,
    pivot: V2,
    mut hit: impl FnMut(V2, V2, V2, bool) -> bool,
) {
    let ring = |c: V2| {
        let d = dot(sub(c, pivot), sub(c, pivot)).sqrt();
        let lo = (d - r).max(0.0);
        (lo * lo * (1.0 - 1e-12), (d + r) * (d + r) * (1.0 + 1e-12))
    };
    let sides = [
        (moving, fixed, ring(fixed_centre), true),
        (fixed, moving, ring(moving_centre), false),
    ];
    for (verts, edges, (lo, hi), forward) in sides {
        for &v in verts {
            let rho = dot(sub(v, pivot), sub(v, pivot));
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

/// Whether two octagons within `r` of their centres meet while `moving` turns a quarter turn
/// about `pivot` (counter-clockwise when `left`), assuming they are apart at the start: the
/// yes/no form of [`first_contact_within`] for full folds.
pub fn quarter_contact_within(
    moving: &[V2; 8],
    moving_centre: V2,
    fixed: &[V2; 8],
    fixed_centre: V2,
    r: f64,
    pivot: V2,
    left: bool,
) -> bool {
    let mut found = false;
    for_each_reachable_pair(
        moving,
        moving_centre,
        fixed,
        fixed_centre,
        r,
        pivot,
        |v, p, q, fwd| {
            found = quarter_arc_hits_segment(v, pivot, left == fwd, p, q);
            found
        },
    );
    found
}

/// [`first_contact`] for two polygons known to lie within distance `r` of the centres
/// `moving_centre` and `fixed_centre`: vertices whose arc stays outside the annulus that holds
/// the other polygon are skipped, which leaves the result unchanged and saves most of the
/// work.
#[allow(clippy::too_many_arguments)]
pub fn first_contact_within(
    moving: &[V2; 8],
    moving_centre: V2,
    fixed: &[V2; 8],
    fixed_centre: V2,
    r: f64,
    pivot: V2,
    theta: f64,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    for_each_reachable_pair(
        moving,
        moving_centre,
        fixed,
        fixed_centre,
        r,
        pivot,
        |v, p, q, fwd| {
            let turn = if fwd { theta } else { -theta };
            if let Some(phi) = arc_hits_segment(v, pivot, turn, p, q) {
                if best.is_none_or(|b| phi < b) {
                    best = Some(phi);
                }
            }
            false
        },
    );
    best
}

/// Whether two convex polygons (counter-clockwise) overlap, by separating axes; touching
/// counts as overlapping.
pub fn convex_overlap(p: &[V2], q: &[V2]) -> bool {
    fn separated(p: &[V2], q: &[V2]) -> bool {
        let n = p.len();
        for i in 0..n {
            let a = p[i];
            let e = sub(p[(i + 1) % n], a);
            // outward normal of a counter-clockwise polygon is (e.y, -e.x)
            if q.iter().all(|&v| cross(e, sub(v, a)) < 0.0) {
                return true;
            }
        }
        false
    }
    !(separated(p, q) || separated(q, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(cx: f64, cy: f64, h: f64) -> Vec<V2> {
        vec![
            (cx - h, cy - h),
            (cx + h, cy - h),
            (cx + h, cy + h),
            (cx - h, cy + h),
        ]
    }

    #[test]
    fn vertex_arc_meets_edge() {
        use std::f64::consts::FRAC_PI_6;
        // (1, 0) turning about the origin crosses y = 0.5 at 30 and 150 degrees
        let seg = ((-1.0, 0.5), (1.0, 0.5));
        let hit = arc_hits_segment((1.0, 0.0), (0.0, 0.0), 2.0, seg.0, seg.1).unwrap();
        assert!((hit - FRAC_PI_6).abs() < 1e-12, "{hit}");
        assert!(arc_hits_segment((1.0, 0.0), (0.0, 0.0), 0.5, seg.0, seg.1).is_none());
        // turning clockwise it goes the long way round: not within 2 rad
        assert!(arc_hits_segment((1.0, 0.0), (0.0, 0.0), -2.0, seg.0, seg.1).is_none());
        let cw = arc_hits_segment((1.0, 0.0), (0.0, 0.0), -2.0, (-1.0, -0.5), (1.0, -0.5)).unwrap();
        assert!((cw - FRAC_PI_6).abs() < 1e-12, "{cw}");
    }

    #[test]
    fn swinging_square_hits_neighbour() {
        // a square at (3, 0) swinging counter-clockwise about the origin hits one at (0, 3)
        // before a quarter turn; with the other one further out it misses.
        let m = square(3.0, 0.0, 0.5);
        let hit = first_contact(
            &m,
            &square(0.0, 3.0, 0.5),
            (0.0, 0.0),
            std::f64::consts::FRAC_PI_2,
        )
        .unwrap();
        assert!(hit > 0.5 && hit < std::f64::consts::FRAC_PI_2, "{hit}");
        assert!(first_contact(
            &m,
            &square(0.0, 5.0, 0.5),
            (0.0, 0.0),
            std::f64::consts::FRAC_PI_2
        )
        .is_none());
        // turning clockwise it meets nothing above
        assert!(first_contact(
            &m,
            &square(0.0, 3.0, 0.5),
            (0.0, 0.0),
            -std::f64::consts::FRAC_PI_2
        )
        .is_none());
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
            let target: Vec<V2> = square(d, 0.0, 0.01)
                .iter()
                .map(|&(x, y)| (c * x - s * y, s * x + c * y))
                .collect();
            assert_eq!(
                first_contact(&m, &target, (0.0, 0.0), theta).is_some(),
                expect,
                "gap {gap}"
            );
        }
    }

    #[test]
    fn quarter_predicate_agrees_with_angles() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
        };
        for _ in 0..20_000 {
            let (v, p, a, b) = (
                (rnd(), rnd()),
                (rnd(), rnd()),
                (rnd(), rnd()),
                (rnd(), rnd()),
            );
            for left in [true, false] {
                let theta = if left {
                    std::f64::consts::FRAC_PI_2
                } else {
                    -std::f64::consts::FRAC_PI_2
                };
                assert_eq!(
                    quarter_arc_hits_segment(v, p, left, a, b),
                    arc_hits_segment(v, p, theta, a, b).is_some(),
                    "{v:?} {p:?} {a:?} {b:?} {left}"
                );
            }
        }
    }

    #[test]
    fn overlap_by_axes() {
        assert!(convex_overlap(
            &square(0.0, 0.0, 1.0),
            &square(1.5, 0.0, 1.0)
        ));
        assert!(!convex_overlap(
            &square(0.0, 0.0, 1.0),
            &square(2.5, 0.0, 1.0)
        ));
    }
}
