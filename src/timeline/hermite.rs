//! The cubic Hermite interpolant of a step: value and rate at both ends, the dense output
//! both simulations read their steps with (the engine's tracks, the reference's reported
//! starts).

/// The cubic Hermite interpolant through `(t0, a.0, a.1)` and `(t1, b.0, b.1)` (value,
/// rate) at `t`; `b.0` for an empty interval.
pub(crate) fn hermite(t0: f64, t1: f64, a: (f64, f64), b: (f64, f64), t: f64) -> f64 {
    let h = t1 - t0;
    if h <= 0.0 {
        return b.0;
    }
    let s = (t - t0) / h;
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    h00 * a.0 + h10 * h * a.1 + h01 * b.0 + h11 * h * b.1
}
