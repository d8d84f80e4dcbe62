//! The result of an engine run: every event, each magnet's start and motion, the folds and
//! the outcome ([`Timeline`]); where every magnet is and every joint's angle at any time.

use crate::engine::local::Solved;
use crate::engine::run_state::RunState;
use crate::engine::speed::{Motion, MotionTable};
use crate::physics::ForceLaw;
use crate::timeline::Event;
use crate::timeline::{
    EventKind, FoldRecord, FreeMotion, Geometry, Outcome, Parameters, RunFacts, SpeedLaw, Summary,
};

/// The result of a run: every event, each magnet's start, the folds and the outcome.
#[derive(Debug)]
pub struct Timeline {
    /// The chain's geometry at rest.
    pub geometry: Geometry,
    /// The speed law used.
    pub speed: SpeedLaw,
    pub(crate) force_law: ForceLaw,
    pub(crate) motions: MotionTable,
    pub(crate) start: Vec<f64>,
    /// Every event, in time order.
    pub events: Vec<Event>,
    /// The folds, in the order they start.
    pub folds: Vec<FoldRecord>,
    /// How propagation ended.
    pub outcome: Outcome,
    /// The most magnets moving at one instant, and the first time it happens.
    pub max_moving: (usize, f64),
    pub(crate) fold_of_joint: Vec<u32>,
    /// The local solves' tracks (`None` for the kinematic baseline).
    pub(crate) solved: Option<Box<Solved>>,
    /// The physical parameters the run used.
    pub parameters: Parameters,
    /// How the chain moved on the water (`None` for the kinematic baseline).
    pub free_motion: Option<FreeMotion>,
}

/// What decides an inhibition in the engine, for its reason.
const DECIDED_BY: &str = "opposite curves, thesis Table 7.1";

impl Timeline {
    /// Every joint's angle at time `t`, radians, positive = left (joints that never fold
    /// stay at 0): the angles [`crate::Pose::chain_at_angles`] takes.
    ///
    /// ```
    /// use foldchain::engine::{run, EngineOptions};
    /// use foldchain::timeline::TileDesigns;
    /// use foldchain::Chain;
    ///
    /// let tl = run(&Chain::parse("SLLS").unwrap(), &TileDesigns::default(), &EngineOptions::default()).unwrap();
    /// let end = tl.joint_angles_at(tl.duration());
    /// assert_eq!(end.len(), 4);
    /// assert!((end[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    /// ```
    pub fn joint_angles_at(&self, t: f64) -> Vec<f64> {
        joint_angles_at(self, t)
    }

    pub(crate) fn progress(&self) -> RunState<'_> {
        RunState {
            start: &self.start,
            motions: &self.motions,
            folds: &self.folds,
            fold_of_joint: &self.fold_of_joint,
            solved: self.solved.as_deref(),
        }
    }

    /// Local solves made and sweeps over the chain (`None` for the kinematic baseline).
    pub fn solve_counts(&self) -> Option<(usize, usize, u64)> {
        self.solved
            .as_ref()
            .map(|s| (s.chain.solves, s.chain.sweeps, s.chain.rhs))
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.geometry.tiles()
    }

    /// The pair law the run's force start rule and energy use.
    pub fn force_law(&self) -> ForceLaw {
        self.force_law
    }

    /// When magnet `k` starts, or `None` if it never moves.
    pub fn start_of(&self, k: usize) -> Option<f64> {
        self.progress().start_of(k)
    }

    /// Magnet `k`'s closed-form motion law (the kinematic baseline's; a local-solve run
    /// keeps it for comparison only: its times are [`Timeline::travel_at`]'s).
    pub(crate) fn motion(&self, k: usize) -> &Motion {
        self.motions.of(k)
    }

    /// When magnet `k` arrives, or `None` if it never moves.
    pub fn arrival_of(&self, k: usize) -> Option<f64> {
        self.progress().arrival_of(k)
    }

    /// The arc length magnet `k` has travelled at time `t`, mm.
    pub fn travel_at(&self, k: usize, t: f64) -> f64 {
        self.progress().travel_at(k, t)
    }

    /// Whether magnet `k` is moving at time `t`.
    pub fn is_moving(&self, k: usize, t: f64) -> bool {
        match (self.start_of(k), self.arrival_of(k)) {
            (Some(s), Some(a)) => t >= s && t < a,
            _ => false,
        }
    }

    /// Magnet `k`'s position in its tile's frame at time `t`, mm.
    pub fn local_position(&self, k: usize, t: f64) -> (f64, f64) {
        self.geometry.path(k).point_at(self.travel_at(k, t))
    }

    /// When the last event happens, s.
    pub fn duration(&self) -> f64 {
        self.events.last().map_or(0.0, |e| e.time)
    }

    /// The fold of joint `j`, if it folds.
    pub fn fold_at(&self, j: usize) -> Option<&FoldRecord> {
        self.progress().fold_at(j)
    }

    /// The folds whose joints turned.
    pub fn folded_joints(&self) -> Vec<usize> {
        self.folds.iter().map(|f| f.joint).collect()
    }

    /// Number of events of a kind.
    pub fn count(&self, kind: EventKind) -> usize {
        self.events.iter().filter(|e| e.kind == kind).count()
    }

    /// The most magnets moving together.
    pub fn max_moving_magnets(&self) -> usize {
        self.max_moving.0
    }

    /// The run's summary (the collision check's verdict is added by
    /// [`crate::simulate`]).
    pub fn summary(&self) -> Summary {
        let summary = Summary::new(RunFacts {
            tiles: self.tiles(),
            outcome: &self.outcome,
            decided_by: DECIDED_BY,
            duration_s: self.duration(),
            events: self.events.len(),
            folds: self.folded_joints(),
            max_moving_magnets: self.max_moving_magnets(),
            speed_law: self.speed,
        })
        .with_parameters(self.parameters.clone());
        match &self.free_motion {
            Some(f) => summary.with_free_motion(f.clone()),
            None => summary,
        }
    }
}

/// The signed angle (radians, positive = left) of the fold `fold` of `timeline` at time `t`
/// (the fold law, [`crate::engine`]).
pub fn fold_angle(timeline: &Timeline, fold: &FoldRecord, t: f64) -> f64 {
    timeline.progress().fold_angle(fold, t)
}

/// Every joint's angle at time `t` (joints that never fold stay at 0).
pub(crate) fn joint_angles_at(timeline: &Timeline, t: f64) -> Vec<f64> {
    let mut a = vec![0.0; timeline.tiles().saturating_sub(1)];
    for f in &timeline.folds {
        a[f.joint] = fold_angle(timeline, f, t);
    }
    a
}
