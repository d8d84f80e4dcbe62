//! The Rosenbrock (linearly implicit) methods, for stiff stretches: each step solves linear
//! systems with `I - gamma h J` instead of iterating a nonlinear one, and stays stable where
//! Dormand-Prince's step would be bounded by the stiffest eigenvalue.
//!
//! - **ROS2** (Verwer, Spee, Blom and Hundsdorfer 1999), on a [`Stepper`] for whole-chain
//!   states: two stages, second order, L-stable, `gamma = 1 + 1/sqrt2`, the first-order
//!   `y + h k1` as the embedded solution. It is second order for any approximation of the
//!   Jacobian (a W-method), so the finite-difference banded Jacobian ([`Band`]) costs no
//!   accuracy. Each step solves two band systems with one factorisation.
//! - **RODAS4** (Hairer and Wanner, *Solving Ordinary Differential Equations II*, section
//!   IV.7), for a few components in arrays ([`rodas4_stages`], the small dense [`Lu`]): six
//!   stages, stiffly accurate and L-stable, order 4 with an embedded order-3 estimate.
//!   `G K_i = f(t0 + alpha_i h, Y_i) + sum_j C_ij / h K_j + gamma_i h df/dt`,
//!   `G = I / (h gamma) - J`, `Y_i = y0 + sum_j A_ij K_j`, `y1 = y0 + sum_j M_j K_j`, error
//!   `K_6` (the coefficients as in Hairer's `rodas.f`, in the `G`-scaled form of Sandu's KPP
//!   integrators). The caller supplies `J` and `df/dt` (the event engine's units take forward
//!   and central differences of their drives).
//!
//! Both are written here rather than taken from a crate: the systems are small or banded, the
//! events are the model's own (modes that clamp unknowns), and a general ODE crate (diffsol)
//! would add minutes of build time on a two-core machine for no gain at these sizes.

use std::fmt::Debug;

use crate::ode::band::Singular;
use crate::ode::stepper::StepStart;
use crate::ode::{StepStats, Stepper, System};

/// ROS2's diagonal `gamma`.
const ROS2_GAMMA: f64 = 1.0 + std::f64::consts::FRAC_1_SQRT_2;

impl<W: Default + Debug> Stepper<W> {
    fn jacobian<S: System<Work = W>>(
        &mut self,
        sys: &S,
        y0: &[f64],
        f0: &[f64],
        stats: &mut StepStats,
    ) {
        let n = y0.len();
        let bw = sys.bandwidth();
        let groups = (2 * bw + 1).min(n);
        self.jac.clear();
        stats.jacobians += 1;
        let mut y = std::mem::take(&mut self.jac_y);
        let mut f = std::mem::take(&mut self.jac_f);
        let delta = |x: f64| if x > 0.5 { -1e-7 } else { 1e-7 };
        for g in 0..groups {
            y.copy_from_slice(y0);
            let mut c = g;
            while c < n {
                y[c] += delta(y0[c]);
                c += groups;
            }
            self.rhs(sys, &y, &mut f, stats);
            let mut c = g;
            while c < n {
                let d = delta(y0[c]);
                let lo = c.saturating_sub(bw);
                let hi = (c + bw).min(n - 1);
                for (i, fi) in f.iter().enumerate().take(hi + 1).skip(lo) {
                    self.jac.set(i, c, (fi - f0[i]) / d);
                }
                c += groups;
            }
        }
        self.jac_y = y;
        self.jac_f = f;
        self.jac_fresh = true;
    }

    pub(super) fn ros2<S: System<Work = W>>(
        &mut self,
        sys: &S,
        from: StepStart<'_>,
        stats: &mut StepStats,
        y: &mut [f64],
    ) -> Result<f64, Singular> {
        let StepStart { y0, f0, h, tol } = from;
        let n = y0.len();
        if !self.jac_fresh {
            self.jacobian(sys, y0, f0, stats);
        }
        let bw = sys.bandwidth();
        self.lu.clear();
        for i in 0..n {
            for j in i.saturating_sub(bw)..=(i + bw).min(n - 1) {
                let id = if i == j { 1.0 } else { 0.0 };
                self.lu.set(i, j, id - ROS2_GAMMA * h * self.jac.get(i, j));
            }
        }
        stats.factorisations += 1;
        self.lu.factor()?;
        // the two stages live in the first two of Dormand-Prince's stage vectors
        let mut k1 = std::mem::take(&mut self.k[0]);
        let mut k2 = std::mem::take(&mut self.k[1]);
        k1.copy_from_slice(f0);
        self.lu.solve(&mut k1);
        for i in 0..n {
            self.tmp[i] = y0[i] + h * k1[i];
        }
        let tmp = std::mem::take(&mut self.tmp);
        self.rhs(sys, &tmp, &mut k2, stats);
        self.tmp = tmp;
        for i in 0..n {
            k2[i] -= 2.0 * k1[i];
        }
        self.lu.solve(&mut k2);
        let mut sum = 0.0;
        let mut count = 0usize;
        for i in 0..n {
            y[i] = y0[i] + h * (1.5 * k1[i] + 0.5 * k2[i]);
            if sys.counts(i) {
                let e = 0.5 * h * (k1[i] + k2[i]);
                let sc = tol * (1.0 + y0[i].abs().max(y[i].abs()));
                sum += (e / sc).powi(2);
                count += 1;
            }
        }
        self.k[0] = k1;
        self.k[1] = k2;
        Ok(if count == 0 {
            0.0
        } else {
            (sum / count as f64).sqrt()
        })
    }
}

// RODAS4

/// Stages.
const S: usize = 6;
/// The diagonal `gamma`.
pub(crate) const RODAS4_GAMMA: f64 = 0.25;
/// Stage times (fractions of the step).
const ALPHA: [f64; S] = [0.0, 0.386, 0.21, 0.63, 1.0, 1.0];
/// Sums `gamma_i` of the stages' `gamma_ij` (weights of `df/dt`).
const GAMMA_I: [f64; S] = [0.25, -0.1043, 0.1035, -0.036_200_000_000_000_23, 0.0, 0.0];
/// The first four weights of the solution, also the last two stages' (stiffly accurate:
/// the fifth stage is the order-3 solution, the last the order-4 one).
const W1: f64 = 1.221_224_509_226_641;
const W2: f64 = 6.019_134_481_288_629;
const W3: f64 = 12.537_083_329_320_87;
const W4: f64 = -0.687_886_036_105_895;
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
    [W1, W2, W3, W4, 0.0, 0.0],
    [W1, W2, W3, W4, 1.0, 0.0],
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
const MW: [f64; S] = [W1, W2, W3, W4, 1.0, 1.0];

/// The stages of a RODAS4 step of `h` from `z` on the components `comps`, given `f0 = f(0, z)`,
/// `ft = df/dt` there, the factors of `G` and `f(t, y)` (`t` from the step's start): the new
/// state and the error's RMS in tolerances `tol` (relative to `1 + |z|`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn rodas4_stages<const Z: usize>(
    z: &[f64; Z],
    h: f64,
    comps: &[usize],
    f0: &[f64; Z],
    ft: &[f64; Z],
    lu: &Lu<Z>,
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

/// The LU factors (partial pivoting) of a small dense matrix (RODAS4's `G` on a unit's few
/// components).
pub(crate) struct Lu<const Z: usize> {
    a: [[f64; Z]; Z],
    perm: [usize; Z],
    n: usize,
}

impl<const Z: usize> Lu<Z> {
    /// Factors the leading `n` by `n` block of `a`; `None` when singular.
    pub(crate) fn new(mut a: [[f64; Z]; Z], n: usize) -> Option<Lu<Z>> {
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
    pub(crate) fn solve(&self, b: [f64; Z]) -> [f64; Z] {
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

    const Z: usize = 6;

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
            g[0][0] = 1.0 / (h * RODAS4_GAMMA) + lambda;
            let lu: Lu<Z> = Lu::new(g, 1).unwrap();
            let (z1, _) = rodas4_stages(&z, h, &[0], &f0, &ft, &lu, (1e-8, 1, 1.0), &mut |t, y| {
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
        let lu: Lu<Z> = Lu::new(a, 3).unwrap();
        let mut b = [0.0; Z];
        b[0] = 4.0;
        b[1] = 5.0;
        b[2] = 8.0;
        let x = lu.solve(b);
        assert!((x[0] - 1.0).abs() < 1e-14 && (x[1] - 2.0).abs() < 1e-14);
        assert!((x[2] - 2.0).abs() < 1e-14);
    }
}
