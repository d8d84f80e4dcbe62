//! Point-dipole magnet interactions (thesis equations 6.11, 6.12 and 8.1).
//!
//! Magnets stand upright with poles alternating along the chain, so every pair of moments is
//! parallel or antiparallel and perpendicular to the line between them. SI units: metres,
//! A m^2, joules, newtons.

use crate::design::MU0;

/// Pair energy (6.11): `U = -sigma mu0/(4 pi) m^2 / r^3`, `sigma = +1` for an attracting
/// (opposite-pole) pair, `-1` for a repelling one.
pub fn pair_energy(moment: f64, r: f64, attract: bool) -> f64 {
    let sigma = if attract { 1.0 } else { -1.0 };
    -sigma * MU0 / (4.0 * std::f64::consts::PI) * moment * moment / (r * r * r)
}

/// Pair force magnitude (6.12): `3 mu0 m^2 / (4 pi r^4)`.
pub fn pair_force(moment: f64, r: f64) -> f64 {
    3.0 * MU0 / (4.0 * std::f64::consts::PI) * moment * moment / (r * r * r * r)
}

/// Total energy (8.1) of magnets at `positions` (metres) with poles alternating by index:
/// the sum of (6.11) over all pairs closer than `cutoff` metres (`f64::INFINITY` for all).
pub fn total_energy(positions: &[(f64, f64)], moment: f64, cutoff: f64) -> f64 {
    let mut u = 0.0;
    for i in 0..positions.len() {
        for j in i + 1..positions.len() {
            let (dx, dy) = (
                positions[j].0 - positions[i].0,
                positions[j].1 - positions[i].1,
            );
            let r = (dx * dx + dy * dy).sqrt();
            if r < cutoff && r > 0.0 {
                u += pair_energy(moment, r, (j - i) % 2 == 1);
            }
        }
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_minus_energy_gradient() {
        let (m, r, h) = (0.036, 0.015, 1e-9);
        let du = (pair_energy(m, r + h, true) - pair_energy(m, r - h, true)) / (2.0 * h);
        assert!((du - pair_force(m, r)).abs() / pair_force(m, r) < 1e-6);
        assert!(pair_energy(m, r, true) < 0.0 && pair_energy(m, r, false) > 0.0);
    }

    #[test]
    fn alternating_chain_energy() {
        let p = [(0.0, 0.0), (0.01, 0.0), (0.02, 0.0)];
        let u = total_energy(&p, 1.0, f64::INFINITY);
        let expect = 2.0 * pair_energy(1.0, 0.01, true) + pair_energy(1.0, 0.02, false);
        assert!((u - expect).abs() < 1e-12 * expect.abs());
        let cut = total_energy(&p, 1.0, 0.015);
        assert!((cut - 2.0 * pair_energy(1.0, 0.01, true)).abs() < 1e-12 * expect.abs());
    }
}
