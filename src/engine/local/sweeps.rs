//! The chain solved unit by unit from the RI end ([`solve_chain`]), in sweeps: in the
//! first, every unit sees the units before it on their solved tracks and the units after it
//! at rest; each later sweep solves every unit again with the units after it on their
//! tracks of the sweep before (a Gauss-Seidel waveform relaxation), until no event moves by
//! more than [`SWEEP_TOLERANCE`] of the run's duration, or [`MAX_SWEEPS`] sweeps.
//!
//! **Relative placement.** In a later sweep the units after unit `u` are placed against `u`
//! as they were in the sweep before: their tracks move by as much as `u`'s time origin moved
//! since. A sweep's period along a straight run differs from the sweep before's, so absolute
//! placement would put unit `u + 1` further off with every unit of the run (a long chain then
//! never settles in [`MAX_SWEEPS`]); relative placement sees the same neighbours in every
//! unit of a steady run. Both have the same fixed point (a converged sweep moves no origin).
//!
//! **Cache.** A unit's solution depends only on the geometry of its window and on its
//! inputs' shapes and offsets relative to its own time origin. Those are the key of a cache
//! (offsets rounded to [`OFFSET_QUANTUM`] time scales). A new solution's shape that agrees
//! within [`SHAPE_TOLERANCE`] with a stored shape of the same kind of unknown (the same path,
//! the same fold) is stored as that one, and so is one that agrees with the same unknown's one
//! unit back: a steady straight run settles on the same shapes after every U-turn. Along a
//! steady run the transient from the RI (or from a U-turn) dies out in a few tiles, after
//! which every unit is the one before it shifted in time: a cache hit, no integration, in
//! every sweep; a U-turn met before in the same state is a hit too. A chain costs the
//! transients of its distinct turns, and a look-up per unit and sweep.

use std::sync::Arc;

use rustc_hash::FxHashMap;

use crate::engine::local::solve::{solve, Solution, SolveOptions};
use crate::engine::local::trajectory::{Shape, Shapes, Track, REST};
use crate::engine::local::window::{Inputs, Var, Window};
use crate::reference::{Dynamics, Model};
use crate::timeline::{Event, EventKind};

/// A unit's time origin is when the magnet before it has travelled this fraction of its
/// path: 0.5.
const ANCHOR_FRACTION: f64 = 0.5;

/// Most sweeps over the chain.
pub const MAX_SWEEPS: usize = 8;
/// Sweeps stop when no event moved by more than this fraction of the run's duration: 1e-6.
pub const SWEEP_TOLERANCE: f64 = 1e-6;
/// Input offsets in a cache key are rounded to this many of the model's time scales: 1e-7.
pub const OFFSET_QUANTUM: f64 = 1e-7;
/// A new shape within this (fraction of a path or fold, and fraction of its duration for
/// its end) of the same unknown's one unit back, shifted by the difference of the two
/// units' origins, is stored as that one: 1e-4, 0.5 um on a 5 mm path. Two solves of the
/// same steady motion on different steps differ by some 1e-5: a magnet that creeps off a
/// near balance amplifies the interpolation error of its inputs.
pub const SHAPE_TOLERANCE: f64 = 1e-4;

/// A unit's solution as the cache keeps it: shape ids instead of shapes.
#[derive(Debug)]
pub(crate) struct Entry {
    /// Each unknown's shape id and start (local time), if it moved.
    pub(crate) shapes: Vec<Option<(u32, f64)>>,
    /// The solution, shapes taken out.
    pub(crate) solution: Solution,
}

/// The chain's solution.
#[derive(Debug)]
pub(crate) struct ChainSolution {
    /// Every shape.
    pub(crate) shapes: Shapes,
    /// Each magnet's track.
    pub(crate) magnets: Vec<Track>,
    /// Each joint's track.
    pub(crate) joints: Vec<Track>,
    /// Each unit's entry and time origin (unit `u` is joint `u - 1`).
    pub(crate) units: Vec<(Arc<Entry>, f64)>,
    /// Sweeps made.
    pub(crate) sweeps: usize,
    /// Local solves made (cache misses).
    pub(crate) solves: usize,
    /// Right-hand sides evaluated.
    pub(crate) rhs: u64,
    /// Local solves made in each sweep.
    pub(crate) solves_per_sweep: Vec<usize>,
}

impl ChainSolution {
    /// Every event, in time order (ties by kind and index).
    pub(crate) fn events(&self) -> Vec<Event> {
        let mut out = vec![Event {
            time: 0.0,
            index: 0,
            kind: EventKind::RiContact,
        }];
        for (u, (e, t_ref)) in self.units.iter().enumerate() {
            let j = u as i64 - 1;
            for ev in &e.solution.events {
                let index = if ev.kind.is_joint_event() {
                    j
                } else {
                    2 * j + ev.rel
                };
                out.push(Event {
                    time: t_ref + ev.time,
                    index: index as u32,
                    kind: ev.kind,
                });
            }
        }
        out.sort_by(|a, b| {
            a.time
                .total_cmp(&b.time)
                .then((a.kind, a.index).cmp(&(b.kind, b.index)))
        });
        out
    }
}

/// Solves `model`'s chain with local solves of tolerance `opts.tol`.
pub(crate) fn solve_chain(model: &Model, opts: SolveOptions) -> ChainSolution {
    solve_chain_with(model, opts, true)
}

/// [`solve_chain`], with or without the cache and the sharing of shapes (`reuse`).
pub(crate) fn solve_chain_with(model: &Model, opts: SolveOptions, reuse: bool) -> ChainSolution {
    let g = &model.geometry;
    let n = g.magnets();
    let tiles = g.tiles();
    let cutoff = model.options().cutoff;
    let quantum = OFFSET_QUANTUM * model.time_scale;
    let mut shapes = Shapes::default();
    let mut magnets = vec![Track::REST; n];
    let mut joints = vec![Track::REST; tiles.saturating_sub(1)];
    let mut cache: FxHashMap<Vec<i64>, Arc<Entry>> = FxHashMap::default();
    let mut units: Vec<(Arc<Entry>, f64)> = Vec::new();
    let (mut solves, mut rhs, mut sweeps) = (0, 0, 0);
    let mut key = Vec::new();
    let mut solves_per_sweep = Vec::new();
    let mut saved = Saved::default();
    let mut library = Library::default();
    let mut anchors = Anchors::default();
    while sweeps < MAX_SWEEPS {
        sweeps += 1;
        let solves_before = solves;
        library.clear();
        let mut moved: f64 = 0.0;
        let mut duration: f64 = 0.0;
        for u in 0..=tiles {
            let j = u as isize - 1;
            let w = Window::new(model, j, cutoff);
            // the unit's time origin: when the magnet before it is half way (a crossing the
            // step sizes hardly move), else when its inputs first move
            let anchor = match w.vars.first() {
                Some(Var::Magnet(a)) if *a >= 1 && w.lo > 0 => {
                    anchors.crossing(&shapes, magnets[a - 1])
                }
                _ => None,
            };
            // the units after this one are placed against it as they were in the sweep
            // before (their tracks moved by as much as its origin moved since)
            let shift = match (anchor, units.get(u)) {
                (Some(t), Some(&(_, old))) => t - old,
                _ => 0.0,
            };
            shift_downstream(&w, &mut magnets, &mut joints, shift, &mut saved);
            let inputs = Inputs {
                shapes: &shapes,
                magnets: &magnets,
                joints: &joints,
            };
            let tracks = w.input_tracks(&inputs);
            let first = tracks
                .iter()
                .filter_map(|&t| shapes.first_move(t))
                .fold(f64::INFINITY, f64::min);
            let t_start = if w.lo == 0 || !first.is_finite() {
                0.0
            } else {
                first
            };
            let t_ref = anchor.unwrap_or(t_start);
            window_key(&w, &tracks, t_ref, quantum, &mut key);
            let entry = match cache.get(&key).filter(|_| reuse) {
                Some(e) => e.clone(),
                None => {
                    let (t0, mut sol) = solve(&w, inputs, opts);
                    debug_assert_eq!(t0, t_start);
                    // local times from the unit's origin
                    let d = t0 - t_ref;
                    for e in &mut sol.events {
                        e.time += d;
                    }
                    for (_, start) in sol.shapes.iter_mut().flatten() {
                        *start += d;
                    }
                    solves += 1;
                    rhs += sol.rhs;
                    // the unit one back, if it is the same kind of unit: its time origin
                    let prev_ref = (u >= 1).then(|| units.get(u - 1).map(|p| p.1)).flatten();
                    let mut ids = Vec::with_capacity(sol.shapes.len());
                    for (i, sh) in sol.shapes.iter_mut().enumerate() {
                        ids.push(sh.take().map(|(shape, start)| {
                            // the same role one unit back, compared in absolute time shifted
                            // by the difference of the two units' origins
                            let prev = match w.vars[i] {
                                Var::Magnet(k) if k >= 2 => Some(magnets[k - 2]),
                                Var::Joint(jj) if jj >= 1 => Some(joints[jj - 1]),
                                _ => None,
                            };
                            let kind = match w.vars[i] {
                                Var::Magnet(k) => (false, g.path_id(k) as i64),
                                Var::Joint(jj) => (true, g.joint_fold(jj).quarter_turns() as i64),
                            };
                            let dt = 0.1 * SHAPE_TOLERANCE * shape.end() + quantum;
                            // a copy of a shape stored before (the steady shape of a straight
                            // run, met again after a U-turn), compared from its start
                            if !reuse {
                                return (shapes.add(shape), start);
                            }
                            if let Some(id) = library.find(&shapes, kind, &shape, dt) {
                                return (id, start);
                            }
                            let same = match (prev, prev_ref) {
                                (Some(p), Some(r0)) if p.shape != REST => {
                                    let shift = p.offset + (t_ref - r0);
                                    let new_offset = t_ref + start;
                                    shapes
                                        .get(p.shape)
                                        .close_shifted(
                                            &shape,
                                            new_offset - shift,
                                            SHAPE_TOLERANCE,
                                            dt,
                                        )
                                        .then_some((p.shape, shift - t_ref))
                                }
                                _ => None,
                            };
                            match same {
                                Some(found) => found,
                                None => {
                                    let end = shape.end();
                                    let id = shapes.add(shape);
                                    library.add(kind, end, id);
                                    (id, start)
                                }
                            }
                        }));
                    }
                    let e = Arc::new(Entry {
                        shapes: ids,
                        solution: sol,
                    });
                    cache.insert(key.clone(), e.clone());
                    e
                }
            };
            saved.restore(&mut magnets, &mut joints);
            for (i, sh) in entry.shapes.iter().enumerate() {
                let track = match sh {
                    Some((id, start)) => Track {
                        shape: *id,
                        offset: t_ref + start,
                    },
                    None => Track::REST,
                };
                match w.vars[i] {
                    Var::Magnet(k) => magnets[k] = track,
                    Var::Joint(jj) => joints[jj] = track,
                }
            }
            if let Some(ev) = entry.solution.events.last() {
                duration = duration.max(t_ref + ev.time);
            }
            match units.get_mut(u) {
                Some(slot) => {
                    moved = moved.max(change(slot, &entry, t_ref));
                    *slot = (entry, t_ref);
                }
                None => {
                    moved = f64::INFINITY;
                    units.push((entry, t_ref));
                }
            }
        }
        solves_per_sweep.push(solves - solves_before);
        if moved <= SWEEP_TOLERANCE * duration.max(model.time_scale) {
            break;
        }
    }
    ChainSolution {
        shapes,
        magnets,
        joints,
        units,
        sweeps,
        solves,
        rhs,
        solves_per_sweep,
    }
}

/// Each shape's crossing of [`ANCHOR_FRACTION`] from its start, found once.
#[derive(Default)]
struct Anchors {
    /// By shape id: NaN not yet found, infinite never reached.
    local: Vec<f64>,
}

impl Anchors {
    /// When `track` reaches [`ANCHOR_FRACTION`], if it does.
    fn crossing(&mut self, shapes: &Shapes, track: Track) -> Option<f64> {
        if track.shape == REST {
            return None;
        }
        let id = track.shape as usize;
        if self.local.len() <= id {
            self.local.resize(id + 1, f64::NAN);
        }
        if self.local[id].is_nan() {
            self.local[id] = shapes
                .get(track.shape)
                .crossing(ANCHOR_FRACTION)
                .unwrap_or(f64::INFINITY);
        }
        let t = self.local[id];
        t.is_finite().then_some(track.offset + t)
    }
}

/// The shapes stored, by kind of unknown (a magnet's path, a joint's fold) with their ends:
/// the shapes a new one may be a copy of.
#[derive(Default)]
struct Library {
    by_kind: FxHashMap<(bool, i64), Vec<(f64, u32)>>,
}

impl Library {
    /// A stored shape of `kind` that agrees with `shape` within [`SHAPE_TOLERANCE`] from
    /// their starts on and ends within `dt` of it.
    fn find(&self, shapes: &Shapes, kind: (bool, i64), shape: &Shape, dt: f64) -> Option<u32> {
        let end = shape.end();
        self.by_kind.get(&kind)?.iter().find_map(|&(e, id)| {
            ((e - end).abs() <= dt
                && shapes
                    .get(id)
                    .close_shifted(shape, 0.0, SHAPE_TOLERANCE, dt))
            .then_some(id)
        })
    }

    fn add(&mut self, kind: (bool, i64), end: f64, id: u32) {
        self.by_kind.entry(kind).or_default().push((end, id));
    }

    /// Forgets every shape: a sweep shares only the shapes it made itself (a shape of the
    /// sweep before, matched within the tolerance, would stop the sweeps' progress there).
    fn clear(&mut self) {
        self.by_kind.clear();
    }
}

/// Downstream tracks as they were before [`shift_downstream`] moved them.
#[derive(Default)]
struct Saved {
    magnets: Vec<(usize, Track)>,
    joints: Vec<(usize, Track)>,
}

impl Saved {
    fn restore(&mut self, magnets: &mut [Track], joints: &mut [Track]) {
        for (k, t) in self.magnets.drain(..) {
            magnets[k] = t;
        }
        for (k, t) in self.joints.drain(..) {
            joints[k] = t;
        }
    }
}

/// Moves the moving tracks of unit `w`'s window after its unknowns (the magnets after its
/// last one, the joints after its own) by `shift`, keeping what they were in `saved`.
fn shift_downstream(
    w: &Window,
    magnets: &mut [Track],
    joints: &mut [Track],
    shift: f64,
    saved: &mut Saved,
) {
    if shift == 0.0 {
        return;
    }
    let last = w
        .vars
        .iter()
        .filter_map(|v| match v {
            Var::Magnet(k) => Some(*k),
            Var::Joint(_) => None,
        })
        .max();
    let Some(last) = last else {
        return;
    };
    for (k, t) in magnets.iter_mut().enumerate().take(w.hi + 1).skip(last + 1) {
        if t.shape != REST {
            saved.magnets.push((k, *t));
            t.offset += shift;
        }
    }
    let first_joint = (w.j + 1).max(0) as usize;
    for (jj, t) in joints
        .iter_mut()
        .enumerate()
        .take(w.hi / 2)
        .skip(first_joint.max(w.lo / 2))
    {
        if t.shape != REST {
            saved.joints.push((jj, *t));
            t.offset += shift;
        }
    }
}

/// The largest change of an event time of a unit between two sweeps (infinite when the
/// events differ).
fn change(old: &(Arc<Entry>, f64), new: &Arc<Entry>, t_ref: f64) -> f64 {
    let (a, b) = (&old.0.solution.events, &new.solution.events);
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter().zip(b).fold(0.0, |m, (x, y)| {
        if x.kind != y.kind || x.rel != y.rel {
            f64::INFINITY
        } else {
            m.max(((old.1 + x.time) - (t_ref + y.time)).abs())
        }
    })
}

/// The cache key of unit `w` with input tracks `tracks` and origin `t_ref`.
fn window_key(w: &Window, tracks: &[Track], t_ref: f64, quantum: f64, key: &mut Vec<i64>) {
    let g = &w.model.geometry;
    key.clear();
    let first = w.vars.iter().find_map(|v| match v {
        Var::Magnet(k) => Some(*k as i64),
        Var::Joint(_) => None,
    });
    let a = first.unwrap_or(0);
    key.push(a - w.lo as i64);
    key.push(w.hi as i64 - a);
    key.push(w.vars.len() as i64);
    if let Dynamics::Inertial(_) = w.model.options().dynamics {
        // an inertial joint's inertia grows with the tiles it swings: its place matters
        for v in &w.vars {
            if let Var::Joint(jj) = v {
                key.push((g.tiles() - 1 - jj) as i64);
            }
        }
    }
    if w.lo == 0 {
        // the RI is in reach: the unit's place in the chain matters
        key.push(w.j as i64);
    }
    for k in w.lo..=w.hi {
        key.push(g.path_id(k) as i64);
    }
    for jj in w.lo / 2..w.hi / 2 {
        key.push(g.joint_fold(jj).quarter_turns() as i64);
    }
    for t in tracks {
        key.push(t.shape as i64);
        if t.shape != REST {
            key.push(((t.offset - t_ref) / quantum).round() as i64);
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::reference::Dynamics;

    /// `word`'s chain at `s` solved with `dynamics`, with or without the cache (`reuse`).
    fn solve_word(word: &str, s: f64, dynamics: Dynamics, reuse: bool) -> ChainSolution {
        solve_word_with(word, s, dynamics, reuse, true)
    }

    /// [`solve_word`], with or without RODAS4 where a unit is stiff.
    fn solve_word_with(word: &str, s: f64, d: Dynamics, reuse: bool, rb: bool) -> ChainSolution {
        let o = crate::engine::local::test_support::Options {
            s,
            dynamics: d,
            reuse,
            rosenbrock: rb,
            rest_skip: true,
        };
        crate::engine::local::test_support::solve_word(word, o)
    }

    /// Solves of each sweep, shapes stored and events.
    fn counts(word: &str) -> (Vec<usize>, usize, f64) {
        counts_with(word, Dynamics::Overdamped)
    }

    fn counts_with(word: &str, dynamics: Dynamics) -> (Vec<usize>, usize, f64) {
        let c = solve_word(word, 0.1, dynamics, true);
        let events = c.events().len() as f64;
        (c.solves_per_sweep, c.shapes.len(), events)
    }

    #[test]
    fn a_longer_steady_run_costs_no_more_solves() {
        // every sweep past the transients is a look-up per unit: four times the straight
        // chain, or twice the U-turns, costs the same solves a sweep and stores the same
        // shapes (a longer chain may take a sweep more: the sweeps stop on absolute times)
        let same_cost = |short: &[usize], long: &[usize]| {
            let most = short.iter().copied().max().unwrap();
            assert!(long.len() <= short.len() + 1, "{short:?} {long:?}");
            assert!(long.iter().all(|&n| n <= most), "{short:?} {long:?}");
            assert_eq!(short[..2], long[..2]);
        };
        let (short, shapes_short, events_short) = counts("S*60");
        let (long, shapes_long, events_long) = counts("S*240");
        assert!(
            events_long > 3.5 * events_short,
            "{events_short} {events_long}"
        );
        same_cost(&short, &long);
        assert!(
            shapes_long <= shapes_short + 10,
            "{shapes_short} {shapes_long}"
        );
        assert!(long.len() <= 5, "{long:?}");
        let row = "S*40 LL S*40 RR";
        let (two, shapes_two, events_two) = counts(&format!("{row} S*40"));
        let (four, shapes_four, events_four) = counts(&format!("{row} {row} S*40"));
        assert!(events_four > 1.6 * events_two, "{events_two} {events_four}");
        same_cost(&two, &four);
        assert!(shapes_four <= shapes_two + 30, "{shapes_two} {shapes_four}");
        // the inertial local solves (fold-run's default) as well
        let inertial = Dynamics::Inertial(Default::default());
        let (short, _, _) = counts_with("S*60", inertial);
        let (long, _, _) = counts_with("S*240", inertial);
        same_cost(&short, &long);
    }

    #[test]
    fn rodas4_where_stiff_saves_work_and_keeps_the_events() {
        // a U-turn swinging a 20,000-tile tail turns slowly while its pair's nearly closed
        // magnets follow it: a stiff stretch (measured: 12% fewer right-hand sides)
        let word = "S*4 LL S*20000";
        let inertial = Dynamics::Inertial(Default::default());
        let with = solve_word_with(word, 0.1, inertial, true, true);
        let without = solve_word_with(word, 0.1, inertial, true, false);
        assert_same_events(&with, &without);
        let (a, b) = (with.rhs as f64, without.rhs as f64);
        assert!(a < 0.92 * b, "{a} {b}");
    }

    #[test]
    fn cached_and_uncached_solves_agree() {
        let word = "S*14 LL S*14 RR S*6";
        let (a, b) = (
            solve_word(word, 0.1, Dynamics::Overdamped, true),
            solve_word(word, 0.1, Dynamics::Overdamped, false),
        );
        assert!(a.solves < b.solves, "{} {}", a.solves, b.solves);
        assert_same_events(&a, &b);
    }

    /// The same events in the same order, every time within 1e-5 of `b`'s duration.
    fn assert_same_events(a: &ChainSolution, b: &ChainSolution) {
        let (ea, eb) = (a.events(), b.events());
        assert_eq!(ea.len(), eb.len());
        let duration = eb.last().unwrap().time;
        let worst = ea
            .iter()
            .zip(&eb)
            .map(|(x, y)| {
                assert_eq!((x.kind, x.index), (y.kind, y.index));
                (x.time - y.time).abs()
            })
            .fold(0.0, f64::max);
        assert!(worst <= 1e-5 * duration, "{worst} of {duration}");
    }
}
