//! How propagation ended: completed, inhibited at a joint whose pair diverges, or stalled
//! where a magnet never started its successor.

use crate::timeline::{Event, EventKind};

/// How propagation ended.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Outcome {
    /// Every magnet that can move arrived; every joint closed.
    Completed,
    /// A pair diverged at `joint`: propagation stops there (thesis Table 7.1, LR and RL).
    Inhibited {
        /// The joint (0 = nearest the RI).
        joint: usize,
        /// When, s.
        time: f64,
        /// Distance between the pair's path ends, mm.
        end_distance_mm: f64,
        /// Distance between the pair at rest, mm.
        rest_distance_mm: f64,
    },
    /// A magnet never started its successor.
    Stalled {
        /// The joint the missing start belongs to (0 = nearest the RI).
        joint: usize,
        /// When the mover passed its nearest approach to starting it, s.
        time: f64,
        /// The magnet that never started.
        magnet: usize,
        /// Why, in words.
        reason: String,
    },
}

impl Outcome {
    /// `completed`, `inhibited` or `stalled`.
    pub fn name(&self) -> &'static str {
        crate::timeline::RunResult::from(self).name()
    }

    /// When propagation stopped, s (infinite when it completed).
    pub fn time(&self) -> f64 {
        match self {
            Outcome::Completed => f64::INFINITY,
            Outcome::Inhibited { time, .. } | Outcome::Stalled { time, .. } => *time,
        }
    }

    /// The event that closes a run's log when propagation stopped at `time` (an inhibition
    /// or a stall at its joint); `None` when it completed.
    pub fn stop_event(&self, time: f64) -> Option<Event> {
        let (kind, joint) = match self {
            Outcome::Completed => return None,
            Outcome::Inhibited { joint, .. } => (EventKind::Inhibited, *joint),
            Outcome::Stalled { joint, .. } => (EventKind::Stalled, *joint),
        };
        Some(Event {
            time,
            index: joint as u32,
            kind,
        })
    }

    /// Why propagation stopped, in words (`None` when it completed); `decided_by` names what
    /// decided an inhibition (e.g. "opposite curves, thesis Table 7.1").
    pub fn reason(&self, decided_by: &str) -> Option<String> {
        match self {
            Outcome::Completed => None,
            Outcome::Inhibited { joint, end_distance_mm, rest_distance_mm, .. } => Some(format!(
                "propagation inhibited at joint {joint}: its pair's path ends lie {end_distance_mm:.3} mm apart, farther than the {rest_distance_mm:.3} mm between them at rest ({decided_by})"
            )),
            Outcome::Stalled { reason, .. } => Some(reason.clone()),
        }
    }
}
