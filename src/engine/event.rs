//! The events of a run: what happens, when, to which magnet or joint.

use std::fmt;

/// What happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum EventKind {
    /// The reaction initiator reaches the edge of tile 0 (index 0).
    RiContact,
    /// A magnet arrives at the end of its path (index: magnet).
    MagnetArrives,
    /// A fold ends: both magnets of the pair have arrived (index: joint).
    FoldEnds,
    /// Propagation is inhibited at a joint whose pair diverges (index: joint).
    Inhibited,
    /// Propagation stalls: a magnet never starts its successor (index: joint).
    Stalled,
    /// A moving magnet reaches the point that starts the next one (index: the moving magnet).
    TriggerReached,
    /// A magnet starts moving (index: magnet).
    MagnetStarts,
    /// A fold starts: both magnets of the pair are moving (index: joint).
    FoldStarts,
}

impl EventKind {
    /// Whether the index names a joint (otherwise a magnet, or nothing for RI contact).
    pub fn is_joint_event(self) -> bool {
        matches!(
            self,
            EventKind::FoldStarts | EventKind::FoldEnds | EventKind::Inhibited | EventKind::Stalled
        )
    }

    /// The snake-case name used in `timeline.json`.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::RiContact => "ri_contact",
            EventKind::MagnetArrives => "magnet_arrives",
            EventKind::FoldEnds => "fold_ends",
            EventKind::Inhibited => "inhibited",
            EventKind::Stalled => "stalled",
            EventKind::TriggerReached => "trigger_reached",
            EventKind::MagnetStarts => "magnet_starts",
            EventKind::FoldStarts => "fold_starts",
        }
    }
}

impl fmt::Display for EventKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One event: 16 bytes, so a million-tile timeline stays about 100 MB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Time, seconds from RI contact.
    pub time: f64,
    /// The magnet or joint (see [`EventKind`]).
    pub index: u32,
    /// What happens.
    pub kind: EventKind,
}

impl Event {
    /// The event as one compact JSON array `[time, "kind", index]`.
    pub fn to_json(&self) -> String {
        format!(
            "[{},\"{}\",{}]",
            json_f64(self.time),
            self.kind.name(),
            self.index
        )
    }
}

/// A finite f64 printed for JSON (shortest round-trip form).
pub(crate) fn json_f64(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        "null".to_string()
    }
}
