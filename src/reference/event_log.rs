//! The reference run's events, in the engine's kinds and indices ([`crate::timeline`]): each
//! mode switch of an unknown becomes the event it means (a magnet starting or arriving, a
//! fold starting or closing), with the fold records and the count of moving magnets.

use crate::model::{Mode, Model, Unknown};
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
    /// Starts are reported at this fraction of the path (0: at the switch; see
    /// [`crate::timeline::S0_START_FRACTION`]).
    start_fraction: f64,
    /// Whether each magnet's start has been reported.
    reported: Vec<bool>,
}

impl EventLog {
    /// The log of a chain with `joints` joints and `magnets` magnets, starts reported at
    /// `start_fraction` of the path: RI contact at 0.
    pub(crate) fn new(joints: usize, magnets: usize, start_fraction: f64) -> EventLog {
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
            start_fraction,
            reported: vec![false; magnets],
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
                if self.start_fraction > 0.0 || self.reported[k] {
                    return;
                }
                self.reported[k] = true;
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

    /// Whether starts are reported at a fraction of the path ([`EventLog::cross`]).
    pub(crate) fn reports_crossings(&self) -> bool {
        self.start_fraction > 0.0
    }

    /// Reports the starts of the magnets that passed the start fraction in a step from
    /// `(t0, y0)` to `(t1, y1)` (rates `f0`, `f1` at the ends: cubic Hermite; linear
    /// without them), before the switches at `t1`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn cross(
        &mut self,
        model: &Model,
        t0: f64,
        y0: &[f64],
        f0: Option<&[f64]>,
        t1: f64,
        y1: &[f64],
        f1: Option<&[f64]>,
    ) {
        let x = self.start_fraction;
        if x <= 0.0 {
            return;
        }
        let mut found = Vec::new();
        for k in 0..self.reported.len() {
            let v = model.magnet_var(k);
            if self.reported[k] || y1[v] < x {
                continue;
            }
            self.reported[k] = true;
            let at = |t: f64| match (f0, f1) {
                (Some(a), Some(b)) => crate::ode::hermite(t0, t1, (y0[v], a[v]), (y1[v], b[v]), t),
                _ => y0[v] + (y1[v] - y0[v]) * (t - t0) / (t1 - t0).max(f64::MIN_POSITIVE),
            };
            let (mut lo, mut hi) = (t0, t1);
            if y0[v] < x {
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if at(mid) >= x {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
            }
            found.push((hi, k));
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (t, k) in found {
            let before_moved = k >= 1 && self.reported[k - 1];
            if before_moved {
                self.events.push(Event {
                    time: t,
                    index: (k - 1) as u32,
                    kind: EventKind::TriggerReached,
                });
            }
            self.events.push(Event {
                time: t,
                index: k as u32,
                kind: EventKind::MagnetStarts,
            });
            self.last_event = self.last_event.max(t);
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
