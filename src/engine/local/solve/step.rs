//! One Dormand-Prince 5(4) step of a unit's state ([`crate::ode::dopri`]), its error
//! estimate, and its dense output: cubic Hermite on each component's values and rates at
//! the step's ends. A first-order unit's state is its positions; a second-order unit's is
//! its positions then its velocities, so that the positions' rates are the velocities and
//! the velocities' rates the accelerations.

use crate::engine::local::solve::{Solver, M, Z};
use crate::ode::{dopri, hermite};

/// A step attempt: the new state, the rates at both ends and the weighted RMS error.
pub(super) struct Step {
    /// The state at the step's end.
    pub(super) z1: [f64; Z],
    /// Rates at the start.
    pub(super) f0: [f64; Z],
    /// Rates at the end.
    pub(super) f1: [f64; Z],
    /// The error over the free unknowns, in tolerances (accept when <= 1).
    pub(super) err: f64,
    /// `h |lambda|`: Dormand-Prince's estimate of the stiffest eigenvalue along the step
    /// (Hairer's: the last two stages' rates over their states), or RODAS4's `h` times the
    /// Jacobian's norm.
    pub(super) stiffness: f64,
    /// The step controller's exponent: one over the error estimate's order plus one.
    pub(super) exponent: f64,
}

/// One step of `h` from `(tau, z)`, the error measured on the unknowns `free` (both their
/// position and velocity for a second-order unit).
pub(super) fn dopri(s: &mut Solver, tau: f64, z: &[f64; Z], h: f64, free: &[usize]) -> Step {
    let dim = s.dim();
    let mut k = [[0.0; Z]; 7];
    let mut d = [0.0; M];
    s.deriv(tau, z, &mut d, &mut k[0]);
    let mut zs = [0.0; Z];
    let mut y6 = [0.0; Z];
    dopri::stages(
        &z[..dim],
        h,
        &mut k,
        &mut zs[..dim],
        Some(&mut y6[..dim]),
        |c, y, out| {
            let mut state = [0.0; Z];
            state[..dim].copy_from_slice(y);
            let mut rates = [0.0; Z];
            s.deriv(tau + c * h, &state, &mut d, &mut rates);
            out.copy_from_slice(&rates[..dim]);
        },
    );
    let mut sum = 0.0;
    let mut count = 0usize;
    let second = dim > s.m;
    for &i in free {
        let comps = if second { [i, s.m + i] } else { [i, i] };
        for &c in &comps[..if second { 2 } else { 1 }] {
            let e = dopri::error_rate(&k, c);
            // a velocity's error weighed by the position error it makes in the unit's
            // inertial time
            let wv = if c >= s.m { s.vel_weight() } else { 1.0 };
            let sc = s.opts.tol * (1.0 + wv * z[c].abs().max(zs[c].abs()));
            sum += (wv * h * e / sc).powi(2);
            count += 1;
        }
    }
    let (mut num, mut den) = (0.0, 0.0);
    for &i in free {
        for c in [i, i + s.m] {
            if c < dim {
                num += (k[6][c] - k[5][c]).powi(2);
                den += (zs[c] - y6[c]).powi(2);
            }
        }
    }
    Step {
        z1: zs,
        f0: k[0],
        f1: k[6],
        err: (sum / count.max(1) as f64).sqrt(),
        stiffness: if den > 0.0 {
            h * (num / den).sqrt()
        } else {
            0.0
        },
        exponent: 0.2,
    }
}

/// The dense output of a step from `(t0, z0, f0)` to `(t1, z1, f1)` at `t`, on the first
/// `dim` components.
#[allow(clippy::too_many_arguments)]
pub(super) fn interpolate(
    dim: usize,
    t0: f64,
    t1: f64,
    z0: &[f64; Z],
    f0: &[f64; Z],
    z1: &[f64; Z],
    f1: &[f64; Z],
    t: f64,
) -> [f64; Z] {
    let mut out = [0.0; Z];
    for c in 0..dim {
        out[c] = hermite(t0, t1, (z0[c], f0[c]), (z1[c], f1[c]), t);
    }
    out
}
