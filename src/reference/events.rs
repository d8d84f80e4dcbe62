//! The reference run: the hybrid driver that integrates the model between events, finds
//! each event (a magnet starting, arriving, a joint starting or ending its fold) by bisection
//! on real integrator steps, switches the unknown's mode there, and ends when nothing moves.
//! Its result carries the event engine's event kinds and summary fields, so both can be
//! written and compared alike.
//!
//! **Event location.** A step that ends with an event condition true is cut back by
//! bisection on its length, each trial a full step from the same start, until the bracket is
//! shorter than `tolerance` times the step (at least 8 and at most 60 halvings): event times
//! are as accurate as the tolerance asks, with no interpolant to trust.
//!
//! **End of a run.** When no unknown is free and no clamped one is driven off its end, the
//! chain is at rest. A free unknown whose rate would change it by less than 1e-9 over the
//! time since the last event counts as at rest too, and so does one settling on a stable
//! balance within the tolerance (a magnet stopped mid-path, its forces along the path
//! cancelling). A run
//! also stops, with the reason in [`ReferenceRun::stopped`], at [`ReferenceOptions::max_steps`]
//! steps or when the step size falls below 1e-14 of the time: never a hang.
//!
//! **Recorded states.** With [`ReferenceOptions::record`] set to [`Recording::Grid`], the
//! run keeps the state at evenly spaced times from 0 ([`ReferenceRun::states`]), for
//! pictures and energy curves: each is the integrator's state interpolated inside the step
//! that holds it (cubic Hermite on the step's end values and rates; for a step cut short at
//! an event, quadratic on the start rate), clamped to `[0, 1]`. When the states would exceed
//! the budget, the spacing doubles and every other state is dropped, so the grid stays even
//! and the memory bounded (see [`Recording::Grid`]). Off by default: then only the final
//! state is kept.
//!
//! **Outcome.** Completed when every magnet but the last arrived and every folding joint
//! closed. Otherwise the first joint left open (or holding a magnet that never arrived) is
//! named: inhibited when its pair's path ends lie farther apart than the pair at rest (the
//! geometry of Table 7.1's LR and RL), stalled otherwise, with what the dynamics left.

use std::f64::consts::FRAC_PI_2;

use crate::engine::{
    joint_of_magnet, Event, EventKind, FoldRecord, Outcome, SpeedLaw, Summary, TileDesigns,
};
use crate::reference::dynamics::{Forces, Mode, Model, ModelError, ModelOptions, Unknown};
use crate::reference::integrators::{Method, StepStats, Stepper};
use crate::{Chain, Fold};

/// Which states a reference run keeps besides the final one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Recording {
    /// None (the default): [`ReferenceRun::states`] is empty.
    #[default]
    Off,
    /// States on an evenly spaced time grid from 0, then the final state at
    /// [`ReferenceRun::end_time`]: at most `max_states` in all (taken as at least 3), so at
    /// most `max_states * (8 * unknowns + 32)` bytes, with one unknown per magnet and one per
    /// folding joint, at most three per tile (2,000 tiles and 1,000 states: under 50 MB). The
    /// spacing starts at a thousandth of the model's time scale and doubles whenever the
    /// budget is reached, so a run that needed a doubling ends with at least about
    /// `max_states / 2` states.
    Grid {
        /// The most states kept, the final one included.
        max_states: usize,
    },
}

/// Options of a reference run. Defaults: Dormand-Prince, tolerance 1e-8, the model's
/// defaults, at most 2,000,000 steps, no states recorded ([`Recording::Off`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceOptions {
    /// The integrator.
    pub method: Method,
    /// Relative and absolute tolerance on the unknowns (fractions of a path or of a fold).
    pub tolerance: f64,
    /// The model's options.
    pub model: ModelOptions,
    /// Most steps (accepted and rejected) before the run stops with a diagnosis.
    pub max_steps: u64,
    /// States to keep for pictures (default [`Recording::Off`]).
    pub record: Recording,
}

impl Default for ReferenceOptions {
    fn default() -> ReferenceOptions {
        ReferenceOptions {
            method: Method::Dopri5,
            tolerance: 1e-8,
            model: ModelOptions::default(),
            max_steps: 2_000_000,
            record: Recording::Off,
        }
    }
}

impl ReferenceOptions {
    /// Another integrator.
    pub fn with_method(mut self, method: Method) -> ReferenceOptions {
        self.method = method;
        self
    }
    /// Another tolerance.
    pub fn with_tolerance(mut self, tolerance: f64) -> ReferenceOptions {
        self.tolerance = tolerance;
        self
    }
    /// Other model options.
    pub fn with_model(mut self, model: ModelOptions) -> ReferenceOptions {
        self.model = model;
        self
    }
    /// Another step limit.
    pub fn with_max_steps(mut self, max_steps: u64) -> ReferenceOptions {
        self.max_steps = max_steps;
        self
    }
    /// Another recording of states.
    pub fn with_record(mut self, record: Recording) -> ReferenceOptions {
        self.record = record;
        self
    }
}

/// Why a reference run could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReferenceError {
    /// The model refused the input.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A tolerance that is not in (0, 0.1].
    #[error("tolerance {0}: expected a number in (0, 0.1]")]
    BadTolerance(f64),
}

/// The result of a reference run.
#[derive(Debug)]
pub struct ReferenceRun {
    /// The model (geometry and unknowns).
    pub model: Model,
    /// The options used.
    pub options: ReferenceOptions,
    /// Every event, in time order (the engine's kinds and indices).
    pub events: Vec<Event>,
    /// The folds, in the order they start (`end` is NaN for a fold that never closed).
    pub folds: Vec<FoldRecord>,
    /// How propagation ended.
    pub outcome: Outcome,
    /// Why integration stopped early (step limit, step-size underflow), if it did.
    pub stopped: Option<String>,
    /// The state at the end.
    pub final_state: Vec<f64>,
    /// Recorded `(time s, state)` pairs in time order, the last one the final state
    /// ([`ReferenceOptions::record`]; empty when off).
    pub states: Vec<(f64, Vec<f64>)>,
    /// When the chain came to rest (or integration stopped), s.
    pub end_time: f64,
    /// The most magnets moving at once, and when first.
    pub max_moving: (usize, f64),
    /// Work counters.
    pub stats: StepStats,
}

fn condition(model: &Model, i: usize, mode: Mode, y: f64, drive: f64) -> Option<Mode> {
    match mode {
        Mode::AtStart if drive > model.threshold(i) => Some(Mode::Free),
        Mode::AtEnd if -drive > model.threshold(i) => Some(Mode::Free),
        Mode::Free if y >= 1.0 => Some(Mode::AtEnd),
        Mode::Free if y <= 0.0 => Some(Mode::AtStart),
        _ => None,
    }
}

fn any_event(model: &Model, modes: &[Mode], y: &[f64], work: &mut Forces) -> bool {
    model.forces(y, work);
    (0..model.len()).any(|i| condition(model, i, modes[i], y[i], work.drive[i]).is_some())
}

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
    Ok(Driver::new(model, opts).run())
}

/// The states of [`Recording::Grid`]: grid index `i` is time `i * dt`.
struct Recorder {
    /// Grid states kept at most (one place is left for the final state).
    max: usize,
    dt: f64,
    /// Grid index of the next state to record.
    next: u64,
    index: Vec<u64>,
    states: Vec<(f64, Vec<f64>)>,
}

impl Recorder {
    fn new(max_states: usize, dt: f64, y0: &[f64]) -> Recorder {
        Recorder {
            max: max_states.max(3) - 1,
            dt,
            next: 1,
            index: vec![0],
            states: vec![(0.0, y0.to_vec())],
        }
    }

    fn next_time(&self) -> f64 {
        self.next as f64 * self.dt
    }

    /// Doubles the spacing, keeping the states on the coarser grid (index 0 always stays).
    fn thin(&mut self) {
        let mut keep = self.index.iter().map(|i| i % 2 == 0);
        self.states.retain(|_| keep.next().unwrap_or(false));
        self.index.retain(|i| i % 2 == 0);
        for i in &mut self.index {
            *i /= 2;
        }
        self.dt *= 2.0;
        self.next = self.next.div_ceil(2);
    }

    /// Records the grid times in `(t0, t1]` of a step from `(t0, y0)`, rates `f0`, to
    /// `(t1, y1)`, rates `f1` if known: cubic Hermite, or quadratic on `f0` without `f1`.
    fn cover(&mut self, t0: f64, y0: &[f64], f0: &[f64], t1: f64, y1: &[f64], f1: Option<&[f64]>) {
        let h = t1 - t0;
        if h.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        loop {
            let t = self.next_time();
            if t > t1 {
                break;
            }
            if self.states.len() >= self.max {
                self.thin();
                continue;
            }
            let s = ((t - t0) / h).clamp(0.0, 1.0);
            let (s2, s3) = (s * s, s * s * s);
            let y: Vec<f64> = (0..y0.len())
                .map(|i| {
                    let v = match f1 {
                        Some(f1) => {
                            y0[i] * (2.0 * s3 - 3.0 * s2 + 1.0)
                                + h * f0[i] * (s3 - 2.0 * s2 + s)
                                + y1[i] * (3.0 * s2 - 2.0 * s3)
                                + h * f1[i] * (s3 - s2)
                        }
                        None => y0[i] + f0[i] * h * s + (y1[i] - y0[i] - f0[i] * h) * s2,
                    };
                    v.clamp(0.0, 1.0)
                })
                .collect();
            self.states.push((t, y));
            self.index.push(self.next);
            self.next += 1;
        }
    }

    /// The recorded states with the final one `(t, y)` last.
    fn finish(mut self, t: f64, y: &[f64]) -> Vec<(f64, Vec<f64>)> {
        if self.states.last().is_some_and(|(last, _)| *last >= t) {
            self.states.pop();
        }
        self.states.push((t, y.to_vec()));
        self.states
    }
}

struct Driver {
    model: Model,
    opts: ReferenceOptions,
    modes: Vec<Mode>,
    y: Vec<f64>,
    t: f64,
    events: Vec<Event>,
    folds: Vec<FoldRecord>,
    fold_index: Vec<usize>,
    stats: StepStats,
    work: Forces,
    moving: usize,
    max_moving: (usize, f64),
    last_event: f64,
}

impl Driver {
    fn new(model: Model, opts: &ReferenceOptions) -> Driver {
        let n = model.len();
        let joints = model.geometry.tiles().saturating_sub(1);
        Driver {
            modes: vec![Mode::AtStart; n],
            y: vec![0.0; n],
            t: 0.0,
            events: vec![Event {
                time: 0.0,
                index: 0,
                kind: EventKind::RiContact,
            }],
            folds: Vec::new(),
            fold_index: vec![usize::MAX; joints],
            stats: StepStats::default(),
            work: Forces::default(),
            moving: 0,
            max_moving: (0, 0.0),
            last_event: 0.0,
            model,
            opts: *opts,
        }
    }

    /// Applies every mode switch whose condition holds at the current state; records them.
    fn switch(&mut self) -> bool {
        self.model.forces(&self.y, &mut self.work);
        let mut batch: Vec<Event> = Vec::new();
        let t = self.t;
        for i in 0..self.model.len() {
            let Some(next) =
                condition(&self.model, i, self.modes[i], self.y[i], self.work.drive[i])
            else {
                continue;
            };
            let prev = self.modes[i];
            self.modes[i] = next;
            match next {
                Mode::AtEnd => self.y[i] = 1.0,
                Mode::AtStart => self.y[i] = 0.0,
                Mode::Free => {}
            }
            let index = match self.model.unknowns[i] {
                Unknown::Magnet(k) | Unknown::Joint(k) => k as u32,
            };
            let ev = |kind| Event {
                time: t,
                index,
                kind,
            };
            match (self.model.unknowns[i], prev, next) {
                (Unknown::Magnet(k), Mode::AtStart, Mode::Free) => {
                    self.moving += 1;
                    if k >= 1 && self.events_has_start(k - 1) {
                        batch.push(Event {
                            time: t,
                            index: (k - 1) as u32,
                            kind: EventKind::TriggerReached,
                        });
                    }
                    batch.push(ev(EventKind::MagnetStarts));
                }
                (Unknown::Magnet(_), Mode::Free, Mode::AtEnd) => {
                    self.moving = self.moving.saturating_sub(1);
                    batch.push(ev(EventKind::MagnetArrives));
                }
                (Unknown::Magnet(_), Mode::Free, Mode::AtStart) => {
                    self.moving = self.moving.saturating_sub(1);
                }
                (Unknown::Magnet(_), Mode::AtEnd, Mode::Free) => self.moving += 1,
                (Unknown::Joint(j), Mode::AtStart, Mode::Free)
                    if self.fold_index[j] == usize::MAX =>
                {
                    let (a, b) = (
                        self.model.magnet_var(2 * j + 1),
                        self.model.magnet_var(2 * j + 2),
                    );
                    let fold = if self.model.joint_sign(j) > 0.0 {
                        Fold::L
                    } else {
                        Fold::R
                    };
                    self.fold_index[j] = self.folds.len();
                    self.folds.push(FoldRecord {
                        joint: j,
                        fold,
                        start: t,
                        end: f64::NAN,
                        p0: 0.5 * (self.y[a] + self.y[b]),
                    });
                    batch.push(ev(EventKind::FoldStarts));
                }
                (Unknown::Joint(j), Mode::Free, Mode::AtEnd) => {
                    if let Some(f) = self.folds.get_mut(self.fold_index[j]) {
                        if f.end.is_nan() {
                            f.end = t;
                            batch.push(ev(EventKind::FoldEnds));
                        }
                    }
                }
                _ => {}
            }
        }
        if self.moving > self.max_moving.0 {
            self.max_moving = (self.moving, t);
        }
        let any = !batch.is_empty();
        batch.sort_by_key(|e| (e.kind, e.index));
        if any {
            self.last_event = t;
        }
        self.events.extend(batch);
        any
    }

    fn events_has_start(&self, k: usize) -> bool {
        self.modes
            .get(self.model.magnet_var(k))
            .is_some_and(|&m| m != Mode::AtStart)
    }

    fn run(mut self) -> ReferenceRun {
        let n = self.model.len();
        let tol = self.opts.tolerance;
        let mut stepper = Stepper::new(self.opts.method, &self.model);
        let q = self.opts.method.error_order() as f64;
        self.switch();
        let mut f = vec![0.0; n];
        stepper.rhs(&self.model, &self.modes, &self.y, &mut f, &mut self.stats);
        let scale = self.model.time_scale;
        // the slowest of the model's time scales: a path at the bonded rest force's speed, or
        // a fold under the bonded rest torque (heavy tiles fold far slower than magnets move)
        let slowest =
            scale.max(self.model.options().rotational_drag * FRAC_PI_2 / self.model.torque_scale);
        let mut h = scale * 1e-3 * tol.powf(1.0 / (q + 1.0));
        let mut stopped = None;
        let mut rec = match self.opts.record {
            Recording::Off => None,
            Recording::Grid { max_states } => {
                Some(Recorder::new(max_states, scale * 1e-3, &self.y))
            }
        };
        loop {
            let free: Vec<usize> = (0..n).filter(|&i| self.modes[i] == Mode::Free).collect();
            if free.is_empty() {
                break;
            }
            let fastest = free.iter().map(|&i| f[i].abs()).fold(0.0, f64::max);
            let since = (self.t - self.last_event).max(scale);
            if fastest * since < 1e-9 {
                break;
            }
            if fastest * since < 1e-2 && self.settled(&free, &f) {
                break;
            }
            if self.t - self.last_event > 1e4 * self.last_event.max(slowest) {
                stopped = Some(format!(
                    "no event for {:.3e} s after the last at {:.6e} s with {} unknowns still creeping",
                    self.t - self.last_event,
                    self.last_event,
                    free.len()
                ));
                break;
            }
            if self.stats.accepted + self.stats.rejected >= self.opts.max_steps {
                stopped = Some(format!(
                    "step limit of {} reached at t = {:.6e} s with {} unknowns moving ({} steps rejected)",
                    self.opts.max_steps,
                    self.t,
                    free.len(),
                    self.stats.rejected
                ));
                break;
            }
            if h < 1e-14 * self.t.max(scale) {
                stopped = Some(format!(
                    "step size underflow at t = {:.6e} s (h = {h:.3e} s): the dynamics is singular here",
                    self.t
                ));
                break;
            }
            let att = match stepper.attempt(
                &self.model,
                &self.modes,
                &self.y,
                &f,
                h,
                tol,
                &mut self.stats,
            ) {
                Ok(a) => a,
                Err(_) => {
                    self.stats.rejected += 1;
                    h *= 0.5;
                    continue;
                }
            };
            let finite = att.error.is_finite() && att.y.iter().all(|v| v.is_finite());
            if !finite || att.error > 1.0 {
                self.stats.rejected += 1;
                let factor = if finite {
                    (0.9 * att.error.powf(-1.0 / (q + 1.0))).clamp(0.1, 0.9)
                } else {
                    0.1
                };
                h *= factor;
                continue;
            }
            self.stats.accepted += 1;
            let grow = if att.error > 0.0 {
                (0.9 * att.error.powf(-1.0 / (q + 1.0))).clamp(0.2, 5.0)
            } else {
                5.0
            };
            if any_event(&self.model, &self.modes, &att.y, &mut self.work) {
                self.stats.rhs += 1;
                // bisection on the step length, each trial a real step from the same start
                let (mut lo, mut hi) = (0.0, h);
                let mut y_hi = att.y;
                let mut iters = 0;
                while iters < 60 && (iters < 8 || hi - lo > tol * h) {
                    iters += 1;
                    let mid = 0.5 * (lo + hi);
                    self.stats.event_steps += 1;
                    let Ok(a) = stepper.attempt(
                        &self.model,
                        &self.modes,
                        &self.y,
                        &f,
                        mid,
                        tol,
                        &mut self.stats,
                    ) else {
                        break;
                    };
                    self.stats.rhs += 1;
                    if any_event(&self.model, &self.modes, &a.y, &mut self.work) {
                        hi = mid;
                        y_hi = a.y;
                    } else {
                        lo = mid;
                    }
                }
                let t0 = self.t;
                self.t += hi;
                let y0 = std::mem::replace(&mut self.y, y_hi);
                self.clamp_free();
                self.switch();
                if let Some(r) = rec.as_mut().filter(|r| r.next_time() <= self.t) {
                    r.cover(t0, &y0, &f, self.t, &self.y, None);
                }
                stepper.invalidate();
                stepper.rhs(&self.model, &self.modes, &self.y, &mut f, &mut self.stats);
                h = h.min(hi * 4.0).max(hi);
                continue;
            }
            let t0 = self.t;
            self.t += h;
            let y0 = std::mem::replace(&mut self.y, att.y);
            let f0 = rec
                .as_ref()
                .filter(|r| r.next_time() <= self.t)
                .map(|_| f.clone());
            stepper.invalidate();
            match stepper.last_derivative() {
                Some(d) => f.copy_from_slice(d),
                None => stepper.rhs(&self.model, &self.modes, &self.y, &mut f, &mut self.stats),
            }
            if let (Some(r), Some(f0)) = (rec.as_mut(), f0) {
                r.cover(t0, &y0, &f0, self.t, &self.y, Some(&f));
            }
            h *= grow;
        }
        let states = rec.map(|r| r.finish(self.t, &self.y)).unwrap_or_default();
        self.finish(stopped, states)
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
            let rate = self.model.rate(i, work.drive[i], Mode::Free);
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

    fn finish(mut self, stopped: Option<String>, states: Vec<(f64, Vec<f64>)>) -> ReferenceRun {
        let m = &self.model;
        let n = m.geometry.magnets();
        let t = self.last_event;
        self.model.forces(&self.y, &mut self.work);
        let m = &self.model;
        let unarrived =
            (0..n.saturating_sub(1)).find(|&k| self.modes[m.magnet_var(k)] != Mode::AtEnd);
        let open = (0..m.geometry.tiles().saturating_sub(1))
            .find(|&j| m.joint_var(j).is_some_and(|v| self.modes[v] != Mode::AtEnd));
        let joint_m = unarrived.map(joint_of_magnet);
        let joint = match (joint_m, open) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let outcome = match joint {
            None => Outcome::Completed,
            Some(j) => {
                let (diverges, end, rest) = if j + 1 < m.geometry.tiles() {
                    m.geometry.pair_diverges(j)
                } else {
                    (false, 0.0, 0.0)
                };
                if diverges {
                    Outcome::Inhibited {
                        joint: j,
                        time: t,
                        end_distance_mm: end,
                        rest_distance_mm: rest,
                    }
                } else {
                    let never = (0..n.saturating_sub(1))
                        .find(|&k| self.modes[m.magnet_var(k)] == Mode::AtStart)
                        .unwrap_or(n.saturating_sub(1));
                    let reason = self.stall_reason(unarrived, open, j);
                    Outcome::Stalled {
                        joint: j,
                        time: t,
                        magnet: never,
                        reason,
                    }
                }
            }
        };
        let mut events = std::mem::take(&mut self.events);
        match &outcome {
            Outcome::Inhibited { joint, time, .. } => events.push(Event {
                time: *time,
                index: *joint as u32,
                kind: EventKind::Inhibited,
            }),
            Outcome::Stalled { joint, time, .. } => events.push(Event {
                time: *time,
                index: *joint as u32,
                kind: EventKind::Stalled,
            }),
            Outcome::Completed => {}
        }
        ReferenceRun {
            end_time: self.t,
            final_state: self.y,
            states,
            model: self.model,
            options: self.opts,
            events,
            folds: self.folds,
            outcome,
            stopped,
            max_moving: self.max_moving,
            stats: self.stats,
        }
    }

    fn stall_reason(&self, unarrived: Option<usize>, open: Option<usize>, j: usize) -> String {
        let m = &self.model;
        if let Some(k) = unarrived.filter(|&k| joint_of_magnet(k) == j) {
            let v = m.magnet_var(k);
            let len = m.path_length(k);
            let drive = self.work.drive[v];
            return match self.modes[v] {
                Mode::AtStart => format!(
                    "magnet {k} never started: the force along its path stays {drive:.3e} N (towards its rest point) once every magnet before it has stopped (reference dynamics)"
                ),
                _ => format!(
                    "magnet {k} came to rest {:.4} mm along its {len:.4} mm path, the forces along it balanced ({drive:.3e} N): it cannot reach the point that starts the next magnet (reference dynamics)",
                    self.y[v] * len
                ),
            };
        }
        if let Some(jj) = open {
            if let Some(v) = m.joint_var(jj) {
                return format!(
                    "joint {jj} stopped at {:.2} degrees, its torque balanced ({:.3e} N m) before the walls close it (reference dynamics)",
                    self.y[v] * 90.0,
                    self.work.drive[v]
                );
            }
        }
        format!("propagation stopped at joint {j} (reference dynamics)")
    }
}

impl ReferenceRun {
    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.model.geometry.tiles()
    }

    /// When the last event happens, s.
    pub fn duration(&self) -> f64 {
        self.events.last().map_or(0.0, |e| e.time)
    }

    /// The joints that folded (closed), in the order they started.
    pub fn folded_joints(&self) -> Vec<usize> {
        self.folds
            .iter()
            .filter(|f| !f.end.is_nan())
            .map(|f| f.joint)
            .collect()
    }

    /// The final signed joint angles, radians.
    pub fn final_angles(&self) -> Vec<f64> {
        self.model.joint_angles(&self.final_state)
    }

    /// The final world positions of the magnets, mm.
    pub fn final_positions(&self) -> Vec<(f64, f64)> {
        self.model.positions(&self.final_state)
    }

    /// The summary, with the same fields as the event engine's `summary.json` (no collision
    /// check: `first_collision` is null; `speed_law` is the overdamped law with the drag).
    pub fn to_summary(&self) -> Summary {
        let (inhibited_at, stalled_at, reason, outcome) =
            self.outcome.summary_fields("reference dynamics");
        let reason = match (&self.stopped, reason) {
            (Some(s), Some(r)) => Some(format!("{s}; {r}")),
            (Some(s), None) => Some(s.clone()),
            (None, r) => r,
        };
        let result = if self.stopped.is_some() {
            "stopped"
        } else {
            outcome
        };
        Summary {
            tiles: self.tiles(),
            completed: result == "completed",
            result,
            duration_s: self.duration(),
            events: self.events.len(),
            folds: self.folded_joints(),
            max_moving_magnets: self.max_moving.0,
            inhibited_at,
            stalled_at,
            reason,
            first_collision: None,
            speed_law: SpeedLaw::Overdamped {
                drag: self.model.options().drag,
            },
        }
    }

    /// `timeline.json` in the event engine's format, the law named `reference`.
    pub fn timeline_json(&self) -> String {
        let mut s = String::with_capacity(40 * self.events.len() + 200);
        s.push_str(&format!(
            "{{\"tiles\":{},\"speed_law\":{{\"reference\":{{\"method\":\"{}\",\"tolerance\":{},\"drag\":{},\"rotational_drag\":{}}}}},\"index\":\"magnet k is magnet k mod 2 of tile k/2; joint events index the joint\",\"events\":[\n",
            self.tiles(),
            self.options.method.name(),
            self.options.tolerance,
            self.model.options().drag,
            self.model.options().rotational_drag
        ));
        for (i, e) in self.events.iter().enumerate() {
            if i > 0 {
                s.push_str(",\n");
            }
            s.push_str(&e.to_json());
        }
        s.push_str("\n]}\n");
        s
    }

    /// The fraction of each fold made at the end (1 = closed by the walls).
    pub fn fold_fractions(&self) -> Vec<(usize, f64)> {
        (0..self.tiles().saturating_sub(1))
            .filter_map(|j| self.model.joint_var(j).map(|v| (j, self.final_state[v])))
            .collect()
    }

    /// The final angle of joint `j` in degrees.
    pub fn final_angle_degrees(&self, j: usize) -> f64 {
        self.final_angles()
            .get(j)
            .map_or(0.0, |a| a / FRAC_PI_2 * 90.0)
    }
}
