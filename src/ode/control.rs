//! Step-size control on the error estimate `e` (in tolerances, accept when `e <= 1`) of an
//! embedded solution of order `q`.
//!
//! - [`integral`]: the classical law, `h * clamp(0.9 * e^-(1/(q+1)), 0.2, 5)` after an accepted
//!   step (5 when `e` is 0), `clamp(0.9 * e^-(1/(q+1)), 0.1, 0.9)` after a rejected one (0.1
//!   when `e` is not finite): the inertial reference and the event engine's units.
//! - [`StepControl`]: the overdamped reference's PI controller (Gustafsson; Hairer and
//!   Wanner, *Solving ODEs II*, IV.2; `dopri5.f`'s `BETA`).
//!
//! **The PI controller.** After an accepted step with error `e` (previous accepted error `e_old`) the next step is
//! `h * clamp(0.9 * e^-(1/(q+1) - 0.75 beta) * e_old^beta, 0.2, 5)`, `beta = 0.2 / (q + 1)`
//! (0.04 for Dormand-Prince, as in `dopri5.f`): the integral term alone is the classical
//! law, the proportional one damps the accept-reject-accept oscillation that law falls into
//! when the stability bound, not the accuracy, limits the step. After a rejection the step
//! shrinks by `clamp(0.9 * e^-(1/(q+1)), 0.1, 0.9)` and the next accepted step may not grow.
//! Gustafsson's predictive term (as in `radau5.f`) caps the factor at
//! `0.9 (h / h_prev) (e_prev / e^2)^(1/(q+1))`: when the errors grow from step to step (a
//! magnet speeding up towards its partner, as every arrival does) the steps shrink ahead of
//! the rejections the other terms would wait for.
//! The step size is kept across events: a located event cuts the step, not the next one.

/// The integral controller's factor on the step with error `err` and exponent
/// `expo = 1 / (q + 1)`: after an accepted step (`accepted`, `err <= 1`) or a rejected one.
pub(crate) fn integral(err: f64, expo: f64, accepted: bool) -> f64 {
    if accepted {
        if err > 0.0 {
            (0.9 * err.powf(-expo)).clamp(0.2, 5.0)
        } else {
            5.0
        }
    } else if err.is_finite() {
        (0.9 * err.powf(-expo)).clamp(0.1, 0.9)
    } else {
        0.1
    }
}

/// The PI controller's memory.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepControl {
    /// `1 / (q + 1)`.
    expo: f64,
    beta: f64,
    /// The last accepted error (at least 1e-4).
    err_old: f64,
    /// Whether the last attempt was rejected.
    rejected: bool,
    /// The last accepted step and its error (at least 1e-2), for the predictive term (0:
    /// none yet).
    h_acc: f64,
    err_acc: f64,
}

impl StepControl {
    /// A controller for an embedded solution of order `q`.
    pub(crate) fn new(q: i32) -> StepControl {
        let expo = 1.0 / (f64::from(q) + 1.0);
        StepControl {
            expo,
            beta: 0.2 * expo,
            err_old: 1e-4,
            rejected: false,
            h_acc: 0.0,
            err_acc: 1e-2,
        }
    }

    /// The factor on the step after an accepted step of `h` with error `err` (<= 1).
    pub(crate) fn accept(&mut self, h: f64, err: f64) -> f64 {
        let mut fac = if err > 0.0 {
            (0.9 * err.powf(-(self.expo - 0.75 * self.beta)) * self.err_old.powf(self.beta))
                .clamp(0.2, 5.0)
        } else {
            5.0
        };
        if self.h_acc > 0.0 && err > 0.0 {
            // Gustafsson's predictive term: errors growing from step to step (a magnet
            // speeding up towards its partner) shrink the step before a rejection does
            let gus = 0.9 * (h / self.h_acc) * (self.err_acc / (err * err)).powf(self.expo);
            fac = fac.min(gus.clamp(0.2, 5.0));
        }
        if self.rejected {
            fac = fac.min(1.0);
        }
        self.err_old = err.max(1e-4);
        self.h_acc = h;
        self.err_acc = err.max(1e-2);
        self.rejected = false;
        fac
    }

    /// The factor on the step after a rejected step with error `err` (> 1, or not finite).
    pub(crate) fn reject(&mut self, err: f64) -> f64 {
        self.rejected = true;
        if err.is_finite() {
            (0.9 * err.powf(-self.expo)).clamp(0.1, 0.9)
        } else {
            0.1
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grows_on_small_errors_shrinks_on_large_and_not_right_after_a_rejection() {
        let mut c = StepControl::new(4);
        assert_eq!(c.accept(1.0, 0.0), 5.0);
        let a = c.accept(1.0, 1e-3);
        assert!(a > 1.0 && a <= 5.0, "{a}");
        // a larger error now than before: a smaller factor than the integral law's alone
        let mut d = StepControl::new(4);
        d.accept(1.0, 1e-3);
        let pi = d.accept(1.0, 0.5);
        let i_only = 0.9 * 0.5f64.powf(-0.2);
        assert!(pi < i_only, "{pi} {i_only}");
        // steps already shrinking with errors growing: the predictive term shrinks it more
        let mut g = StepControl::new(4);
        g.accept(1.0, 0.3);
        let shrinking = g.accept(0.8, 0.6);
        assert!(shrinking < 0.8, "{shrinking}");
        let r = c.reject(10.0);
        assert!((0.1..0.9).contains(&r), "{r}");
        assert_eq!(c.reject(f64::NAN), 0.1);
        assert!(c.accept(1.0, 1e-6) <= 1.0);
        assert!(c.accept(1.0, 1e-6) > 1.0);
    }
}
