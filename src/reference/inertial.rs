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
use crate::ode::{integral, StepStats, Stepper, System};
use crate::reference::event_log::EventLog;
use crate::reference::options::{Recording, ReferenceOptions};
use crate::reference::recorder::Recorder;
use crate::reference::run_result::ReferenceRun;

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
        self.model.forces(&work.y, &mut work.forces);
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

/// Starts the clamped unknowns that their drive pulls off their wall (by more than the
/// static threshold and the Coulomb friction), at rest; notes them at time `t`.
fn release(
    model: &Model,
    im: &InertialModel,
    modes: &mut [Mode],
    z: &mut [f64],
    t: f64,
    log: &mut EventLog,
    work: &mut Forces,
) {
    let n = model.len();
    let y: Vec<f64> = (0..n).map(|i| z[2 * i]).collect();
    model.forces(&y, work);
    for i in 0..n {
        if im.released(model, i, modes[i], work.drive[i]) {
            let prev = std::mem::replace(&mut modes[i], Mode::Free);
            z[2 * i + 1] = 0.0;
            log.note(model, i, prev, Mode::Free, t, modes, &y);
        }
    }
    log.close(t);
}

/// A release found within the last this fraction of a step is taken at the step's end.
const RELEASE_SLACK: f64 = 1e-3;

/// Steps cut for a release since the last event after which the start has not come, past
/// which a clamped unknown's pull is taken to sit on its threshold within the rounding (a
/// design on a knife edge): the run is undecided. A start is found in a few cuts, but at
/// s = 0 (magnets starting at their rest points) some 7-tile words need more than 2,000
/// (LRRLLLS and five others were undecided at 0.0056 s); 50,000 keeps the knife edge of
/// three tiles under half a second.
const MAX_FUTILE_CUTS: usize = 50_000;

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
    model.forces(y1, work);
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
    let joints = model.geometry.tiles().saturating_sub(1);
    let mut log = EventLog::new(
        joints,
        model.geometry.magnets(),
        crate::timeline::start_fraction(&model.geometry),
    );
    let mut stats = StepStats::default();
    let mut modes = vec![Mode::AtStart; n];
    let mut z = vec![0.0; 2 * n];
    let mut work = Forces::default();
    let tol = opts.tolerance;
    let (_, move_time, drag_time) = im.c.times(&model);
    let scale = im.scale;
    let mut stepper: Stepper<Work> = Stepper::new(opts.method, 2 * n, 2 * model.bandwidth() + 1);
    let expo = 1.0 / (opts.method.error_order() as f64 + 1.0);
    let mut t = 0.0;
    let mut h = im.first_step * 1e-3;
    let mut stopped = None;
    let mut undecided = false;
    let mut cuts = ReleaseCuts::default();
    let positions = |z: &[f64]| -> Vec<f64> { (0..n).map(|i| z[2 * i]).collect() };
    let velocities = |z: &[f64]| -> Vec<f64> { (0..n).map(|i| z[2 * i + 1]).collect() };
    let mut rec = match opts.record {
        Recording::Off => None,
        Recording::Grid { max_states } => Some(Recorder::new(
            max_states,
            move_time.min(drag_time) * 1e-2,
            &positions(&z),
        )),
    };
    // the wall contacts of ReferenceRun::walls, when recording
    let mut walls = Vec::new();
    let mut f = vec![0.0; 2 * n];
    let mut z1 = vec![0.0; 2 * n];
    release(&model, &im, &mut modes, &mut z, t, &mut log, &mut work);
    // the drives at the step's start (the clamped unknowns' pulls off their walls)
    let mut drive0 = work.drive.clone();
    loop {
        let free: Vec<usize> = (0..n).filter(|&i| modes[i] == Mode::Free).collect();
        if free.is_empty() {
            break;
        }
        {
            let sys = Inertial {
                model: &model,
                modes: &modes,
                im: &im,
            };
            stepper.rhs(&sys, &z, &mut f, &mut stats);
        }
        let quiet = free
            .iter()
            .all(|&i| im.quiet(i, z[2 * i + 1], f[2 * i + 1]));
        if quiet && t > log.last_event + scale {
            break;
        }
        // the work budget (ReferenceOptions): a balance not decided within it is said, with
        // its margin, and the run is undecided
        let budget = opts.step_budget(model.geometry.tiles());
        let exhausted = if stats.accepted + stats.rejected >= budget {
            Some(format!("{budget} steps"))
        } else if cuts.futile() {
            Some(cuts.reason())
        } else if t - log.last_event > 1e4 * scale.max(log.last_event) {
            Some(format!(
                "no event for {:.3e} s after the last at {:.6e} s",
                t - log.last_event,
                log.last_event
            ))
        } else {
            None
        };
        if let Some(budget) = exhausted {
            model.forces(&positions(&z), &mut work);
            let margin =
                undecided_margin(&model, free.iter().map(|&i| (i, z[2 * i], work.drive[i])));
            stopped = Some(format!(
                "undecided at t = {t:.6e} s within the work budget ({budget}): {margin}"
            ));
            undecided = true;
            break;
        }
        let sys = Inertial {
            model: &model,
            modes: &modes,
            im: &im,
        };
        let err = match stepper.attempt(&sys, &z, &f, h, tol, &mut stats, &mut z1) {
            Ok(a) => a,
            Err(_) => {
                h *= 0.5;
                continue;
            }
        };
        let finite = err.is_finite() && z1.iter().all(|v| v.is_finite());
        if !finite || err > 1.0 {
            stats.rejected += 1;
            h *= if finite {
                integral(err, expo, false)
            } else {
                0.1
            };
            if h < 1e-14 * t.max(scale) {
                stopped = Some(format!(
                    "step size underflow at t = {t:.6e} s (h = {h:.3e} s)"
                ));
                break;
            }
            continue;
        }
        // a wall crossed: cut the step to end just past the first crossing
        let mut theta: f64 = 1.0;
        for &i in &free {
            let (a, b) = (z[2 * i], z1[2 * i]);
            for wall in [0.0, 1.0] {
                let past = if wall == 0.0 { b < 0.0 } else { b > 1.0 };
                if past && (b - wall).abs() > 1e-9 {
                    theta = theta.min(((wall - a) / (b - a)).clamp(0.0, 1.0));
                }
            }
        }
        if theta < 1.0 {
            let cut = h * (theta + 1e-9 * (1.0 - theta)).max(1e-6);
            if cut < h * 0.999_999 && cut > 1e-14 * t.max(scale) {
                h = cut;
                continue;
            }
        }
        // a clamped unknown pulled off its wall inside the step: cut the step to end at
        // that moment (the pull taken linear over the step), so that it starts there and
        // not up to a step late
        let theta = release_within(&model, &im, &modes, &drive0, &positions(&z1), &mut work);
        if theta < 1.0 - RELEASE_SLACK {
            let cut = h * theta.max(1e-6);
            if cut > 1e-14 * t.max(scale) {
                h = cut;
                cuts.note(log.last_event);
                continue;
            }
        }
        stats.accepted += 1;
        let grow = integral(err, expo, true);
        std::mem::swap(&mut z, &mut z1);
        // z1 keeps the step's start
        let (t0, z0) = (t, &z1);
        t += h;
        if log.reports_crossings() {
            // starts at a fraction of the path: positions and velocities are the step's
            // Hermite data
            log.cross(
                &model,
                t0,
                &positions(z0),
                Some(&velocities(z0)),
                t,
                &positions(&z),
                Some(&velocities(&z)),
            );
        }
        // the step's own end rates, for the recorded states inside it (a bounce below
        // reverses the velocity at its end)
        let v_end = velocities(&z);
        // walls: bounce or stay
        let y_now = positions(&z);
        model.forces(&y_now, &mut work);
        let mut switched = false;
        for &i in &free {
            let x = z[2 * i];
            let wall = if x >= 1.0 {
                1.0
            } else if x <= 0.0 {
                0.0
            } else {
                continue;
            };
            let v = z[2 * i + 1];
            z[2 * i] = wall;
            if !at_wall(wall, v) {
                continue;
            }
            if rec.is_some() {
                walls.push((t, i, wall));
            }
            if let Some(rebound) = im.bounce(i, wall, v, work.drive[i]) {
                z[2 * i + 1] = rebound;
            } else {
                let next = if wall == 1.0 {
                    Mode::AtEnd
                } else {
                    Mode::AtStart
                };
                let prev = std::mem::replace(&mut modes[i], next);
                z[2 * i + 1] = 0.0;
                let y = positions(&z);
                log.note(&model, i, prev, next, t, &modes, &y);
                switched = true;
            }
        }
        if switched {
            log.close(t);
        }
        let before = modes.clone();
        release(&model, &im, &mut modes, &mut z, t, &mut log, &mut work);
        drive0.clone_from(&work.drive);
        if before != modes || switched {
            stepper.invalidate();
        }
        if let Some(r) = rec.as_mut().filter(|r| r.next_time() <= t) {
            r.cover(
                t0,
                &positions(z0),
                &velocities(z0),
                t,
                &positions(&z),
                Some(&v_end),
            );
        }
        h *= grow;
    }
    let y = positions(&z);
    let time = log.last_event;
    model.forces(&y, &mut work);
    let outcome = RestState {
        model: &model,
        modes: &modes,
        y: &y,
        drive: &work.drive,
    }
    .outcome(time);
    let mut events = log.events;
    events.extend(outcome.stop_event(time));
    let states = rec.map(|r| r.finish(t, &y)).unwrap_or_default();
    ReferenceRun {
        made_by: "joint-angle reference",
        end_time: t,
        final_state: y,
        states,
        walls,
        model,
        options: *opts,
        events,
        folds: log.folds,
        outcome,
        stopped,
        undecided,
        max_moving: log.max_moving,
        stats,
    }
}
