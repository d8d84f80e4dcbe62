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
use crate::ode::{StepStats, Stepper, System};
use crate::reference::event_log::EventLog;
use crate::reference::options::ReferenceOptions;
use crate::reference::recorder::Recorder;
use crate::reference::run_result::ReferenceRun;
use crate::reference::stepping::{
    exhausted, rest_mode, wall_reached, ReleaseCuts, StepSize, Verdict,
};

/// Scratch of one evaluation: the positions and the drives there.
#[derive(Debug, Default)]
pub(crate) struct Work {
    y: Vec<f64>,
    forces: Forces,
}

/// The inertial system with its modes: state `[x_0, v_0, x_1, v_1, ...]`.
struct Inertial<'a> {
    model: &'a Model,
    modes: &'a [Mode],
    im: &'a InertialModel,
}

impl System for Inertial<'_> {
    type Work = Work;

    fn bandwidth(&self) -> usize {
        2 * self.model.bandwidth() + 1
    }

    fn counts(&self, i: usize) -> bool {
        self.modes[i / 2] == Mode::Free
    }

    fn rhs(&self, z: &[f64], work: &mut Work, out: &mut [f64]) {
        let n = self.model.len();
        work.y.clear();
        work.y.extend((0..n).map(|i| z[2 * i]));
        // only where a free unknown reaches (the clamped ones' drives kept)
        self.model
            .forces_moving(&work.y, self.modes, &mut work.forces);
        for i in 0..n {
            if self.modes[i] != Mode::Free {
                out[2 * i] = 0.0;
                out[2 * i + 1] = 0.0;
                continue;
            }
            let v = z[2 * i + 1];
            out[2 * i] = v;
            out[2 * i + 1] = self.im.acceleration(i, z[2 * i], work.forces.drive[i], v);
        }
    }
}

/// The values of the state `z = [x_0, v_0, x_1, v_1, ...]`.
fn positions(z: &[f64]) -> Vec<f64> {
    z.iter().step_by(2).copied().collect()
}

/// The rates of the state `z = [x_0, v_0, x_1, v_1, ...]`.
fn velocities(z: &[f64]) -> Vec<f64> {
    z.iter().skip(1).step_by(2).copied().collect()
}

/// An inertial run between steps: the modes, the state, the time, the events so far and
/// the scratch of the forces.
struct State {
    modes: Vec<Mode>,
    z: Vec<f64>,
    t: f64,
    log: EventLog,
    work: Forces,
    stats: StepStats,
    /// The recorded states, when recording, and the wall contacts of
    /// [`ReferenceRun::walls`].
    rec: Option<Recorder>,
    walls: Vec<(f64, usize, f64)>,
}

impl State {
    /// Every unknown of `model` at the start of its range, at rest, at time 0.
    fn new(model: &Model) -> State {
        let n = model.len();
        State {
            modes: vec![Mode::AtStart; n],
            z: vec![0.0; 2 * n],
            t: 0.0,
            log: EventLog::new(
                model.geometry.tiles().saturating_sub(1),
                model.geometry.magnets(),
                crate::timeline::start_fraction(&model.geometry),
            ),
            work: Forces::default(),
            stats: StepStats::default(),
            rec: None,
            walls: Vec::new(),
        }
    }

    /// Starts the clamped unknowns that their drive pulls off their wall (by more than the
    /// static threshold and the Coulomb friction), at rest; notes them. Leaves the drives
    /// in `work`.
    fn release(&mut self, model: &Model, im: &InertialModel) {
        let y = positions(&self.z);
        model.forces_moving(&y, &self.modes, &mut self.work);
        for i in 0..model.len() {
            if im.released(model, i, self.modes[i], self.work.drive[i]) {
                let prev = std::mem::replace(&mut self.modes[i], Mode::Free);
                self.z[2 * i + 1] = 0.0;
                self.log
                    .note(model, i, prev, Mode::Free, self.t, &self.modes, &y);
            }
        }
        self.log.close(self.t);
    }

    /// The unknowns `free` at or past a wall: put on it, then bounce or stay (a rest noted
    /// as a mode switch); the contacts noted in `walls` when recording. Whether any mode
    /// changed. Leaves the drives before the rests in `work`.
    fn settle_at_walls(&mut self, model: &Model, im: &InertialModel, free: &[usize]) -> bool {
        let y_now = positions(&self.z);
        model.forces_moving(&y_now, &self.modes, &mut self.work);
        let mut switched = false;
        for &i in free {
            let x = self.z[2 * i];
            let Some(wall) = wall_reached(x) else {
                continue;
            };
            let v = self.z[2 * i + 1];
            self.z[2 * i] = wall;
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
                let y = positions(&self.z);
                self.log.note(model, i, prev, next, self.t, &self.modes, &y);
                switched = true;
            }
        }
        if switched {
            self.log.close(self.t);
        }
        switched
    }

    /// Takes the accepted step of size `h` whose start `z1` keeps (the state has moved to
    /// its end): the crossings of start fractions, the walls, the releases (the drives
    /// after them into `drive0`), the recorded states inside the step. Whether the modes
    /// changed.
    fn advance(
        &mut self,
        model: &Model,
        im: &InertialModel,
        h: f64,
        z1: &[f64],
        free: &[usize],
        drive0: &mut Vec<f64>,
    ) -> bool {
        let (t0, z0) = (self.t, z1);
        self.t += h;
        if self.log.reports_crossings() {
            // starts at a fraction of the path: positions and velocities are the step's
            // Hermite data
            self.log.cross(
                model,
                t0,
                &positions(z0),
                Some(&velocities(z0)),
                self.t,
                &positions(&self.z),
                Some(&velocities(&self.z)),
            );
        }
        // the step's own end rates, for the recorded states inside it (a bounce below
        // reverses the velocity at its end)
        let v_end = velocities(&self.z);
        let switched = self.settle_at_walls(model, im, free);
        let before = self.modes.clone();
        self.release(model, im);
        drive0.clone_from(&self.work.drive);
        let t = self.t;
        if let Some(r) = self.rec.as_mut().filter(|r| r.next_time() <= t) {
            let (y0, v0, y1) = (positions(z0), velocities(z0), positions(&self.z));
            r.cover(t0, &y0, &v0, t, &y1, Some(&v_end));
        }
        before != self.modes || switched
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
        let y = positions(&self.z);
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

/// The fraction of a step from drives `drive0` to positions `y1` at which the first clamped
/// unknown is pulled off its wall by more than its threshold (as [`release`] asks), its
/// pull taken linear in between; 1 when none is. Leaves the drives at `y1` in `work`.
fn release_within(
    model: &Model,
    im: &InertialModel,
    modes: &[Mode],
    drive0: &[f64],
    y1: &[f64],
    work: &mut Forces,
) -> f64 {
    if modes.iter().all(|&m| m == Mode::Free) {
        return 1.0;
    }
    model.forces_moving(y1, modes, work);
    let mut theta: f64 = 1.0;
    for (i, &mode) in modes.iter().enumerate() {
        let th = im.threshold(model, i);
        let pull = |d: f64| match mode {
            Mode::AtStart => d - th,
            Mode::AtEnd => -d - th,
            Mode::Free => f64::NAN,
        };
        let (p0, p1) = (pull(drive0[i]), pull(work.drive[i]));
        if p1 > 0.0 && p0 <= 0.0 {
            theta = theta.min(p0 / (p0 - p1));
        }
    }
    theta
}

/// Runs the inertial model (the driver of [`crate::reference::run_reference`] for
/// [`crate::model::Dynamics::Inertial`]).
pub(crate) fn run_inertial(
    model: Model,
    im: InertialModel,
    opts: &ReferenceOptions,
) -> ReferenceRun {
    let n = model.len();
    let mut s = State::new(&model);
    let tol = opts.tolerance;
    let (_, move_time, drag_time) = im.c.times(&model);
    let scale = im.scale;
    let mut stepper: Stepper<Work> = Stepper::new(opts.method, 2 * n, 2 * model.bandwidth() + 1);
    let mut step = StepSize::new(im.first_step * 1e-3, opts.method, scale);
    let mut stopped = None;
    let mut undecided = false;
    let mut cuts = ReleaseCuts::default();
    s.rec = Recorder::of(
        opts.record,
        move_time.min(drag_time) * 1e-2,
        &positions(&s.z),
    );
    let mut f = vec![0.0; 2 * n];
    let mut z1 = vec![0.0; 2 * n];
    s.release(&model, &im);
    // the drives at the step's start (the clamped unknowns' pulls off their walls)
    let mut drive0 = s.work.drive.clone();
    loop {
        let free: Vec<usize> = (0..n).filter(|&i| s.modes[i] == Mode::Free).collect();
        if free.is_empty() {
            break;
        }
        let (t, z, stats) = (s.t, &s.z, &mut s.stats);
        let sys = Inertial {
            model: &model,
            modes: &s.modes,
            im: &im,
        };
        stepper.rhs(&sys, z, &mut f, stats);
        let quiet = free
            .iter()
            .all(|&i| im.quiet(i, z[2 * i + 1], f[2 * i + 1]));
        if quiet && t > s.log.last_event + scale {
            break;
        }
        // the work budget (ReferenceOptions): a balance not decided within it is said, with
        // its margin, and the run is undecided
        let budget = opts.step_budget(model.geometry.tiles());
        if let Some(budget) = exhausted(budget, stats, &cuts, t, s.log.last_event, scale) {
            model.forces(&positions(z), &mut s.work);
            let drive = &s.work.drive;
            let margin = undecided_margin(&model, free.iter().map(|&i| (i, z[2 * i], drive[i])));
            stopped = Some(format!(
                "undecided at t = {t:.6e} s within the work budget ({budget}): {margin}"
            ));
            undecided = true;
            break;
        }
        let attempt = stepper.attempt(&sys, z, &f, step.h, tol, stats, &mut z1);
        let err = match step.judge(attempt, &z1, t, stats) {
            Verdict::Taken(err) => err,
            Verdict::Retry => continue,
            Verdict::Underflow(why) => {
                stopped = Some(why);
                break;
            }
        };
        // a wall crossed: cut the step to end just past the first crossing
        if step.cut_at_walls(t, free.iter().map(|&i| (z[2 * i], z1[2 * i]))) {
            continue;
        }
        // a clamped unknown pulled off its wall inside the step: cut the step to end at
        // that moment (the pull taken linear over the step), so that it starts there and
        // not up to a step late
        let y1 = positions(&z1);
        let theta = release_within(&model, &im, &s.modes, &drive0, &y1, &mut s.work);
        if step.cut_at_release(t, theta, &mut cuts, s.log.last_event) {
            continue;
        }
        let grow = step.accept(err, stats);
        // z1 keeps the step's start
        std::mem::swap(&mut s.z, &mut z1);
        if s.advance(&model, &im, step.h, &z1, &free, &mut drive0) {
            stepper.invalidate();
        }
        step.h *= grow;
    }
    s.finish(model, opts, stopped, undecided)
}
