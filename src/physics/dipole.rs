//! The point-dipole pair law (thesis equations 6.11 and 6.12): magnets as point dipoles
//! standing upright, so every pair of moments is parallel or antiparallel and perpendicular
//! to the line between them, and the pair force is central.
//!
//! - energy `U = -sigma mu0 m_a m_b / (4 pi r^3)`, `sigma = +1` for an attracting
//!   (opposite-pole) pair and `-1` for a repelling one;
//! - force `F = 3 mu0 m_a m_b / (4 pi r^4)` along the line between them.

use std::f64::consts::PI;

use kurbo::{Point, Vec2};

use crate::design::MU0;

/// `3 mu0 / (4 pi)`, N m^4 / (A m^2)^2: the pair force is this times the two moments over
/// `r^4`.
pub(crate) const FORCE_CONSTANT: f64 = 3.0 * MU0 / (4.0 * PI);

/// The force magnitude (N) between moments `m_a` and `m_b` (A m^2) `r` metres apart.
pub(crate) fn magnitude(m_a: f64, m_b: f64, r: f64) -> f64 {
    FORCE_CONSTANT * m_a * m_b / r.powi(4)
}

/// The force (N) on the magnet at `on` from the one at `from` (both mm), moments `m_from` and
/// `m_on`; zero for coincident points.
pub(crate) fn force(from: Point, on: Point, m_from: f64, m_on: f64, attract: bool) -> Vec2 {
    let d = (on - from) * 1e-3;
    let r2 = d.hypot2();
    if r2 <= 0.0 {
        return Vec2::ZERO;
    }
    let r = r2.sqrt();
    let mag = FORCE_CONSTANT * m_from * m_on / (r2 * r2);
    let sign = if attract { -1.0 } else { 1.0 };
    Vec2::new(sign * mag * d.x / r, sign * mag * d.y / r)
}

/// [`force`] with the moments and the polarity folded into `coefficient` (`FORCE_CONSTANT
/// m_from m_on`, negative for an attracting pair): one division and one square root where
/// [`force`] takes three divisions, for the reference's inner loop. The same force to a few
/// units in the last place.
pub(crate) fn force_with(from: Point, on: Point, coefficient: f64) -> Vec2 {
    let d = (on - from) * 1e-3;
    let r2 = d.hypot2();
    if r2 <= 0.0 {
        return Vec2::ZERO;
    }
    let inv = 1.0 / r2;
    let s = coefficient * inv * inv * inv.sqrt();
    Vec2::new(s * d.x, s * d.y)
}

/// The pair energy (J) of magnets at `a` and `b` (mm), moments `m_a` and `m_b`; zero for
/// coincident points.
pub(crate) fn energy(a: Point, b: Point, m_a: f64, m_b: f64, attract: bool) -> f64 {
    let r = a.distance(b) * 1e-3;
    if r > 0.0 {
        let sigma = if attract { 1.0 } else { -1.0 };
        -sigma * MU0 / (4.0 * PI) * m_a * m_b / (r * r * r)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_minus_the_energy_gradient() {
        // along x: F_x on b = -dU/dx_b, for both polarities
        let (m, x, h) = (0.036, 15.0, 1e-6);
        for attract in [true, false] {
            let u = |x: f64| energy(Point::ORIGIN, Point::new(x, 0.0), m, m, attract);
            let du = (u(x + h) - u(x - h)) / (2.0 * h * 1e-3);
            let f = force(Point::ORIGIN, Point::new(x, 0.0), m, m, attract);
            assert!(
                (f.x + du).abs() < 1e-6 * f.x.abs(),
                "{attract}: {} {du}",
                f.x
            );
            assert_eq!(f.y, 0.0);
            assert!((f.x.abs() - magnitude(m, m, x * 1e-3)).abs() < 1e-12 * f.x.abs());
        }
        assert!(energy(Point::ORIGIN, Point::new(x, 0.0), m, m, true) < 0.0);
    }

    #[test]
    fn force_with_a_coefficient_is_the_force() {
        let (a, b) = (Point::new(1.0, 2.0), Point::new(4.0, -2.5));
        for attract in [true, false] {
            let f = force(a, b, 0.02, 0.03, attract);
            let sign = if attract { -1.0 } else { 1.0 };
            let g = force_with(a, b, sign * FORCE_CONSTANT * 0.02 * 0.03);
            assert!((f - g).hypot() < 1e-15 * f.hypot(), "{f:?} {g:?}");
        }
        assert_eq!(force_with(a, a, 1.0), Vec2::ZERO);
    }

    #[test]
    fn force_is_central_and_opposite() {
        let (a, b) = (Point::new(1.0, 2.0), Point::new(4.0, -2.0));
        let f_on_b = force(a, b, 0.02, 0.03, true);
        let f_on_a = force(b, a, 0.03, 0.02, true);
        assert!((f_on_b + f_on_a).hypot() < 1e-15 * f_on_b.hypot());
        // attracting: towards a, along the line
        let towards = a - b;
        assert!(f_on_b.cross(towards).abs() < 1e-12 * f_on_b.hypot() * towards.hypot());
        assert!(f_on_b.dot(towards) > 0.0);
        assert_eq!(force(a, a, 1.0, 1.0, true), Vec2::ZERO);
        assert_eq!(energy(a, a, 1.0, 1.0, true), 0.0);
    }
}
