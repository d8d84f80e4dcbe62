//! Events of the reference model and where they happen. An event is an unknown switching
//! mode: a clamped one driven off its end (harder than its threshold), a free one reaching
//! an end of its range.
//!
//! **Location.** A step that ends with an event condition true is cut back by bisection on
//! its length, each trial a full step from the same start, until the bracket is shorter than
//! `tolerance` times the step (at least 8 and at most 60 halvings): event times are as
//! accurate as the tolerance asks, with no interpolant to trust.

use crate::reference::dynamics::{Forces, Mode, Model, Moving};
use crate::reference::integrators::{StepStats, Stepper};

/// The mode unknown `i` switches to from `mode` at value `y` under `drive`, if it switches.
pub(crate) fn condition(model: &Model, i: usize, mode: Mode, y: f64, drive: f64) -> Option<Mode> {
    match mode {
        Mode::AtStart if drive > model.threshold(i) => Some(Mode::Free),
        Mode::AtEnd if -drive > model.threshold(i) => Some(Mode::Free),
        Mode::Free if y >= 1.0 => Some(Mode::AtEnd),
        Mode::Free if y <= 0.0 => Some(Mode::AtStart),
        _ => None,
    }
}

/// Whether any unknown switches at state `y` (its drives are left in `work`).
pub(crate) fn any_event(model: &Model, modes: &[Mode], y: &[f64], work: &mut Forces) -> bool {
    model.forces(y, work);
    (0..model.len()).any(|i| condition(model, i, modes[i], y[i], work.drive[i]).is_some())
}

/// A step from one state, with what it needs to be taken again shorter.
pub(crate) struct StepFrom<'a> {
    /// The model and its modes.
    pub(crate) system: Moving<'a>,
    /// The state at the start.
    pub(crate) y: &'a [f64],
    /// Its rates.
    pub(crate) f: &'a [f64],
    /// The tolerance.
    pub(crate) tol: f64,
}

impl StepFrom<'_> {
    /// The first event in a step of length `h` whose end `y_end` has one: the step's length
    /// to the event (within the tolerance) and the state there.
    pub(crate) fn locate(
        &self,
        stepper: &mut Stepper<Forces>,
        h: f64,
        y_end: Vec<f64>,
        stats: &mut StepStats,
        work: &mut Forces,
    ) -> (f64, Vec<f64>) {
        let (mut lo, mut hi) = (0.0, h);
        let mut y_hi = y_end;
        let mut iters = 0;
        while iters < 60 && (iters < 8 || hi - lo > self.tol * h) {
            iters += 1;
            let mid = 0.5 * (lo + hi);
            stats.event_steps += 1;
            let Ok(a) = stepper.attempt(&self.system, self.y, self.f, mid, self.tol, stats) else {
                break;
            };
            stats.rhs += 1;
            if any_event(self.system.model, self.system.modes, &a.y, work) {
                hi = mid;
                y_hi = a.y;
            } else {
                lo = mid;
            }
        }
        (hi, y_hi)
    }
}
