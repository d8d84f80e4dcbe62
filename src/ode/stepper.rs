//! One step of a system of many unknowns with an error estimate ([`Stepper`]), by either
//! integrator ([`Method`]): Dormand-Prince 5(4) ([`crate::ode::dopri`](super::dopri)) or
//! ROS2 with a banded Jacobian ([`crate::ode::rosenbrock`](super::rosenbrock)). Step-size
//! control ([`crate::ode::StepControl`]) and events belong to the stepping loop that calls it.
//! Nothing is allocated per step.

use std::fmt::Debug;

use crate::ode::band::{Band, Singular};
use crate::ode::dopri;

/// An integrator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Dormand-Prince 5(4), explicit.
    Dopri5,
    /// ROS2, linearly implicit (Rosenbrock), for stiff cases.
    Ros2,
}

impl Method {
    /// The name used in tables and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Method::Dopri5 => "dopri5",
            Method::Ros2 => "ros2",
        }
    }

    /// The order of the embedded (error) solution, for the step-size law.
    pub fn error_order(self) -> i32 {
        match self {
            Method::Dopri5 => 4,
            Method::Ros2 => 1,
        }
    }
}

/// Work counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct StepStats {
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Right-hand-side evaluations (all of them, Jacobians and event location included).
    pub rhs: u64,
    /// Jacobian evaluations.
    pub jacobians: u64,
    /// LU factorisations.
    pub factorisations: u64,
    /// Trial steps spent locating events.
    pub event_steps: u64,
}

/// A system `dy/dt = f(y)` the integrators step: the reference model with its unknowns'
/// modes, or a test problem.
pub(crate) trait System {
    /// Scratch space of one evaluation of `f`.
    type Work: Default + Debug;
    /// Half-bandwidth of the Jacobian: unknowns farther apart never interact.
    fn bandwidth(&self) -> usize;
    /// Whether unknown `i` counts in the error estimate (it moves freely).
    fn counts(&self, i: usize) -> bool;
    /// `f(y)` into `out`.
    fn rhs(&self, y: &[f64], work: &mut Self::Work, out: &mut [f64]);
}

/// Where a step attempt starts: the state `y0`, its rates `f0 = dy/dt(y0)`, the step size
/// `h` and the tolerance `tol`.
#[derive(Clone, Copy)]
pub(super) struct StepStart<'a> {
    pub(super) y0: &'a [f64],
    pub(super) f0: &'a [f64],
    pub(super) h: f64,
    pub(super) tol: f64,
}

/// One integrator's working storage for a system of `n` unknowns with scratch `W`: nothing
/// is allocated per step.
#[derive(Debug)]
pub(crate) struct Stepper<W> {
    /// The method.
    pub(crate) method: Method,
    pub(super) k: [Vec<f64>; 7],
    pub(super) tmp: Vec<f64>,
    pub(super) work: W,
    pub(super) jac: Band,
    pub(super) lu: Band,
    pub(super) jac_fresh: bool,
    /// Scratch of the Jacobian's differences: a state and its rates.
    pub(super) jac_y: Vec<f64>,
    pub(super) jac_f: Vec<f64>,
}

impl<W: Default + Debug> Stepper<W> {
    /// Storage for `n` unknowns whose Jacobian has half-bandwidth `bandwidth`.
    pub(crate) fn new(method: Method, n: usize, bandwidth: usize) -> Stepper<W> {
        Stepper {
            method,
            k: std::array::from_fn(|_| vec![0.0; n]),
            tmp: vec![0.0; n],
            work: W::default(),
            jac: Band::zeros(n, bandwidth, bandwidth),
            lu: Band::zeros(n, bandwidth, bandwidth),
            jac_fresh: false,
            jac_y: vec![0.0; n],
            jac_f: vec![0.0; n],
        }
    }

    /// Forgets the Jacobian (the state or the modes changed).
    pub(crate) fn invalidate(&mut self) {
        self.jac_fresh = false;
    }

    /// The scratch of the last evaluation of `f` (for the model: the drives there; after a
    /// Dormand-Prince step, at the step's new state).
    pub(crate) fn work(&self) -> &W {
        &self.work
    }

    /// The scratch of `f`, to evaluate the system's forces elsewhere with it (the model's
    /// drives near the free unknowns only, [`crate::model::Model`]).
    pub(crate) fn work_mut(&mut self) -> &mut W {
        &mut self.work
    }

    /// The stages of the last Dormand-Prince step (`[0]` the rates at its start, `[6]` at
    /// its end), for its dense output ([`crate::reference::dense`]).
    pub(crate) fn stages(&self) -> &[Vec<f64>] {
        &self.k[..]
    }

    /// `dy/dt` at `y`.
    pub(crate) fn rhs<S: System<Work = W>>(
        &mut self,
        sys: &S,
        y: &[f64],
        out: &mut [f64],
        stats: &mut StepStats,
    ) {
        stats.rhs += 1;
        sys.rhs(y, &mut self.work, out);
    }

    /// One step of size `h` from `y0` (with `f0 = dy/dt(y0)`), tolerance `tol`: the new
    /// state into `y1`; returns the weighted RMS error over the free unknowns (accept when
    /// <= 1).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn attempt<S: System<Work = W>>(
        &mut self,
        sys: &S,
        y0: &[f64],
        f0: &[f64],
        h: f64,
        tol: f64,
        stats: &mut StepStats,
        y1: &mut [f64],
    ) -> Result<f64, Singular> {
        let from = StepStart { y0, f0, h, tol };
        match self.method {
            Method::Dopri5 => Ok(self.dopri5(sys, from, stats, y1)),
            Method::Ros2 => self.ros2(sys, from, stats, y1),
        }
    }

    fn dopri5<S: System<Work = W>>(
        &mut self,
        sys: &S,
        from: StepStart<'_>,
        stats: &mut StepStats,
        y: &mut [f64],
    ) -> f64 {
        let StepStart { y0, f0, h, tol } = from;
        let n = y0.len();
        self.k[0].copy_from_slice(f0);
        let mut k = std::mem::take(&mut self.k);
        dopri::stages(y0, h, &mut k, y, None, |_, y, out| {
            self.rhs(sys, y, out, stats)
        });
        self.k = k;
        // y is now the fifth-order solution (row 6 of A is b)
        let mut sum = 0.0;
        let mut count = 0usize;
        for i in 0..n {
            if !sys.counts(i) {
                continue;
            }
            let e = dopri::error_rate(&self.k, i);
            let sc = tol * (1.0 + y0[i].abs().max(y[i].abs()));
            sum += (h * e / sc).powi(2);
            count += 1;
        }
        if count == 0 {
            0.0
        } else {
            (sum / count as f64).sqrt()
        }
    }

    /// The last stage's derivative, `dy/dt` at the new state (Dormand-Prince only).
    pub(crate) fn last_derivative(&self) -> Option<&[f64]> {
        (self.method == Method::Dopri5).then(|| self.k[6].as_slice())
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use std::f64::consts::PI;

    use super::*;

    /// `y' = k A y`, `A` = tridiagonal(1, -2, 1) on `n` unknowns (a diffusion line): banded
    /// with half-bandwidth 1, eigenvectors `v_m(i) = sin((i + 1) m pi / (n + 1))` with
    /// eigenvalues `k (2 cos(m pi / (n + 1)) - 2)`, so `y(t)` is known exactly.
    struct Diffusion {
        n: usize,
        k: f64,
    }

    impl Diffusion {
        fn mode(&self, m: usize) -> (f64, Vec<f64>) {
            let th = m as f64 * PI / (self.n + 1) as f64;
            let v = (0..self.n).map(|i| ((i + 1) as f64 * th).sin()).collect();
            (self.k * (2.0 * th.cos() - 2.0), v)
        }

        /// The slowest and the fastest mode, each with amplitude 1, at time `t`.
        fn exact(&self, t: f64) -> Vec<f64> {
            let ((l1, v1), (l2, v2)) = (self.mode(1), self.mode(self.n));
            (0..self.n)
                .map(|i| (l1 * t).exp() * v1[i] + (l2 * t).exp() * v2[i])
                .collect()
        }
    }

    impl System for Diffusion {
        type Work = ();

        fn bandwidth(&self) -> usize {
            1
        }

        fn counts(&self, _: usize) -> bool {
            true
        }

        fn rhs(&self, y: &[f64], _: &mut (), out: &mut [f64]) {
            for i in 0..self.n {
                let left = if i > 0 { y[i - 1] } else { 0.0 };
                let right = if i + 1 < self.n { y[i + 1] } else { 0.0 };
                out[i] = self.k * (left - 2.0 * y[i] + right);
            }
        }
    }

    const LINE: Diffusion = Diffusion { n: 8, k: 1.0 };

    /// The largest error at t = 2 after `steps` equal steps of `method`.
    fn global_error(method: Method, steps: usize) -> f64 {
        let mut stepper: Stepper<()> = Stepper::new(method, LINE.n, 1);
        let mut stats = StepStats::default();
        let h = 2.0 / steps as f64;
        let mut y = LINE.exact(0.0);
        let mut f = vec![0.0; LINE.n];
        for _ in 0..steps {
            stepper.rhs(&LINE, &y, &mut f, &mut stats);
            let mut y1 = vec![0.0; LINE.n];
            stepper
                .attempt(&LINE, &y, &f, h, 1.0, &mut stats, &mut y1)
                .unwrap();
            y = y1;
            stepper.invalidate();
        }
        let exact = LINE.exact(2.0);
        y.iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// The observed orders of `method` on halving its step twice from `steps` steps: the
    /// base-2 logarithms of the global error's ratios.
    fn observed_orders(method: Method, steps: usize) -> [f64; 2] {
        let e: Vec<f64> = [steps, 2 * steps, 4 * steps]
            .iter()
            .map(|&n| global_error(method, n))
            .collect();
        [(e[0] / e[1]).log2(), (e[1] / e[2]).log2()]
    }

    #[test]
    fn dormand_prince_is_fifth_order() {
        // h = 1/16 to 1/64 (h |lambda| 0.24 to 0.06 on the fastest mode): 5.28 and 5.14
        // measured, closing on 5 as the step shrinks (an error of 1e-12 at the smallest, far
        // above rounding)
        for p in observed_orders(Method::Dopri5, 32) {
            assert!((p - 5.0).abs() < 0.35, "{p}");
        }
    }

    #[test]
    fn ros2_is_second_order_with_its_finite_difference_jacobian() {
        // h = 1/32 to 1/128: 1.84 and 1.90 measured, closing on 2 (the next term is about
        // 20 h of the leading one on the fastest mode)
        for p in observed_orders(Method::Ros2, 64) {
            assert!((p - 2.0).abs() < 0.2, "{p}");
        }
        // the banded Jacobian from 3 grouped differences is the matrix k A
        let mut stepper: Stepper<()> = Stepper::new(Method::Ros2, LINE.n, 1);
        let mut stats = StepStats::default();
        let y = LINE.exact(0.0);
        let mut f = vec![0.0; LINE.n];
        stepper.rhs(&LINE, &y, &mut f, &mut stats);
        stepper
            .attempt(&LINE, &y, &f, 0.1, 1.0, &mut stats, &mut [0.0; LINE.n])
            .unwrap();
        assert_eq!(stats.jacobians, 1);
        assert_eq!(stats.rhs, 1 + 3 + 1); // f0, three column groups, the second stage
        for i in 0..LINE.n {
            for j in 0..LINE.n {
                let want = match i.abs_diff(j) {
                    0 => -2.0,
                    1 => 1.0,
                    _ => 0.0,
                };
                assert!((stepper.jac.get(i, j) - want).abs() < 1e-7, "{i} {j}");
            }
        }
    }

    #[test]
    fn error_estimates_shrink_as_the_embedded_order_says() {
        // one step from the same state: the estimate goes as h^(q + 1), q the embedded order,
        // once h is small against the fastest mode (5.0 measured for Dormand-Prince at
        // h = 0.1; 1.94 for ROS2 at h = 0.005, whose next term is about 20 h of the leading)
        for (method, h) in [(Method::Dopri5, 0.1), (Method::Ros2, 0.005)] {
            let mut stepper: Stepper<()> = Stepper::new(method, LINE.n, 1);
            let mut stats = StepStats::default();
            let y = LINE.exact(0.0);
            let mut f = vec![0.0; LINE.n];
            stepper.rhs(&LINE, &y, &mut f, &mut stats);
            let est = |stepper: &mut Stepper<()>, h: f64, stats: &mut StepStats| {
                let mut y1 = vec![0.0; LINE.n];
                stepper
                    .attempt(&LINE, &y, &f, h, 1.0, stats, &mut y1)
                    .unwrap()
            };
            let (a, b) = (
                est(&mut stepper, h, &mut stats),
                est(&mut stepper, h / 2.0, &mut stats),
            );
            let p = (a / b).log2();
            let want = method.error_order() as f64 + 1.0;
            assert!((p - want).abs() < 0.2, "{method:?}: {p}");
        }
    }

    #[test]
    fn ros2_damps_a_stiff_mode_that_breaks_the_explicit_method() {
        // h |lambda| = 1e4 on the fastest mode: far outside Dormand-Prince's stability region,
        // while ROS2 (L-stable) damps it
        let stiff = Diffusion { n: 8, k: 2500.0 };
        for (method, stable) in [(Method::Ros2, true), (Method::Dopri5, false)] {
            let mut stepper: Stepper<()> = Stepper::new(method, stiff.n, 1);
            let mut stats = StepStats::default();
            let y0 = stiff.exact(0.0);
            let mut f = vec![0.0; stiff.n];
            stepper.rhs(&stiff, &y0, &mut f, &mut stats);
            let mut y1 = vec![0.0; stiff.n];
            stepper
                .attempt(&stiff, &y0, &f, 1.0, 1.0, &mut stats, &mut y1)
                .unwrap();
            let norm = |y: &[f64]| y.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert_eq!(norm(&y1) < norm(&y0), stable, "{method:?}: {}", norm(&y1));
        }
    }
}
