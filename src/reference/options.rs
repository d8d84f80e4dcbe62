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
/// defaults, at most 2,000,000 steps, no states recorded ([`Recording::Off`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
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
