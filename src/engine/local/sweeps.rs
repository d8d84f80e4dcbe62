//! The chain solved unit by unit from the RI end ([`solve_chain`]), in sweeps: in the
//! first, every unit sees the units before it on their solved tracks and the units after it
//! at rest; each later sweep solves every unit again with the units after it on their
//! tracks of the sweep before (a Gauss-Seidel waveform relaxation), until no event moves by
//! more than [`SWEEP_TOLERANCE`] of the run's duration, or [`MAX_SWEEPS`] sweeps.
//!
//! **Cache.** A unit's solution depends only on the geometry of its window and on its
//! inputs' shapes and offsets relative to its own time origin. Those are the key of a cache
//! (offsets rounded to [`OFFSET_QUANTUM`] time scales); a new solution's shapes that agree
//! within [`SHAPE_TOLERANCE`] with the previous unit's are stored once. Along a steady
//! straight run the transient from the RI (or from a U-turn) dies out in a few tiles, after
//! which every unit is the one before it shifted in time: a cache hit, no integration.

use std::sync::Arc;

use rustc_hash::FxHashMap;

use crate::engine::local::solve::{solve, Solution, SolveOptions};
use crate::engine::local::trajectory::{Shapes, Track, REST};
use crate::engine::local::window::{Inputs, Var, Window};
use crate::reference::Model;
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
    while sweeps < MAX_SWEEPS {
        sweeps += 1;
        let mut moved: f64 = 0.0;
        let mut duration: f64 = 0.0;
        for u in 0..=tiles {
            let j = u as isize - 1;
            let w = Window::new(model, j, cutoff);
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
            // the unit's time origin: when the magnet before it is half way (a crossing the
            // step sizes hardly move), else when its inputs first move
            let t_ref = match w.vars.first() {
                Some(Var::Magnet(a)) if *a >= 1 && w.lo > 0 => shapes
                    .crossing(magnets[a - 1], ANCHOR_FRACTION)
                    .unwrap_or(t_start),
                _ => t_start,
            };
            window_key(&w, &tracks, t_ref, quantum, &mut key);
            let entry = match cache.get(&key) {
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
                                            0.1 * SHAPE_TOLERANCE * shape.end() + quantum,
                                        )
                                        .then_some((p.shape, shift - t_ref))
                                }
                                _ => None,
                            };
                            match same {
                                Some(found) => found,
                                None => (shapes.add(shape), start),
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
