//! The engine's event queue: earliest first; at the same time by kind (arrivals first, then
//! stops, triggers and starts, the order of [`EventKind`]), then in the order pushed.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::timeline::{Event, EventKind};

#[derive(Clone, Copy, Debug)]
struct Queued {
    time: f64,
    kind: EventKind,
    seq: u64,
    index: u32,
}

impl PartialEq for Queued {
    fn eq(&self, o: &Queued) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Queued {}

impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Queued) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Queued {
    // reversed: BinaryHeap is a max-heap and we want the earliest first
    fn cmp(&self, o: &Queued) -> Ordering {
        o.time
            .total_cmp(&self.time)
            .then(o.kind.cmp(&self.kind))
            .then(o.seq.cmp(&self.seq))
    }
}

/// Events waiting to happen.
#[derive(Default)]
pub(crate) struct Queue {
    heap: BinaryHeap<Queued>,
    seq: u64,
}

impl Queue {
    /// Schedules `kind` for magnet or joint `index` at `time`.
    pub(crate) fn push(&mut self, time: f64, kind: EventKind, index: usize) {
        self.seq += 1;
        self.heap.push(Queued {
            time,
            kind,
            seq: self.seq,
            index: index as u32,
        });
    }

    /// The next event.
    pub(crate) fn pop(&mut self) -> Option<Event> {
        self.heap.pop().map(|q| Event {
            time: q.time,
            index: q.index,
            kind: q.kind,
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn earliest_then_kind_then_pushed() {
        let mut q = Queue::default();
        q.push(1.0, EventKind::MagnetStarts, 5);
        q.push(1.0, EventKind::MagnetArrives, 4);
        q.push(0.5, EventKind::FoldStarts, 1);
        q.push(1.0, EventKind::MagnetStarts, 3);
        let order: Vec<(f64, EventKind, u32)> = std::iter::from_fn(|| q.pop())
            .map(|e| (e.time, e.kind, e.index))
            .collect();
        assert_eq!(
            order,
            vec![
                (0.5, EventKind::FoldStarts, 1),
                (1.0, EventKind::MagnetArrives, 4),
                (1.0, EventKind::MagnetStarts, 5),
                (1.0, EventKind::MagnetStarts, 3),
            ]
        );
    }
}
