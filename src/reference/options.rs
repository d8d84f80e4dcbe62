//! The options of a reference run: the integrator and its tolerance, the model, the step
//! limit and the states kept for pictures; and why a run could not be made.

use crate::model::{ModelError, ModelOptions};
use crate::ode::Method;

/// Which states a reference run keeps besides the final one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Recording {
    /// None (the default): [`crate::reference::ReferenceRun::states`] is empty.
    #[default]
    Off,
    /// States on an evenly spaced time grid from 0, then the final state at
    /// [`crate::reference::ReferenceRun::end_time`]: at most `max_states` in all (taken as at
    /// least 3), so at most `max_states * (8 * unknowns + 32)` bytes, with one unknown per
    /// magnet and one per folding joint, at most three per tile (2,000 tiles and 1,000
    /// states: under 50 MB). The spacing starts at a thousandth of the model's time scale and
    /// doubles whenever the budget is reached, so a run that needed a doubling ends with at
    /// least about `max_states / 2` states.
    Grid {
        /// The most states kept, the final one included.
        max_states: usize,
    },
}

impl Recording {
    /// A grid of states within a memory budget for a chain of `tiles` tiles: 48 MiB worth
    /// (one state is 8 bytes per unknown, at most three unknowns per tile), from 64 to 4,096
    /// states (about 1,000 at 2,000 tiles). What the pictures and the viewer of a run need.
    ///
    /// ```
    /// use foldchain::reference::Recording;
    ///
    /// assert_eq!(Recording::within_budget(10), Recording::Grid { max_states: 4096 });
    /// assert!(matches!(Recording::within_budget(2000), Recording::Grid { max_states } if max_states > 1000));
    /// ```
    pub fn within_budget(tiles: usize) -> Recording {
        Recording::Grid {
            max_states: crate::reference::state_budget(tiles),
        }
    }
}

/// Options of a reference run. Defaults: Dormand-Prince, tolerance 1e-8, the model's
/// defaults, a work budget of 200,000 steps per tile up to 2,000,000 steps, no states
/// recorded ([`Recording::Off`]).
///
/// **Work budget.** A run takes at most [`ReferenceOptions::step_budget`] steps (accepted
/// and rejected), proportional to its chain, and goes at most 1e4 times its slowest time
/// scale (or its time so far) without an event, and (inertial) cuts its steps at most 2,000
/// times for a start that does not come. A run that reaches any of these has not decided:
/// a magnet or fold creeping towards a balance it neither passes nor settles on (a design
/// on a knife edge). Its result is `undecided`, with that balance and its margin
/// ([`crate::timeline::RunResult::Undecided`]). 200,000 steps a tile: runs of the tests and
/// benchmarks take under 1,000 steps a tile (SLRRRL at s = 0, 7 tiles: 1,188 steps), but an
/// explicit integration of magnets a tenth of the thesis' mass (the stiff limit of
/// `tests/reference_inertial.rs`) needs more than 20,000.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ReferenceOptions {
    /// The integrator.
    pub method: Method,
    /// Relative and absolute tolerance on the unknowns (fractions of a path or of a fold).
    pub tolerance: f64,
    /// The model's options.
    pub model: ModelOptions,
    /// Most steps (accepted and rejected) whatever the chain's length (default 2,000,000).
    pub max_steps: u64,
    /// Steps a tile of the work budget (default
    /// [`ReferenceOptions::DEFAULT_STEPS_PER_TILE`]).
    pub steps_per_tile: u64,
    /// States to keep for pictures (default [`Recording::Off`]).
    pub record: Recording,
    /// Inertial dynamics only: the joints turning at once integrated together (default
    /// `false`: each joint on its own, its two sides rigid in their sequential shapes). The
    /// groups between turning joints are rigid bodies whose accelerations come from the
    /// free-body reference's articulated-body recursion with the chain's momentum held at
    /// zero (its base's velocity follows the joints' rates), a held face lets go when the
    /// torque it passes would have to pull the part after it back, and a fold meeting its
    /// walls is an impulse on the whole chain (docs/free-body.md, "The coupled joint-angle
    /// reference"). Dormand-Prince only.
    pub coupled: bool,
}

impl Default for ReferenceOptions {
    fn default() -> ReferenceOptions {
        ReferenceOptions {
            method: Method::Dopri5,
            tolerance: 1e-8,
            model: ModelOptions::default(),
            max_steps: 2_000_000,
            steps_per_tile: ReferenceOptions::DEFAULT_STEPS_PER_TILE,
            record: Recording::Off,
            coupled: false,
        }
    }
}

impl ReferenceOptions {
    /// The work budget's steps a tile: 200,000 (see the type's documentation).
    pub const DEFAULT_STEPS_PER_TILE: u64 = 200_000;

    /// The most steps a run of `tiles` tiles takes: `steps_per_tile` times the tiles, at
    /// most `max_steps`.
    pub fn step_budget(&self, tiles: usize) -> u64 {
        self.steps_per_tile
            .saturating_mul(tiles.max(1) as u64)
            .min(self.max_steps)
    }

    /// Another work budget a tile.
    pub fn with_steps_per_tile(mut self, steps: u64) -> ReferenceOptions {
        self.steps_per_tile = steps;
        self
    }

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
    /// The joints turning at once integrated together, or not ([`ReferenceOptions::coupled`]).
    pub fn with_coupled(mut self, coupled: bool) -> ReferenceOptions {
        self.coupled = coupled;
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
    /// A free-body option out of range ([`crate::reference::FreeBodyOptions`]).
    #[error("free-body option `{name}` = {value}: expected {expected}")]
    FreeBodyOption {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// The recorded fold schedule handed to the collision check was malformed (a bug of the
    /// run, reported rather than hidden): what was wrong with it.
    #[error("fold schedule: {0}")]
    Schedule(String),
    /// Something the free-body reference does not do.
    #[error("the free-body reference does not take {what}: {why}")]
    FreeBodyUnsupported {
        /// What was asked for.
        what: &'static str,
        /// Why not.
        why: &'static str,
    },
}
