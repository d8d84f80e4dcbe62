//! What a run's summary calls its result: how propagation ended, or what overruled it.

use std::fmt;

use crate::timeline::Outcome;

/// The result of a run, as `summary.json` writes it (`"completed"`, `"inhibited"`, ...): how
/// propagation ended ([`Outcome`]), unless a collision, a stop or an undecidable check
/// overruled it.
///
/// ```
/// use foldchain::timeline::{Outcome, RunResult};
///
/// assert_eq!(RunResult::from(&Outcome::Completed), RunResult::Completed);
/// assert_eq!(RunResult::Collided.to_string(), "collided");
/// assert_eq!(serde_json::to_string(&RunResult::Stopped).unwrap(), "\"stopped\"");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum RunResult {
    /// Every magnet that can move arrived, every joint closed, and nothing overruled it.
    Completed,
    /// Propagation was inhibited at a joint ([`Outcome::Inhibited`]).
    Inhibited,
    /// A magnet never started its successor ([`Outcome::Stalled`]).
    Stalled,
    /// Two tiles collided on the way or in the final shape.
    Collided,
    /// The run stopped before its end (a step size underflow: dynamics singular there).
    Stopped,
    /// The run could not decide within its work budget: a balance that a simulation's
    /// bounded work neither passes nor settles on (the reason says which and its margin), or
    /// a collision check that ran out of its budget.
    Undecided,
}

impl RunResult {
    /// The name `summary.json` writes: `completed`, `inhibited`, `stalled`, `collided`,
    /// `stopped` or `undecided`.
    pub fn name(self) -> &'static str {
        match self {
            RunResult::Completed => "completed",
            RunResult::Inhibited => "inhibited",
            RunResult::Stalled => "stalled",
            RunResult::Collided => "collided",
            RunResult::Stopped => "stopped",
            RunResult::Undecided => "undecided",
        }
    }
}

impl From<&Outcome> for RunResult {
    fn from(outcome: &Outcome) -> RunResult {
        match outcome {
            Outcome::Completed => RunResult::Completed,
            Outcome::Inhibited { .. } => RunResult::Inhibited,
            Outcome::Stalled { .. } => RunResult::Stalled,
        }
    }
}

impl fmt::Display for RunResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl PartialEq<&str> for RunResult {
    fn eq(&self, other: &&str) -> bool {
        self.name() == *other
    }
}
