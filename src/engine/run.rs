//! The discrete-event engine: an ordered event queue, no time steps and no force integration.
//!
//! The reaction initiator touches tile 0 at `t = 0` and starts magnet 0. When a magnet
//! starts, the engine asks the geometry where on its path the next magnet becomes
//! equidistant from its two neighbours ([`Geometry::trigger`]) and schedules that moment and
//! the arrival from the closed-form speed law ([`Motion`]). Reaching the trigger point starts
//! the next magnet, unless the next pair diverges (propagation inhibited); a path that ends,
//! or a curve that turns away, before the trigger stalls propagation. A fold starts when the
//! second magnet of its pair starts and ends when both have arrived. Events at the same time
//! are taken arrivals first, then stops, triggers and starts, so a magnet that starts its
//! successor exactly on arrival (`s = e/3`) never counts as moving together with it.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::engine::designs::TileDesigns;
use crate::engine::event::{Event, EventKind};
use crate::engine::geometry::{FastMap, Geometry, Trigger};
use crate::engine::speed::{Motion, SpeedLaw};
use crate::engine::start_rule::{force_start, ForceStart, RunState, StartRule};
use crate::magnet_path::PathError;
use crate::{Chain, Fold, PathKind};

/// Engine options. Default: the overdamped speed law with the default drag, and the
/// distance rule for starting magnets (the thesis' inequalities).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct EngineOptions {
    /// The speed law.
    pub speed: SpeedLaw,
    /// The rule that starts each magnet.
    pub start: StartRule,
}

impl EngineOptions {
    /// Another start rule.
    pub fn with_start_rule(mut self, start: StartRule) -> EngineOptions {
        self.start = start;
        self
    }

    /// Another speed law.
    pub fn with_speed(mut self, speed: SpeedLaw) -> EngineOptions {
        self.speed = speed;
        self
    }
}

/// Why the engine could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum EngineError {
    /// A design parameter out of range.
    #[error("design: {0}")]
    Design(#[from] crate::engine::designs::DesignsError),
    /// A curved path that cannot be built.
    #[error("{0}")]
    PathKind(#[from] PathError),
    /// A drag coefficient that is not a finite positive number.
    #[error("drag coefficient {0} N s/m: expected a finite number > 0")]
    BadDrag(f64),
    /// A force-rule cutoff of 0.
    #[error("start rule cutoff 0: expected at least 1 (pairs this many apart in chain index)")]
    BadCutoff,
    /// More magnets than the compact event index holds.
    #[error("chain of {0} tiles: the engine handles at most 2^31 - 1 magnets")]
    TooLong(usize),
}

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
    /// The summary's fields for this outcome: `(inhibited_at, stalled_at, reason, result)`;
    /// `source` names what decided it in the inhibition message (e.g. "thesis Table 7.1").
    pub fn summary_fields(
        &self,
        source: &str,
    ) -> (Option<usize>, Option<usize>, Option<String>, &'static str) {
        match self {
            Outcome::Completed => (None, None, None, "completed"),
            Outcome::Inhibited { joint, end_distance_mm, rest_distance_mm, .. } => (
                Some(*joint),
                None,
                Some(format!(
                    "propagation inhibited at joint {joint}: its pair's path ends lie {end_distance_mm:.3} mm apart, farther than the {rest_distance_mm:.3} mm between them at rest ({source})"
                )),
                "inhibited",
            ),
            Outcome::Stalled { joint, reason, .. } => (None, Some(*joint), Some(reason.clone()), "stalled"),
        }
    }
}

/// One fold: a joint of an LL or RR pair turning from straight to 90 degrees.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FoldRecord {
    /// The joint.
    pub joint: usize,
    /// The direction.
    pub fold: Fold,
    /// Start, s (the pair's second magnet starts).
    pub start: f64,
    /// End, s (both magnets arrived).
    pub end: f64,
    /// The pair's progress when the fold starts (see [`crate::engine::fold_angle`]).
    pub p0: f64,
}

/// The result of a run: every event, each magnet's start, the folds and the outcome.
#[derive(Debug)]
pub struct Timeline {
    /// The chain's geometry at rest.
    pub geometry: Geometry,
    /// The speed law used.
    pub speed: SpeedLaw,
    motions: Vec<Motion>,
    motion_of: Vec<u32>,
    start: Vec<f64>,
    /// Every event, in time order.
    pub events: Vec<Event>,
    /// The folds, in the order they start.
    pub folds: Vec<FoldRecord>,
    /// How propagation ended.
    pub outcome: Outcome,
    /// The most magnets moving at one instant, and the first time it happens.
    pub max_moving: (usize, f64),
    fold_of_joint: Vec<u32>,
}

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

struct Queue {
    heap: BinaryHeap<Queued>,
    seq: u64,
}

impl Queue {
    fn push(&mut self, time: f64, kind: EventKind, index: usize) {
        self.seq += 1;
        self.heap.push(Queued {
            time,
            kind,
            seq: self.seq,
            index: index as u32,
        });
    }
}

/// Runs the event engine on `chain` with `designs`.
pub fn run(
    chain: &Chain,
    designs: &TileDesigns,
    opts: &EngineOptions,
) -> Result<Timeline, EngineError> {
    if let SpeedLaw::Overdamped { drag } = opts.speed {
        if !drag.is_finite() || drag <= 0.0 {
            return Err(EngineError::BadDrag(drag));
        }
    }
    if opts.start == (StartRule::Force { cutoff: 0 }) {
        return Err(EngineError::BadCutoff);
    }
    if chain.len() >= (u32::MAX / 4) as usize {
        return Err(EngineError::TooLong(chain.len()));
    }
    designs.validate("design")?;
    let (design_list, tile_design) = designs.resolve(chain.len());
    let mut geometry = Geometry::new(chain, design_list, tile_design)?;
    let n = geometry.magnets();

    // motions, deduplicated by (path, end gap)
    let mut motions: Vec<Motion> = Vec::new();
    // The end gap depends on the two paths of the pair and the fold between them only.
    let mut motion_index: FastMap<(u32, u32, u8), u32> = Default::default();
    let mut motion_of = Vec::with_capacity(n);
    let tiles = chain.tiles();
    for k in 0..n {
        let other = if k == 0 {
            u32::MAX
        } else if k % 2 == 1 {
            if k + 1 < n {
                geometry.path_id(k + 1)
            } else {
                u32::MAX - 1
            }
        } else {
            geometry.path_id(k - 1)
        };
        let j = if k % 2 == 1 {
            k / 2
        } else {
            (k / 2).wrapping_sub(1)
        };
        let fold = if k == 0 || j + 1 >= tiles.len() {
            0
        } else {
            match (tiles[j].second, tiles[j + 1].first) {
                (PathKind::L, PathKind::L) => 1,
                (PathKind::R, PathKind::R) => 2,
                _ => 0,
            }
        };
        let key = (geometry.path_id(k), other, fold);
        let id = *motion_index.entry(key).or_insert_with(|| {
            let p = geometry.path(k);
            motions.push(Motion::new(
                p.length(),
                geometry.end_gap(k),
                geometry.design(k / 2),
                opts.speed,
            ));
            (motions.len() - 1) as u32
        });
        motion_of.push(id);
    }

    let fold_of = |j: usize| -> Fold {
        match (tiles[j].second, tiles[j + 1].first) {
            (PathKind::L, PathKind::L) => Fold::L,
            (PathKind::R, PathKind::R) => Fold::R,
            _ => Fold::S,
        }
    };

    let mut start = vec![f64::NAN; n];
    let mut events: Vec<Event> = Vec::with_capacity(3 * n);
    let mut folds = Vec::new();
    let mut fold_of_joint = vec![u32::MAX; chain.len().saturating_sub(1)];
    let mut outcome = Outcome::Completed;
    let mut moving = 0usize;
    let mut max_moving = (0usize, 0.0);
    let mut queue = Queue {
        heap: BinaryHeap::new(),
        seq: 0,
    };
    queue.push(0.0, EventKind::RiContact, 0);

    while let Some(ev) = queue.heap.pop() {
        let t = ev.time;
        let i = ev.index as usize;
        events.push(Event {
            time: t,
            index: ev.index,
            kind: ev.kind,
        });
        match ev.kind {
            EventKind::RiContact => {
                let (starts, ri, partner) = geometry.ri_starts_first_magnet();
                if starts {
                    queue.push(t, EventKind::MagnetStarts, 0);
                } else {
                    queue.push(t, EventKind::Stalled, 0);
                    set_outcome(
                        &mut outcome,
                        Outcome::Stalled {
                            joint: 0,
                            time: t,
                            magnet: 0,
                            reason: format!(
                                "the RI at the tile edge is {ri:.4} mm from magnet 0, not nearer than its partner at {partner:.4} mm: inequality (6.2) c + a < b fails"
                            ),
                        },
                    );
                }
            }
            EventKind::MagnetStarts => {
                start[i] = t;
                moving += 1;
                if moving > max_moving.0 {
                    max_moving = (moving, t);
                }
                let motion = motions[motion_of[i] as usize];
                queue.push(t + motion.duration(), EventKind::MagnetArrives, i);
                if i % 2 == 0 && i >= 2 {
                    let j = i / 2 - 1;
                    let fold = fold_of(j);
                    if fold != Fold::S {
                        let a = 2 * j + 1;
                        let ma = motions[motion_of[a] as usize];
                        let end = (start[a] + ma.duration()).max(t + motion.duration());
                        let p0 = 0.5 * ma.distance_at(t - start[a]) / ma.length;
                        fold_of_joint[j] = folds.len() as u32;
                        folds.push(FoldRecord {
                            joint: j,
                            fold,
                            start: t,
                            end,
                            p0,
                        });
                        queue.push(t, EventKind::FoldStarts, j);
                        queue.push(end, EventKind::FoldEnds, j);
                    }
                }
                let m = i + 1;
                if m + 1 < n {
                    if let StartRule::Force { cutoff } = opts.start {
                        let state = RunState {
                            geometry: &geometry,
                            start: &start,
                            motions: &motions,
                            motion_of: &motion_of,
                            folds: &folds,
                            fold_of_joint: &fold_of_joint,
                        };
                        match force_start(&state, m, cutoff, t) {
                            ForceStart::At(when) => queue.push(when, EventKind::TriggerReached, i),
                            ForceStart::Never { time, drive } => {
                                let joint = joint_of_magnet(m);
                                queue.push(time, EventKind::Stalled, joint);
                                set_outcome(
                                    &mut outcome,
                                    Outcome::Stalled {
                                        joint,
                                        time,
                                        magnet: m,
                                        reason: format!(
                                            "magnet {m} never started: the force along its path from the magnets within {cutoff} of it stays towards its rest point (at most {drive:.3e} N, at {time:.4} s) while magnet {i} and those behind it move (force rule)"
                                        ),
                                    },
                                );
                            }
                        }
                        continue;
                    }
                    match geometry.trigger(m) {
                        Trigger::At(u) => {
                            queue.push(t + motion.time_to(u), EventKind::TriggerReached, i)
                        }
                        Trigger::Never {
                            u,
                            shortfall,
                            before_end,
                        } => {
                            let joint = joint_of_magnet(m);
                            let when = t + motion.time_to(u);
                            let path = geometry.path(i);
                            let reason = if before_end {
                                format!(
                                    "magnet {i} on its curved path passes its closest approach to starting magnet {m} ({u:.4} mm along) still {shortfall:.4} mm short: the next magnet must start before then (thesis 6.5)"
                                )
                            } else {
                                format!(
                                    "magnet {i} reaches the end of its {} path ({:.4} mm) {shortfall:.4} mm short of starting magnet {m}: a straight path must be at least 4s long, s < e/3 (6.8, 6.9)",
                                    if path.is_curved() { "curved" } else { "straight" },
                                    path.length()
                                )
                            };
                            queue.push(when, EventKind::Stalled, joint);
                            set_outcome(
                                &mut outcome,
                                Outcome::Stalled {
                                    joint,
                                    time: when,
                                    magnet: m,
                                    reason,
                                },
                            );
                        }
                    }
                }
            }
            EventKind::TriggerReached => {
                let m = i + 1;
                if m % 2 == 1 {
                    let j = (m - 1) / 2;
                    let (diverges, end, rest) = geometry.pair_diverges(j);
                    if diverges {
                        queue.push(t, EventKind::Inhibited, j);
                        set_outcome(
                            &mut outcome,
                            Outcome::Inhibited {
                                joint: j,
                                time: t,
                                end_distance_mm: end,
                                rest_distance_mm: rest,
                            },
                        );
                        continue;
                    }
                }
                queue.push(t, EventKind::MagnetStarts, m);
            }
            EventKind::MagnetArrives => moving -= 1,
            EventKind::FoldStarts
            | EventKind::FoldEnds
            | EventKind::Inhibited
            | EventKind::Stalled => {}
        }
    }
    // An outcome found after an earlier one keeps the earliest (set_outcome), but stalls are
    // pushed when found, not when they happen: keep the one that happens first.
    Ok(Timeline {
        fold_of_joint,
        geometry,
        speed: opts.speed,
        motions,
        motion_of,
        start,
        events,
        folds,
        outcome,
        max_moving,
    })
}

fn set_outcome(slot: &mut Outcome, new: Outcome) {
    let time = |o: &Outcome| match o {
        Outcome::Completed => f64::INFINITY,
        Outcome::Inhibited { time, .. } | Outcome::Stalled { time, .. } => *time,
    };
    if time(&new) < time(slot) {
        *slot = new;
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

impl Timeline {
    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.geometry.tiles()
    }

    /// When magnet `k` starts, or `None` if it never moves.
    pub fn start_of(&self, k: usize) -> Option<f64> {
        let t = self.start[k];
        (!t.is_nan()).then_some(t)
    }

    /// Magnet `k`'s motion law.
    pub fn motion(&self, k: usize) -> &Motion {
        &self.motions[self.motion_of[k] as usize]
    }

    /// When magnet `k` arrives, or `None` if it never moves.
    pub fn arrival_of(&self, k: usize) -> Option<f64> {
        self.start_of(k).map(|s| s + self.motion(k).duration())
    }

    /// The arc length magnet `k` has travelled at time `t`, mm.
    pub fn travel_at(&self, k: usize, t: f64) -> f64 {
        match self.start_of(k) {
            Some(s) if t > s => self.motion(k).distance_at(t - s),
            _ => 0.0,
        }
    }

    /// Whether magnet `k` is moving at time `t`.
    pub fn is_moving(&self, k: usize, t: f64) -> bool {
        match (self.start_of(k), self.arrival_of(k)) {
            (Some(s), Some(a)) => t >= s && t < a,
            _ => false,
        }
    }

    /// Magnet `k`'s position in its tile's frame at time `t`, mm.
    pub fn local_position(&self, k: usize, t: f64) -> (f64, f64) {
        self.geometry.path(k).point_at(self.travel_at(k, t))
    }

    /// When the last event happens, s.
    pub fn duration(&self) -> f64 {
        self.events.last().map_or(0.0, |e| e.time)
    }

    /// The fold of joint `j`, if it folds.
    pub fn fold_at(&self, j: usize) -> Option<&FoldRecord> {
        self.fold_of_joint
            .get(j)
            .and_then(|&i| self.folds.get(i as usize))
    }

    /// The folds whose joints turned.
    pub fn folded_joints(&self) -> Vec<usize> {
        self.folds.iter().map(|f| f.joint).collect()
    }

    /// Number of events of a kind.
    pub fn count(&self, kind: EventKind) -> usize {
        self.events.iter().filter(|e| e.kind == kind).count()
    }

    /// The most magnets moving together.
    pub fn max_moving_magnets(&self) -> usize {
        self.max_moving.0
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::Design;

    fn run_word(word: &str, s: f64, speed: SpeedLaw) -> Timeline {
        let chain = Chain::parse(word).unwrap();
        run(
            &chain,
            &TileDesigns::global(Design::thesis().with_s(s)),
            &EngineOptions::default().with_speed(speed),
        )
        .unwrap()
    }

    #[test]
    fn events_are_ordered_and_every_mover_arrives() {
        let t = run_word("SSLLSS", 0.3, SpeedLaw::default());
        assert_eq!(t.outcome, Outcome::Completed);
        assert!(t.events.windows(2).all(|w| w[0].time <= w[1].time));
        let starts = t.count(EventKind::MagnetStarts);
        assert_eq!(starts, 2 * t.tiles() - 1);
        assert_eq!(t.count(EventKind::MagnetArrives), starts);
        assert_eq!(t.folded_joints(), vec![2, 3]);
        assert_eq!(t.count(EventKind::FoldStarts), 2);
    }

    #[test]
    fn unit_speed_start_times_are_multiples_of_4s() {
        let t = run_word("SSSSS", 0.3, SpeedLaw::Unit);
        for k in 0..t.geometry.magnets() - 1 {
            let s = t.start_of(k).unwrap();
            assert!((s - 1.2 * k as f64).abs() < 1e-9, "{k}: {s}");
        }
        assert_eq!(t.start_of(t.geometry.magnets() - 1), None);
    }
}
