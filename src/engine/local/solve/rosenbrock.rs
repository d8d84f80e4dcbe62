//! One RODAS4 step of a unit's state ([`crate::ode::rosenbrock`]'s method), for the stretches
//! where a unit is stiff.
//!
//! **Where a unit is stiff.** A folding joint that swings a long tail turns slowly (its
//! inertia grows with the tiles it swings), while the magnets of its pair, nearly closed,
//! follow the balance the turning fold moves, relaxing to it at their own fast rate (the
//! drag over the mass, about 190 per second for the thesis magnets, and the pair's magnetic
//! stiffness). Dormand-Prince's stability region then bounds its step by about
//! `3.3 / |lambda|` however smooth the motion: thousands of steps for a fold of a 100,000-tile
//! chain's first U-turn. An L-stable method steps at the pace the fold's accuracy asks.
//!
//! `J` and `df/dt` are forward differences at the step's start: one drive evaluation per free
//! position and one in time (a velocity's column needs none: the drives depend on the
//! positions only). The dense output is the cubic Hermite on the step's ends, as for
//! Dormand-Prince, so events are located the same way.

use crate::engine::local::solve::step::Step;
use crate::engine::local::solve::{Solver, M, Z};
use crate::ode::rosenbrock::{rodas4_stages, Lu, RODAS4_GAMMA};

/// Relative size of a finite-difference increment: the square root of the machine epsilon.
const DIFF: f64 = 1e-5;

/// One RODAS4 step of `h` from `(tau, z)`, its error on the unknowns `free`; its
/// `stiffness` is `h` times the infinity norm of the Jacobian's free rows (below 1 the unit
/// is not stiff at this step and Dormand-Prince is the cheaper method).
pub(super) fn rodas(s: &mut Solver, tau: f64, z: &[f64; Z], h: f64, free: &[usize]) -> Step {
    let dim = s.dim();
    let m = s.m;
    let second = dim > m;
    // the components that move: free positions (and their velocities)
    let mut comps = [0usize; Z];
    let mut nc = 0;
    for &i in free {
        comps[nc] = i;
        nc += 1;
        if second {
            comps[nc] = m + i;
            nc += 1;
        }
    }
    let comps = &comps[..nc];
    // f0, the Jacobian and df/dt at the step's start
    let mut d0 = [0.0; M];
    let mut f0 = [0.0; Z];
    s.deriv(tau, z, &mut d0, &mut f0);
    let mut jac = [[0.0; Z]; Z];
    for &c in comps {
        let dz = DIFF * z[c].abs().max(1.0);
        let (mut zp, mut zm) = (*z, *z);
        zp[c] += dz;
        zm[c] -= dz;
        let dz = zp[c] - zm[c];
        let (mut fp, mut fm) = ([0.0; Z], [0.0; Z]);
        if c < m {
            // central differences: the drives are a small difference of large pair forces
            let mut dp = [0.0; M];
            s.deriv(tau, &zp, &mut dp, &mut fp);
            s.deriv(tau, &zm, &mut dp, &mut fm);
        } else {
            // a velocity's column: the drives are the same
            s.rates(&zp, &d0, &mut fp);
            s.rates(&zm, &d0, &mut fm);
        }
        for &r in comps {
            jac[r][c] = (fp[r] - fm[r]) / dz;
        }
    }
    let t_abs = (s.t_ref + tau).abs();
    let dt = DIFF * t_abs.max(s.time_scale());
    let mut ft = [0.0; Z];
    {
        let mut dp = [0.0; M];
        let mut fp = [0.0; Z];
        s.deriv(tau + dt, z, &mut dp, &mut fp);
        for &r in comps {
            ft[r] = (fp[r] - f0[r]) / dt;
        }
    }
    let jnorm = comps
        .iter()
        .map(|&r| comps.iter().map(|&c| jac[r][c].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    // G = I / (h gamma) - J on the moving components, factored
    let mut g = [[0.0; Z]; Z];
    for (a, &r) in comps.iter().enumerate() {
        for (b, &c) in comps.iter().enumerate() {
            g[a][b] = -jac[r][c];
        }
        g[a][a] += 1.0 / (h * RODAS4_GAMMA);
    }
    let Some(lu) = Lu::new(g, nc) else {
        // singular: report a failed step (the caller halves it)
        return Step {
            z1: *z,
            f0,
            f1: f0,
            err: f64::INFINITY,
            stiffness: h * jnorm,
            exponent: 0.25,
        };
    };
    let weights = (s.opts.tol, m, s.vel_weight());
    let (z1, err) = rodas4_stages(z, h, comps, &f0, &ft, &lu, weights, &mut |t, y| {
        let mut d = [0.0; M];
        let mut f = [0.0; Z];
        s.deriv(tau + t, y, &mut d, &mut f);
        f
    });
    let mut d = [0.0; M];
    let mut f1 = [0.0; Z];
    s.deriv(tau + h, &z1, &mut d, &mut f1);
    Step {
        z1,
        f0,
        f1,
        err,
        stiffness: h * jnorm,
        exponent: 0.25,
    }
}
