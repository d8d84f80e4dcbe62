//! How one run's events compare with a reference run's.
//!
//! Events are matched by kind and index (magnet starts and arrivals, fold starts and ends).
//! `error_time` is the largest difference of a matched event's time from the reference's,
//! over the reference's duration. Events one run has and the other has not are counted
//! (`missing`), and the order of the matched events is compared pair by pair, ties excepted:
//! `inversions` counts pairs of events of the same kind (two starts, two arrivals, two fold
//! starts or two fold ends) that the two runs put in opposite order, the order in which the
//! chain propagates; `interleavings` counts pairs of different kinds (a start against an
//! arrival, say) in opposite order, which depends on how fast each magnet moves and so
//! measures the speed law, not the propagation.

use rustc_hash::FxHashMap;

use foldchain::timeline::{Event, EventKind};

/// Timed events of a run keyed by (kind, index), in time order.
type Keyed = Vec<((EventKind, u32), f64)>;

fn keyed(events: &[Event]) -> Keyed {
    events
        .iter()
        .filter(|e| e.kind.is_motion())
        .map(|e| ((e.kind, e.index), e.time))
        .collect()
}

/// How one run's events compare with the reference's (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EventComparison {
    /// Largest difference of a matched event's time, over the reference's duration.
    pub error_time: f64,
    /// Events one run has and the other has not.
    pub missing: usize,
    /// Matched pairs of the same kind in opposite order.
    pub inversions: usize,
    /// Matched pairs of different kinds in opposite order.
    pub interleavings: usize,
    /// The single factor that best maps the run's event times onto the reference's (least
    /// squares through the origin; 1 when nothing matched).
    pub time_factor: f64,
    /// `error_time` after scaling the run's times by `time_factor`: what is left once the
    /// time scale is right.
    pub error_time_scaled: f64,
}

/// Compares `run`'s events with `reference`'s, whose run lasted `duration` s; two events
/// within 1e-9 of the duration of each other count as tied (not out of order).
pub fn compare_events(reference: &[Event], run: &[Event], duration: f64) -> EventComparison {
    compare_events_within(reference, run, duration, 1e-9)
}

/// [`compare_events`], with two events within `tie` of the duration of each other (in either
/// run) counted as tied: a run whose event times are known only to some fraction of its
/// duration cannot order events closer than that (the event engine's sweeps stop when no
/// event moves by 1e-6 of the duration).
pub fn compare_events_within(
    reference: &[Event],
    run: &[Event],
    duration: f64,
    tie: f64,
) -> EventComparison {
    let a = keyed(reference);
    let b = keyed(run);
    let map: FxHashMap<(EventKind, u32), f64> = b.iter().copied().collect();
    let mut pairs = Vec::new();
    for (k, t) in &a {
        if let Some(u) = map.get(k) {
            pairs.push((k.0, *t, *u));
        }
    }
    let missing = a.len() + b.len() - 2 * pairs.len();
    let span = duration.max(f64::MIN_POSITIVE);
    let error_time = pairs.iter().map(|p| (p.1 - p.2).abs()).fold(0.0, f64::max) / span;
    let (num, den) = pairs
        .iter()
        .fold((0.0, 0.0), |(n, d), p| (n + p.1 * p.2, d + p.2 * p.2));
    let time_factor = if den > 0.0 { num / den } else { 1.0 };
    let error_time_scaled = pairs
        .iter()
        .map(|p| (p.1 - time_factor * p.2).abs())
        .fold(0.0, f64::max)
        / span;
    // tied within `tie` of the duration in either run: not out of order
    let tie = tie * duration;
    let (mut inversions, mut interleavings) = (0, 0);
    for i in 0..pairs.len() {
        for j in i + 1..pairs.len() {
            let da = pairs[j].1 - pairs[i].1;
            let db = pairs[j].2 - pairs[i].2;
            if da.abs() > tie && db.abs() > tie && (da > 0.0) != (db > 0.0) {
                if pairs[i].0 == pairs[j].0 {
                    inversions += 1;
                } else {
                    interleavings += 1;
                }
            }
        }
    }
    EventComparison {
        error_time,
        missing,
        inversions,
        interleavings,
        time_factor,
        error_time_scaled,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Events written `S1@0.5` (magnet 1 starts at 0.5 s): S starts, A arrivals, F fold
    /// starts, T triggers.
    fn events(text: &str) -> Vec<Event> {
        text.split_whitespace()
            .map(|e| {
                let (what, time) = e.split_once('@').unwrap();
                let kind = match &what[..1] {
                    "S" => EventKind::MagnetStarts,
                    "A" => EventKind::MagnetArrives,
                    "F" => EventKind::FoldStarts,
                    _ => EventKind::TriggerReached,
                };
                Event {
                    time: time.parse().unwrap(),
                    index: what[1..].parse().unwrap(),
                    kind,
                }
            })
            .collect()
    }

    #[test]
    fn counts_what_differs() {
        // triggers are not compared
        let reference = events("S0@0 S1@1 A0@2 S2@3 F0@4 T2@4.5");
        // twice as slow, magnets 1 and 2 swapped, the fold missing, one extra arrival
        let run = events("S0@0 S1@6 A0@4 S2@2 A1@9");
        let c = compare_events(&reference, &run, 4.0);
        assert_eq!(c.missing, 2);
        // starts 1 and 2 in opposite order: one inversion; start 1 against arrival 0 and
        // start 2 against arrival 0: two interleavings
        assert_eq!((c.inversions, c.interleavings), (1, 2));
        assert_eq!(c.error_time, 5.0 / 4.0);
        let same = compare_events(&reference, &reference, 4.0);
        assert_eq!(
            (
                same.error_time,
                same.missing,
                same.inversions,
                same.interleavings
            ),
            (0.0, 0, 0, 0)
        );
        assert_eq!(same.time_factor, 1.0);
        // a pure rescale is all in the factor
        let slow: Vec<Event> = reference
            .iter()
            .map(|e| Event {
                time: 2.0 * e.time,
                ..*e
            })
            .collect();
        let c = compare_events(&reference, &slow, 4.0);
        assert_eq!(c.time_factor, 0.5);
        assert!(c.error_time_scaled < 1e-15);
        assert_eq!((c.inversions, c.interleavings), (0, 0));
    }
}
