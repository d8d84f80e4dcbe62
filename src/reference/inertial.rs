//! The inertial reference dynamics ([`crate::model::Dynamics::Inertial`]): every magnet and folding joint
//! of [`Model`] with mass, drag and a wall at each end of its range, integrated on
//! positions and velocities (interleaved, so the Jacobian stays banded for ROS2) with the
//! run's method.
//!
//! **Motion** and **walls** are the model's ([`InertialModel`]: accelerations, bounces, rests
//! and releases). The forces and torques are the overdamped model's ([`Model`]), so the two
//! models differ only in how the chain answers them. An unknown reaching 0 or 1: the step is
//! cut to end just past the wall (within 1e-9 of the range), the unknown is put on the wall
//! and bounces or stays there (its arrival, or a fold's end). A step in which a clamped unknown's pull crosses that threshold is cut to end
//! there (within 1e-3 of the step, the pull taken linear over it), so a start is not up to a
//! step late: at `s = 0`, where a start hangs on a rounding-sized balance, a step's lag on a
//! fold's start (5e-4 s at tolerance 1e-8) left SLRRRL's folds 2e-4 rad behind the event
//! engine's for the rest of the run. The run ends when every free unknown has come to rest
//! (speed under 1e-7 of its range per inertial time, acceleration likewise) or nothing is
//! free. When states are recorded, so is every wall contact ([`ReferenceRun::walls`]).

use crate::model::{at_wall, undecided_margin, Forces, InertialModel, Mode, Model, RestState};
use crate::ode::{Method, StepStats, Stepper, System};
use crate::reference::event_log::EventLog;
use crate::reference::options::ReferenceOptions;
use crate::reference::recorder::Recorder;
use crate::reference::run_result::ReferenceRun;
use crate::reference::stepping::{
    exhausted, rest_mode, wall_reached, ReleaseCuts, StepSize, Verdict,
};

/// Scratch of one evaluation: the whole chain's positions (the free unknowns' scattered in
/// from the packed state, the clamped ones' as the modes last changed) and the drives there.
#[derive(Debug, Default)]
pub(crate) struct Work {
    y: Vec<f64>,
    forces: Forces,
}

/// The inertial system of the free unknowns `free` (in order), the clamped ones held where
/// they are: the packed state `[x_a, v_a, x_b, v_b, ...]` for `free = [a, b, ...]`. Packed,
/// the stepper's stages, the error and the right-hand side's copies cost O(what moves); the
/// forces are computed again near the free unknowns only ([`Model::forces_free`], at the
/// modes' `epoch`). The band of the whole state bounds the packed one's (a packed index
/// difference is at most the whole one's).
struct Inertial<'a> {
    model: &'a Model,
    im: &'a InertialModel,
    free: &'a [usize],
    epoch: u64,
}

impl System for Inertial<'_> {
    type Work = Work;

    fn bandwidth(&self) -> usize {
        2 * self.model.bandwidth() + 1
    }

    fn counts(&self, _: usize) -> bool {
        true
    }

    fn rhs(&self, z: &[f64], work: &mut Work, out: &mut [f64]) {
        for (p, &i) in self.free.iter().enumerate() {
            work.y[i] = z[2 * p];
        }
        self.model
            .forces_free(&work.y, self.free, self.epoch, &mut work.forces);
        for (p, &i) in self.free.iter().enumerate() {
            let v = z[2 * p + 1];
            out[2 * p] = v;
            out[2 * p + 1] = self.im.acceleration(i, z[2 * p], work.forces.drive[i], v);
        }
    }
}

/// The rates of the state `z = [x_0, v_0, x_1, v_1, ...]`.
fn velocities(z: &[f64]) -> Vec<f64> {
    z.iter().skip(1).step_by(2).copied().collect()
}

/// An inertial run between steps: the modes, the state (whole and packed), the time, the
/// events so far and the scratch of the forces.
struct State {
    modes: Vec<Mode>,
    /// The whole state `[x_0, v_0, x_1, v_1, ...]` and its positions, current between steps.
    z: Vec<f64>,
    y: Vec<f64>,
    /// The free unknowns in order, and the stepper's packed state of them.
    free: Vec<usize>,
    zp: Vec<f64>,
    /// Counts the changes of modes (from 1): the clamped values change only with them, so
    /// the forces near the free unknowns hold between two ([`Model::forces_free`]).
    epoch: u64,
    /// The whole positions with a trial step's end scattered in.
    ys: Vec<f64>,
    stepper: Stepper<Work>,
    t: f64,
    log: EventLog,
    work: Forces,
    /// The drives at the step's start (the clamped unknowns' pulls off their walls), the
    /// same as `work`'s but where the forces changed since its full evaluation number
    /// `synced`.
    drive0: Vec<f64>,
    synced: u64,
    stats: StepStats,
    /// The recorded states, when recording, and the wall contacts of
    /// [`ReferenceRun::walls`].
    rec: Option<Recorder>,
    walls: Vec<(f64, usize, f64)>,
}

impl State {
    /// Every unknown of `model` at the start of its range, at rest, at time 0, to be stepped
    /// by `method`.
    fn new(model: &Model, method: Method) -> State {
        let n = model.len();
        State {
            modes: vec![Mode::AtStart; n],
            z: vec![0.0; 2 * n],
            y: vec![0.0; n],
            free: Vec::new(),
            zp: Vec::new(),
            epoch: 1,
            ys: vec![0.0; n],
            stepper: Stepper::new(method, 0, 2 * model.bandwidth() + 1),
            t: 0.0,
            log: EventLog::new(
                model.geometry.tiles().saturating_sub(1),
                model.geometry.magnets(),
                crate::timeline::start_fraction(&model.geometry),
            ),
            work: Forces::default(),
            drive0: vec![0.0; n],
            synced: 0,
            stats: StepStats::default(),
            rec: None,
            walls: Vec::new(),
        }
    }

    /// The free unknowns after a change of modes: the packed state from the whole one, the
    /// stepper's storage for it, and the whole positions its evaluations start from.
    fn pack(&mut self, model: &Model) {
        self.free.clear();
        self.free
            .extend((0..self.modes.len()).filter(|&i| self.modes[i] == Mode::Free));
        let len = 2 * self.free.len();
        if self.zp.len() != len {
            let bandwidth = 2 * model.bandwidth() + 1;
            let mut stepper = Stepper::new(self.stepper.method, len, bandwidth);
            std::mem::swap(stepper.work_mut(), self.stepper.work_mut());
            self.stepper = stepper;
            self.zp = vec![0.0; len];
        }
        self.stepper.invalidate();
        self.stepper.work_mut().y.clone_from(&self.y);
        self.ys.clone_from(&self.y);
        self.sync_packed();
    }

    /// The packed state from the whole one.
    fn sync_packed(&mut self) {
        for (p, &i) in self.free.iter().enumerate() {
            self.zp[2 * p] = self.z[2 * i];
            self.zp[2 * p + 1] = self.z[2 * i + 1];
        }
    }

    /// The whole state's free entries from the packed one.
    fn unpack(&mut self) {
        for (p, &i) in self.free.iter().enumerate() {
            self.z[2 * i] = self.zp[2 * p];
            self.z[2 * i + 1] = self.zp[2 * p + 1];
            self.y[i] = self.zp[2 * p];
        }
    }

    /// The unknowns whose drives in `work` may differ from `drive0`'s: every one after a
    /// full evaluation since `drive0` was taken, else those near the free ones.
    fn changed(&self, model: &Model) -> Vec<std::ops::Range<usize>> {
        if self.work.evaluations() == self.synced {
            model.changed(&self.work).collect()
        } else {
            std::iter::once(0..self.modes.len()).collect()
        }
    }

    /// Starts the clamped unknowns that their drive pulls off their wall (by more than the
    /// static threshold and the Coulomb friction), at rest; notes them. Leaves the drives
    /// before the starts in `work` and `drive0`. Whether any started.
    fn release(&mut self, model: &Model, im: &InertialModel) -> bool {
        model.forces_free(&self.y, &self.free, self.epoch, &mut self.work);
        // a clamped unknown whose drive is what it was at the last release stays
        let changed = self.changed(model);
        let mut started = false;
        for i in changed.iter().flat_map(|r| r.clone()) {
            if im.released(model, i, self.modes[i], self.work.drive[i]) {
                let prev = std::mem::replace(&mut self.modes[i], Mode::Free);
                self.z[2 * i + 1] = 0.0;
                self.log
                    .note(model, i, prev, Mode::Free, self.t, &self.modes, &self.y);
                started = true;
            }
        }
        self.log.close(self.t);
        for r in changed {
            self.drive0[r.clone()].copy_from_slice(&self.work.drive[r]);
        }
        self.synced = self.work.evaluations();
        if started {
            self.epoch += 1;
        }
        started
    }

    /// The free unknowns at or past a wall: put on it, then bounce or stay (a rest noted
    /// as a mode switch); the contacts noted in `walls` when recording. Whether any mode
    /// changed. Leaves the drives before the rests in `work`.
    fn settle_at_walls(&mut self, model: &Model, im: &InertialModel) -> bool {
        if !self.free.iter().any(|&i| wall_reached(self.y[i]).is_some()) {
            return false;
        }
        model.forces_free(&self.y, &self.free, self.epoch, &mut self.work);
        let mut switched = false;
        for p in 0..self.free.len() {
            let i = self.free[p];
            let Some(wall) = wall_reached(self.z[2 * i]) else {
                continue;
            };
            let v = self.z[2 * i + 1];
            self.z[2 * i] = wall;
            self.y[i] = wall;
            if !at_wall(wall, v) {
                continue;
            }
            if self.rec.is_some() {
                self.walls.push((self.t, i, wall));
            }
            if let Some(rebound) = im.bounce(i, wall, v, self.work.drive[i]) {
                self.z[2 * i + 1] = rebound;
            } else {
                let next = rest_mode(wall);
                let prev = std::mem::replace(&mut self.modes[i], next);
                self.z[2 * i + 1] = 0.0;
                self.log
                    .note(model, i, prev, next, self.t, &self.modes, &self.y);
                switched = true;
            }
        }
        if switched {
            self.log.close(self.t);
            self.epoch += 1;
        }
        switched
    }

    /// The fraction of the step to the packed state `z1` at which the first clamped unknown
    /// is pulled off its wall by more than its threshold (as [`State::release`] asks), its
    /// pull taken linear in between from `drive0`; 1 when none is. Leaves the drives at the
    /// step's end in `work`.
    fn release_within(&mut self, model: &Model, im: &InertialModel, z1: &[f64]) -> f64 {
        if self.free.len() == self.modes.len() {
            return 1.0;
        }
        for (p, &i) in self.free.iter().enumerate() {
            self.ys[i] = z1[2 * p];
        }
        model.forces_free(&self.ys, &self.free, self.epoch, &mut self.work);
        let mut theta: f64 = 1.0;
        // a drive that did not change since `drive0` crosses nothing
        for i in self.changed(model).into_iter().flatten() {
            let th = im.threshold(model, i);
            let pull = |d: f64| match self.modes[i] {
                Mode::AtStart => d - th,
                Mode::AtEnd => -d - th,
                Mode::Free => f64::NAN,
            };
            let (p0, p1) = (pull(self.drive0[i]), pull(self.work.drive[i]));
            if p1 > 0.0 && p0 <= 0.0 {
                theta = theta.min(p0 / (p0 - p1));
            }
        }
        theta
    }

    /// Takes the accepted step of size `h` whose end the packed state holds (the whole
    /// state still holds its start): the crossings of start fractions, the walls, the
    /// releases (the drives after them into `drive0`), the recorded states inside the step.
    /// Whether the modes changed (then the state is packed again).
    fn advance(&mut self, model: &Model, im: &InertialModel, h: f64) -> bool {
        let t0 = self.t;
        self.t += h;
        let t = self.t;
        let crossings = self.log.reports_crossings();
        let record = self.rec.as_ref().is_some_and(|r| r.next_time() <= t);
        // the step's start, for the start crossings and the recorded states
        let start = (crossings || record).then(|| (self.y.clone(), velocities(&self.z)));
        self.unpack();
        // the step's own end rates (a bounce below reverses the velocity at its end)
        let v_end = start.as_ref().map(|_| velocities(&self.z));
        if let (true, Some((y0, v0)), Some(v1)) = (crossings, &start, &v_end) {
            // starts at a fraction of the path: positions and velocities are the step's
            // Hermite data
            self.log
                .cross(model, t0, y0, Some(v0), t, &self.y, Some(v1));
        }
        let switched = self.settle_at_walls(model, im);
        let started = self.release(model, im);
        if let (Some(r), Some((y0, v0))) = (self.rec.as_mut().filter(|_| record), &start) {
            r.cover(t0, y0, v0, t, &self.y, v_end.as_deref());
        }
        let changed = switched || started;
        if changed {
            self.pack(model);
        } else {
            self.sync_packed();
        }
        changed
    }

    /// The run at its end on `model` with `opts`: the outcome at rest, why it stopped
    /// (`stopped`, `undecided` on the work budget), the recorded states.
    fn finish(
        mut self,
        model: Model,
        opts: &ReferenceOptions,
        stopped: Option<String>,
        undecided: bool,
    ) -> ReferenceRun {
        let y = self.y;
        let time = self.log.last_event;
        model.forces(&y, &mut self.work);
        let outcome = RestState {
            model: &model,
            modes: &self.modes,
            y: &y,
            drive: &self.work.drive,
        }
        .outcome(time);
        let mut events = self.log.events;
        events.extend(outcome.stop_event(time));
        let states = self.rec.map(|r| r.finish(self.t, &y)).unwrap_or_default();
        ReferenceRun {
            made_by: "joint-angle reference",
            end_time: self.t,
            final_state: y,
            states,
            walls: self.walls,
            model,
            options: *opts,
            events,
            folds: self.log.folds,
            outcome,
            stopped,
            undecided,
            max_moving: self.log.max_moving,
            stats: self.stats,
        }
    }
}

/// Runs the inertial model (the driver of [`crate::reference::run_reference`] for
/// [`crate::model::Dynamics::Inertial`]).
pub(crate) fn run_inertial(
    model: Model,
    im: InertialModel,
    opts: &ReferenceOptions,
) -> ReferenceRun {
    let mut s = State::new(&model, opts.method);
    let tol = opts.tolerance;
    let (_, move_time, drag_time) = im.c.times(&model);
    let scale = im.scale;
    let mut step = StepSize::new(im.first_step * 1e-3, opts.method, scale);
    let mut stopped = None;
    let mut undecided = false;
    let mut cuts = ReleaseCuts::default();
    s.rec = Recorder::of(opts.record, move_time.min(drag_time) * 1e-2, &s.y);
    let (mut f, mut z1) = (Vec::new(), Vec::new());
    s.release(&model, &im);
    s.pack(&model);
    loop {
        if s.free.is_empty() {
            break;
        }
        f.resize(s.zp.len(), 0.0);
        z1.resize(s.zp.len(), 0.0);
        let t = s.t;
        let sys = Inertial {
            model: &model,
            im: &im,
            free: &s.free,
            epoch: s.epoch,
        };
        s.stepper.rhs(&sys, &s.zp, &mut f, &mut s.stats);
        let quiet = s
            .free
            .iter()
            .enumerate()
            .all(|(p, &i)| im.quiet(i, s.zp[2 * p + 1], f[2 * p + 1]));
        if quiet && t > s.log.last_event + scale {
            break;
        }
        // the work budget (ReferenceOptions): a balance not decided within it is said, with
        // its margin, and the run is undecided
        let budget = opts.step_budget(model.geometry.tiles());
        if let Some(budget) = exhausted(budget, &s.stats, &cuts, t, s.log.last_event, scale) {
            model.forces(&s.y, &mut s.work);
            let drive = &s.work.drive;
            let margin = undecided_margin(&model, s.free.iter().map(|&i| (i, s.y[i], drive[i])));
            stopped = Some(format!(
                "undecided at t = {t:.6e} s within the work budget ({budget}): {margin}"
            ));
            undecided = true;
            break;
        }
        let attempt = s
            .stepper
            .attempt(&sys, &s.zp, &f, step.h, tol, &mut s.stats, &mut z1);
        let err = match step.judge(attempt, &z1, t, &mut s.stats) {
            Verdict::Taken(err) => err,
            Verdict::Retry => continue,
            Verdict::Underflow(why) => {
                stopped = Some(why);
                break;
            }
        };
        // a wall crossed: cut the step to end just past the first crossing
        let ends = (0..s.free.len()).map(|p| (s.zp[2 * p], z1[2 * p]));
        if step.cut_at_walls(t, ends) {
            continue;
        }
        // a clamped unknown pulled off its wall inside the step: cut the step to end at
        // that moment (the pull taken linear over the step), so that it starts there and
        // not up to a step late
        let theta = s.release_within(&model, &im, &z1);
        if step.cut_at_release(t, theta, &mut cuts, s.log.last_event) {
            continue;
        }
        let grow = step.accept(err, &mut s.stats);
        std::mem::swap(&mut s.zp, &mut z1);
        s.advance(&model, &im, step.h);
        step.h *= grow;
    }
    s.finish(model, opts, stopped, undecided)
}
