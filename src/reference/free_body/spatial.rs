//! Planar spatial vectors (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, ch. 2 and
//! 9, reduced to the plane): a motion `[w, vx, vy]` (the turn rate and the velocity of the
//! body point at the reference point), a force `[n, fx, fy]` (the moment about the
//! reference point and the force), and 3x3 spatial inertias. Every body's vectors are taken
//! about its own reference point, a point fixed in the world at the instant, in one set of
//! axes: changing point is a shift (no rotation), so a long chain loses no precision to
//! large coordinates. SI units.

/// A motion or force vector.
pub(crate) type Vec3 = [f64; 3];
/// A 3x3 matrix (row major).
pub(crate) type Mat3 = [[f64; 3]; 3];

/// The motion `m` (at point A) seen at point B, `r = B - A`.
pub(crate) fn shift_motion(m: Vec3, r: [f64; 2]) -> Vec3 {
    [m[0], m[1] - m[0] * r[1], m[2] + m[0] * r[0]]
}

/// The force `f` (at point B) seen at point A, `r = B - A` (the transpose of
/// [`shift_motion`]).
pub(crate) fn shift_force_back(f: Vec3, r: [f64; 2]) -> Vec3 {
    [f[0] + r[0] * f[2] - r[1] * f[1], f[1], f[2]]
}

/// `T^T I T`, `T` the motion shift by `r` (an inertia at point B seen at point A).
pub(crate) fn shift_inertia_back(i: &Mat3, r: [f64; 2]) -> Mat3 {
    // columns of I T: T's columns are e0 + (-r_y, r_x) in rows 1, 2; e1; e2
    let mut it = [[0.0; 3]; 3];
    for (row, out) in i.iter().zip(it.iter_mut()) {
        out[0] = row[0] - row[1] * r[1] + row[2] * r[0];
        out[1] = row[1];
        out[2] = row[2];
    }
    // T^T (I T): row 0 of T^T is (1, -r_y, r_x), rows 1, 2 are e1, e2
    let mut out = [[0.0; 3]; 3];
    for c in 0..3 {
        out[0][c] = it[0][c] - r[1] * it[1][c] + r[0] * it[2][c];
        out[1][c] = it[1][c];
        out[2][c] = it[2][c];
    }
    out
}

/// `m1 x m2` of two motions (the rate of a motion carried by a body moving with `m1`).
pub(crate) fn cross_motion(a: Vec3, b: Vec3) -> Vec3 {
    [0.0, -a[0] * b[2] + b[0] * a[2], a[0] * b[1] - b[0] * a[1]]
}

/// `v x* f` of a motion and a force (the rate of a momentum carried by a body moving with
/// `v`).
pub(crate) fn cross_force(v: Vec3, f: Vec3) -> Vec3 {
    [v[1] * f[2] - v[2] * f[1], -v[0] * f[2], v[0] * f[1]]
}

/// `I v`.
pub(crate) fn mul(i: &Mat3, v: Vec3) -> Vec3 {
    [
        i[0][0] * v[0] + i[0][1] * v[1] + i[0][2] * v[2],
        i[1][0] * v[0] + i[1][1] * v[1] + i[1][2] * v[2],
        i[2][0] * v[0] + i[2][1] * v[1] + i[2][2] * v[2],
    ]
}

/// `a . b`.
pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a + s b`.
pub(crate) fn axpy(a: Vec3, s: f64, b: Vec3) -> Vec3 {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// The spatial inertia about a point of bodies of total mass `m`, first moment `s` about the
/// point (mass times the centre of mass's offset) and second moment `j` about it: also the
/// matrix of a linear drag with the same moments.
pub(crate) fn inertia(m: f64, s: [f64; 2], j: f64) -> Mat3 {
    [[j, -s[1], s[0]], [-s[1], m, 0.0], [s[0], 0.0, m]]
}

/// `a + b`.
pub(crate) fn add(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut out = *a;
    for (r, br) in out.iter_mut().zip(b) {
        for (x, y) in r.iter_mut().zip(br) {
            *x += y;
        }
    }
    out
}

/// `i - u u^T / d`.
pub(crate) fn minus_outer(i: &Mat3, u: Vec3, d: f64) -> Mat3 {
    let mut out = *i;
    for (r, row) in out.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x -= u[r] * u[c] / d;
        }
    }
    out
}

/// `x` with `i x = b` (a symmetric positive definite `i`, by Cholesky); `None` when it is
/// not.
pub(crate) fn solve(i: &Mat3, b: Vec3) -> Option<Vec3> {
    let l00 = i[0][0].sqrt();
    let l10 = i[1][0] / l00;
    let l20 = i[2][0] / l00;
    let l11 = (i[1][1] - l10 * l10).sqrt();
    let l21 = (i[2][1] - l20 * l10) / l11;
    let l22 = (i[2][2] - l20 * l20 - l21 * l21).sqrt();
    if !(l00 > 0.0 && l11 > 0.0 && l22 > 0.0) {
        return None;
    }
    let y0 = b[0] / l00;
    let y1 = (b[1] - l10 * y0) / l11;
    let y2 = (b[2] - l20 * y0 - l21 * y1) / l22;
    let x2 = y2 / l22;
    let x1 = (y1 - l21 * x2) / l11;
    let x0 = (y0 - l10 * x1 - l20 * x2) / l00;
    Some([x0, x1, x2])
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn shifts_keep_power_and_inertias_shift_by_the_parallel_axis_rule() {
        // the power f . m is the same at any point
        let (m, f, r) = ([0.7, -1.1, 2.3], [0.4, 1.9, -0.6], [0.31, -0.52]);
        let p_a = dot(shift_force_back(f, r), m);
        let p_b = dot(f, shift_motion(m, r));
        assert!((p_a - p_b).abs() < 1e-15, "{p_a} {p_b}");
        // a point mass at B seen from A is a point mass at offset r
        let at_b = inertia(2.0, [0.0, 0.0], 0.0);
        let at_a = shift_inertia_back(&at_b, r);
        let want = inertia(
            2.0,
            [2.0 * r[0], 2.0 * r[1]],
            2.0 * (r[0] * r[0] + r[1] * r[1]),
        );
        for (x, y) in at_a.iter().flatten().zip(want.iter().flatten()) {
            assert!((x - y).abs() < 1e-15, "{at_a:?} {want:?}");
        }
        let x = solve(&want, [1.0, 2.0, 3.0]);
        assert!(x.is_none(), "a point mass has no inertia about itself");
        let body = inertia(2.0, [0.2, -0.1], 0.5);
        let x = solve(&body, [1.0, 2.0, 3.0]).unwrap();
        let back = mul(&body, x);
        for (a, b) in back.iter().zip([1.0, 2.0, 3.0]) {
            assert!((a - b).abs() < 1e-12);
        }
        // a momentum carried by its own motion does not change (v x* I v is the gyroscopic
        // term; for a body turning about its centre of mass it is zero)
        let centred = inertia(2.0, [0.0, 0.0], 0.5);
        let v = [1.5, 0.0, 0.0];
        assert_eq!(cross_force(v, mul(&centred, v)), [0.0, 0.0, 0.0]);
        assert_eq!(cross_motion(v, v), [0.0, 0.0, 0.0]);
    }
}
