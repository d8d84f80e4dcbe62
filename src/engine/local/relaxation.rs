//! The chain solved unit by unit from the RI end ([`solve_chain`]), in sweeps: in the
//! first, every unit sees the units before it on their solved tracks and the units after it
//! at rest; each later sweep solves every unit again with the units after it on their
//! tracks of the sweep before (a Gauss-Seidel waveform relaxation), until no event moves by
//! more than [`SWEEP_TOLERANCE`](crate::engine::local::sweep::SWEEP_TOLERANCE) of the run's duration, or [`MAX_SWEEPS`] sweeps. With
//! coupled folds the sweeps settle a window of time at a time ([`COUPLED_WINDOW`]).
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
//! (offsets rounded to [`OFFSET_QUANTUM`](crate::engine::local::sweep::OFFSET_QUANTUM) time scales). A new solution's shape that agrees
//! within [`SHAPE_TOLERANCE`](crate::engine::local::sweep::SHAPE_TOLERANCE) with a stored shape of the same kind of unknown (the same path,
//! the same fold) is stored as that one, and so is one that agrees with the same unknown's one
//! unit back: a steady straight run settles on the same shapes after every U-turn. Along a
//! steady run the transient from the RI (or from a U-turn) dies out in a few tiles, after
//! which every unit is the one before it shifted in time: a cache hit, no integration, in
//! every sweep; a U-turn met before in the same state is a hit too. A chain costs the
//! transients of its distinct turns, and a look-up per unit and sweep.
//!
//! **Two sweeps at once.** Unit `u` of sweep `k + 1` needs only that sweep's units before
//! `u` and sweep `k`'s up to the last its window reaches (`cutoff / 2` units on): so sweep
//! `k + 1` can run on a second thread, trailing sweep `k` by a few units
//! ([`crate::engine::local::sweep`]). When sweep `k` ends, it is the last if it converged
//! (sweep `k + 1` is then cancelled); if not, sweep `k + 2` trails `k + 1`. Two threads take
//! the sweeps two by two: on two free cores, four sweeps take about the wall time of two
//! (each sweep's work is the same as on one thread). The solution is the
//! same, bit for bit, with one thread or two and whatever their timing: every shape's id
//! numbers its sweep and its place among that sweep's shapes, each sweep reads the shapes it
//! may (those of the sweeps before and its own), and a cache look-up sees exactly the entries
//! of [`crate::engine::local::cache`]'s rule, one thread or two.

use std::sync::mpsc::channel;
use std::sync::Arc;

use crate::engine::local::cache::{Cache, Entry};
use crate::engine::local::solve::SolveOptions;
use crate::engine::local::sweep::{sweep, Ctx, Gate, Place, SweepOut, SWEEP_TOLERANCE};
use crate::engine::local::trajectory::{Shapes, Track, MAX_STORED_SWEEPS};

// every sweep's shapes are told apart in the store (the coupled folds' later sweeps share
// the first ones' slots: `engine::local::sweep`)
const _: () = assert!(MAX_SWEEPS <= MAX_STORED_SWEEPS);
use crate::model::Model;
use crate::timeline::{Event, EventKind};

/// Most sweeps over the chain.
pub(crate) const MAX_SWEEPS: usize = 8;

/// Most sweeps over the chain when its folds turn by the coupled equations
/// ([`Model::coupled_folds`]), over all its windows of time: 400.
pub(crate) const COUPLED_MAX_SWEEPS: usize = 400;

/// With coupled folds the sweeps solve the run a window of time at a time: each sweep
/// stops its solves at a horizon, which moves on by a window once two sweeps agree up to
/// it within [`COUPLED_TOLERANCE`] (or after [`WINDOW_SWEEPS`] in one window). The first
/// window, s: 0.05; a window that took at most 3 sweeps doubles the next, one that took
/// [`WINDOW_SWEEPS`] halves it (down to a quarter of the first). Over a long window the
/// relaxation of strongly coupled folds grows its errors for many sweeps before they shrink
/// (a closed fold pulled open by the sweep before's wrong tracks of the folds after it,
/// which then turn wrongly in turn: `LLRL`'s evaluations grew 1.7 times a sweep and it
/// never settled); over a short one they shrink from the first.
pub(crate) const COUPLED_WINDOW: f64 = 0.05;

/// Most sweeps in one window of time: 12.
const WINDOW_SWEEPS: usize = 12;

/// With coupled folds, two sweeps agree when no event moved by more than this fraction of
/// the run's duration: 1e-5 (their solves' own scatter is some 1e-6).
const COUPLED_TOLERANCE: f64 = 1e-5;

/// The most sweeps over `model`'s chain.
fn max_sweeps(model: &Model) -> usize {
    if model.coupled_folds {
        COUPLED_MAX_SWEEPS
    } else {
        MAX_SWEEPS
    }
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

/// Threads 0 (the default) runs chains of fewer tiles than this on one thread: 500.
pub(crate) const AUTO_MIN_TILES: usize = 500;

/// Solves `model`'s chain with local solves of tolerance `opts.tol`, the sweeps on
/// `threads` threads (more than 2 are not used; 0: as many as the machine has, but one for
/// a chain of fewer than [`AUTO_MIN_TILES`] tiles or when called on a rayon pool's thread).
pub(crate) fn solve_chain(model: &Model, opts: SolveOptions, threads: usize) -> ChainSolution {
    // a unit that reads the folds upstream of its window is not keyed by them: no cache
    if model.swung_faces || model.coupled_folds {
        return solve_chain_with(model, opts, false, 1);
    }
    solve_chain_with(model, opts, true, threads)
}

/// [`solve_chain`], with or without the cache and the sharing of shapes (`reuse`).
pub(crate) fn solve_chain_with(
    model: &Model,
    opts: SolveOptions,
    reuse: bool,
    threads: usize,
) -> ChainSolution {
    // a unit's window reaches `cutoff` magnets past its own: half as many units
    let cache = Cache::new(model.options().cutoff.div_ceil(2) + LAG_MARGIN);
    let ctx = Ctx {
        model,
        opts,
        reuse,
        cache: &cache,
    };
    let threads = match threads {
        // a short chain's sweeps cost less than starting threads, and a caller that runs
        // chains on a pool's threads keeps its cores busy already
        0 if model.geometry.tiles() < AUTO_MIN_TILES || rayon::current_thread_index().is_some() => {
            1
        }
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        t => t,
    };
    let mut done = Done::new(model);
    let last = if threads >= 2 {
        pipelined(ctx, &mut done)
    } else {
        one_by_one(ctx, &mut done)
    };
    ChainSolution {
        shapes: last.shapes,
        magnets: last.magnets,
        joints: last.joints,
        units: last.units,
        sweeps: done.solves_per_sweep.len(),
        solves: done.solves_per_sweep.iter().sum(),
        rhs: done.rhs,
        solves_per_sweep: done.solves_per_sweep,
    }
}

/// A unit waits for, and sees the cache entries of, the sweep before's units this many
/// past the last one its window reaches: 1.
const LAG_MARGIN: usize = 1;

/// The sweeps made so far.
struct Done {
    solves_per_sweep: Vec<usize>,
    rhs: u64,
    /// Where the next sweep's solves stop (coupled folds; else infinite).
    horizon: f64,
    /// The sweeps made in the current window of time.
    in_window: usize,
    /// The current window's length, s.
    window: f64,
}

impl Done {
    /// No sweep made yet on `model`'s chain.
    fn new(model: &Model) -> Done {
        Done {
            solves_per_sweep: Vec::new(),
            rhs: 0,
            horizon: if model.coupled_folds {
                COUPLED_WINDOW
            } else {
                f64::INFINITY
            },
            in_window: 0,
            window: COUPLED_WINDOW,
        }
    }

    /// Counts sweep `out`; whether it is the last (converged with no solve stopped at its
    /// horizon, or the last allowed). With coupled folds, moves the horizon on when the
    /// sweeps agree up to it (at least two sweeps in a window).
    fn add(&mut self, model: &Model, out: &SweepOut) -> bool {
        debug_assert!(out.complete, "a sweep waited for stopped short");
        self.solves_per_sweep.push(out.solves);
        self.rhs += out.rhs;
        self.in_window += 1;
        let scale = out.duration.max(model.time_scale);
        if self.solves_per_sweep.len() >= max_sweeps(model) {
            return true;
        }
        if !model.coupled_folds {
            return out.moved <= SWEEP_TOLERANCE * scale;
        }
        let converged = out.moved <= COUPLED_TOLERANCE * scale;
        if (converged && self.in_window >= 2) || self.in_window >= WINDOW_SWEEPS {
            if !out.cut {
                return true;
            }
            if self.in_window <= 3 {
                self.window *= 2.0;
            } else if self.in_window >= WINDOW_SWEEPS {
                self.window = (0.5 * self.window).max(0.25 * COUPLED_WINDOW);
            }
            self.horizon += self.window;
            self.in_window = 0;
        }
        false
    }
}

/// The sweeps one after the other on this thread; the last.
fn one_by_one(ctx: Ctx, done: &mut Done) -> SweepOut {
    let open = Gate::opened();
    // the shapes of the sweeps before the one before the next, and before the next
    let (mut base, mut base_next) = (Shapes::default(), Shapes::default());
    let mut before = None;
    loop {
        let (out, rx) = channel();
        let place = Place {
            k: done.solves_per_sweep.len() + 1,
            before: before.take(),
            out,
            gate: &open,
            next: &open,
            duration: 0.0,
        };
        // (the solves stop at the window's horizon)
        let mut ctx = ctx;
        ctx.opts.horizon = done.horizon;
        let out = sweep(ctx, place, base);
        if done.add(ctx.model, &out) {
            return out;
        }
        base = std::mem::replace(&mut base_next, out.shapes);
        before = Some(rx);
    }
}

/// The sweeps on two threads, each but the first trailing the one before; the last.
///
/// While sweep `k` runs, sweep `k + 1` trails it, from when `k` shows it will not converge
/// ([`Gate`]); when `k` ends it is the last if it converged (then `k + 1` is cancelled),
/// else `k + 2` is readied to trail `k + 1`.
fn pipelined(ctx: Ctx, done: &mut Done) -> SweepOut {
    let most = max_sweeps(ctx.model);
    let gates: Vec<Gate> = (0..=most + 1).map(|_| Gate::default()).collect();
    let gates = &gates;
    gates[1].open();
    std::thread::scope(|scope| {
        let join = |h: std::thread::ScopedJoinHandle<'_, SweepOut>| {
            h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))
        };
        let (out, mut rx) = channel();
        let place = Place {
            k: 1,
            before: None,
            out,
            gate: &gates[1],
            next: &gates[2],
            duration: 0.0,
        };
        let mut running = scope.spawn(move || sweep(ctx, place, Shapes::default()));
        // the shapes of the sweeps before the one running, and the run's duration in the
        // last sweep that ended
        let mut base = Shapes::default();
        let mut duration = 0.0;
        let mut k = 1;
        loop {
            let next = (k < most).then(|| {
                let (out, next_rx) = channel();
                let place = Place {
                    k: k + 1,
                    before: Some(std::mem::replace(&mut rx, next_rx)),
                    out,
                    gate: &gates[k + 1],
                    next: &gates[k + 2],
                    duration,
                };
                let base = std::mem::take(&mut base);
                scope.spawn(move || sweep(ctx, place, base))
            });
            let out = join(running);
            let last = done.add(ctx.model, &out);
            match next {
                Some(next) if !last => {
                    gates[k + 1].open();
                    base = out.shapes;
                    duration = out.duration;
                    running = next;
                    k += 1;
                }
                next => {
                    gates[k + 1].cancel();
                    if let Some(next) = next {
                        let _ = join(next);
                    }
                    return out;
                }
            }
        }
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::model::Dynamics;

    /// `word`'s chain at `s` solved with `dynamics`, with or without the cache (`reuse`).
    fn solve_word(word: &str, s: f64, dynamics: Dynamics, reuse: bool) -> ChainSolution {
        solve_word_with(word, s, dynamics, reuse, true)
    }

    /// [`solve_word`], with or without RODAS4 where a unit is stiff.
    fn solve_word_with(word: &str, s: f64, d: Dynamics, reuse: bool, rb: bool) -> ChainSolution {
        solve_word_on(word, s, d, reuse, rb, 2)
    }

    /// [`solve_word_with`], the sweeps on `threads` threads.
    fn solve_word_on(
        word: &str,
        s: f64,
        d: Dynamics,
        reuse: bool,
        rb: bool,
        threads: usize,
    ) -> ChainSolution {
        let o = crate::engine::local::test_support::Options {
            s,
            dynamics: d,
            reuse,
            rosenbrock: rb,
            rest_skip: true,
            threads,
        };
        crate::engine::local::test_support::solve_word(word, o)
    }

    #[test]
    fn one_thread_or_two_give_the_same_solution_bit_for_bit() {
        // two sweeps at once, the later trailing the earlier: every event time, every track
        // and the work done the same as one sweep after the other
        let inertial = Dynamics::Inertial;
        for (word, d) in [
            ("S*30 LL S*30 RR S*30 LL S*30", inertial),
            ("S*14 LL S*14 RR S*6", Dynamics::Overdamped),
        ] {
            let one = solve_word_on(word, 0.1, d, true, true, 1);
            assert!(one.sweeps >= 3, "{word}: {:?}", one.solves_per_sweep);
            for _ in 0..2 {
                let two = solve_word_on(word, 0.1, d, true, true, 2);
                let (a, b) = (one.events(), two.events());
                assert_eq!(a.len(), b.len(), "{word}");
                for (x, y) in a.iter().zip(&b) {
                    assert_eq!(
                        (x.time.to_bits(), x.kind, x.index),
                        (y.time.to_bits(), y.kind, y.index),
                        "{word}"
                    );
                }
                assert_eq!(one.magnets, two.magnets, "{word}");
                assert_eq!(one.joints, two.joints, "{word}");
                assert_eq!(one.solves_per_sweep, two.solves_per_sweep, "{word}");
                assert_eq!(one.rhs, two.rhs, "{word}");
                assert_eq!(one.shapes.len(), two.shapes.len(), "{word}");
            }
        }
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
        // a U-turn's two sides differ from one U-turn to the next (its inertia and drag are
        // those of the whole chain either side), so each U-turn is solved: twice the U-turns
        // cost at most twice the solves a sweep, the straight runs between them nothing more
        let row = "S*40 LL S*40 RR";
        let (two, _, events_two) = counts(&format!("{row} S*40"));
        let (four, _, events_four) = counts(&format!("{row} {row} S*40"));
        assert!(events_four > 1.6 * events_two, "{events_two} {events_four}");
        assert!(four.len() <= two.len() + 1, "{two:?} {four:?}");
        let most = two.iter().copied().max().unwrap();
        assert!(four.iter().all(|&n| n <= 2 * most), "{two:?} {four:?}");
        // the inertial local solves (fold-run's default) as well
        let inertial = Dynamics::Inertial;
        let (short, _, _) = counts_with("S*60", inertial);
        let (long, _, _) = counts_with("S*240", inertial);
        same_cost(&short, &long);
    }

    #[test]
    fn rodas4_where_stiff_saves_work_and_keeps_the_events() {
        // a U-turn between two 300-tile runs turns slowly (each side's drag about the hinge
        // grows as its length cubed) while its pair's nearly closed magnets follow it: a stiff
        // stretch. (A short head against a long tail turns fast: it is the head that turns.)
        let word = "S*300 LL S*300";
        let inertial = Dynamics::Inertial;
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
