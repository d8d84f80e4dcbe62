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

use crate::reference::dense::Dense;
use crate::reference::dynamics::{Forces, Mode, Model};
use crate::reference::integrators::StepStats;

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
            self.model.forces(y, work);
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
        let (mut lo, mut hi) = (0.0, 1.0);
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
        let mut g_hi = self.smallest(self.ends[1].0, self.ends[1].1).min(0.0);
        // the side kept twice in a row, for the Illinois halving (-1 low, 1 high)
        let mut kept = 0i32;
        let mut iters = 0;
        while hi - lo > width && iters < 100 {
            iters += 1;
            let before = hi - lo;
            let secant = lo + (hi - lo) * g_lo / (g_lo - g_hi);
            let mid = if secant.is_finite() && secant > lo && secant < hi {
                secant
            } else {
                0.5 * (lo + hi)
            };
            let g = self.margin(mid, y, work, stats);
            if g <= 0.0 {
                hi = mid;
                g_hi = g;
                if kept == -1 {
                    g_lo *= 0.5;
                }
                kept = -1;
            } else {
                lo = mid;
                g_lo = g;
                if kept == 1 {
                    g_hi *= 0.5;
                }
                kept = 1;
            }
            // a bracket that did not halve: bisect once
            if hi - lo > 0.5 * before && hi - lo > width {
                let mid = 0.5 * (lo + hi);
                let g = self.margin(mid, y, work, stats);
                if g <= 0.0 {
                    hi = mid;
                    g_hi = g;
                } else {
                    lo = mid;
                    g_lo = g;
                }
                kept = 0;
            }
        }
        self.dense.at(hi, y);
        hi
    }
}
