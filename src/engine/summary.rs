//! The summary of a run: what `summary.json` holds and `fold-run --json` prints.

use crate::collision::Collision;
use crate::engine::run::Timeline;

/// The first collision of a run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CollisionReport {
    /// Time of contact, s (`None` when found only in the final shape).
    pub time: Option<f64>,
    /// The joint folding at contact (0 = nearest the RI), if any.
    pub joint: Option<usize>,
    /// The two tiles, lower index first.
    pub tiles: (usize, usize),
}

impl From<&Collision> for CollisionReport {
    fn from(c: &Collision) -> CollisionReport {
        CollisionReport {
            time: c.time,
            joint: c.joint,
            tiles: c.tiles,
        }
    }
}

/// The summary of a run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Summary {
    /// Number of tiles.
    pub tiles: usize,
    /// Whether the chain folded completely and cleanly (no stop, no collision).
    pub completed: bool,
    /// `completed`, `inhibited`, `stalled` or `collided`.
    pub result: &'static str,
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
    /// The speed law (`overdamped` with its drag, or `unit`).
    pub speed_law: crate::engine::SpeedLaw,
}

impl Summary {
    /// The summary of `timeline` with the collision check's verdict.
    pub fn new(tl: &Timeline, collision: Option<&Collision>) -> Summary {
        let (inhibited_at, stalled_at, mut reason, outcome) = tl
            .outcome
            .summary_fields("opposite curves, thesis Table 7.1");
        let first_collision = collision.map(CollisionReport::from);
        if let Some(c) = collision {
            let msg = c.to_string();
            reason = Some(match reason {
                Some(r) => format!("{msg}; {r}"),
                None => msg,
            });
        }
        let result = if first_collision.is_some() {
            "collided"
        } else {
            outcome
        };
        Summary {
            tiles: tl.tiles(),
            completed: result == "completed",
            result,
            duration_s: tl.duration(),
            events: tl.events.len(),
            folds: tl.folded_joints(),
            max_moving_magnets: tl.max_moving_magnets(),
            inhibited_at,
            stalled_at,
            reason,
            first_collision,
            speed_law: tl.speed,
        }
    }

    /// Pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}
