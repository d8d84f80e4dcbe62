//! The reference run's events, in the engine's kinds and indices ([`crate::timeline`]): each
//! mode switch of an unknown becomes the event it means (a magnet starting or arriving, a
//! fold starting or closing), with the fold records and the count of moving magnets.

use crate::reference::dynamics::{Mode, Model, Unknown};
use crate::timeline::{Event, EventKind, FoldRecord};
use crate::Fold;

/// The events so far.
pub(crate) struct EventLog {
    /// Every event, in time order.
    pub(crate) events: Vec<Event>,
    /// The folds, in the order they start (`end` NaN until closed).
    pub(crate) folds: Vec<FoldRecord>,
    /// Index into `folds` of each joint's fold (`usize::MAX`: none yet).
    fold_index: Vec<usize>,
    moving: usize,
    /// The most magnets moving at once, and when first.
    pub(crate) max_moving: (usize, f64),
    /// When the last event happened, s.
    pub(crate) last_event: f64,
    /// The events of the switches at the current time.
    batch: Vec<Event>,
}

impl EventLog {
    /// The log of a chain with `joints` joints: RI contact at 0.
    pub(crate) fn new(joints: usize) -> EventLog {
        EventLog {
            events: vec![Event {
                time: 0.0,
                index: 0,
                kind: EventKind::RiContact,
            }],
            folds: Vec::new(),
            fold_index: vec![usize::MAX; joints],
            moving: 0,
            max_moving: (0, 0.0),
            last_event: 0.0,
            batch: Vec::new(),
        }
    }

    /// Notes unknown `i` switching from `prev` to `next` at time `t`; `modes` and `y` are the
    /// modes and state with the switches made so far.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn note(
        &mut self,
        model: &Model,
        i: usize,
        prev: Mode,
        next: Mode,
        t: f64,
        modes: &[Mode],
        y: &[f64],
    ) {
        let unknown = model.unknowns[i];
        let index = match unknown {
            Unknown::Magnet(k) | Unknown::Joint(k) => k as u32,
        };
        let ev = |kind| Event {
            time: t,
            index,
            kind,
        };
        match (unknown, prev, next) {
            (Unknown::Magnet(k), Mode::AtStart, Mode::Free) => {
                self.moving += 1;
                // the magnet before it, moving, reached the point that starts it
                let before_moves = k >= 1
                    && modes
                        .get(model.magnet_var(k - 1))
                        .is_some_and(|&m| m != Mode::AtStart);
                if before_moves {
                    self.batch.push(Event {
                        time: t,
                        index: (k - 1) as u32,
                        kind: EventKind::TriggerReached,
                    });
                }
                self.batch.push(ev(EventKind::MagnetStarts));
            }
            (Unknown::Magnet(_), Mode::Free, Mode::AtEnd) => {
                self.moving = self.moving.saturating_sub(1);
                self.batch.push(ev(EventKind::MagnetArrives));
            }
            (Unknown::Magnet(_), Mode::Free, Mode::AtStart) => {
                self.moving = self.moving.saturating_sub(1);
            }
            (Unknown::Magnet(_), Mode::AtEnd, Mode::Free) => self.moving += 1,
            (Unknown::Joint(j), Mode::AtStart, Mode::Free) if self.fold_index[j] == usize::MAX => {
                let (a, b) = (model.magnet_var(2 * j + 1), model.magnet_var(2 * j + 2));
                let fold = if model.joint_sign(j) > 0.0 {
                    Fold::L
                } else {
                    Fold::R
                };
                self.fold_index[j] = self.folds.len();
                self.folds.push(FoldRecord {
                    joint: j,
                    fold,
                    start: t,
                    end: f64::NAN,
                    p0: 0.5 * (y[a] + y[b]),
                });
                self.batch.push(ev(EventKind::FoldStarts));
            }
            (Unknown::Joint(j), Mode::Free, Mode::AtEnd) => {
                if let Some(f) = self.folds.get_mut(self.fold_index[j]) {
                    if f.end.is_nan() {
                        f.end = t;
                        self.batch.push(ev(EventKind::FoldEnds));
                    }
                }
            }
            _ => {}
        }
    }

    /// Ends the switches at time `t`: their events join the log in (kind, index) order.
    /// Whether there were any.
    pub(crate) fn close(&mut self, t: f64) -> bool {
        if self.moving > self.max_moving.0 {
            self.max_moving = (self.moving, t);
        }
        let any = !self.batch.is_empty();
        self.batch.sort_by_key(|e| (e.kind, e.index));
        if any {
            self.last_event = t;
        }
        self.events.append(&mut self.batch);
        any
    }
}
