//! Plane regions in mm: polygons with holes as `i_overlay` gives them (each shape an outer
//! contour, counter-clockwise, then its holes, clockwise), the unions that build them, and the
//! measures the part builder checks them with (area, the distance between two regions'
//! boundaries, whether a point lies inside).

use i_overlay::core::fill_rule::FillRule;
use i_overlay::float::simplify::SimplifyShape;

/// The shortest edge a region keeps, mm ([`cleaned`]): a thousandth of a millimetre.
pub const MIN_EDGE: f64 = 1e-3;

/// A point in the plane, mm.
pub type Pt = [f64; 2];
/// A closed contour (the last point joins the first).
pub type Contour = Vec<Pt>;
/// A region: shapes, each an outer contour then its holes.
pub type Region = Vec<Vec<Contour>>;

/// The signed area of a contour (positive counter-clockwise).
pub fn signed_area(c: &[Pt]) -> f64 {
    let n = c.len();
    let mut a = 0.0;
    for i in 0..n {
        let (p, q) = (c[i], c[(i + 1) % n]);
        a += p[0] * q[1] - q[0] * p[1];
    }
    0.5 * a
}

/// The area of a region (holes taken off).
pub fn area(r: &Region) -> f64 {
    r.iter().flatten().map(|c| signed_area(c)).sum()
}

/// The contour made counter-clockwise.
pub fn ccw(mut c: Contour) -> Contour {
    if signed_area(&c) < 0.0 {
        c.reverse();
    }
    c
}

/// A disc of radius `r` about `centre` as a polygon whose vertices lie on the circle and
/// whose edges stay within `tol` of it (at least 12 vertices), counter-clockwise.
pub fn disc(centre: Pt, r: f64, tol: f64) -> Contour {
    let n = segments_for_angle(std::f64::consts::TAU, r, tol).max(12);
    (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
        })
        .collect()
}

/// How many chords keep an arc of `angle` radians and radius `r` within `tol` of its chords.
pub fn segments_for_angle(angle: f64, r: f64, tol: f64) -> usize {
    if r <= tol || angle <= 0.0 {
        return 1;
    }
    let step = 2.0 * (1.0 - tol / r).clamp(-1.0, 1.0).acos();
    ((angle / step).ceil() as usize).clamp(1, 100_000)
}

/// The union of counter-clockwise pieces (non-zero fill).
pub fn union(pieces: &[Contour]) -> Region {
    if pieces.is_empty() {
        return Vec::new();
    }
    pieces.to_vec().simplify_shape(FillRule::NonZero)
}

/// The region without edges shorter than `eps`: of an edge's two ends the one whose removal
/// changes the area least goes (a boolean operation leaves such slivers where pieces meet
/// at a tangent). The files keep coordinates as 32-bit floats (about 2e-6 mm at 30 mm),
/// which would merge such points. Contours left with fewer than 3 points are dropped (a
/// shape whose outer contour goes, whole).
pub fn cleaned(r: Region, eps: f64) -> Region {
    let mut out: Region = Vec::new();
    for shape in r {
        let mut kept: Vec<Contour> = Vec::new();
        for (k, mut c) in shape.into_iter().enumerate() {
            let tri = |a: Pt, b: Pt, c: Pt| orient(a, b, c).abs();
            loop {
                let n = c.len();
                if n < 3 {
                    break;
                }
                let short = (0..n).find(|&i| {
                    let (a, b) = (c[i], c[(i + 1) % n]);
                    (a[0] - b[0]).hypot(a[1] - b[1]) < eps
                });
                let Some(i) = short else { break };
                let j = (i + 1) % n;
                let cost_i = tri(c[(i + n - 1) % n], c[i], c[j]);
                let cost_j = tri(c[i], c[j], c[(j + 1) % n]);
                c.remove(if cost_i <= cost_j { i } else { j });
            }
            if c.len() >= 3 {
                kept.push(c);
            } else if k == 0 {
                break;
            }
        }
        if !kept.is_empty() {
            out.push(kept);
        }
    }
    out
}

/// Every contour of a region.
pub fn contours(r: &Region) -> impl Iterator<Item = &Contour> {
    r.iter().flatten()
}

/// The distance between segments `ab` and `cd` (0 when they cross).
pub fn segment_distance(a: Pt, b: Pt, c: Pt, d: Pt) -> f64 {
    if segments_cross(a, b, c, d) {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

/// The distance from `p` to segment `ab`.
pub fn point_segment_distance(p: Pt, a: Pt, b: Pt) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

fn orient(a: Pt, b: Pt, c: Pt) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn segments_cross(a: Pt, b: Pt, c: Pt, d: Pt) -> bool {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// The segments of a set of contours.
fn segments<'a>(cs: impl Iterator<Item = &'a Contour>) -> Vec<(Pt, Pt)> {
    let mut out = Vec::new();
    for c in cs {
        for i in 0..c.len() {
            out.push((c[i], c[(i + 1) % c.len()]));
        }
    }
    out
}

/// The least distance between the boundaries of two sets of contours (0 when they cross).
pub fn boundary_distance<'a, 'b>(
    a: impl Iterator<Item = &'a Contour>,
    b: impl Iterator<Item = &'b Contour>,
) -> f64 {
    let (sa, sb) = (segments(a), segments(b));
    let mut best = f64::INFINITY;
    for &(p, q) in &sa {
        // a cheap bound first: boxes farther apart than the best so far cannot do better
        let (lox, hix) = (p[0].min(q[0]), p[0].max(q[0]));
        let (loy, hiy) = (p[1].min(q[1]), p[1].max(q[1]));
        for &(r, s) in &sb {
            let gx = (r[0].min(s[0]) - hix).max(lox - r[0].max(s[0])).max(0.0);
            let gy = (r[1].min(s[1]) - hiy).max(loy - r[1].max(s[1])).max(0.0);
            if gx.hypot(gy) >= best {
                continue;
            }
            best = best.min(segment_distance(p, q, r, s));
        }
    }
    best
}

/// Whether `p` lies inside the contours by the even-odd rule.
pub fn inside<'a>(cs: impl Iterator<Item = &'a Contour>, p: Pt) -> bool {
    let mut odd = false;
    for c in cs {
        let n = c.len();
        for i in 0..n {
            let (a, b) = (c[i], c[(i + 1) % n]);
            if (a[1] > p[1]) != (b[1] > p[1]) {
                let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
                if x > p[0] {
                    odd = !odd;
                }
            }
        }
    }
    odd
}

/// The region turned by `angle` radians about the origin.
pub fn rotated(r: &Region, angle: f64) -> Region {
    let (s, c) = angle.sin_cos();
    r.iter()
        .map(|shape| {
            shape
                .iter()
                .map(|ct| {
                    ct.iter()
                        .map(|p| [c * p[0] - s * p[1], s * p[0] + c * p[1]])
                        .collect()
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn a_disc_is_round_within_its_tolerance() {
        let d = disc([1.0, 2.0], 1.5, 0.002);
        let n = d.len() as f64;
        let exact = std::f64::consts::PI * 1.5 * 1.5;
        let polygon = 0.5 * n * 1.5 * 1.5 * (std::f64::consts::TAU / n).sin();
        assert!((signed_area(&d) - polygon).abs() < 1e-9);
        assert!(exact - polygon < 2.0 * std::f64::consts::PI * 1.5 * 0.002);
    }

    #[test]
    fn two_overlapping_squares_unite() {
        let sq = |x: f64| vec![[x, 0.0], [x + 2.0, 0.0], [x + 2.0, 2.0], [x, 2.0]];
        let u = union(&[sq(0.0), sq(1.0)]);
        assert_eq!(u.len(), 1);
        assert!((area(&u) - 6.0).abs() < 1e-6, "{}", area(&u));
        let apart = union(&[sq(0.0), sq(5.0)]);
        assert_eq!(apart.len(), 2);
        let d = boundary_distance(contours(&apart).take(1), contours(&apart).skip(1));
        assert!((d - 3.0).abs() < 1e-6, "{d}");
        assert!(inside(contours(&u), [1.5, 1.0]));
        assert!(!inside(contours(&u), [3.5, 1.0]));
    }
}
