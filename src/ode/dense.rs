//! The dense output of one accepted step: the state anywhere inside it without a new step,
//! which events are located on ([`crate::ode::locate`](super::locate)).
//!
//! - **Dormand-Prince**: its free continuous extension of order 4 (Hairer, Norsett and
//!   Wanner, *Solving ODEs I*, II.6; the coefficients of `dopri5.f`'s `CONTD5`,
//!   [`crate::ode::dopri::D`](super::dopri::D)), built from the seven stages the step already
//!   has, so it costs no evaluation of the right-hand side.
//! - **Cubic Hermite** on the step's ends (states and rates), of order 3: for the Rosenbrock
//!   methods, and for the event engine's small units whatever their method ([`hermite`], one
//!   component at a time; its tracks are Hermite pieces too).
//!
//! [`Dense`] writes both as `y0 + th (r1 + (1 - th) (r2 + th (r3 + (1 - th) r4)))` with
//! `th = (t - t0) / h`; the Hermite interpolant is the case `r4 = 0`.

use crate::ode::dopri::D;

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

/// The interpolant of one step (its storage is kept from step to step).
#[derive(Clone, Debug, Default)]
pub(crate) struct Dense {
    y0: Vec<f64>,
    r: [Vec<f64>; 4],
}

impl Dense {
    /// The interpolant of the step of length `h` from `y0` (rates `f0`) to `y1` (rates
    /// `f1`); `stages` the Dormand-Prince step's seven stages, or `None` for the cubic
    /// Hermite interpolant.
    pub(crate) fn set(
        &mut self,
        y0: &[f64],
        y1: &[f64],
        f0: &[f64],
        f1: &[f64],
        h: f64,
        stages: Option<&[Vec<f64>]>,
    ) {
        let n = y0.len();
        self.y0.clear();
        self.y0.extend_from_slice(y0);
        for r in &mut self.r {
            r.clear();
            r.resize(n, 0.0);
        }
        for i in 0..n {
            let dy = y1[i] - y0[i];
            let r2 = h * f0[i] - dy;
            self.r[0][i] = dy;
            self.r[1][i] = r2;
            self.r[2][i] = dy - h * f1[i] - r2;
            if let Some(k) = stages {
                let mut acc = 0.0;
                for (j, d) in D.iter().enumerate() {
                    acc += d * k[j][i];
                }
                self.r[3][i] = h * acc;
            }
        }
    }

    /// The state at fraction `th` of the step into `out`.
    pub(crate) fn at(&self, th: f64, out: &mut [f64]) {
        let th1 = 1.0 - th;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.y0[i]
                + th * (self.r[0][i]
                    + th1 * (self.r[1][i] + th * (self.r[2][i] + th1 * self.r[3][i])));
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::ode::{Method, StepStats, Stepper, System};

    /// `y' = -y + cos(3 t)` written autonomously (`t` is the second unknown): smooth, with
    /// a known solution from `y(0) = 1`.
    struct Forced;

    impl System for Forced {
        type Work = ();
        fn bandwidth(&self) -> usize {
            1
        }
        fn counts(&self, _: usize) -> bool {
            true
        }
        fn rhs(&self, y: &[f64], _: &mut (), out: &mut [f64]) {
            out[0] = -y[0] + (3.0 * y[1]).cos();
            out[1] = 1.0;
        }
    }

    fn exact(t: f64) -> f64 {
        // particular (cos 3t + 3 sin 3t) / 10 plus the homogeneous part
        (0.1 * ((3.0 * t).cos() + 3.0 * (3.0 * t).sin())) + 0.9 * (-t).exp()
    }

    /// The largest error of the dense output of one step of `h` from t = 0.2, at nine points
    /// inside it.
    fn dense_error(method: Method, h: f64) -> f64 {
        let mut stepper: Stepper<()> = Stepper::new(method, 2, 1);
        let mut stats = StepStats::default();
        let y0 = [exact(0.2), 0.2];
        let (mut f0, mut f1, mut y1) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        stepper.rhs(&Forced, &y0, &mut f0, &mut stats);
        stepper
            .attempt(&Forced, &y0, &f0, h, 1.0, &mut stats, &mut y1)
            .unwrap();
        stepper.rhs(&Forced, &y1, &mut f1, &mut stats);
        let mut dense = Dense::default();
        let stages = (method == Method::Dopri5).then(|| stepper.stages());
        dense.set(&y0, &y1, &f0, &f1, h, stages);
        let mut out = [0.0; 2];
        dense.at(0.0, &mut out);
        assert_eq!(out, y0);
        dense.at(1.0, &mut out);
        assert!((out[0] - y1[0]).abs() < 1e-15 && (out[1] - y1[1]).abs() < 1e-15);
        (1..10)
            .map(|m| {
                let th = m as f64 / 10.0;
                dense.at(th, &mut out);
                (out[0] - exact(0.2 + th * h)).abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn dense_outputs_have_their_orders() {
        // the local error of a dense output of order p goes as h^(p + 1): Dormand-Prince's
        // continuous extension is of order 4, ROS2's cubic Hermite of order 2 (the step's)
        for (method, order, h) in [(Method::Dopri5, 4.0, 0.1), (Method::Ros2, 2.0, 0.02)] {
            let (a, b) = (dense_error(method, h), dense_error(method, h / 2.0));
            let p = (a / b).log2();
            assert!(
                (p - (order + 1.0)).abs() < 0.4,
                "{method:?}: {p} ({a:e}, {b:e})"
            );
        }
    }
}
