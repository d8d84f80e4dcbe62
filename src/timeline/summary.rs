//! The summary of a run: what `summary.json` holds and `fold-run --json` prints, the same
//! fields whichever simulation made the run.

use crate::timeline::{FreeMotion, Outcome, Parameters, RunResult, SpeedLaw};

/// The first collision of a run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CollisionReport {
    /// Time of contact, s (`None` when found only in the final shape).
    pub time: Option<f64>,
    /// The joint folding at contact (0 = nearest the RI), if any: the fold front, the highest
    /// joint between the two tiles turning at contact ([`crate::collision::Collision::joint`]).
    pub joint: Option<usize>,
    /// The two tiles, lower index first.
    pub tiles: (usize, usize),
}

/// How close two tiles that are not neighbours came over a run (the closest approach of
/// [`crate::collision`]'s clearance measurement).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Clearance {
    /// The smallest distance between the outlines of two tiles that are not neighbours, mm:
    /// negative for an overlap (its depth, the least translation that parts them). Within
    /// `precision_mm` above the true minimum, never below it.
    pub mm: f64,
    /// The two tiles, lower index first.
    pub tiles: (usize, usize),
    /// When, s.
    pub time: f64,
    /// The fold front then: the highest joint between the tiles turning and whose fold goes
    /// on, else the highest turning; null when none turns (the chain at rest).
    pub joint: Option<usize>,
    /// An overlap no deeper than the overlap tolerance: the run counts it as touching.
    pub graze: bool,
    /// The overlap tolerance of the run's collision check, mm
    /// ([`crate::collision::CheckOptions::overlap_mm`]).
    pub overlap_tolerance_mm: f64,
    /// The precision of `mm`, mm.
    pub precision_mm: f64,
}

/// The facts of a run a summary reports (see `Summary::new`).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RunFacts<'a> {
    /// Number of tiles.
    pub tiles: usize,
    /// How propagation ended.
    pub outcome: &'a Outcome,
    /// What decided an inhibition, for its reason (e.g. "reference dynamics").
    pub decided_by: &'a str,
    /// Time of the last event, s.
    pub duration_s: f64,
    /// Number of events.
    pub events: usize,
    /// The joints that folded.
    pub folds: Vec<usize>,
    /// The most magnets moving at one instant.
    pub max_moving_magnets: usize,
    /// The speed law the times are in.
    pub speed_law: SpeedLaw,
}

/// The summary of a run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    /// Number of tiles.
    pub tiles: usize,
    /// Whether the chain folded completely and cleanly (no stop, no collision).
    pub completed: bool,
    /// `completed`, `inhibited`, `stalled`, or what overruled the outcome (`collided`,
    /// `stopped`, `undecided`).
    pub result: RunResult,
    /// Time of the last event, s (mm of travel at unit speed).
    pub duration_s: f64,
    /// Number of events in `timeline.json`.
    pub events: usize,
    /// The joints that folded.
    pub folds: Vec<usize>,
    /// The most magnets moving at one instant.
    pub max_moving_magnets: usize,
    /// The joint where propagation was inhibited (0 = nearest the RI), or null.
    pub inhibited_at: Option<usize>,
    /// The joint where propagation stalled, or null.
    pub stalled_at: Option<usize>,
    /// Why it stopped, in words, or null.
    pub reason: Option<String>,
    /// The first collision, or null.
    pub first_collision: Option<CollisionReport>,
    /// How close two tiles that are not neighbours came, or null when not measured (no
    /// collision check, fewer than three tiles, a chain over 10 million tiles or a
    /// measurement over its work budget).
    pub clearance: Option<Clearance>,
    /// The speed law (`overdamped` with its drag, or `unit`).
    pub speed_law: SpeedLaw,
    /// The physical parameters the run used (null when not known: a summary made from a
    /// run's facts alone).
    pub parameters: Option<Parameters>,
    /// How the chain moved on the water, nothing anchored (null for the kinematic baseline
    /// and a summary made from a run's facts alone).
    pub free_motion: Option<FreeMotion>,
}

impl Summary {
    /// The summary of a run with `facts`, its result the outcome's.
    pub(crate) fn new(facts: RunFacts) -> Summary {
        let outcome = facts.outcome;
        let result = RunResult::from(outcome);
        Summary {
            tiles: facts.tiles,
            completed: result == RunResult::Completed,
            result,
            duration_s: facts.duration_s,
            events: facts.events,
            folds: facts.folds,
            max_moving_magnets: facts.max_moving_magnets,
            inhibited_at: match outcome {
                Outcome::Inhibited { joint, .. } => Some(*joint),
                _ => None,
            },
            stalled_at: match outcome {
                Outcome::Stalled { joint, .. } => Some(*joint),
                _ => None,
            },
            reason: outcome.reason(facts.decided_by),
            first_collision: None,
            clearance: None,
            speed_law: facts.speed_law,
            parameters: None,
            free_motion: None,
        }
    }

    /// The same summary stating the parameters the run used.
    pub fn with_parameters(mut self, parameters: Parameters) -> Summary {
        self.parameters = Some(parameters);
        self
    }

    /// The same summary stating how the chain moved on the water.
    pub fn with_free_motion(mut self, free_motion: FreeMotion) -> Summary {
        self.free_motion = Some(free_motion);
        self
    }

    /// The same summary, `undecided` because the run ran out of its work budget before the
    /// physics decided (`why`: the budget, the balance and its margin): `why` replaces the
    /// outcome's reason, and no stall is claimed.
    pub(crate) fn undecided(mut self, why: String) -> Summary {
        self.result = RunResult::Undecided;
        self.completed = false;
        self.stalled_at = None;
        self.reason = Some(why);
        self
    }

    /// The same summary with its result overruled: the run counts as `result` (not
    /// completed), and `why` goes before the outcome's reason.
    pub(crate) fn overruled(mut self, result: RunResult, why: String) -> Summary {
        self.result = result;
        self.completed = false;
        self.reason = Some(match self.reason {
            Some(r) => format!("{why}; {r}"),
            None => why,
        });
        self
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    fn facts(outcome: &Outcome) -> RunFacts<'_> {
        RunFacts {
            tiles: 5,
            outcome,
            decided_by: "test",
            duration_s: 1.5,
            events: 12,
            folds: vec![1, 2],
            max_moving_magnets: 3,
            speed_law: SpeedLaw::Unit,
        }
    }

    #[test]
    fn fields_follow_the_outcome() {
        let s = Summary::new(facts(&Outcome::Completed));
        assert!(s.completed);
        assert_eq!(
            (s.result, s.inhibited_at, s.stalled_at),
            (RunResult::Completed, None, None)
        );
        assert_eq!(s.reason, None);
        let inhibited = Outcome::Inhibited {
            joint: 2,
            time: 1.0,
            end_distance_mm: 9.0,
            rest_distance_mm: 8.0,
        };
        let s = Summary::new(facts(&inhibited));
        assert!(!s.completed);
        assert_eq!(
            (s.result, s.inhibited_at, s.stalled_at),
            (RunResult::Inhibited, Some(2), None)
        );
        let reason = s.reason.clone().unwrap();
        assert!(
            reason.contains("joint 2") && reason.contains("9.000 mm") && reason.ends_with("(test)"),
            "{reason}"
        );
        let s = s.overruled(RunResult::Stopped, "step limit".into());
        assert_eq!(s.result, "stopped");
        assert_eq!(s.reason.unwrap(), format!("step limit; {reason}"));
        let stalled = Outcome::Stalled {
            joint: 1,
            time: 1.0,
            magnet: 3,
            reason: "why".into(),
        };
        let s =
            Summary::new(facts(&stalled)).overruled(RunResult::Collided, "tiles 0 and 4".into());
        assert_eq!(
            (s.result, s.completed, s.stalled_at),
            (RunResult::Collided, false, Some(1))
        );
        assert_eq!(s.reason.as_deref(), Some("tiles 0 and 4; why"));
        let json: serde_json::Value = serde_json::to_value(&s).unwrap();
        assert_eq!(json["speed_law"], "unit");
        assert_eq!(json["folds"], serde_json::json!([1, 2]));
        // the result is written as its name, as when it was a string
        assert_eq!(json["result"], "collided");
    }
}
