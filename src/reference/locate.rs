//! Events of the reference model and where they happen. An event is an unknown switching
//! mode: a clamped one driven off its end (harder than its threshold), a free one reaching
//! an end of its range.
//!
//! **Location.** An accepted step whose end has event conditions true is searched on its
//! dense output ([`crate::reference`]'s `dense` module, of the step's own order or above)
//! for the first moment one of them holds: the step is cut there. The conditions of the
//! step's end are made continuous margins (a free unknown's distance to its end; a clamped
//! one's threshold less its drive, over the drive's scale), and the earliest root of their
//! minimum is bracketed by the Illinois method (regula falsi that halves the kept end's
//! value, with a bisection whenever a bracket fails to halve), to `1e-3` of the tolerance
//! times the step or less. A margin on the state costs nothing; one on a drive costs an
//! evaluation of the forces at the interpolated state, about 7 per event against the 20
//! full steps (140 evaluations) of bisection with full steps at 1e-6.

use crate::model::{condition, Forces, Mode, Model};
use crate::ode::locate::illinois;
use crate::ode::{Dense, StepStats};

/// The unknowns whose condition holds at state `y` with drives `drive`, into `out`;
/// whether there are any.
pub(crate) fn events_at(
    model: &Model,
    modes: &[Mode],
    y: &[f64],
    drive: &[f64],
    out: &mut Vec<usize>,
) -> bool {
    out.clear();
    out.extend(
        (0..model.len()).filter(|&i| condition(model, i, modes[i], y[i], drive[i]).is_some()),
    );
    !out.is_empty()
}

/// How far unknown `i` in `mode` is from its event at value `y` under `drive`: positive
/// before, zero or negative once its condition holds (a fraction of the range, or of the
/// drive's scale).
fn margin(model: &Model, i: usize, mode: Mode, y: f64, drive: f64) -> f64 {
    match mode {
        Mode::AtStart => (model.threshold(i) - drive) / model.drive_scale(i),
        Mode::AtEnd => (model.threshold(i) + drive) / model.drive_scale(i),
        Mode::Free if y >= 0.5 => 1.0 - y,
        Mode::Free => y,
    }
}

/// An accepted step to search for its first event.
pub(crate) struct StepEvents<'a> {
    /// The model.
    pub(crate) model: &'a Model,
    /// The unknowns' modes.
    pub(crate) modes: &'a [Mode],
    /// The step's dense output.
    pub(crate) dense: &'a Dense,
    /// The unknowns whose condition holds at the step's end ([`events_at`]).
    pub(crate) candidates: &'a [usize],
    /// The state and the drives at the step's start and at its end.
    pub(crate) ends: [(&'a [f64], &'a [f64]); 2],
    /// The tolerance.
    pub(crate) tol: f64,
}

impl StepEvents<'_> {
    /// The smallest margin of the candidates at fraction `th` of the step; the state there
    /// is left in `y` (and the drives in `work` when a candidate is clamped).
    fn margin(&self, th: f64, y: &mut [f64], work: &mut Forces, stats: &mut StepStats) -> f64 {
        self.dense.at(th, y);
        let clamped = self.candidates.iter().any(|&i| self.modes[i] != Mode::Free);
        if clamped {
            stats.rhs += 1;
            self.model.forces_moving(y, self.modes, work);
        }
        self.smallest(y, &work.drive)
    }

    /// The smallest margin of the candidates at state `y` with drives `drive`.
    fn smallest(&self, y: &[f64], drive: &[f64]) -> f64 {
        self.candidates
            .iter()
            .map(|&i| margin(self.model, i, self.modes[i], y[i], drive[i]))
            .fold(f64::INFINITY, f64::min)
    }

    /// The fraction of the step at which the first candidate's condition holds (within
    /// `1e-3` of the tolerance, or 1e-12 of the step at least), with the state there in
    /// `y`: the upper end of the final bracket, where a margin is zero or negative.
    pub(crate) fn first(&self, y: &mut [f64], work: &mut Forces, stats: &mut StepStats) -> f64 {
        let width = (1e-3 * self.tol).max(1e-12);
        let mut lo = 0.0;
        let mut g_lo = self.smallest(self.ends[0].0, self.ends[0].1);
        if g_lo <= 0.0 {
            // on a boundary at the start (an unknown just released from its end, which the
            // step brings back past it): the event is the first return, after the first
            // of 16 points where every margin is positive; with none, the unknown never
            // left its end, and the step is cut at the first point
            let mut left = None;
            for m in 1..16 {
                let th = f64::from(m) / 16.0;
                let g = self.margin(th, y, work, stats);
                if g > 0.0 {
                    left = Some((th, g));
                    break;
                }
            }
            let Some((th, g)) = left else {
                self.dense.at(1.0 / 16.0, y);
                return 1.0 / 16.0;
            };
            lo = th;
            g_lo = g;
        }
        let g_hi = self.smallest(self.ends[1].0, self.ends[1].1).min(0.0);
        let hi = illinois((lo, g_lo), (1.0, g_hi), width, |th| {
            self.margin(th, y, work, stats)
        });
        self.dense.at(hi, y);
        hi
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::ode::{Method, StepControl, Stepper};
    use crate::reference::driver::Moving;

    /// Whether an event holds at the end of a full step of `h` from `y0` (rates `f0`).
    fn event_after(
        sys: &Moving,
        stepper: &mut Stepper<Forces>,
        (y0, f0): (&[f64], &[f64]),
        h: f64,
        stats: &mut StepStats,
    ) -> bool {
        let mut y1 = vec![0.0; y0.len()];
        stepper
            .attempt(sys, y0, f0, h, 1.0, stats, &mut y1)
            .unwrap();
        let mut work = Forces::default();
        sys.model.forces(&y1, &mut work);
        let mut c = Vec::new();
        events_at(sys.model, sys.modes, &y1, &work.drive, &mut c)
    }

    #[test]
    fn events_on_the_dense_output_agree_with_bisection_on_full_steps() {
        // the three-tile SL at s = 0.3: magnet 0 starts at once (the RI pulls it); step
        // with the driver's controller at 1e-8 until a step ends past the first events (a
        // start, then an arrival), then locate each both ways: on the step's dense output,
        // and by bisection on the step's length, each trial a full step from the same start
        // (the old location, to 1e-12 of the step)
        let model = Model::thesis("SL", 0.3);
        let n = model.len();
        let tol = 1e-8;
        let mut modes = vec![Mode::AtStart; n];
        let mut y = vec![0.0; n];
        let mut work = Forces::default();
        model.forces(&y, &mut work);
        modes[model.magnet_var(0)] = Mode::Free;
        let mut stepper: Stepper<Forces> = Stepper::new(Method::Dopri5, n, model.bandwidth());
        let mut stats = StepStats::default();
        let mut control = StepControl::new(4);
        let mut h = model.time_scale * 1e-4;
        let (mut f, mut f1, mut y1) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut located = 0;
        for _ in 0..10_000 {
            let sys = Moving {
                model: &model,
                modes: &modes,
            };
            stepper.rhs(&sys, &y, &mut f, &mut stats);
            let drive0 = stepper.work().drive.clone();
            let err = stepper
                .attempt(&sys, &y, &f, h, tol, &mut stats, &mut y1)
                .unwrap();
            if err > 1.0 {
                h *= control.reject(err);
                continue;
            }
            let grow = control.accept(h, err);
            f1.copy_from_slice(stepper.last_derivative().unwrap());
            let drive1 = stepper.work().drive.clone();
            let mut cands = Vec::new();
            if !events_at(&model, &modes, &y1, &drive1, &mut cands) {
                std::mem::swap(&mut y, &mut y1);
                h *= grow;
                continue;
            }
            let mut dense = Dense::default();
            dense.set(&y, &y1, &f, &f1, h, Some(stepper.stages()));
            let mut y_ev = vec![0.0; n];
            let th = StepEvents {
                model: &model,
                modes: &modes,
                dense: &dense,
                candidates: &cands,
                ends: [(&y, &drive0), (&y1, &drive1)],
                tol,
            }
            .first(&mut y_ev, &mut work, &mut stats);
            let (mut lo, mut hi) = (0.0, h);
            while hi - lo > 1e-12 * h {
                let mid = 0.5 * (lo + hi);
                if event_after(&sys, &mut stepper, (&y, &f), mid, &mut stats) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            // the two agree: the states there within the tolerance (3e-14 and 1e-10
            // measured), the times within 1e-4 of the step (8e-7 and 5e-6 measured: a
            // start is a drive crossing its threshold slowly, so a state 1e-10 off moves
            // it by that much)
            let mut y_full = vec![0.0; n];
            stepper
                .attempt(&sys, &y, &f, hi, tol, &mut stats, &mut y_full)
                .unwrap();
            let apart = y_ev
                .iter()
                .zip(&y_full)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(apart < tol, "{apart}");
            assert!((th * h - hi).abs() < 1e-4 * h, "{} {hi} (h {h})", th * h);
            assert!(th > 0.0 && th < 1.0, "{th}");
            let i = cands[0];
            located += 1;
            // switch as the driver does, then go on from the event
            model.forces(&y_ev, &mut work);
            for &i in &cands {
                if let Some(next) = condition(&model, i, modes[i], y_ev[i], work.drive[i]) {
                    modes[i] = next;
                    match next {
                        Mode::AtEnd => y_ev[i] = 1.0,
                        Mode::AtStart => y_ev[i] = 0.0,
                        Mode::Free => {}
                    }
                }
            }
            assert!(modes[i] != Mode::AtStart || y_ev[i] == 0.0);
            y = y_ev;
            if located == 3 {
                break;
            }
        }
        assert_eq!(located, 3);
    }
}
