//! The transition diagram's data (thesis figure 6.3): each magnet's travel along its path
//! against time for a range of tiles, and where a moving magnet started the next one.

use crate::timeline::{Event, EventKind};

/// One magnet's line in the transition diagram.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MagnetTrack {
    /// When it first starts, if it does (a dot is drawn there).
    pub start: Option<f64>,
    /// `(time s, arc length travelled from the rest point mm)`, in time order.
    pub travel: Vec<(f64, f64)>,
}

/// What the transition diagram shows: the same whichever simulation made it (the event
/// engine's timeline or the reference integrator's recorded states, through
/// [`crate::timeline::RunSource::transition`]).
#[derive(Clone, Debug, PartialEq)]
pub struct TransitionData {
    /// First tile shown.
    pub first: usize,
    /// Last tile shown (inclusive).
    pub last: usize,
    /// The time axis runs from 0 to this, s.
    pub t1: f64,
    /// One track per magnet `2 * first ..= 2 * last + 1`.
    pub tracks: Vec<MagnetTrack>,
    /// Where a moving magnet started the next one: `(magnet, time s, travel mm)`.
    pub triggers: Vec<(usize, f64, f64)>,
}

impl TransitionData {
    /// The diagram of magnets `2 * first ..= 2 * last + 1` with their `tracks` (in magnet
    /// order) on an axis to `t1`, its trigger ticks from the `events` of those magnets: each
    /// at the travel `travel_at(track, magnet, time)` of the magnet that reached it.
    pub(crate) fn from_tracks(
        (first, last): (usize, usize),
        t1: f64,
        tracks: Vec<MagnetTrack>,
        events: &[Event],
        travel_at: impl Fn(&MagnetTrack, usize, f64) -> f64,
    ) -> TransitionData {
        let magnets = 2 * first..=2 * last + 1;
        let triggers = events
            .iter()
            .filter(|e| e.kind == EventKind::TriggerReached)
            .map(|e| (e.index as usize, e.time))
            .filter(|(k, _)| magnets.contains(k))
            .map(|(k, t)| (k, t, travel_at(&tracks[k - 2 * first], k, t)))
            .collect();
        TransitionData {
            first,
            last,
            t1,
            tracks,
            triggers,
        }
    }

    /// The time axis' end for a diagram whose last shown magnet arrives at `end_time`.
    pub fn axis_end(end_time: f64) -> f64 {
        end_time.max(1e-9) * 1.08
    }

    /// The tiles shown for a request of `first..=last` on a chain of `tiles` (clamped).
    pub fn tile_range(tiles: usize, first: usize, last: usize) -> (usize, usize) {
        let last = last.min(tiles.saturating_sub(1));
        (first.min(last), last)
    }
}
