//! The stepping loop of a free-body run ([`run_free_body`]): Dormand-Prince steps of the
//! free-body equations ([`crate::reference::free_body`]), cut at every wall an unknown
//! reaches and at every release, as the joint-angle reference's inertial driver does.
//!
//! **Walls.** A magnet reaching an end of its path bounces with the restitution or stays (the
//! model's rule, [`InertialModel`]). A joint reaching straight or closed is an impact between
//! the two parts of the chain it joins: an impulse about its hinge reverses its turn rate
//! times the restitution, or stops it when the rebound would rise less than
//! [`REST_HEIGHT`] of the fold against what presses it on, and the joint is then held (its
//! two groups become one). The impulse acts on the whole free chain (by the
//! articulated-body recursion's response to a unit torque), so momentum is conserved through
//! it. **Releases.** A held magnet starts when its drive pulls it off its end by more than
//! the model's threshold; a held joint when the torque it passes ([`FreeBody::held_drives`])
//! would have to pull. A step in which either happens is cut to end there (the pull taken
//! linear over the step), within 1e-3 of the step.

use std::f64::consts::FRAC_PI_2;

use crate::model::REST_HEIGHT;
use crate::model::{
    at_wall, undecided_margin, Allow, Dynamics, Forces, InertialModel, Mode, Model, RestState,
    Unknown,
};
use crate::ode::{Method, StepStats, Stepper};
use crate::reference::event_log::EventLog;
use crate::reference::free_body::groups::Groups;
use crate::reference::free_body::options::FreeBodyOptions;
use crate::reference::free_body::run::FreeBodyRun;
use crate::reference::free_body::spatial::solve;
use crate::reference::free_body::system::{FreeBody, Momentum, Setup, Work, BASE};
use crate::reference::free_body::tile_body::TileBodies;
use crate::reference::options::{ReferenceError, ReferenceOptions};
use crate::reference::recorder::Recorder;
use crate::reference::run_result::ReferenceRun;
use crate::reference::stepping::{
    exhausted, packed_entries, repack, rest_mode, wall_reached, ReleaseCuts, StepSize, Verdict,
};
use crate::timeline::{start_fraction, TileDesigns};
use crate::{Chain, Octagon};

/// The system of the driver's modes, groups and free unknowns (a macro, not a method, so
/// that it borrows only those fields and the driver's scratch stays free to borrow).
macro_rules! free_body {
    ($driver:expr) => {
        FreeBody {
            setup: &$driver.setup,
            groups: &$driver.groups,
            modes: &$driver.modes,
            packed: &$driver.packed,
        }
    };
}

/// Runs the free-body reference on `chain` with `designs`.
pub fn run_free_body(
    chain: &Chain,
    designs: &TileDesigns,
    opts: &FreeBodyOptions,
) -> Result<FreeBodyRun, ReferenceError> {
    let ro = &opts.reference;
    if !(ro.tolerance > 0.0 && ro.tolerance <= 0.1) {
        return Err(ReferenceError::BadTolerance(ro.tolerance));
    }
    opts.validate()?;
    // the free-body reference integrates the water's form drag too
    let model = Model::build(chain, designs, &ro.model, Allow { form_drag: true })
        .map_err(ReferenceError::from)?;
    let (Dynamics::Inertial, Some(im)) = (model.options().dynamics, InertialModel::new(&model))
    else {
        return Err(ReferenceError::FreeBodyUnsupported {
            what: "overdamped dynamics",
            why: "the free-body reference integrates tiles with mass (use the inertial dynamics)",
        });
    };
    Ok(Driver::new(setup(model, im, false), opts).run())
}

/// The coupled joint-angle reference ([`ReferenceOptions::coupled`]) on `model` with `opts`:
/// the free body's equations with the chain's momentum held at zero (the base's velocity
/// follows the joints' rates and is not stepped), so that the joints turning at once are
/// integrated together, their groups' inertia and drag coupling them, with the free body's
/// start rule and impacts.
pub(crate) fn run_coupled(
    model: Model,
    im: InertialModel,
    opts: &ReferenceOptions,
) -> ReferenceRun {
    let fo = FreeBodyOptions::default().with_reference(*opts);
    Driver::new(setup(model, im, true), &fo).run().run
}

/// What stays the same over a run of `model` (the base's momentum held at zero when
/// `zero_momentum`).
pub(crate) fn setup(model: Model, im: InertialModel, zero_momentum: bool) -> Setup {
    let geometry = &model.geometry;
    let bodies = TileBodies::new(geometry, |t| geometry.design(t).magnet_mass * 1e-3);
    let oct = Octagon::new(geometry.w);
    let hinges = [oct.hinge(true).into(), oct.hinge(false).into()];
    let moments = (0..geometry.magnets())
        .map(|k| geometry.design(k / 2).moment())
        .collect();
    let folding = (0..geometry.tiles().saturating_sub(1))
        .filter(|&j| model.joint_var(j).is_some())
        .collect();
    Setup {
        ri: geometry.ri(),
        cutoff: model.options().cutoff,
        im,
        bodies,
        moments,
        hinges,
        folding,
        restitution: geometry.design(0).restitution,
        zero_momentum,
        model,
    }
}

struct Driver {
    setup: Setup,
    opts: FreeBodyOptions,
    modes: Vec<Mode>,
    groups: Groups,
    /// The whole state (the free unknowns' entries current after each step).
    z: Vec<f64>,
    /// The free unknowns, and the stepper's packed state: the base, then their values and
    /// rates.
    packed: Vec<usize>,
    zp: Vec<f64>,
    /// A whole state to evaluate a trial step's end in.
    zs: Vec<f64>,
    stepper: Stepper<Work>,
    t: f64,
    log: EventLog,
    stats: StepStats,
    work: Work,
    /// Drives of the held unknowns near the moving ones at the step's start, and at a trial
    /// step's end.
    drive0: Vec<f64>,
    drive1: Vec<f64>,
    /// Scratch: held joints' drives; the held magnets whose drives may change.
    held: Vec<(usize, f64)>,
    near: Vec<usize>,
    momentum: Vec<Momentum>,
    base: Vec<(f64, [f64; 3])>,
    base_stride: usize,
    steps: usize,
    most_groups: usize,
}

impl Driver {
    fn new(setup: Setup, opts: &FreeBodyOptions) -> Driver {
        let n = setup.model.len();
        let geometry = &setup.model.geometry;
        let log = EventLog::new(
            geometry.tiles().saturating_sub(1),
            geometry.magnets(),
            start_fraction(geometry),
        );
        let modes = vec![Mode::AtStart; n];
        let z = vec![0.0; BASE + 2 * n];
        let groups = Groups::build(
            &setup.model,
            &setup.bodies,
            &modes,
            &setup.values(&z),
            setup.hinges,
        );
        Driver {
            opts: *opts,
            modes,
            groups,
            zs: z.clone(),
            z,
            packed: Vec::new(),
            zp: vec![0.0; BASE],
            stepper: Stepper::new(Method::Dopri5, BASE, 0),
            t: 0.0,
            log,
            stats: StepStats::default(),
            work: Work::default(),
            drive0: vec![0.0; n],
            drive1: vec![0.0; n],
            held: Vec::new(),
            near: Vec::new(),
            momentum: Vec::new(),
            base: Vec::new(),
            base_stride: 1,
            steps: 0,
            most_groups: 1,
            setup,
        }
    }

    fn regroup(&mut self) {
        self.groups = Groups::build(
            &self.setup.model,
            &self.setup.bodies,
            &self.modes,
            &self.setup.values(&self.z),
            self.setup.hinges,
        );
        self.most_groups = self.most_groups.max(self.groups.len());
    }

    /// The held magnets whose drives can have changed since the modes last changed: those
    /// within the cutoff of a free magnet or of the magnets either side of a turning joint
    /// (all of them when `all`).
    fn near_moving(&mut self, all: bool) {
        let model = &self.setup.model;
        let n = model.geometry.magnets();
        let c = self.setup.cutoff;
        self.near.clear();
        if all {
            self.near
                .extend((0..n).filter(|&k| self.modes[model.magnet_var(k)] != Mode::Free));
            return;
        }
        for &i in &self.packed {
            let (lo, hi) = match model.unknowns[i] {
                Unknown::Magnet(k) => (k.saturating_sub(c), k + c),
                Unknown::Joint(j) => ((2 * j + 2).saturating_sub(c), 2 * j + 1 + c),
            };
            self.near.extend(lo..=hi.min(n - 1));
        }
        self.near.sort_unstable();
        self.near.dedup();
        let modes = &self.modes;
        self.near
            .retain(|&k| modes[model.magnet_var(k)] != Mode::Free);
    }

    /// Drives of the held unknowns of `near` and of the held joints at state `z` into
    /// `out` (by model unknown); returns nothing, leaves the evaluation in `work`.
    fn held_drives(&mut self, z: &[f64], out: &mut [f64]) {
        let sys = free_body!(self);
        sys.evaluate(z, &mut self.work);
        for &k in &self.near {
            out[self.setup.model.magnet_var(k)] = sys.magnet_drive(k, &mut self.work);
        }
        sys.held_drives(&mut self.work, &mut self.held);
        for &(v, d) in &self.held {
            out[v] = d;
        }
    }

    /// Starts the held unknowns pulled off their walls, at rest, until none is; notes
    /// them. Leaves the held drives of the final modes in `drive0`. Whether any started.
    fn release(&mut self, all: bool) -> bool {
        let mut any = false;
        let mut all = all;
        loop {
            self.near_moving(all);
            let mut drive = std::mem::take(&mut self.drive0);
            let z = std::mem::take(&mut self.z);
            self.held_drives(&z, &mut drive);
            self.z = z;
            self.drive0 = drive;
            let model = &self.setup.model;
            let mut started = Vec::new();
            for &k in &self.near {
                let i = model.magnet_var(k);
                if self
                    .setup
                    .im
                    .released(model, i, self.modes[i], self.drive0[i])
                {
                    started.push(i);
                }
            }
            for &(v, d) in &self.held {
                if self.setup.im.released(model, v, self.modes[v], d) {
                    started.push(v);
                }
            }
            if started.is_empty() {
                break;
            }
            any = true;
            started.sort_unstable();
            let y = self.setup.values(&self.z);
            let mut joints = false;
            for i in started {
                let prev = std::mem::replace(&mut self.modes[i], Mode::Free);
                self.z[Setup::at(i) + 1] = 0.0;
                joints |= matches!(model.unknowns[i], Unknown::Joint(_));
                self.log
                    .note(model, i, prev, Mode::Free, self.t, &self.modes, &y);
            }
            self.log.close(self.t);
            if joints {
                self.regroup();
            }
            self.pack();
            all = true;
        }
        any
    }

    /// The fraction of the step to `z1` at which the first held unknown is pulled off its
    /// wall (its pull linear over the step from `drive0`); 1 when none is.
    fn release_within(&mut self, z1: &[f64]) -> f64 {
        let mut zs = std::mem::take(&mut self.zs);
        zs[..BASE].copy_from_slice(&z1[..BASE]);
        for (p, &i) in self.packed.iter().enumerate() {
            zs[Setup::at(i)] = z1[BASE + 2 * p];
            zs[Setup::at(i) + 1] = z1[BASE + 2 * p + 1];
        }
        let mut drive1 = std::mem::take(&mut self.drive1);
        self.held_drives(&zs, &mut drive1);
        self.zs = zs;
        let model = &self.setup.model;
        let mut theta: f64 = 1.0;
        let mut check = |i: usize| {
            let mode = self.modes[i];
            let th = self.setup.im.threshold(model, i);
            let pull = |d: f64| match mode {
                Mode::AtStart => d - th,
                Mode::AtEnd => -d - th,
                Mode::Free => f64::NAN,
            };
            let (p0, p1) = (pull(self.drive0[i]), pull(drive1[i]));
            if p1 > 0.0 && p0 <= 0.0 {
                theta = theta.min(p0 / (p0 - p1));
            }
        };
        for &k in &self.near {
            check(model.magnet_var(k));
        }
        for &(v, _) in &self.held {
            check(v);
        }
        self.drive1 = drive1;
        theta
    }

    /// Free unknowns at or past a wall: put on it, then bounce or stay (a joint by an
    /// impulse on the whole chain). Notes the contacts in `walls` when recording. Whether
    /// any mode changed.
    fn walls(&mut self, walls: Option<&mut Vec<(f64, usize, f64)>>) -> bool {
        let mut hits = Vec::new();
        let past = self
            .packed
            .iter()
            .any(|&i| !(0.0..=1.0).contains(&self.z[Setup::at(i)]));
        let before = (past && !self.setup.zero_momentum).then(|| {
            let sys = free_body!(self);
            sys.evaluate(&self.z, &mut self.work);
            sys.base_momentum(&self.work).0
        });
        for &i in &self.packed {
            let at = Setup::at(i);
            let x = self.z[at];
            let Some(wall) = wall_reached(x) else {
                continue;
            };
            self.z[at] = wall;
            if at_wall(wall, self.z[at + 1]) {
                hits.push((i, wall));
            }
        }
        if let Some(before) = before {
            // putting a joint on its wall moved it (by at most a step's overshoot) at the
            // same rates: the base takes up the momentum that changed, so that the chain's
            // stays what it was
            let sys = free_body!(self);
            sys.evaluate(&self.z, &mut self.work);
            let (after, composite) = sys.base_momentum(&self.work);
            let dh = [
                before[0] - after[0],
                before[1] - after[1],
                before[2] - after[2],
            ];
            if let Some(dv) = solve(&composite, dh) {
                let (sp, cp) = self.z[2].sin_cos();
                self.z[3] += cp * dv[1] - sp * dv[2];
                self.z[4] += sp * dv[1] + cp * dv[2];
                self.z[5] += dv[0];
            }
        }
        if hits.is_empty() {
            return false;
        }
        if let Some(walls) = walls {
            walls.extend(hits.iter().map(|&(i, wall)| (self.t, i, wall)));
        }
        let mut switched = false;
        // magnets first (their bounces move nothing else), on one evaluation
        free_body!(self).evaluate(&self.z, &mut self.work);
        let mut rests = Vec::new();
        for &(i, wall) in &hits {
            let Unknown::Magnet(k) = self.setup.model.unknowns[i] else {
                continue;
            };
            let drive = free_body!(self).magnet_drive(k, &mut self.work);
            let at = Setup::at(i);
            match self.setup.im.bounce(i, wall, self.z[at + 1], drive) {
                Some(rebound) => self.z[at + 1] = rebound,
                None => rests.push((i, wall)),
            }
        }
        for &(i, wall) in &hits {
            if let Unknown::Joint(j) = self.setup.model.unknowns[i] {
                if self.joint_impact(i, j, wall) {
                    rests.push((i, wall));
                }
            }
        }
        for (i, wall) in rests {
            let next = rest_mode(wall);
            let prev = std::mem::replace(&mut self.modes[i], next);
            self.z[Setup::at(i) + 1] = 0.0;
            let y = self.setup.values(&self.z);
            self.log
                .note(&self.setup.model, i, prev, next, self.t, &self.modes, &y);
            switched = true;
        }
        if switched {
            self.log.close(self.t);
            self.regroup();
            self.pack();
        }
        switched
    }

    /// Joint `j` (model unknown `i`) meeting wall `wall` while turning: the impulse that
    /// reverses its rate times the restitution, or stops it; whether it stays (stopped).
    fn joint_impact(&mut self, i: usize, j: usize, wall: f64) -> bool {
        let sys = free_body!(self);
        sys.evaluate(&self.z, &mut self.work);
        let g = self.groups.of_tile[j + 1];
        let sign = self.setup.model.joint_sign(j);
        let at = Setup::at(i);
        let psi_dot = self.z[at + 1];
        // what presses it on against the wall, as an acceleration of the fold fraction
        let psi_acc = sign * self.work.qdd[g] / FRAC_PI_2;
        let press = if wall == 1.0 { psi_acc } else { -psi_acc };
        let e = self.setup.restitution;
        let rebound = -e * psi_dot;
        let stays = e <= 0.0 || rebound * rebound < 2.0 * press.max(0.0) * REST_HEIGHT;
        // the chain's response to a unit torque about the hinge, from rest
        sys.articulated(&mut self.work, |gg| if gg == g { 1.0 } else { 0.0 }, false);
        let r = self.work.qdd[g];
        let theta_dot = sign * psi_dot * FRAC_PI_2;
        let coeff = if stays { 1.0 } else { 1.0 + e };
        let lambda = -coeff * theta_dot / r;
        if !self.setup.zero_momentum {
            let a0 = self.work.a[0];
            let (sp, cp) = self.z[2].sin_cos();
            self.z[3] += lambda * (cp * a0[1] - sp * a0[2]);
            self.z[4] += lambda * (sp * a0[1] + cp * a0[2]);
            self.z[5] += lambda * a0[0];
        }
        for gg in 1..self.groups.len() {
            let jj = self.groups.last[gg - 1];
            if let Some(v) = self.setup.model.joint_var(jj) {
                let s = self.setup.model.joint_sign(jj);
                self.z[Setup::at(v) + 1] += s * lambda * self.work.qdd[gg] / FRAC_PI_2;
            }
        }
        if stays {
            self.z[at + 1] = 0.0;
        }
        stays
    }

    /// The free unknowns after a change of modes: the packed state from the whole one, the
    /// stepper's storage for it, and the whole state its evaluations start from.
    fn pack(&mut self) {
        let (modes, stepper) = (&self.modes, &mut self.stepper);
        repack(modes, &mut self.packed, BASE, &mut self.zp, stepper, 0);
        self.stepper.work_mut().full.clone_from(&self.z);
        self.zs.clone_from(&self.z);
        self.sync_packed();
    }

    /// The packed state from the whole one.
    fn sync_packed(&mut self) {
        for (w, q) in packed_entries(&self.packed, BASE, Setup::at) {
            self.zp[q] = self.z[w];
        }
    }

    /// The whole state's free entries from the packed one.
    fn unpack(&mut self) {
        for (w, q) in packed_entries(&self.packed, BASE, Setup::at) {
            self.z[w] = self.zp[q];
        }
    }

    fn note_base(&mut self) {
        self.steps += 1;
        if self.steps % self.base_stride != 0 {
            return;
        }
        if self.base.len() >= 4096 {
            let mut keep = false;
            self.base.retain(|_| {
                keep = !keep;
                keep
            });
            self.base_stride *= 2;
        }
        self.base.push((self.t, [self.z[0], self.z[1], self.z[2]]));
    }

    /// Steps until every free unknown has come to rest, nothing is free, or the work
    /// budget runs out.
    fn run(mut self) -> FreeBodyRun {
        let opts = self.opts.reference;
        let tol = opts.tolerance;
        let (_, move_time, drag_time) = self.setup.im.c.times(&self.setup.model);
        let scale = self.setup.im.scale;
        let mut step = StepSize::new(self.setup.im.first_step * 1e-3, Method::Dopri5, scale);
        let mut stopped = None;
        let mut cuts = ReleaseCuts::default();
        let y0 = self.setup.values(&self.z);
        let mut rec = Recorder::of(opts.record, move_time.min(drag_time) * 1e-2, &y0);
        let mut walls = Vec::new();
        let mut f = Vec::new();
        let mut z1 = Vec::new();
        self.pack();
        self.release(true);
        self.note_base();
        loop {
            if self.packed.is_empty() {
                break;
            }
            let len = self.zp.len();
            f.resize(len, 0.0);
            z1.resize(len, 0.0);
            let sys = free_body!(self);
            self.stepper.rhs(&sys, &self.zp, &mut f, &mut self.stats);
            if self.opts.track_momentum {
                let m = sys.momentum(self.t, &self.zp, self.stepper.work());
                self.momentum.push(m);
            }
            let t = self.t;
            let last_event = self.log.last_event;
            let quiet = self.packed.iter().enumerate().all(|(p, &i)| {
                let v = BASE + 2 * p + 1;
                self.setup.im.quiet(i, self.zp[v], f[v])
            });
            if quiet && t > last_event + scale {
                break;
            }
            // the work budget (ReferenceOptions): undecided, its margin said at the end
            let budget = opts.step_budget(self.setup.model.geometry.tiles());
            if let Some(budget) = exhausted(budget, &self.stats, &cuts, t, last_event, scale) {
                stopped = Some(format!(
                    "undecided at t = {t:.6e} s within the work budget ({budget})"
                ));
                break;
            }
            let attempt =
                self.stepper
                    .attempt(&sys, &self.zp, &f, step.h, tol, &mut self.stats, &mut z1);
            let err = match step.judge(attempt, &z1, t, &mut self.stats) {
                Verdict::Taken(err) => err,
                Verdict::Retry => continue,
                Verdict::Underflow(why) => {
                    stopped = Some(why);
                    break;
                }
            };
            // a wall crossed: cut the step to end just past the first crossing
            let ends = (0..self.packed.len()).map(|p| (self.zp[BASE + 2 * p], z1[BASE + 2 * p]));
            if step.cut_at_walls(t, ends) {
                continue;
            }
            // a held unknown pulled off its wall inside the step: cut the step to end there
            let theta = self.release_within(&z1);
            if step.cut_at_release(t, theta, &mut cuts, last_event) {
                continue;
            }
            let grow = step.accept(err, &mut self.stats);
            self.advance(step.h, &mut z1, &mut rec, &mut walls);
            step.h *= grow;
        }
        self.finish(stopped, rec, walls)
    }

    /// Takes the accepted step of size `h` to the packed state `z1` (which then keeps the
    /// step's start): the crossings of start fractions, the walls, the releases, the
    /// recorded states (and wall contacts, into `walls`) inside the step.
    fn advance(
        &mut self,
        h: f64,
        z1: &mut Vec<f64>,
        rec: &mut Option<Recorder>,
        walls: &mut Vec<(f64, usize, f64)>,
    ) {
        // the step's start, for the recorded states and the start crossings
        let t0 = self.t;
        let start = (rec.as_ref().is_some_and(|r| r.next_time() <= t0 + h)
            || self.log.reports_crossings())
        .then(|| (self.setup.values(&self.z), self.setup.rates(&self.z)));
        std::mem::swap(&mut self.zp, z1);
        self.unpack();
        self.t = t0 + h;
        let v_end = start.as_ref().map(|_| self.setup.rates(&self.z));
        if let (true, Some((y0, v0))) = (self.log.reports_crossings(), &start) {
            let (y1, v1) = (self.setup.values(&self.z), self.setup.rates(&self.z));
            self.log
                .cross(&self.setup.model, t0, y0, Some(v0), self.t, &y1, Some(&v1));
        }
        let switched = self.walls(rec.is_some().then_some(walls));
        self.release(switched);
        self.sync_packed();
        if let (Some(r), Some((y0, v0)), Some(v_end)) = (rec.as_mut(), &start, &v_end) {
            if r.next_time() <= self.t {
                r.cover(t0, y0, v0, self.t, &self.setup.values(&self.z), Some(v_end));
            }
        }
        self.note_base();
    }

    /// The run at its end: the outcome at rest, why it stopped (`stopped`; a stop on the
    /// work budget with the balance nearest), the recorded states and wall contacts.
    fn finish(
        mut self,
        stopped: Option<String>,
        rec: Option<Recorder>,
        walls: Vec<(f64, usize, f64)>,
    ) -> FreeBodyRun {
        let y = self.setup.values(&self.z);
        let time = self.log.last_event;
        let mut forces = Forces::default();
        self.setup.model.forces(&y, &mut forces);
        let outcome = RestState {
            model: &self.setup.model,
            modes: &self.modes,
            y: &y,
            drive: &forces.drive,
        }
        .outcome(time);
        let mut events = self.log.events;
        events.extend(outcome.stop_event(time));
        // a stop on the work budget: with the balance nearest
        let undecided = stopped
            .as_deref()
            .is_some_and(|w: &str| w.starts_with("undecided"));
        let stopped = stopped.map(|why| {
            if !undecided {
                return why;
            }
            let free = (0..self.modes.len()).filter(|&i| self.modes[i] == Mode::Free);
            let margin =
                undecided_margin(&self.setup.model, free.map(|i| (i, y[i], forces.drive[i])));
            format!("{why}: {margin}")
        });
        let states = rec.map(|r| r.finish(self.t, &y)).unwrap_or_default();
        self.base.push((self.t, [self.z[0], self.z[1], self.z[2]]));
        FreeBodyRun {
            run: ReferenceRun {
                made_by: if self.setup.zero_momentum {
                    "coupled joint-angle reference"
                } else {
                    "free-body reference"
                },
                end_time: self.t,
                final_state: y,
                states,
                walls,
                model: self.setup.model,
                options: self.opts.reference,
                events,
                folds: self.log.folds,
                outcome,
                stopped,
                undecided,
                max_moving: self.log.max_moving,
                stats: self.stats,
            },
            options: self.opts,
            base: self.base,
            momentum: self.momentum,
            most_groups: self.most_groups,
        }
    }
}
