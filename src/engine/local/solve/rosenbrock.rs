//! One RODAS4 step of a unit's state (Hairer and Wanner, *Solving Ordinary Differential
//! Equations II*, section IV.7: a stiffly accurate, L-stable Rosenbrock method of order 4
//! with an embedded order-3 estimate), for the stretches where a unit is stiff.
//!
//! **Where a unit is stiff.** A folding joint that swings a long tail turns slowly (its
//! inertia grows with the tiles it swings), while the magnets of its pair, nearly closed,
//! follow the balance the turning fold moves, relaxing to it at their own fast rate (the
//! drag over the mass, about 190 per second for the thesis magnets, and the pair's magnetic
//! stiffness). Dormand-Prince's stability region then bounds its step by about
//! `3.3 / |lambda|` however smooth the motion: thousands of steps for a fold of a 100,000-tile
//! chain's first U-turn. An L-stable method steps at the pace the fold's accuracy asks.
//!
//! **The step.** `G K_i = f(t0 + alpha_i h, Y_i) + sum_j C_ij / h K_j + gamma_i h df/dt`,
//! `G = I / (h gamma) - J`, `Y_i = y0 + sum_j A_ij K_j`, `y1 = y0 + sum_j M_j K_j`, error
//! `K_6` (the coefficients as in Hairer's `rodas.f`, in the `G`-scaled form of Sandu's KPP
//! integrators). `J` and `df/dt` are forward differences at the step's start: one drive
//! evaluation per free position and one in time (a velocity's column needs none: the drives
//! depend on the positions only). The dense output is the cubic Hermite on the step's ends,
//! as for Dormand-Prince, so events are located the same way.

use crate::engine::local::solve::step::Step;
use crate::engine::local::solve::{Solver, M, Z};

/// Stages.
const S: usize = 6;
/// The diagonal `gamma`.
const GAMMA: f64 = 0.25;
/// Stage times (fractions of the step).
const ALPHA: [f64; S] = [0.0, 0.386, 0.21, 0.63, 1.0, 1.0];
/// Sums `gamma_i` of the stages' `gamma_ij` (weights of `df/dt`).
const GAMMA_I: [f64; S] = [0.25, -0.1043, 0.1035, -0.036_200_000_000_000_23, 0.0, 0.0];
/// `A_ij`, row by row (`j < i`).
const A: [[f64; S]; S] = [
    [0.0; S],
    [1.544, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        0.946_678_528_081_582_6,
        0.255_701_169_898_328_4,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        3.314_825_187_068_521,
        2.896_124_015_972_201,
        0.998_641_913_997_781_7,
        0.0,
        0.0,
        0.0,
    ],
    [
        1.221_224_509_226_641,
        6.019_134_481_288_629,
        12.537_083_329_320_87,
        -0.687_886_036_105_895,
        0.0,
        0.0,
    ],
    [
        1.221_224_509_226_641,
        6.019_134_481_288_629,
        12.537_083_329_320_87,
        -0.687_886_036_105_895,
        1.0,
        0.0,
    ],
];
/// `C_ij`, row by row (`j < i`).
const C: [[f64; S]; S] = [
    [0.0; S],
    [-5.6688, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        -2.430_093_356_833_875,
        -0.206_359_915_709_191_5,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        -0.107_352_905_815_137_5,
        -9.594_562_251_023_355,
        -20.470_286_148_096_16,
        0.0,
        0.0,
        0.0,
    ],
    [
        7.496_443_313_967_647,
        -10.246_804_314_643_52,
        -33.999_903_528_199_05,
        11.708_908_932_061_6,
        0.0,
        0.0,
    ],
    [
        8.083_246_795_921_522,
        -7.981_132_988_064_893,
        -31.521_594_328_743_71,
        16.319_305_431_231_36,
        -6.058_818_238_834_054,
        0.0,
    ],
];
/// Weights of the solution (`y1 = Y_6 + K_6`: stiffly accurate).
const MW: [f64; S] = [
    1.221_224_509_226_641,
    6.019_134_481_288_629,
    12.537_083_329_320_87,
    -0.687_886_036_105_895,
    1.0,
    1.0,
];

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
        g[a][a] += 1.0 / (h * GAMMA);
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
    let (z1, err) = stages(z, h, comps, &f0, &ft, &lu, weights, &mut |t, y| {
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

/// The stages of a step of `h` from `z` on the components `comps`, given `f0 = f(0, z)`,
/// `ft = df/dt` there, the factors of `G` and `f(t, y)` (`t` from the step's start): the new
/// state and the error's RMS in tolerances `tol` (relative to `1 + |z|`).
#[allow(clippy::too_many_arguments)]
fn stages(
    z: &[f64; Z],
    h: f64,
    comps: &[usize],
    f0: &[f64; Z],
    ft: &[f64; Z],
    lu: &Lu,
    (tol, m, vw): (f64, usize, f64),
    f: &mut impl FnMut(f64, &[f64; Z]) -> [f64; Z],
) -> ([f64; Z], f64) {
    let mut k = [[0.0; Z]; S];
    for st in 0..S {
        // the stage's state
        let mut y = *z;
        for (j, kj) in k.iter().enumerate().take(st) {
            let a = A[st][j];
            if a != 0.0 {
                for &c in comps {
                    y[c] += a * kj[c];
                }
            }
        }
        let fs = if st == 0 { *f0 } else { f(ALPHA[st] * h, &y) };
        let mut rhs = [0.0; Z];
        for (a, &c) in comps.iter().enumerate() {
            let mut v = fs[c] + GAMMA_I[st] * h * ft[c];
            for (j, kj) in k.iter().enumerate().take(st) {
                v += C[st][j] / h * kj[c];
            }
            rhs[a] = v;
        }
        let sol = lu.solve(rhs);
        for (a, &c) in comps.iter().enumerate() {
            k[st][c] = sol[a];
        }
    }
    let mut z1 = *z;
    for (j, kj) in k.iter().enumerate() {
        for &c in comps {
            z1[c] += MW[j] * kj[c];
        }
    }
    let mut sum = 0.0;
    for &c in comps {
        let w = if c >= m { vw } else { 1.0 };
        let sc = tol * (1.0 + w * z[c].abs().max(z1[c].abs()));
        sum += (w * k[S - 1][c] / sc).powi(2);
    }
    (z1, (sum / comps.len().max(1) as f64).sqrt())
}

/// The LU factors (partial pivoting) of a small matrix.
struct Lu {
    a: [[f64; Z]; Z],
    perm: [usize; Z],
    n: usize,
}

impl Lu {
    /// Factors the leading `n` by `n` block of `a`; `None` when singular.
    fn new(mut a: [[f64; Z]; Z], n: usize) -> Option<Lu> {
        let mut perm = [0usize; Z];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        for col in 0..n {
            let piv = (col..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))?;
            if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
                return None;
            }
            a.swap(col, piv);
            perm.swap(col, piv);
            let pivot_row = a[col];
            for row in a.iter_mut().take(n).skip(col + 1) {
                let f = row[col] / pivot_row[col];
                row[col] = f;
                for (x, p) in row.iter_mut().zip(pivot_row).take(n).skip(col + 1) {
                    *x -= f * p;
                }
            }
        }
        Some(Lu { a, perm, n })
    }

    /// Solves `A x = b` on the leading `n` components.
    fn solve(&self, b: [f64; Z]) -> [f64; Z] {
        let n = self.n;
        let mut x = [0.0; Z];
        for i in 0..n {
            x[i] = b[self.perm[i]];
        }
        for i in 0..n {
            for j in 0..i {
                x[i] -= self.a[i][j] * x[j];
            }
        }
        for i in (0..n).rev() {
            for j in i + 1..n {
                x[i] -= self.a[i][j] * x[j];
            }
            x[i] /= self.a[i][i];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y' = -lambda (y - cos t) - sin t` from `y(0) = 1` (exactly `cos t`) over [0, 1] in
    /// `n` steps: the error at the end.
    fn cosine_error(lambda: f64, n: usize) -> f64 {
        let h = 1.0 / n as f64;
        let rhs = |t: f64, y: f64| -lambda * (y - t.cos()) - t.sin();
        let mut y = 1.0;
        for i in 0..n {
            let t0 = i as f64 * h;
            let mut z = [0.0; Z];
            z[0] = y;
            let mut f0 = [0.0; Z];
            f0[0] = rhs(t0, y);
            let mut ft = [0.0; Z];
            ft[0] = -lambda * t0.sin() - t0.cos();
            let mut g = [[0.0; Z]; Z];
            g[0][0] = 1.0 / (h * GAMMA) + lambda;
            let lu = Lu::new(g, 1).unwrap();
            let (z1, _) = stages(&z, h, &[0], &f0, &ft, &lu, (1e-8, 1, 1.0), &mut |t, y| {
                let mut f = [0.0; Z];
                f[0] = rhs(t0 + t, y[0]);
                f
            });
            y = z1[0];
        }
        (y - 1f64.cos()).abs()
    }

    #[test]
    fn rodas4_is_fourth_order_and_stable_when_stiff() {
        // non-stiff: halving the step divides the error by about 2^4
        let (e1, e2) = (cosine_error(1.0, 20), cosine_error(1.0, 40));
        assert!(e2 < 1e-7, "{e1} {e2}");
        let ratio = e1 / e2;
        assert!((12.0..24.0).contains(&ratio), "{e1} {e2} {ratio}");
        // very stiff (lambda h = 5e4): no blow-up, the solution follows cos t closely
        let e = cosine_error(1e6, 20);
        assert!(e < 1e-8, "{e}");
    }

    #[test]
    fn lu_solves_a_small_system() {
        let mut a = [[0.0; Z]; Z];
        a[0][0] = 0.0;
        a[0][1] = 2.0;
        a[1][0] = 3.0;
        a[1][1] = 1.0;
        a[2][2] = 4.0;
        let lu = Lu::new(a, 3).unwrap();
        let mut b = [0.0; Z];
        b[0] = 4.0;
        b[1] = 5.0;
        b[2] = 8.0;
        let x = lu.solve(b);
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 2.0).abs() < 1e-14);
        assert!((x[2] - 2.0).abs() < 1e-14);
    }
}
