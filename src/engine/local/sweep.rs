//! One sweep over the chain ([`sweep`]): every unit solved in turn from the RI end, with the
//! units before it on this sweep's tracks and the units after it on the sweep before's
//! ([`crate::engine::local::relaxation`] tells the method).
//!
//! A sweep reads the sweep before as a stream of unit results ([`UnitOut`]: the unit's
//! entry and origin, from which its tracks follow, and the shapes it made), and writes its
//! own the same way, so that
//! the next sweep can trail it on another thread: unit `u` waits only for the sweep before's
//! units up to `u + lag` ([`Cache::lag`]), the last ones its window reaches. Everything a
//! unit reads (its inputs' tracks and shapes, the cache entries it sees, its sweep's own
//! shapes) is then fixed by the sweep and the unit alone, whatever runs beside it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender};
use std::sync::{Arc, Condvar, Mutex, PoisonError};

use crate::engine::local::cache::{Anchors, Cache, Entry, Library};
use crate::engine::local::solve::{solve, SolveOptions};
use crate::engine::local::trajectory::{Shape, Shapes, Track, MAX_STORED_SWEEPS, REST};
use crate::engine::local::unit_forces::{unit_vars, Inputs, UnitForces, Var};
use crate::model::Model;

/// A unit's time origin is when the magnet before it has travelled this fraction of its
/// path: 0.5.
pub(crate) const ANCHOR_FRACTION: f64 = 0.5;

/// Sweeps stop when no event moved by more than this fraction of the run's duration: 1e-6.
pub(crate) const SWEEP_TOLERANCE: f64 = 1e-6;
/// Input offsets in a cache key are rounded to this many of the model's time scales: 1e-7.
pub(crate) const OFFSET_QUANTUM: f64 = 1e-7;
/// A new shape within this (fraction of a path or fold, and fraction of its duration for
/// its end) of the same unknown's one unit back, shifted by the difference of the two
/// units' origins, is stored as that one: 1e-4, 0.5 um on a 5 mm path. Two solves of the
/// same steady motion on different steps differ by some 1e-5: a magnet that creeps off a
/// near balance amplifies the interpolation error of its inputs.
pub(crate) const SHAPE_TOLERANCE: f64 = 1e-4;

/// A sweep hands its unit results on in chunks of at most this many units, or at every
/// local solve (a chunk of look-ups is cheap to wait for; a solve is not): 64.
const CHUNK: usize = 64;

/// What the sweeps share.
#[derive(Clone, Copy)]
pub(crate) struct Ctx<'a> {
    /// The chain's model.
    pub(crate) model: &'a Model,
    /// The local solves' options.
    pub(crate) opts: SolveOptions<'a>,
    /// Whether units use the cache and share shapes.
    pub(crate) reuse: bool,
    /// The cache of unit solutions.
    pub(crate) cache: &'a Cache,
}

/// A unit's result as the next sweep reads it.
pub(crate) struct UnitOut {
    /// The unit's entry.
    entry: Arc<Entry>,
    /// The unit's time origin.
    t_ref: f64,
    /// The shapes the sweep made at this unit, in the order it made them.
    made: Vec<Arc<Shape>>,
}

/// A sweep's result.
pub(crate) struct SweepOut {
    /// The shapes of this sweep and of every sweep before.
    pub(crate) shapes: Shapes,
    /// Each magnet's track.
    pub(crate) magnets: Vec<Track>,
    /// Each joint's track.
    pub(crate) joints: Vec<Track>,
    /// Each unit's entry and time origin.
    pub(crate) units: Vec<(Arc<Entry>, f64)>,
    /// The largest change of an event time since the sweep before (infinite: the first).
    pub(crate) moved: f64,
    /// The last event's time.
    pub(crate) duration: f64,
    /// Local solves made.
    pub(crate) solves: usize,
    /// Right-hand sides evaluated.
    pub(crate) rhs: u64,
    /// Whether every unit was solved (not cancelled).
    pub(crate) complete: bool,
    /// Whether a unit's solve stopped at the horizon with an unknown still moving.
    pub(crate) cut: bool,
}

/// When a sweep that may not be needed starts, and whether it stops short: it is needed
/// only if the sweep it trails does not converge. That sweep opens the gate as soon as an
/// event has moved more than the sweeps' tolerance (it will not converge, unless the run
/// turns out much longer than the sweeps so far); the sweeps' driver opens it, or cancels
/// the sweep, when that sweep ends. Which does it and when changes no result: only how much
/// work is done in vain.
#[derive(Default)]
pub(crate) struct Gate {
    /// Undecided, go, or never start.
    state: Mutex<Option<bool>>,
    changed: Condvar,
    cancel: AtomicBool,
}

impl Gate {
    /// A gate open from the start.
    pub(crate) fn opened() -> Gate {
        Gate {
            state: Mutex::new(Some(true)),
            ..Gate::default()
        }
    }

    /// Lets the sweep start (if it was not cancelled).
    pub(crate) fn open(&self) {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if state.is_none() {
            *state = Some(true);
            self.changed.notify_all();
        }
    }

    /// Stops the sweep at its next unit, or before it starts.
    pub(crate) fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        if state.is_none() {
            *state = Some(false);
        }
        self.changed.notify_all();
    }

    /// Waits until the sweep may start or is cancelled; whether it may start.
    fn wait(&self) -> bool {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        loop {
            match *state {
                Some(go) => return go,
                None => {
                    state = self
                        .changed
                        .wait(state)
                        .unwrap_or_else(PoisonError::into_inner)
                }
            }
        }
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The sweep before, as read so far.
struct Before {
    rx: Option<Receiver<Vec<UnitOut>>>,
    /// Its units' entries and origins read so far.
    units: Vec<(Arc<Entry>, f64)>,
}

impl Before {
    /// Reads the sweep before of `model`'s chain up to unit `need` (all of it if it has
    /// fewer), writing its tracks and adding its shapes (sweep `k - 1`'s); false if it
    /// stopped short.
    fn read_to(
        &mut self,
        model: &Model,
        need: usize,
        k: usize,
        shapes: &mut Shapes,
        magnets: &mut [Track],
        joints: &mut [Track],
    ) -> bool {
        let Some(rx) = &self.rx else {
            return true;
        };
        while self.units.len() <= need {
            let Ok(chunk) = rx.recv() else {
                return false;
            };
            for unit in chunk {
                for shape in unit.made {
                    shapes.add(slot(k - 1), shape);
                }
                let j = self.units.len() as isize - 1;
                write_tracks(
                    &unit_vars(model, j),
                    &unit.entry,
                    unit.t_ref,
                    magnets,
                    joints,
                );
                self.units.push((unit.entry, unit.t_ref));
            }
        }
        true
    }
}

/// Where sweep `k`'s shapes are stored: the sweeps after the store's last (the coupled
/// folds' windows of time) share its slots with the first ones, which no sweep reads any
/// more (a sweep reads its own shapes and the sweep before's; without the cache no shape
/// is shared with an older sweep).
fn slot(k: usize) -> usize {
    (k - 1) % MAX_STORED_SWEEPS + 1
}

/// The unit whose unknowns include magnet `m`.
fn unit_of_magnet(m: usize) -> usize {
    m.div_ceil(2)
}

/// Where a sweep stands among the others.
pub(crate) struct Place<'a> {
    /// The sweep, from 1.
    pub(crate) k: usize,
    /// Sweep `k - 1`'s units as it makes them (none for the first sweep).
    pub(crate) before: Option<Receiver<Vec<UnitOut>>>,
    /// Takes this sweep's units.
    pub(crate) out: Sender<Vec<UnitOut>>,
    /// This sweep's gate: it starts when the gate opens, stops short when cancelled.
    pub(crate) gate: &'a Gate,
    /// The next sweep's gate, opened when this sweep will not converge.
    pub(crate) next: &'a Gate,
    /// The run's duration in the last sweep that ended (0: none yet).
    pub(crate) duration: f64,
}

/// Sweep `place.k` of `ctx`'s chain: `shapes` holds every shape of the sweeps before
/// `k - 1`. It stops short when cancelled, or when the sweep before stopped short.
pub(crate) fn sweep(ctx: Ctx, place: Place, mut shapes: Shapes) -> SweepOut {
    let Place {
        k,
        before,
        out,
        gate,
        next,
        duration: known,
    } = place;
    let model = ctx.model;
    let g = &model.geometry;
    let n = g.magnets();
    let tiles = g.tiles();
    let cutoff = model.options().cutoff;
    let mut magnets = vec![Track::REST; n];
    let mut joints = vec![Track::REST; tiles.saturating_sub(1)];
    let mut before = Before {
        rx: before,
        units: Vec::new(),
    };
    let mut units: Vec<(Arc<Entry>, f64)> = Vec::with_capacity(tiles + 1);
    let mut library = Library::default();
    let mut anchors = Anchors::new(ANCHOR_FRACTION);
    let mut saved = Saved::default();
    let mut key = Vec::new();
    let mut chunk = Vec::new();
    let (mut moved, mut duration, mut solves, mut rhs) = (0.0_f64, 0.0_f64, 0, 0);
    let mut complete = gate.wait();
    let mut go = false;
    for u in 0..=tiles {
        if !complete || gate.cancelled() {
            complete = false;
            break;
        }
        let j = u as isize - 1;
        let w = UnitForces::new(model, j, cutoff);
        // (a coupled joint reads the whole chain: every unit of the sweep before)
        let need = if model.coupled_folds {
            tiles
        } else {
            (u + ctx.cache.lag()).max(unit_of_magnet(w.hi)).min(tiles)
        };
        if !before.read_to(model, need, k, &mut shapes, &mut magnets, &mut joints) {
            complete = false;
            break;
        }
        let old = before.units.get(u).map(|&(_, old)| old);
        let (magnets_joints, keep) = (
            (&mut magnets[..], &mut joints[..]),
            (&mut anchors, &mut saved),
        );
        let (t_start, t_ref) = place_unit(&w, &shapes, magnets_joints, old, keep, &mut key);
        let hit = if ctx.reuse {
            ctx.cache.get(&key, (k, u))
        } else {
            None
        };
        let mut made = Vec::new();
        let solved = hit.is_none();
        let entry = match hit {
            Some(e) => e,
            None => {
                // the unit one back, if it is the same kind of unit: its time origin
                let prev_ref = (u >= 1).then(|| units.get(u - 1).map(|p| p.1)).flatten();
                let origin = (t_start, t_ref, prev_ref);
                let mut store = Store {
                    shapes: &mut shapes,
                    library: &mut library,
                    made: &mut made,
                };
                let (e, n) = solve_unit(
                    ctx,
                    (k, u),
                    &w,
                    origin,
                    (&magnets, &joints),
                    &key,
                    &mut store,
                );
                solves += 1;
                rhs += n;
                e
            }
        };
        saved.restore(&mut magnets, &mut joints);
        write_tracks(&w.vars, &entry, t_ref, &mut magnets, &mut joints);
        if let Some(ev) = entry.solution.events.last() {
            duration = duration.max(t_ref + ev.time);
        }
        moved = match before.units.get(u) {
            Some(old) => moved.max(change(old, &entry, t_ref)),
            None => f64::INFINITY,
        };
        if !go && moved > SWEEP_TOLERANCE * known.max(duration).max(model.time_scale) {
            next.open();
            go = true;
        }
        units.push((entry.clone(), t_ref));
        chunk.push(UnitOut { entry, t_ref, made });
        if solved || chunk.len() >= CHUNK {
            // the next sweep may have stopped: nothing to tell it then
            let _ = out.send(std::mem::take(&mut chunk));
        }
    }
    if !chunk.is_empty() {
        let _ = out.send(chunk);
    }
    SweepOut {
        shapes,
        magnets,
        joints,
        cut: units.iter().any(|u| u.0.solution.cut),
        units,
        moved,
        duration,
        solves,
        rhs,
        complete,
    }
}

/// Places unit `w` in time: its time origin, when the magnet before it is half way (a
/// crossing the step sizes hardly move), else when its inputs first move; the units after
/// it moved against it as they were in the sweep before (their tracks moved by as much as
/// its origin moved since its origin there, `old`; what they were kept in `saved`); its
/// window's cache key into `key`. Its inputs' first move and its origin.
fn place_unit(
    w: &UnitForces,
    shapes: &Shapes,
    (magnets, joints): (&mut [Track], &mut [Track]),
    old: Option<f64>,
    (anchors, saved): (&mut Anchors, &mut Saved),
    key: &mut Vec<i64>,
) -> (f64, f64) {
    let anchor = match w.vars.first() {
        Some(Var::Magnet(a)) if *a >= 1 && w.lo > 0 => anchors.crossing(shapes, magnets[a - 1]),
        _ => None,
    };
    let shift = match (anchor, old) {
        (Some(t), Some(old)) => t - old,
        _ => 0.0,
    };
    shift_downstream(w, magnets, joints, shift, saved);
    let inputs = Inputs {
        shapes,
        magnets,
        joints,
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
    let quantum = OFFSET_QUANTUM * w.model.time_scale;
    window_key(w, &tracks, t_ref, quantum, key);
    (t_start, t_ref)
}

/// Where a sweep keeps the shapes its local solves make.
struct Store<'s> {
    /// The shapes of this sweep and of every sweep before.
    shapes: &'s mut Shapes,
    /// This sweep's shapes by kind and end (the copies a new shape may be).
    library: &'s mut Library,
    /// The shapes this sweep made at the unit.
    made: &'s mut Vec<Arc<Shape>>,
}

/// Solves unit `u` of sweep `k` (`w`) against `tracks` (the magnets' and the joints'),
/// its origin being `(t_start, t_ref, prev_ref)` (its inputs' first move, its time origin,
/// the unit one back's); stores its new shapes (or the stored ones they are copies of) and
/// its entry under `key` in the cache. The entry and the right-hand sides evaluated.
fn solve_unit(
    ctx: Ctx,
    (k, u): (usize, usize),
    w: &UnitForces,
    (t_start, t_ref, prev_ref): (f64, f64, Option<f64>),
    (magnets, joints): (&[Track], &[Track]),
    key: &[i64],
    store: &mut Store,
) -> (Arc<Entry>, u64) {
    let quantum = OFFSET_QUANTUM * ctx.model.time_scale;
    let inputs = Inputs {
        shapes: store.shapes,
        magnets,
        joints,
    };
    let (t0, mut sol) = solve(w, inputs, ctx.opts);
    debug_assert_eq!(t0, t_start);
    // local times from the unit's origin
    let d = t0 - t_ref;
    for e in &mut sol.events {
        e.time += d;
    }
    for (_, start) in sol.shapes.iter_mut().flatten() {
        *start += d;
    }
    let rhs = sol.rhs;
    let mut ids = Vec::with_capacity(sol.shapes.len());
    for (i, sh) in sol.shapes.iter_mut().enumerate() {
        ids.push(sh.take().map(|(shape, start)| {
            let found = if ctx.reuse {
                shared_shape(
                    store.shapes,
                    store.library,
                    magnets,
                    joints,
                    w,
                    i,
                    &shape,
                    start,
                    t_ref,
                    prev_ref,
                    quantum,
                )
            } else {
                None
            };
            found.unwrap_or_else(|| {
                let end = shape.end();
                let shape = Arc::new(shape);
                let id = store.shapes.add(slot(k), shape.clone());
                store.made.push(shape);
                store
                    .library
                    .add(kind(&ctx.model.geometry, w.vars[i]), end, id);
                (id, start)
            })
        }));
    }
    let e = Arc::new(Entry {
        shapes: ids,
        solution: sol,
    });
    if ctx.reuse {
        ctx.cache.insert(key, (k, u), e.clone());
    }
    (e, rhs)
}

/// Writes the tracks of a unit with unknowns `vars`, solution `entry` and origin `t_ref`.
fn write_tracks(
    vars: &[Var],
    entry: &Entry,
    t_ref: f64,
    magnets: &mut [Track],
    joints: &mut [Track],
) {
    for (v, sh) in vars.iter().zip(&entry.shapes) {
        let track = match sh {
            Some((id, start)) => Track {
                shape: *id,
                offset: t_ref + start,
            },
            None => Track::REST,
        };
        match *v {
            Var::Magnet(m) => magnets[m] = track,
            Var::Joint(jj) => joints[jj] = track,
        }
    }
}

/// The kind of unknown `v` (a magnet's path, a joint's fold): the shapes a new one may be
/// a copy of.
fn kind(g: &crate::timeline::Geometry, v: Var) -> (bool, i64) {
    match v {
        Var::Magnet(m) => (false, g.path_id(m) as i64),
        Var::Joint(jj) => (true, g.joint_fold(jj).quarter_turns() as i64),
    }
}

/// A stored shape that unknown `i` of unit `w`'s new `shape` (starting at `start`, local
/// time) may be taken as, with its start: a copy of a shape this sweep stored before (the
/// steady shape of a straight run, met again after a U-turn), compared from its start, or
/// the same role's one unit back, compared in absolute time shifted by the difference of
/// the two units' origins.
#[allow(clippy::too_many_arguments)]
fn shared_shape(
    shapes: &Shapes,
    library: &Library,
    magnets: &[Track],
    joints: &[Track],
    w: &UnitForces,
    i: usize,
    shape: &Shape,
    start: f64,
    t_ref: f64,
    prev_ref: Option<f64>,
    quantum: f64,
) -> Option<(u32, f64)> {
    let prev = match w.vars[i] {
        Var::Magnet(m) if m >= 2 => Some(magnets[m - 2]),
        Var::Joint(jj) if jj >= 1 => Some(joints[jj - 1]),
        _ => None,
    };
    let dt = 0.1 * SHAPE_TOLERANCE * shape.end() + quantum;
    let kind = kind(&w.model.geometry, w.vars[i]);
    if let Some(id) = library.find(shapes, kind, shape, SHAPE_TOLERANCE, dt) {
        return Some((id, start));
    }
    match (prev, prev_ref) {
        (Some(p), Some(r0)) if p.shape != REST => {
            let shift = p.offset + (t_ref - r0);
            let new_offset = t_ref + start;
            shapes
                .get(p.shape)
                .close_shifted(shape, new_offset - shift, SHAPE_TOLERANCE, dt)
                .then_some((p.shape, shift - t_ref))
        }
        _ => None,
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
        for (m, t) in self.magnets.drain(..) {
            magnets[m] = t;
        }
        for (jj, t) in self.joints.drain(..) {
            joints[jj] = t;
        }
    }
}

/// Moves the moving tracks of unit `w`'s window after its unknowns (the magnets after its
/// last one, the joints after its own) by `shift`, keeping what they were in `saved`.
fn shift_downstream(
    w: &UnitForces,
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
            Var::Magnet(m) => Some(*m),
            Var::Joint(_) => None,
        })
        .max();
    let Some(last) = last else {
        return;
    };
    for (m, t) in magnets.iter_mut().enumerate().take(w.hi + 1).skip(last + 1) {
        if t.shape != REST {
            saved.magnets.push((m, *t));
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
fn window_key(w: &UnitForces, tracks: &[Track], t_ref: f64, quantum: f64, key: &mut Vec<i64>) {
    let g = &w.model.geometry;
    key.clear();
    let first = w.vars.iter().find_map(|v| match v {
        Var::Magnet(m) => Some(*m as i64),
        Var::Joint(_) => None,
    });
    let a = first.unwrap_or(0);
    key.push(a - w.lo as i64);
    key.push(w.hi as i64 - a);
    key.push(w.vars.len() as i64);
    // a joint's inertia and drag are its two sides': its place in the chain matters unless
    // another joint has the same sides to the last bit
    for v in &w.vars {
        if let Var::Joint(jj) = v {
            if let Some(bits) = w.model.joint_key(*jj) {
                key.extend(bits.iter().map(|b| *b as i64));
            }
        }
    }
    if w.lo == 0 {
        // the RI is in reach: the unit's place in the chain matters
        key.push(w.j as i64);
    }
    for m in w.lo..=w.hi {
        key.push(g.path_id(m) as i64);
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
