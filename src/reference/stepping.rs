//! What the inertial drivers' stepping loops share (the joint-angle reference's
//! [`run_inertial`](crate::reference::inertial::run_inertial) and the free-body reference's):
//! the step size and its verdict on an attempted step, the cuts of a step at a wall and at a
//! release, and the work budget that leaves a run undecided.

use std::fmt::Debug;

use crate::model::Mode;
use crate::ode::{integral, Method, StepStats, Stepper};

/// A release found within the last this fraction of a step is taken at the step's end.
pub(crate) const RELEASE_SLACK: f64 = 1e-3;

/// Steps cut for a release since the last event after which the start has not come, past
/// which a clamped unknown's pull is taken to sit on its threshold within the rounding (a
/// design on a knife edge): the run is undecided. A start is found in a few cuts, but at
/// s = 0 (magnets starting at their rest points) some 7-tile words need more than 2,000
/// (LRRLLLS and five others were undecided at 0.0056 s); 50,000 keeps the knife edge of
/// three tiles under half a second.
const MAX_FUTILE_CUTS: usize = 50_000;

/// The free unknowns of `modes` into `free` (in order), after a change of modes, and the
/// storage of a packed state of them: `lead` leading entries (the free-body base), then each
/// free unknown's value and rate. `zp` and `stepper` (`bandwidth` its Jacobian's
/// half-bandwidth) are made anew when the length changed, the stepper keeping its scratch;
/// the stepper's Jacobian is forgotten.
pub(crate) fn repack<W: Default + Debug>(
    modes: &[Mode],
    free: &mut Vec<usize>,
    lead: usize,
    zp: &mut Vec<f64>,
    stepper: &mut Stepper<W>,
    bandwidth: usize,
) {
    free.clear();
    free.extend((0..modes.len()).filter(|&i| modes[i] == Mode::Free));
    let len = lead + 2 * free.len();
    if zp.len() != len {
        let mut fresh = Stepper::new(stepper.method, len, bandwidth);
        std::mem::swap(fresh.work_mut(), stepper.work_mut());
        *stepper = fresh;
        *zp = vec![0.0; len];
    }
    stepper.invalidate();
}

/// The entries a packed state shares with the whole one, as `(whole index, packed index)`:
/// the `lead` leading ones, then the value and rate of each free unknown of `free` (as
/// [`repack`] lays them out), unknown `i`'s value at `at(i)` of the whole state and its rate
/// next. The packed state from the whole one copies each pair one way, the whole state's
/// free entries from the packed one the other.
pub(crate) fn packed_entries(
    free: &[usize],
    lead: usize,
    at: fn(usize) -> usize,
) -> impl Iterator<Item = (usize, usize)> + '_ {
    let values = free.iter().enumerate().flat_map(move |(p, &i)| {
        let (w, q) = (at(i), lead + 2 * p);
        [(w, q), (w + 1, q + 1)]
    });
    (0..lead).map(|k| (k, k)).chain(values)
}

/// The steps cut for a release that did not come, since the last event.
#[derive(Debug, Default)]
pub(crate) struct ReleaseCuts {
    since: f64,
    count: usize,
}

impl ReleaseCuts {
    /// A step cut for a release, the last event at `last_event`.
    pub(crate) fn note(&mut self, last_event: f64) {
        if last_event != self.since {
            (self.since, self.count) = (last_event, 0);
        }
        self.count += 1;
    }

    /// Whether the cuts since the last event are past [`MAX_FUTILE_CUTS`].
    pub(crate) fn futile(&self) -> bool {
        self.count > MAX_FUTILE_CUTS
    }

    /// What the work budget ran out on.
    pub(crate) fn reason(&self) -> String {
        format!(
            "{} steps cut for a start that did not come: a pull on its threshold within the rounding",
            self.count
        )
    }
}

/// What the work budget ran out on at time `t` (`None` while it lasts): `budget` steps taken
/// (`stats`), the futile cuts of `cuts`, or no event for 1e4 times the larger of the time
/// scale `scale` and the last event's time `last_event`.
pub(crate) fn exhausted(
    budget: u64,
    stats: &StepStats,
    cuts: &ReleaseCuts,
    t: f64,
    last_event: f64,
    scale: f64,
) -> Option<String> {
    if stats.accepted + stats.rejected >= budget {
        Some(format!("{budget} steps"))
    } else if cuts.futile() {
        Some(cuts.reason())
    } else if t - last_event > 1e4 * scale.max(last_event) {
        Some(format!(
            "no event for {:.3e} s after the last at {:.6e} s",
            t - last_event,
            last_event
        ))
    } else {
        None
    }
}

/// The wall (0 or 1) that a value `x` of a range `[0, 1]` has reached or passed, if any.
pub(crate) fn wall_reached(x: f64) -> Option<f64> {
    if x >= 1.0 {
        Some(1.0)
    } else if x <= 0.0 {
        Some(0.0)
    } else {
        None
    }
}

/// The mode of an unknown that comes to rest on wall `wall` (0 or 1).
pub(crate) fn rest_mode(wall: f64) -> Mode {
    if wall == 1.0 {
        Mode::AtEnd
    } else {
        Mode::AtStart
    }
}

/// The verdict on an attempted step.
pub(crate) enum Verdict {
    /// Accepted so far with this error (the cuts at walls and releases still to come).
    Taken(f64),
    /// Rejected: the step size is cut, try again.
    Retry,
    /// The step size underflowed: why the run stops.
    Underflow(String),
}

/// The step size of an inertial driver's loop, with the integral controller's exponent and
/// the time scale its floor is taken on.
pub(crate) struct StepSize {
    /// The next step's size.
    pub(crate) h: f64,
    expo: f64,
    scale: f64,
}

impl StepSize {
    /// A first step `h` for `method`, the model's time scale `scale`.
    pub(crate) fn new(h: f64, method: Method, scale: f64) -> StepSize {
        StepSize {
            h,
            expo: 1.0 / (method.error_order() as f64 + 1.0),
            scale,
        }
    }

    /// The smallest step at time `t` (1e-14 of `t` or of the time scale).
    fn floor(&self, t: f64) -> f64 {
        1e-14 * t.max(self.scale)
    }

    /// Judges an attempt at time `t` with error `attempt` (in tolerances; an error of the
    /// stepper halves the step) ending at state `z1`: a rejection (error over 1, or a value
    /// not finite) shrinks the step by the integral controller (by 10 when not finite) and
    /// counts in `stats`.
    pub(crate) fn judge<E>(
        &mut self,
        attempt: Result<f64, E>,
        z1: &[f64],
        t: f64,
        stats: &mut StepStats,
    ) -> Verdict {
        let Ok(err) = attempt else {
            self.h *= 0.5;
            return Verdict::Retry;
        };
        let finite = err.is_finite() && z1.iter().all(|v| v.is_finite());
        if finite && err <= 1.0 {
            return Verdict::Taken(err);
        }
        stats.rejected += 1;
        self.h *= if finite {
            integral(err, self.expo, false)
        } else {
            0.1
        };
        if self.h < self.floor(t) {
            return Verdict::Underflow(format!(
                "step size underflow at t = {t:.6e} s (h = {:.3e} s)",
                self.h
            ));
        }
        Verdict::Retry
    }

    /// Cuts the step at time `t` to end just past the first wall (0 or 1) that one of the
    /// unknowns going from `a` to `b` (the pairs `steps`) crosses by more than 1e-9; whether
    /// it was cut (then try again).
    pub(crate) fn cut_at_walls(&mut self, t: f64, steps: impl Iterator<Item = (f64, f64)>) -> bool {
        let mut theta: f64 = 1.0;
        for (a, b) in steps {
            for wall in [0.0, 1.0] {
                let past = if wall == 0.0 { b < 0.0 } else { b > 1.0 };
                if past && (b - wall).abs() > 1e-9 {
                    theta = theta.min(((wall - a) / (b - a)).clamp(0.0, 1.0));
                }
            }
        }
        if theta < 1.0 {
            let cut = self.h * (theta + 1e-9 * (1.0 - theta)).max(1e-6);
            if cut < self.h * 0.999_999 && cut > self.floor(t) {
                self.h = cut;
                return true;
            }
        }
        false
    }

    /// Cuts the step at time `t` to end at fraction `theta` of it, where a clamped unknown
    /// is pulled off its wall (unless within [`RELEASE_SLACK`] of its end), noting the cut
    /// in `cuts` (the last event at `last_event`); whether it was cut (then try again).
    pub(crate) fn cut_at_release(
        &mut self,
        t: f64,
        theta: f64,
        cuts: &mut ReleaseCuts,
        last_event: f64,
    ) -> bool {
        if theta < 1.0 - RELEASE_SLACK {
            let cut = self.h * theta.max(1e-6);
            if cut > self.floor(t) {
                self.h = cut;
                cuts.note(last_event);
                return true;
            }
        }
        false
    }

    /// Counts an accepted step with error `err` in `stats`; the factor the next step grows by.
    pub(crate) fn accept(&self, err: f64, stats: &mut StepStats) -> f64 {
        stats.accepted += 1;
        integral(err, self.expo, true)
    }
}
