//! The sequential check of a word that grows: [`PrefixCheck`] says whether the chain built
//! so far folds cleanly ([`super::check_word`] with the default options is `Ok`), checking
//! only what each added run of folds changes.
//!
//! A planner that grows chains (a route through cells, one leg at a time, with a beam of
//! partial routes) asks the question for every extension. Checked from scratch, each answer
//! costs the whole prefix; here the state of the checked prefix is kept:
//! - the final shape: each added tile is tested against the tiles before it (the same exact
//!   lattice test as [`super::final_overlap`]);
//! - the sweeps: whether the straight tail of joint `k` meets a placed tile depends only on
//!   tiles `0..=k` and on how long the tail is (the first-hit memo,
//!   [`super::first_hit::TailHits`]). For each folding joint the state keeps the tail length up
//!   to which that is known to be clear, or the length from which the memo says it meets; a
//!   longer chain extends only the joints whose cleared length it passes, by at least doubling
//!   it, so each joint is looked at a few times over the whole growth. The tiles a joint's tail
//!   can meet (tiles `0..=k`) never change, so a joint keeps the least first hit among the
//!   tiles its cleared tail can reach, and extending it looks up only the tiles the longer tail
//!   reaches beyond them. A joint the memo says meets is swept pair by pair in world
//!   coordinates, as [`super::check_word`] does.
//!
//! Tiles are kept in runs (one per [`PrefixCheck::push`]) shared between clones, so cloning a
//! state to try an extension costs a few pointers per run and per joint, not the chain.

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::f64::consts::FRAC_PI_2;
use std::sync::{Arc, Mutex, MutexGuard};

use kurbo::{Point, Rect};

use crate::exact::ExactPose;
use crate::{kinematics, Fold};

use super::first_hit::{canonical_offset, TailHits, NEVER};
use super::index_boxes::{meets, union, union_pt, EMPTY};
use super::lattice::lattice_overlap;
use super::sequential::UnitTile;
use super::sweep::{swept_query, TurningPair};
use super::CheckOptions;

/// Tiles per leaf box of a run.
const LEAF: usize = 8;
/// Leaf boxes per group box of a run.
const GROUP: usize = 8;

/// The memos a growing check consults: first hits by lattice offset, and the tile the
/// sweeps use. Shared by a [`PrefixCheck`] and its clones; it never changes a verdict, only
/// saves work.
struct Memo {
    hits: TailHits,
    tile: UnitTile,
}

impl Memo {
    fn new(opts: &CheckOptions) -> Memo {
        Memo {
            hits: TailHits::new(opts.tolerance),
            tile: UnitTile::new(opts.tolerance),
        }
    }
}

/// A run of consecutive tiles, with boxes over its leaves and groups of leaves.
#[derive(Debug)]
struct Run {
    /// Index of the run's first tile in the chain.
    first: usize,
    poses: Vec<ExactPose>,
    centres: Vec<Point>,
    /// The fold of the joint leading into each tile (joint `first + t - 1`); `S` for tile 0.
    into: Vec<Fold>,
    leaves: Vec<Rect>,
    groups: Vec<Rect>,
    bbox: Rect,
}

fn closed_contains(r: &Rect, c: Point) -> bool {
    c.x >= r.x0 && c.x <= r.x1 && c.y >= r.y0 && c.y <= r.y1
}

impl Run {
    fn new(first: usize, poses: Vec<ExactPose>, into: Vec<Fold>) -> Run {
        let centres: Vec<Point> = poses
            .iter()
            .map(|p| Point::from(p.centre.to_f64(1.0)))
            .collect();
        let leaves: Vec<Rect> = centres
            .chunks(LEAF)
            .map(|c| c.iter().fold(EMPTY, |b, &p| union_pt(b, p)))
            .collect();
        let groups: Vec<Rect> = leaves
            .chunks(GROUP)
            .map(|l| l.iter().fold(EMPTY, |b, &r| union(b, r)))
            .collect();
        let bbox = groups.iter().fold(EMPTY, |b, &r| union(b, r));
        Run {
            first,
            poses,
            centres,
            into,
            leaves,
            groups,
            bbox,
        }
    }

    /// Calls `visit(i, centre, pose)` for the run's tiles `i <= last` (chain indices) whose
    /// centre lies in `query` (closed), until `visit` returns `true`; returns whether it did.
    fn for_each_in(
        &self,
        last: usize,
        query: &Rect,
        visit: &mut impl FnMut(usize, Point, ExactPose) -> bool,
    ) -> bool {
        if last < self.first || !meets(&self.bbox, query) {
            return false;
        }
        let end = (last + 1 - self.first).min(self.centres.len());
        for (g, gb) in self.groups.iter().enumerate() {
            let g0 = g * GROUP * LEAF;
            if g0 >= end {
                break;
            }
            if !meets(gb, query) {
                continue;
            }
            for l in g * GROUP..((g + 1) * GROUP).min(self.leaves.len()) {
                let l0 = l * LEAF;
                if l0 >= end {
                    break;
                }
                if !meets(&self.leaves[l], query) {
                    continue;
                }
                for t in l0..(l0 + LEAF).min(end) {
                    let c = self.centres[t];
                    if closed_contains(query, c) && visit(self.first + t, c, self.poses[t]) {
                        return true;
                    }
                }
            }
        }
        false
    }
}

/// The sequential fold check of a chain that grows at its free end (see the module
/// documentation). Clone a state to try an extension; clones share the tiles and the memo of
/// first hits, and [`PrefixCheck::emptied`] starts another chain with that memo (a planner
/// keeps one per thread between calls).
///
/// ```
/// use foldchain::collision::PrefixCheck;
/// use foldchain::Fold::{L, S};
///
/// let mut chain = PrefixCheck::new();
/// chain.push(&[S, L, L]); // four tiles, a U-turn
/// assert!(chain.folds_cleanly());
/// let mut longer = chain.clone();
/// longer.push(&[L, L]); // the tail turns back into tile 0
/// assert!(!longer.folds_cleanly());
/// assert!(chain.folds_cleanly()); // the clone left it as it was
/// ```
#[derive(Clone)]
pub struct PrefixCheck {
    runs: Vec<Arc<Run>>,
    tiles: usize,
    /// A collision was found; every longer chain collides too (its tiles and tails contain
    /// this one's).
    collided: bool,
    /// Folding joints not known to meet: `(n, k, m)`, joint `k`'s tail is clear while the
    /// chain has at most `n` tiles, and `m` is the least first hit (tail index, or
    /// [`NEVER`]) among the tiles that tail reaches; smallest `n` first.
    clear: BinaryHeap<Reverse<(usize, usize, u32)>>,
    /// Folding joints the memo says meet: `(n, k)`, from `n` tiles on.
    meets: Vec<(usize, usize)>,
    /// The memo, shared with the clones (locked once per query).
    memo: Arc<Mutex<Memo>>,
}

/// A memo, locked (a memo left by a panicking thread is still consistent: an entry is stored
/// only once computed).
fn lock(memo: &Mutex<Memo>) -> MutexGuard<'_, Memo> {
    memo.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

impl std::fmt::Debug for PrefixCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PrefixCheck")
            .field("tiles", &self.tiles)
            .field("collided", &self.collided)
            .finish_non_exhaustive()
    }
}

impl Default for PrefixCheck {
    fn default() -> PrefixCheck {
        PrefixCheck::with_options(&CheckOptions::default())
    }
}

impl PrefixCheck {
    /// An empty chain (no tile yet), checked as [`super::check_word`] with the default
    /// options.
    pub fn new() -> PrefixCheck {
        PrefixCheck::default()
    }

    /// An empty chain checked as [`super::check_word`] with `opts` (its touching tolerance).
    pub fn with_options(opts: &CheckOptions) -> PrefixCheck {
        PrefixCheck::with_memo(Arc::new(Mutex::new(Memo::new(opts))))
    }

    /// An empty chain that shares this one's memo (what it learnt about other chains saves
    /// work on the new one; it never changes a verdict).
    pub fn emptied(&self) -> PrefixCheck {
        PrefixCheck::with_memo(Arc::clone(&self.memo))
    }

    /// An empty chain with `memo`.
    fn with_memo(memo: Arc<Mutex<Memo>>) -> PrefixCheck {
        PrefixCheck {
            runs: Vec::new(),
            tiles: 0,
            collided: false,
            clear: BinaryHeap::new(),
            meets: Vec::new(),
            memo,
        }
    }

    /// Tiles so far.
    pub fn tiles(&self) -> usize {
        self.tiles
    }

    /// The run holding tile `i`, and the tile's place in it.
    fn locate(&self, i: usize) -> (&Run, usize) {
        let r = self.runs.partition_point(|r| r.first <= i) - 1;
        let run = &self.runs[r];
        (run, i - run.first)
    }

    /// Calls `visit` for every tile `i <= last` whose centre lies in `query` (closed), until
    /// it returns `true`; returns whether it did. The latest runs come first (their tiles lie
    /// nearest tile `last` along the chain, where a first hit is likeliest found early).
    fn for_each_in(
        &self,
        last: usize,
        query: &Rect,
        mut visit: impl FnMut(usize, Point, ExactPose) -> bool,
    ) -> bool {
        for run in self.runs.iter().rev() {
            if run.first > last {
                continue;
            }
            if run.for_each_in(last, query, &mut visit) {
                return true;
            }
        }
        false
    }

    /// Adds tiles: the first tile (at the origin, heading +x) when the chain is empty, then
    /// one tile per fold in `folds`. The final shape is checked for the new tiles here; the
    /// sweeps when asked ([`PrefixCheck::folds_cleanly`]).
    pub fn push(&mut self, folds: &[Fold]) {
        let first = self.tiles;
        let mut poses = Vec::with_capacity(folds.len() + 1);
        let mut into = Vec::with_capacity(folds.len() + 1);
        let mut pose = if first == 0 {
            poses.push(ExactPose::default());
            into.push(Fold::S);
            ExactPose::default()
        } else {
            let (run, t) = self.locate(first - 1);
            run.poses[t]
        };
        for &f in folds {
            pose = kinematics::next_exact_pose(pose, f);
            poses.push(pose);
            into.push(f);
        }
        if poses.is_empty() {
            return;
        }
        let run = Run::new(first, poses, into);
        let added = run.poses.len();
        self.runs.push(Arc::new(run));
        self.tiles += added;
        for j in first.max(1)..self.tiles {
            let (run, t) = self.locate(j);
            let k = j - 1;
            if run.into[t] != Fold::S {
                // a tail of no tiles is clear
                self.clear.push(Reverse((k + 1, k, NEVER)));
            }
        }
        if !self.collided {
            self.collided = (first..self.tiles).any(|j| self.overlaps_before(j));
        }
    }

    /// Whether tile `j` overlaps a tile before it in the final shape (exactly, as
    /// [`super::final_overlap`]).
    fn overlaps_before(&self, j: usize) -> bool {
        if j == 0 {
            return false;
        }
        // the f64 screen of the exact test: centres farther apart than this on an axis
        // cannot overlap (see `lattice::clearly_apart`)
        const AXIS: f64 = 1.0 + 1e-6;
        const DIAGONAL: f64 = std::f64::consts::SQRT_2 + 1e-6;
        let (run, t) = self.locate(j);
        let (c, p) = (run.centres[t], run.poses[t]);
        let query = Rect::new(c.x - AXIS, c.y - AXIS, c.x + AXIS, c.y + AXIS);
        self.for_each_in(j - 1, &query, |_, ci, pi| {
            let (dx, dy) = (c.x - ci.x, c.y - ci.y);
            let apart = dx.abs() > AXIS
                || dy.abs() > AXIS
                || (dx + dy).abs() > DIAGONAL
                || (dx - dy).abs() > DIAGONAL;
            !apart && lattice_overlap(pi.centre, p.centre)
        })
    }

    /// Extends the cleared tails of the joints so far to a chain of `tiles` tiles (each at
    /// least doubled), recording the joints the memo says meet. A state that will be cloned
    /// for several extensions does this once, for the longest, so that the clones share it.
    pub fn clear_to(&mut self, tiles: usize) {
        let memo = Arc::clone(&self.memo);
        let mut memo = lock(&memo);
        self.clear_with(tiles, &mut memo);
    }

    /// [`PrefixCheck::clear_to`] with the memo locked.
    fn clear_with(&mut self, tiles: usize, memo: &mut Memo) {
        while let Some(&Reverse((n, k, seen))) = self.clear.peek() {
            if n >= tiles {
                break;
            }
            self.clear.pop();
            let cleared = n - k - 1;
            let need = tiles - 1 - k;
            let to = need.max(2 * cleared).max(8);
            // a tail of no tiles reached none; a cleared one reached tiles whose least first
            // hit is `seen`
            let known = (cleared > 0).then_some((cleared, seen));
            match self.first_hit(k, to, known, memo) {
                Some(m) if m <= to => self.meets.push((k + 1 + m, k)),
                m => {
                    let m = m.map_or(NEVER, |m| u32::try_from(m).unwrap_or(NEVER));
                    self.clear.push(Reverse((k + 1 + to, k, m)));
                }
            }
        }
    }

    /// The smallest tail index `m` (tile `k + m`) at which the memo says joint `k`'s tail
    /// meets a placed tile, among the placed tiles a tail of `tail_len` tiles can reach; the
    /// same lookups as the sequential check's `tail_meets_placed`. With `known = Some((len,
    /// m))`, `m` is that least index among the tiles a tail of `len` tiles reaches (the same
    /// query and distance test, with that length), and only the tiles beyond them are looked
    /// up: the tiles `0..=k` never change, so the answer is the same.
    fn first_hit(
        &self,
        k: usize,
        tail_len: usize,
        known: Option<(usize, u32)>,
        memo: &mut Memo,
    ) -> Option<usize> {
        let (run, t) = self.locate(k + 1);
        let fold = run.into[t];
        let (run, t) = self.locate(k);
        let at = run.poses[t];
        let ck = run.centres[t];
        let hinge = kinematics::exact_hinge(at, fold)?;
        let pivot = Point::from(hinge.to_f64(1.0));
        let hits = &mut memo.hits;
        let window = hits.window();
        let u = at.heading.unit_vector();
        let v = if fold == Fold::R {
            -u.turn_90()
        } else {
            u.turn_90()
        };
        let h = window.hinge;
        let corner = |x: f64, y: f64| ck + x * u + y * v;
        let query_of = |reach: f64| {
            let (x0, x1) = (h.x + window.min_x, h.x + reach);
            let (y0, y1) = (h.y + window.min_y, h.y + reach);
            Rect::from_points(corner(x0, y0), corner(x1, y1))
        };
        let reach = hits.reach(tail_len);
        let query = query_of(reach);
        // the tiles a shorter tail reached, exactly as that scan chose them
        let scanned = known.map(|(len, _)| {
            let r = hits.reach(len);
            (query_of(r), r)
        });
        let mut best: Option<usize> = known.map(|(_, m)| m as usize);
        self.for_each_in(k, &query, |_, ci, pi| {
            let d = (ci - pivot).hypot();
            if d > reach || scanned.is_some_and(|(q, r)| d <= r && closed_contains(&q, ci)) {
                return false;
            }
            // a tile this far from the hinge is met, if at all, no sooner than the best so far
            if best.is_some_and(|b| hits.least_hit(d) >= b) {
                return false;
            }
            let m = hits.get(canonical_offset(pi.centre, at, fold)) as usize;
            if best.is_none_or(|b| m < b) {
                best = Some(m);
            }
            false
        });
        best
    }

    /// Whether the chain so far folds cleanly: [`super::check_word`] of its word with the
    /// options it was made with ([`PrefixCheck::with_options`]) is `Ok`.
    pub fn folds_cleanly(&mut self) -> bool {
        if self.collided {
            return false;
        }
        let n = self.tiles;
        let memo = Arc::clone(&self.memo);
        let mut memo = lock(&memo);
        self.clear_with(n, &mut memo);
        let flagged: Vec<usize> = self
            .meets
            .iter()
            .filter(|&&(from, _)| from <= n)
            .map(|&(_, k)| k)
            .collect();
        if flagged.iter().any(|&k| self.sweep_meets(k, &memo.tile)) {
            self.collided = true;
        }
        !self.collided
    }

    /// Whether joint `k`'s tail, as long as the chain, meets a placed tile while it turns:
    /// the pair-by-pair sweep of the sequential check, in world coordinates.
    fn sweep_meets(&self, k: usize, tile: &UnitTile) -> bool {
        let (run, t) = self.locate(k + 1);
        let fold = run.into[t];
        let (run, t) = self.locate(k);
        let at = run.poses[t];
        let ck = run.centres[t];
        let Some(hinge) = kinematics::exact_hinge(at, fold) else {
            return false;
        };
        let pivot = Point::from(hinge.to_f64(1.0));
        let theta = fold.quarter_turns() as f64 * FRAC_PI_2;
        let tail_len = self.tiles - k - 1;
        let u = at.heading.unit_vector();
        let tail_centre = |t: usize| -> Point { ck + (t + 1) as f64 * u };
        let r = tile.radius;
        let query = swept_query(pivot, tail_centre(0), tail_centre(tail_len - 1), theta, r);
        self.for_each_in(k, &query, |i, ci, _| {
            let d = (ci - pivot).hypot2().sqrt();
            let Some((t0, t1)) = tile.tail_range(d, tail_len) else {
                return false;
            };
            let fixed = tile.at(ci);
            (t0..=t1).any(|t| {
                let j = k + 1 + t;
                if i == k && j == k + 1 {
                    return false; // hinged neighbours
                }
                let c = tail_centre(t);
                if !tile.may_meet(c, ci, pivot, theta) {
                    return false;
                }
                let moving = tile.at(c);
                let pair = TurningPair::new(&moving, c, &fixed, ci, r, pivot);
                pair.quarter_contact(theta > 0.0) && pair.first_contact(theta).is_some()
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FoldWord;

    fn whole(folds: &[Fold]) -> bool {
        super::super::check_word(
            &FoldWord::from_folds(folds.to_vec()),
            &CheckOptions::default(),
        )
        .is_ok()
    }

    /// Grows random words (serpentines with stray letters, and mostly straight words) in
    /// random pieces, cloning at every step as a beam does, and compares every prefix's
    /// verdict with the check of the whole prefix.
    #[test]
    fn every_prefix_agrees_with_the_whole_check() {
        let mut next = super::super::xorshift(0x9E37_79B9_7F4A_7C15);
        let (mut clean, mut collided) = (0, 0);
        let memo = PrefixCheck::new();
        for round in 0..160 {
            let w: Vec<Fold> = if round % 2 == 0 {
                (0..5 + next() % 80)
                    .map(|_| [Fold::L, Fold::R, Fold::S, Fold::S, Fold::S][(next() % 5) as usize])
                    .collect()
            } else {
                let row = 2 + (next() % 15) as usize;
                let mut w = Vec::new();
                for r in 0..(300 / row) {
                    w.extend(std::iter::repeat_n(Fold::S, row));
                    let f = if r % 2 == 0 { Fold::L } else { Fold::R };
                    w.extend([f, f]);
                }
                for _ in 0..(next() % 3) {
                    let at = (next() % w.len() as u64) as usize;
                    w[at] = [Fold::L, Fold::R, Fold::S][(next() % 3) as usize];
                }
                w
            };
            // one memo for every round, as a planner's thread keeps it
            let mut state = memo.emptied();
            state.push(&[]);
            let mut at = 0;
            while at < w.len() {
                let step = 1 + (next() % 40) as usize;
                let end = (at + step).min(w.len());
                // a sibling that is thrown away must not change the state it came from
                let mut sibling = state.clone();
                sibling.push(&w[at..end.min(at + 3)]);
                let _ = sibling.folds_cleanly();
                state.clear_to(end + 1);
                let mut grown = state.clone();
                grown.push(&w[at..end]);
                let got = grown.folds_cleanly();
                assert_eq!(got, whole(&w[..end]), "round {round}, prefix {end}");
                if got {
                    clean += 1;
                } else {
                    collided += 1;
                }
                state = grown;
                at = end;
            }
        }
        assert!(clean > 300 && collided > 300, "{clean} {collided}");
    }
}
