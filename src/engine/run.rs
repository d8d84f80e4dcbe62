//! The discrete-event engine: an ordered event queue, no time steps and no force integration.
//!
//! The reaction initiator touches tile 0 at `t = 0` and starts magnet 0. When a magnet
//! starts, the engine asks where on its path the next magnet becomes equidistant from its two
//! neighbours ([`crate::engine::StartRule`]) and schedules that moment and the arrival from
//! the closed-form speed law ([`Motion`]). Reaching the trigger point starts the next magnet,
//! unless the next pair diverges (propagation inhibited); a path that ends, or a curve that
//! turns away, before the trigger stalls propagation. A fold starts when the second magnet of
//! its pair starts and ends when both have arrived. Events at the same time are taken
//! arrivals first, then stops, triggers and starts, so a magnet that starts its successor
//! exactly on arrival (`s = e/3`) never counts as moving together with it.

use crate::engine::local::run_local;
use crate::engine::queue::Queue;
use crate::engine::result::Timeline;
use crate::engine::run_state::RunState;
use crate::engine::speed::{Motion, MotionTable};
use crate::engine::start_rule::{ForceCache, ForceRule, ForceStart, StartRule};
use crate::engine::trigger::{ri_starts_first_magnet, Trigger, Triggers};
use crate::engine::DEFAULT_LOCAL_TOLERANCE;
use crate::magnet_path::PathError;
use crate::model::{Dynamics, Model, ModelError, ModelOptions};
use crate::physics::ForceLaw;
use crate::timeline::{
    joint_of_magnet, DesignsError, Event, EventKind, FoldRecord, Geometry, GeometryError, Outcome,
    Parameters, SpeedLaw, TileDesigns,
};
use crate::{Chain, Fold};

/// How the engine times its events.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EngineMethod {
    /// Local solves of the reference's physics, one joint at a time from the RI end
    /// ([`crate::engine`]'s local solve; the default).
    #[default]
    Local,
    /// The kinematic baseline: a start rule ([`StartRule`]) and a closed-form speed law
    /// ([`SpeedLaw`]); with [`SpeedLaw::Unit`] the thesis' transition diagram.
    Kinematic,
}

/// Engine options. Default: local solves ([`EngineMethod::Local`]) of the reference's
/// default model ([`ModelOptions::default`]) at tolerance
/// 1e-8. The kinematic baseline's defaults: the
/// overdamped speed law with the default drag, the distance rule (the thesis'
/// inequalities), the point-dipole pair law.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct EngineOptions {
    /// How events are timed.
    pub method: EngineMethod,
    /// The physics of the local solves (the reference's model options).
    pub model: ModelOptions,
    /// Tolerance of the local solves (fraction of a path or fold).
    pub tolerance: f64,
    /// The kinematic baseline's speed law.
    pub speed: SpeedLaw,
    /// The kinematic baseline's rule that starts each magnet.
    pub start: StartRule,
    /// Threads of the local solves' sweeps: 1 runs them one after the other, 2 or more
    /// runs two at once, the later trailing the earlier (more than 2 are not used); 0, the
    /// default: [`std::thread::available_parallelism`], but one thread for a chain of fewer
    /// than 500 tiles or when the engine runs on a rayon
    /// pool's thread. The events are the same, bit for bit, whatever the number.
    pub threads: usize,
    /// Most steps of one local solve (one joint's unit over one window), or
    /// [`EngineOptions::steps_per_tile`] per tile of the chain if that is more: the work
    /// budget, one per joint, so the run's is bounded in proportion to the chain. A solve
    /// that reaches it, or goes 1e4 of its time scales without an event once its inputs are
    /// still, has not decided (a magnet creeping towards a balance on a knife edge): the run
    /// is then `undecided`, its reason the balance and its margin, as a reference run that
    /// runs out of its budget ([`crate::reference::ReferenceOptions::step_budget`]). Default
    /// 20,000: units of short and serpentine chains take under 1,000 (954: a U-turn of the
    /// inertial 5,100-tile serpentine `(S*50 LL S*50 RR)*50` at s = 0.1; 613 for
    /// `S*160 L S*160`, 610 in the key plan, 300-450 for the thesis words), so a knife edge
    /// of a short chain stops within about a second of CPU; a U-turn between two long sides
    /// takes more (`S*3000 LL S*3000`: over 20,000), hence the share per tile.
    pub max_steps: usize,
    /// The local solves' work budget per tile of the chain, steps, where that is more than
    /// `max_steps`. Default [`EngineOptions::STEPS_PER_TILE`]; 0 after
    /// [`EngineOptions::with_max_steps`].
    pub steps_per_tile: usize,
}

impl Default for EngineOptions {
    fn default() -> EngineOptions {
        EngineOptions {
            method: EngineMethod::default(),
            model: ModelOptions::default(),
            tolerance: DEFAULT_LOCAL_TOLERANCE,
            speed: SpeedLaw::default(),
            start: StartRule::default(),
            threads: 0,
            max_steps: 20_000,
            steps_per_tile: EngineOptions::STEPS_PER_TILE,
        }
    }
}

impl EngineOptions {
    /// The default of [`EngineOptions::steps_per_tile`]: 20 (a 6,003-tile chain's solves may
    /// take 120,060 steps; see [`EngineOptions::max_steps`]).
    pub const STEPS_PER_TILE: usize = 20;

    /// The kinematic baseline with another start rule.
    pub fn with_start_rule(mut self, start: StartRule) -> EngineOptions {
        self.start = start;
        self.method = EngineMethod::Kinematic;
        self
    }

    /// The kinematic baseline with another speed law.
    pub fn with_speed(mut self, speed: SpeedLaw) -> EngineOptions {
        self.speed = speed;
        self.method = EngineMethod::Kinematic;
        self
    }

    /// Another pair law (of the local solves' model too).
    pub fn with_force_law(mut self, force_law: ForceLaw) -> EngineOptions {
        self.model.force_law = force_law;
        self
    }

    /// Another method.
    pub fn with_method(mut self, method: EngineMethod) -> EngineOptions {
        self.method = method;
        self
    }

    /// Other model options for the local solves.
    pub fn with_model(mut self, model: ModelOptions) -> EngineOptions {
        self.model = model;
        self
    }

    /// Another number of threads for the local solves' sweeps (0: the machine's).
    pub fn with_threads(mut self, threads: usize) -> EngineOptions {
        self.threads = threads;
        self
    }

    /// A fixed step limit for each local solve, whatever the chain's length (no share per
    /// tile: `steps_per_tile` 0).
    pub fn with_max_steps(mut self, max_steps: usize) -> EngineOptions {
        self.max_steps = max_steps;
        self.steps_per_tile = 0;
        self
    }

    /// Another tolerance for the local solves.
    pub fn with_tolerance(mut self, tolerance: f64) -> EngineOptions {
        self.tolerance = tolerance;
        self
    }
}

/// Why the engine could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EngineError {
    /// A design parameter out of range.
    #[error("design: {0}")]
    Design(#[from] DesignsError),
    /// A curved path that cannot be built.
    #[error(transparent)]
    Path(#[from] PathError),
    /// A drag coefficient that is not a finite positive number.
    #[error("drag coefficient {0} N s/m: expected a finite number > 0")]
    BadDrag(f64),
    /// A force-rule cutoff of 0.
    #[error("start rule cutoff 0: expected at least 1 (pairs this many apart in chain index)")]
    BadCutoff,
    /// The reference's model refused the options.
    #[error(transparent)]
    Model(#[from] Box<ModelError>),
    /// Model options the local solves do not follow yet.
    #[error("engine: {0}")]
    Unsupported(&'static str),
    /// A local-solve tolerance out of range.
    #[error("engine tolerance {0}: expected a number in (0, 0.1]")]
    BadTolerance(f64),
    /// More magnets than the compact event index holds.
    #[error("chain of {0} tiles: the engine handles at most 2^31 - 1 magnets")]
    TooLong(usize),
    /// The fold schedule handed to the collision check was malformed (an engine bug,
    /// reported rather than hidden): what was wrong with it.
    #[error("fold schedule: {0}")]
    Schedule(String),
}

impl From<GeometryError> for EngineError {
    fn from(e: GeometryError) -> EngineError {
        match e {
            GeometryError::Design(e) => EngineError::Design(e),
            GeometryError::Path(e) => EngineError::Path(e),
        }
    }
}

/// Runs the event engine on `chain` with `designs`.
pub fn run(
    chain: &Chain,
    designs: &TileDesigns,
    opts: &EngineOptions,
) -> Result<Timeline, EngineError> {
    if let SpeedLaw::Overdamped { drag } | SpeedLaw::Inertial { drag } = opts.speed {
        if !drag.is_finite() || drag <= 0.0 {
            return Err(EngineError::BadDrag(drag));
        }
    }
    if opts.start == (StartRule::Force { cutoff: 0 }) {
        return Err(EngineError::BadCutoff);
    }
    if chain.len() >= (u32::MAX / 4) as usize {
        return Err(EngineError::TooLong(chain.len()));
    }
    if opts.method == EngineMethod::Local {
        return run_local_engine(chain, designs, opts);
    }
    let geometry = Geometry::from_designs(chain, designs)?;
    let mut runner = Runner::new(geometry, *opts);
    runner.queue.push(0.0, EventKind::RiContact, 0);
    while let Some(event) = runner.queue.pop() {
        runner.events.push(event);
        runner.take(event);
    }
    Ok(runner.finish())
}

/// The engine by local solves.
fn run_local_engine(
    chain: &Chain,
    designs: &TileDesigns,
    opts: &EngineOptions,
) -> Result<Timeline, EngineError> {
    if !(opts.tolerance > 0.0 && opts.tolerance <= 0.1) {
        return Err(EngineError::BadTolerance(opts.tolerance));
    }
    let model = match Model::new(chain, designs, &opts.model) {
        Ok(m) => m,
        Err(ModelError::Design(e)) => return Err(EngineError::Design(e)),
        Err(ModelError::Path(e)) => return Err(EngineError::Path(e)),
        Err(e) => return Err(EngineError::Model(Box::new(e))),
    };
    let budget = opts
        .max_steps
        .max(opts.steps_per_tile.saturating_mul(chain.len()));
    let local = run_local(&model, opts.tolerance, opts.threads, budget);
    let speed = SpeedLaw::Overdamped { drag: model.drag };
    let motions = MotionTable::new(&model.geometry, speed);
    // the law the times are in, as summary.json and timeline.json report it
    let reported = match opts.model.dynamics {
        Dynamics::Inertial => SpeedLaw::Inertial { drag: model.drag },
        _ => speed,
    };
    let mut timeline = Timeline {
        speed: reported,
        force_law: opts.model.force_law,
        motions,
        start: local.solved.start.clone(),
        events: local.events,
        folds: local.folds,
        outcome: local.outcome,
        max_moving: local.max_moving,
        fold_of_joint: local.fold_of_joint,
        solved: Some(Box::new(local.solved)),
        parameters: model.parameters("event engine"),
        free_motion: None,
        geometry: Geometry::from_designs(chain, designs)?,
    };
    timeline.free_motion = Some(model.free_motion(&timeline));
    Ok(timeline)
}

/// A run in the making.
struct Runner {
    opts: EngineOptions,
    geometry: Geometry,
    triggers: Triggers,
    force_cache: ForceCache,
    motions: MotionTable,
    start: Vec<f64>,
    events: Vec<Event>,
    folds: Vec<FoldRecord>,
    fold_of_joint: Vec<u32>,
    outcome: Outcome,
    moving: usize,
    max_moving: (usize, f64),
    queue: Queue,
}

impl Runner {
    fn new(geometry: Geometry, opts: EngineOptions) -> Runner {
        let n = geometry.magnets();
        let joints = geometry.tiles().saturating_sub(1);
        Runner {
            motions: MotionTable::new(&geometry, opts.speed),
            opts,
            triggers: Triggers::default(),
            force_cache: ForceCache::default(),
            start: vec![f64::NAN; n],
            events: Vec::with_capacity(3 * n),
            folds: Vec::new(),
            fold_of_joint: vec![u32::MAX; joints],
            outcome: Outcome::Completed,
            moving: 0,
            max_moving: (0, 0.0),
            queue: Queue::default(),
            geometry,
        }
    }

    fn progress(&self) -> RunState<'_> {
        RunState {
            start: &self.start,
            motions: &self.motions,
            folds: &self.folds,
            fold_of_joint: &self.fold_of_joint,
            solved: None,
        }
    }

    /// What follows from `event`.
    fn take(&mut self, event: Event) {
        let (t, i) = (event.time, event.index as usize);
        match event.kind {
            EventKind::RiContact => self.ri_contact(t),
            EventKind::MagnetStarts => self.magnet_starts(i, t),
            EventKind::TriggerReached => self.trigger_reached(i, t),
            EventKind::MagnetArrives => self.moving -= 1,
            EventKind::FoldStarts
            | EventKind::FoldEnds
            | EventKind::Inhibited
            | EventKind::Stalled => {}
        }
    }

    fn ri_contact(&mut self, t: f64) {
        let (starts, ri, partner) = ri_starts_first_magnet(&self.geometry);
        if starts {
            self.queue.push(t, EventKind::MagnetStarts, 0);
        } else {
            self.stall(t, 0, format!(
                "the RI at the tile edge is {ri:.4} mm from magnet 0, not nearer than its partner at {partner:.4} mm: inequality (6.2) c + a < b fails"
            ));
        }
    }

    fn magnet_starts(&mut self, i: usize, t: f64) {
        self.start[i] = t;
        self.moving += 1;
        if self.moving > self.max_moving.0 {
            self.max_moving = (self.moving, t);
        }
        let motion = *self.motions.of(i);
        self.queue
            .push(t + motion.duration(), EventKind::MagnetArrives, i);
        if i % 2 == 0 && i >= 2 {
            self.fold_starts(i / 2 - 1, t, &motion);
        }
        let m = i + 1;
        if m + 1 < self.geometry.magnets() {
            match self.opts.start {
                StartRule::Force { cutoff } => self.force_trigger(i, t, cutoff),
                StartRule::Distance => self.distance_trigger(i, t, &motion),
            }
        }
    }

    /// Joint `j`'s fold starts at `t` if it folds: its pair's second magnet, moving by
    /// `motion`, starts then.
    fn fold_starts(&mut self, j: usize, t: f64, motion: &Motion) {
        let fold = self.geometry.joint_fold(j);
        if fold == Fold::S {
            return;
        }
        let a = 2 * j + 1;
        let ma = *self.motions.of(a);
        let end = (self.start[a] + ma.duration()).max(t + motion.duration());
        let p0 = 0.5 * ma.distance_at(t - self.start[a]) / ma.length;
        self.fold_of_joint[j] = self.folds.len() as u32;
        self.folds.push(FoldRecord {
            joint: j,
            fold,
            start: t,
            end,
            p0,
        });
        self.queue.push(t, EventKind::FoldStarts, j);
        self.queue.push(end, EventKind::FoldEnds, j);
    }

    /// The distance rule: magnet `i`, started at `t`, starts magnet `i + 1` where the
    /// geometry says, or stalls.
    fn distance_trigger(&mut self, i: usize, t: f64, motion: &Motion) {
        let m = i + 1;
        match self.triggers.trigger(&self.geometry, m) {
            Trigger::At(u) => self
                .queue
                .push(t + motion.time_to(u), EventKind::TriggerReached, i),
            Trigger::Never {
                u,
                shortfall,
                before_end,
            } => {
                let path = self.geometry.path(i);
                let reason = if before_end {
                    format!(
                        "magnet {i} on its curved path passes its closest approach to starting magnet {m} ({u:.4} mm along) still {shortfall:.4} mm short: the next magnet must start before then (thesis 6.5)"
                    )
                } else {
                    format!(
                        "magnet {i} reaches the end of its {} path ({:.4} mm) {shortfall:.4} mm short of starting magnet {m}: a straight path must be at least 4s long, s < e/3 (6.8, 6.9)",
                        if path.is_curved() { "curved" } else { "straight" },
                        path.length()
                    )
                };
                self.stall(t + motion.time_to(u), m, reason);
            }
        }
    }

    /// The force rule: magnet `i`, started at `t`, starts magnet `i + 1` when the forces
    /// within `cutoff` say, or stalls.
    fn force_trigger(&mut self, i: usize, t: f64, cutoff: usize) {
        let m = i + 1;
        let mut cache = std::mem::take(&mut self.force_cache);
        let rule = ForceRule {
            geometry: &self.geometry,
            progress: self.progress(),
            law: self.opts.model.force_law,
            cutoff,
        };
        let found = rule.start(&mut cache, m, t);
        self.force_cache = cache;
        match found {
            ForceStart::At(when) => self.queue.push(when, EventKind::TriggerReached, i),
            ForceStart::Never { time, drive } => self.stall(time, m, format!(
                "magnet {m} never started: the force along its path from the magnets within {cutoff} of it stays towards its rest point (at most {drive:.3e} N, at {time:.4} s) while magnet {i} and those behind it move (force rule)"
            )),
        }
    }

    fn trigger_reached(&mut self, i: usize, t: f64) {
        let m = i + 1;
        if m % 2 == 1 {
            let j = (m - 1) / 2;
            let (diverges, end, rest) = self.geometry.pair_diverges(j);
            if diverges {
                self.queue.push(t, EventKind::Inhibited, j);
                self.set_outcome(Outcome::Inhibited {
                    joint: j,
                    time: t,
                    end_distance_mm: end,
                    rest_distance_mm: rest,
                });
                return;
            }
        }
        self.queue.push(t, EventKind::MagnetStarts, m);
    }

    /// Magnet `magnet` never starts: propagation stalls at its joint at `time`.
    fn stall(&mut self, time: f64, magnet: usize, reason: String) {
        let joint = joint_of_magnet(magnet);
        self.queue.push(time, EventKind::Stalled, joint);
        self.set_outcome(Outcome::Stalled {
            joint,
            time,
            magnet,
            reason,
        });
    }

    /// Keeps the earliest stop: stalls are pushed when found, not when they happen.
    fn set_outcome(&mut self, new: Outcome) {
        if new.time() < self.outcome.time() {
            self.outcome = new;
        }
    }

    fn finish(self) -> Timeline {
        let parameters = kinematic_parameters(&self.geometry, &self.opts);
        Timeline {
            parameters,
            free_motion: None,
            geometry: self.geometry,
            speed: self.opts.speed,
            force_law: self.opts.model.force_law,
            motions: self.motions,
            start: self.start,
            events: self.events,
            folds: self.folds,
            outcome: self.outcome,
            max_moving: self.max_moving,
            fold_of_joint: self.fold_of_joint,
            solved: None,
        }
    }
}

/// The parameters of a kinematic run: its speed law's drag and the design's masses (which its
/// closed-form motion does not use: it moves every magnet at the overdamped speed law's pace).
fn kinematic_parameters(geometry: &Geometry, opts: &EngineOptions) -> Parameters {
    let d = geometry.design(0);
    let drag = match opts.speed {
        SpeedLaw::Overdamped { drag } | SpeedLaw::Inertial { drag } => drag,
        SpeedLaw::Unit => 0.0,
    };
    Parameters {
        dynamics: "kinematic",
        cutoff: match opts.start {
            StartRule::Force { cutoff } => cutoff,
            StartRule::Distance => 1,
        },
        distance_cutoff_mm: None,
        ..crate::model::parameters(d, &opts.model, "kinematic baseline", drag, d.friction)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::Design;

    fn run_word(word: &str, s: f64, speed: SpeedLaw) -> Timeline {
        let chain = Chain::parse(word).unwrap();
        run(
            &chain,
            &TileDesigns::global(Design::thesis().with_s(s)),
            &EngineOptions::default().with_speed(speed),
        )
        .unwrap()
    }

    #[test]
    fn the_reported_law_is_the_dynamics_of_the_run() {
        // a local run under inertia reports the inertial law, not the overdamped one its
        // kinematic motion table uses
        let chain = Chain::parse("SLLS").unwrap();
        let designs = TileDesigns::global(Design::thesis());
        for (dynamics, want) in [
            (
                Dynamics::Inertial,
                SpeedLaw::Inertial {
                    drag: crate::physics::DEFAULT_INERTIAL_DRAG,
                },
            ),
            (Dynamics::Overdamped, SpeedLaw::default()),
        ] {
            let model = ModelOptions::default().with_dynamics(dynamics);
            let opts = EngineOptions::default().with_model(model);
            let tl = run(&chain, &designs, &opts).unwrap();
            assert_eq!(tl.summary().speed_law, want, "{dynamics:?}");
        }
    }

    #[test]
    fn events_are_ordered_and_every_mover_arrives() {
        let t = run_word("SSLLSS", 0.3, SpeedLaw::default());
        assert_eq!(t.outcome, Outcome::Completed);
        assert!(t.events.windows(2).all(|w| w[0].time <= w[1].time));
        let starts = t.count(EventKind::MagnetStarts);
        assert_eq!(starts, 2 * t.tiles() - 1);
        assert_eq!(t.count(EventKind::MagnetArrives), starts);
        assert_eq!(t.folded_joints(), vec![2, 3]);
        assert_eq!(t.count(EventKind::FoldStarts), 2);
    }

    #[test]
    fn unit_speed_start_times_are_multiples_of_4s() {
        let t = run_word("SSSSS", 0.3, SpeedLaw::Unit);
        for k in 0..t.geometry.magnets() - 1 {
            let s = t.start_of(k).unwrap();
            assert!((s - 1.2 * k as f64).abs() < 1e-9, "{k}: {s}");
        }
        assert_eq!(t.start_of(t.geometry.magnets() - 1), None);
    }

    #[test]
    fn bad_options_are_refused_by_name() {
        let chain = Chain::parse("SS").unwrap();
        let designs = TileDesigns::default();
        let e = run(
            &chain,
            &designs,
            &EngineOptions::default().with_speed(SpeedLaw::Overdamped { drag: -1.0 }),
        )
        .unwrap_err();
        assert!(e.to_string().contains("drag coefficient -1"), "{e}");
        let bad = TileDesigns::global(Design::thesis().with_s(-0.5));
        let e = run(&chain, &bad, &EngineOptions::default()).unwrap_err();
        assert!(matches!(e, EngineError::Design(_)), "{e:?}");
        assert!(e.to_string().starts_with("design: "), "{e}");
    }
}
