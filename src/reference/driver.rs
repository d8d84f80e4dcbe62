//! The hybrid driver of a reference run ([`run_reference`]): it integrates the model between
//! events with adaptive steps, locates each event (a magnet starting or arriving, a joint
//! starting or ending its fold) on the step's dense output ([`crate::reference`]'s event
//! location), switches the unknown's mode there, and ends when nothing moves. The step size
//! is a PI controller's (the `control` module) and is kept across events; nothing is
//! allocated per step.
//!
//! **End of a run.** When no unknown is free and no clamped one is driven off its end, the
//! chain is at rest. A free unknown whose rate would change it by less than 1e-9 over the
//! time since the last event counts as at rest too, and so does one settling on a stable
//! balance within the tolerance (a magnet stopped mid-path, its forces along the path
//! cancelling). A run also stops, with the reason in
//! [`crate::reference::ReferenceRun::stopped`], at [`ReferenceOptions::max_steps`] steps,
//! after `1e4` times its slowest time scale without an event, or when the step size falls
//! below 1e-14 of the time: never a hang.

use crate::model::Forces;
use crate::model::RestState;
use crate::model::{condition, undecided_margin};
use crate::model::{InertialModel, Mode, Model};
use crate::ode::System;
use crate::ode::{Dense, Method, StepControl, StepStats, Stepper};
use crate::reference::event_log::EventLog;
use crate::reference::inertial::run_inertial;
use crate::reference::locate::{events_at, StepEvents};
use crate::reference::options::{Recording, ReferenceError, ReferenceOptions};
use crate::reference::recorder::Recorder;
use crate::reference::run_result::ReferenceRun;
use crate::timeline::{start_fraction, TileDesigns};
use crate::Chain;

/// Runs the reference model on `chain` with `designs`.
pub fn run_reference(
    chain: &Chain,
    designs: &TileDesigns,
    opts: &ReferenceOptions,
) -> Result<ReferenceRun, ReferenceError> {
    if !(opts.tolerance > 0.0 && opts.tolerance <= 0.1) {
        return Err(ReferenceError::BadTolerance(opts.tolerance));
    }
    let model = Model::new(chain, designs, &opts.model)?;
    if opts.coupled {
        let unsupported = |what| {
            ReferenceError::FreeBodyUnsupported {
            what,
            why: "the coupled joint-angle reference steps the free body's inertial equations with Dormand-Prince 5(4) and weighs pairs by chain index only",
        }
        };
        if opts.method != Method::Dopri5 {
            return Err(unsupported("the ROS2 method"));
        }
        if opts.model.distance_cutoff.is_some() {
            return Err(unsupported("a distance cutoff"));
        }
        let Some(im) = InertialModel::new(&model) else {
            return Err(unsupported("overdamped dynamics"));
        };
        return Ok(crate::reference::free_body::run_coupled(model, im, opts));
    }
    // inertial dynamics have the model's inertial coefficients; overdamped ones none
    Ok(match InertialModel::new(&model) {
        Some(im) => run_inertial(model, im, opts),
        None => Driver::new(model, opts).run(),
    })
}

/// The model with its unknowns' modes: the system the integrators step.
pub(crate) struct Moving<'a> {
    pub(crate) model: &'a Model,
    pub(crate) modes: &'a [Mode],
}

impl System for Moving<'_> {
    type Work = Forces;

    fn bandwidth(&self) -> usize {
        self.model.bandwidth()
    }

    fn counts(&self, i: usize) -> bool {
        self.modes[i] == Mode::Free
    }

    fn rhs(&self, y: &[f64], work: &mut Forces, out: &mut [f64]) {
        self.model.rhs(y, self.modes, work, out);
    }
}

struct Driver {
    model: Model,
    opts: ReferenceOptions,
    modes: Vec<Mode>,
    y: Vec<f64>,
    t: f64,
    log: EventLog,
    stats: StepStats,
    work: Forces,
    /// The wall contacts of [`ReferenceRun::walls`], when recording.
    walls: Option<Vec<(f64, usize, f64)>>,
}

impl Driver {
    fn new(model: Model, opts: &ReferenceOptions) -> Driver {
        let n = model.len();
        let joints = model.geometry.tiles().saturating_sub(1);
        Driver {
            modes: vec![Mode::AtStart; n],
            y: vec![0.0; n],
            t: 0.0,
            log: EventLog::new(
                joints,
                model.geometry.magnets(),
                start_fraction(&model.geometry),
            ),
            stats: StepStats::default(),
            work: Forces::default(),
            walls: (opts.record != Recording::Off).then(Vec::new),
            model,
            opts: *opts,
        }
    }

    /// Applies every mode switch whose condition holds at the current state; records them.
    fn switch(&mut self) -> bool {
        self.model.forces(&self.y, &mut self.work);
        for i in 0..self.model.len() {
            let Some(next) =
                condition(&self.model, i, self.modes[i], self.y[i], self.work.drive[i])
            else {
                continue;
            };
            let prev = std::mem::replace(&mut self.modes[i], next);
            match next {
                Mode::AtEnd => self.y[i] = 1.0,
                Mode::AtStart => self.y[i] = 0.0,
                Mode::Free => {}
            }
            if let Some(walls) = self.walls.as_mut().filter(|_| prev == Mode::Free) {
                walls.push((self.t, i, self.y[i]));
            }
            self.log
                .note(&self.model, i, prev, next, self.t, &self.modes, &self.y);
        }
        self.log.close(self.t)
    }

    /// The rates `dy/dt` at the current state into `f`.
    fn rates(&mut self, stepper: &mut Stepper<Forces>, f: &mut [f64]) {
        let moving = Moving {
            model: &self.model,
            modes: &self.modes,
        };
        stepper.rhs(&moving, &self.y, f, &mut self.stats);
    }

    /// Why the run must stop before a step of `h` with the unknowns `free` moving (their
    /// drives `drive`), if it must, and whether that is its work budget (the run undecided:
    /// the reason says the balance nearest and its margin); `slowest` is the model's slowest
    /// time scale.
    fn stop_reason(
        &self,
        free: &[usize],
        drive: &[f64],
        h: f64,
        slowest: f64,
    ) -> Option<(String, bool)> {
        let last = self.log.last_event;
        let margin =
            || undecided_margin(&self.model, free.iter().map(|&i| (i, self.y[i], drive[i])));
        if self.t - last > 1e4 * last.max(slowest) {
            return Some((
                format!(
                    "undecided at t = {:.6e} s within the work budget (no event for {:.3e} s after the last at {:.6e} s): {}",
                    self.t,
                    self.t - last,
                    last,
                    margin()
                ),
                true,
            ));
        }
        let budget = self.opts.step_budget(self.model.geometry.tiles());
        if self.stats.accepted + self.stats.rejected >= budget {
            return Some((
                format!(
                    "undecided at t = {:.6e} s within the work budget ({budget} steps, {} rejected): {}",
                    self.t,
                    self.stats.rejected,
                    margin()
                ),
                true,
            ));
        }
        if h < 1e-14 * self.t.max(self.model.time_scale) {
            return Some((
                format!(
                    "step size underflow at t = {:.6e} s (h = {h:.3e} s): the dynamics is singular here",
                    self.t
                ),
                false,
            ));
        }
        None
    }

    fn run(mut self) -> ReferenceRun {
        let n = self.model.len();
        let tol = self.opts.tolerance;
        let mut stepper: Stepper<Forces> =
            Stepper::new(self.opts.method, self.model.len(), self.model.bandwidth());
        let q = self.opts.method.error_order();
        let mut control = StepControl::new(q);
        self.switch();
        // the rates and drives at the current state, and at a step's end
        let (mut f, mut f1) = (vec![0.0; n], vec![0.0; n]);
        let (mut drive, mut drive1) = (Vec::with_capacity(n), Vec::with_capacity(n));
        // a step's end (then the state before it), and the state at an event
        let (mut y1, mut y_event) = (vec![0.0; n], vec![0.0; n]);
        let mut free: Vec<usize> = Vec::with_capacity(n);
        let mut candidates: Vec<usize> = Vec::with_capacity(n);
        let mut dense = Dense::default();
        self.rates(&mut stepper, &mut f);
        drive.clone_from(&stepper.work().drive);
        let scale = self.model.time_scale;
        // the slowest of the model's time scales: a path at the bonded rest force's speed, or
        // a fold under the bonded rest torque (heavy tiles fold far slower than magnets move)
        let slowest = scale.max(self.model.slowest_fold_time());
        let mut h = scale * 1e-3 * tol.powf(1.0 / (f64::from(q) + 1.0));
        let mut stopped = None;
        let mut rec = self.recorder(scale);
        loop {
            free.clear();
            free.extend((0..n).filter(|&i| self.modes[i] == Mode::Free));
            if free.is_empty() {
                break;
            }
            if self.at_rest(&free, &f, scale) {
                break;
            }
            if let Some(why) = self.stop_reason(&free, &drive, h, slowest) {
                stopped = Some(why);
                break;
            }
            let moving = Moving {
                model: &self.model,
                modes: &self.modes,
            };
            let err = match stepper.attempt(&moving, &self.y, &f, h, tol, &mut self.stats, &mut y1)
            {
                Ok(e) => e,
                Err(_) => {
                    self.stats.rejected += 1;
                    h *= 0.5;
                    continue;
                }
            };
            let finite = err.is_finite() && y1.iter().all(|v| v.is_finite());
            if !finite || err > 1.0 {
                self.stats.rejected += 1;
                h *= control.reject(if finite { err } else { f64::NAN });
                continue;
            }
            self.stats.accepted += 1;
            let grow = control.accept(h, err);
            // the rates and drives at the step's end: Dormand-Prince's last stage, or one
            // more evaluation for ROS2
            match stepper.last_derivative() {
                Some(d) => f1.copy_from_slice(d),
                None => stepper.rhs(&moving, &y1, &mut f1, &mut self.stats),
            }
            drive1.clone_from(&stepper.work().drive);
            stepper.invalidate();
            let t0 = self.t;
            if events_at(&self.model, &self.modes, &y1, &drive1, &mut candidates) {
                let stages = (self.opts.method == Method::Dopri5).then(|| stepper.stages());
                dense.set(&self.y, &y1, &f, &f1, h, stages);
                let th = StepEvents {
                    model: &self.model,
                    modes: &self.modes,
                    dense: &dense,
                    candidates: &candidates,
                    ends: [(&self.y, &drive), (&y1, &drive1)],
                    tol,
                }
                .first(&mut y_event, stepper.work_mut(), &mut self.stats);
                self.stats.event_steps += 1;
                self.t += th * h;
                // y1 keeps the state before the event
                y1.copy_from_slice(&self.y);
                self.y.copy_from_slice(&y_event);
                self.clamp_free();
                self.log
                    .cross(&self.model, t0, &y1, None, self.t, &self.y, None);
                self.switch();
                if let Some(r) = rec.as_mut().filter(|r| r.next_time() <= self.t) {
                    r.cover(t0, &y1, &f, self.t, &self.y, None);
                }
                self.rates(&mut stepper, &mut f);
                drive.clone_from(&stepper.work().drive);
            } else {
                self.t += h;
                std::mem::swap(&mut self.y, &mut y1);
                std::mem::swap(&mut f, &mut f1);
                std::mem::swap(&mut drive, &mut drive1);
                // now y1 and f1 hold the step's start
                if self.log.reports_crossings() {
                    self.log
                        .cross(&self.model, t0, &y1, Some(&f1), self.t, &self.y, Some(&f));
                }
                if let Some(r) = rec.as_mut().filter(|r| r.next_time() <= self.t) {
                    r.cover(t0, &y1, &f1, self.t, &self.y, Some(&f));
                }
            }
            h *= grow;
        }
        let states = rec.map(|r| r.finish(self.t, &self.y)).unwrap_or_default();
        self.finish(stopped, states)
    }

    /// The recorder of the states the options ask for (`None`: none recorded).
    fn recorder(&self, scale: f64) -> Option<Recorder> {
        Recorder::of(self.opts.record, scale * 1e-3, &self.y)
    }

    /// Whether the free unknowns `free` (rates `f`) have come to rest: none has moved by a
    /// billionth of its range in the time since the last event (at least the time scale
    /// `scale`), or they move by less than a hundredth and every one is settling on a
    /// stable balance ([`Self::settled`]).
    fn at_rest(&mut self, free: &[usize], f: &[f64], scale: f64) -> bool {
        let fastest = free.iter().map(|&i| f[i].abs()).fold(0.0, f64::max);
        let since = (self.t - self.log.last_event).max(scale);
        fastest * since < 1e-9 || (fastest * since < 1e-2 && self.settled(free, f))
    }

    /// Whether every free unknown is settling on a stable balance inside its range: its
    /// own rate falls as it moves (`lambda = d rate / d y < 0`) and the linearised distance
    /// left, `|rate / lambda|`, is under the tolerance (at least 1e-6) of its range (5 nm on
    /// a 5 mm path at tight tolerances).
    fn settled(&mut self, free: &[usize], f: &[f64]) -> bool {
        let mut y = self.y.clone();
        let mut work = Forces::default();
        for &i in free {
            let delta = if y[i] > 0.5 { -1e-7 } else { 1e-7 };
            y[i] += delta;
            self.model.forces(&y, &mut work);
            self.stats.rhs += 1;
            let rate = self.model.rate(i, y[i], work.drive[i], Mode::Free);
            y[i] = self.y[i];
            let lambda = (rate - f[i]) / delta;
            let left = (f[i] / lambda).abs();
            if lambda >= 0.0
                || left > self.opts.tolerance.max(1e-6)
                || self.y[i] < left
                || 1.0 - self.y[i] < left
            {
                return false;
            }
        }
        true
    }

    /// Keeps clamped unknowns exactly at their ends.
    fn clamp_free(&mut self) {
        for i in 0..self.y.len() {
            match self.modes[i] {
                Mode::AtStart => self.y[i] = 0.0,
                Mode::AtEnd => self.y[i] = 1.0,
                Mode::Free => {}
            }
        }
    }

    fn finish(
        mut self,
        stopped: Option<(String, bool)>,
        states: Vec<(f64, Vec<f64>)>,
    ) -> ReferenceRun {
        let time = self.log.last_event;
        self.model.forces(&self.y, &mut self.work);
        let outcome = RestState {
            model: &self.model,
            modes: &self.modes,
            y: &self.y,
            drive: &self.work.drive,
        }
        .outcome(time);
        let mut events = self.log.events;
        events.extend(outcome.stop_event(time));
        ReferenceRun {
            made_by: "joint-angle reference",
            end_time: self.t,
            final_state: self.y,
            states,
            walls: self.walls.unwrap_or_default(),
            model: self.model,
            options: self.opts,
            events,
            folds: self.log.folds,
            outcome,
            undecided: stopped.as_ref().is_some_and(|s| s.1),
            stopped: stopped.map(|s| s.0),
            max_moving: self.log.max_moving,
            stats: self.stats,
        }
    }
}
