//! The events of a run: what happens, when, to which magnet or joint; and which joint a
//! magnet closes.

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

    /// Whether the event is a motion's start or end: a magnet starts or arrives, a fold
    /// starts or ends (not the RI's contact, not a verdict).
    pub fn is_motion(self) -> bool {
        matches!(
            self,
            EventKind::MagnetStarts
                | EventKind::MagnetArrives
                | EventKind::FoldStarts
                | EventKind::FoldEnds
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

/// One event: 16 bytes, so a million-tile timeline stays about 100 MB. In JSON, the array
/// `[time, "kind", index]` (a time that is not finite is `null`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    /// Time, seconds from RI contact.
    pub time: f64,
    /// The magnet or joint (see [`EventKind`]).
    pub index: u32,
    /// What happens.
    pub kind: EventKind,
}

impl serde::Serialize for Event {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        (self.time, self.kind, self.index).serialize(serializer)
    }
}

/// Where the chain has `s = 0` every interior magnet rests exactly balanced and is driven off
/// its rest point by a rounding-sized force, so the moment its drive first turns positive
/// is no physical start (a 10 nm change of `s` moves it by several percent of the run). Both
/// simulations then report a magnet's start when it has travelled this fraction of its path:
/// 0.01.
pub(crate) const S0_START_FRACTION: f64 = 0.01;

/// The start fraction of a chain: [`S0_START_FRACTION`] when any of its tiles has `s = 0`,
/// else 0 (a start is reported when the magnet is first driven off its rest point).
pub fn start_fraction(geometry: &crate::timeline::Geometry) -> f64 {
    if (0..geometry.tiles()).any(|t| geometry.design(t).s == 0.0) {
        S0_START_FRACTION
    } else {
        0.0
    }
}

/// The joint whose closing a magnet takes part in: odd magnet `2j + 1` and even magnet
/// `2j + 2` close joint `j` (magnet 0 belongs to the RI contact: joint 0).
pub fn joint_of_magnet(k: usize) -> usize {
    if k % 2 == 1 {
        (k - 1) / 2
    } else {
        (k / 2).saturating_sub(1)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn events_are_compact_json_arrays() {
        let e = Event {
            time: 0.25,
            index: 7,
            kind: EventKind::MagnetStarts,
        };
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"[0.25,"magnet_starts",7]"#
        );
        let e = Event {
            time: f64::NAN,
            ..e
        };
        assert_eq!(
            serde_json::to_string(&e).unwrap(),
            r#"[null,"magnet_starts",7]"#
        );
        assert_eq!(std::mem::size_of::<Event>(), 16);
    }

    #[test]
    fn each_joint_is_closed_by_its_pair() {
        assert_eq!(joint_of_magnet(0), 0);
        for j in 0..5 {
            assert_eq!(joint_of_magnet(2 * j + 1), j);
            assert_eq!(joint_of_magnet(2 * j + 2), j);
        }
    }
}
