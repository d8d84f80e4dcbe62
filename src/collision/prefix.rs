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
use std::ops::RangeInclusive;
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
    /// The tiles by cell, for small queries.
    grid: RunGrid,
}

/// A run's tiles bucketed by square cell (compressed rows): a query a few cells wide (a new
/// tile's neighbours) looks at the tiles of those cells, where the boxes of a long run would
/// be walked group by group (a cost that grows with the run's length, so a leg of `n` tiles
/// checked tile by tile cost `n^2 / 64` box tests).
#[derive(Debug)]
struct RunGrid {
    x0: f64,
    y0: f64,
    /// One over the cell's side.
    inv: f64,
    nx: usize,
    ny: usize,
    /// `start[c]..start[c + 1]` indexes `ids` for cell `c` (row-major).
    start: Vec<u32>,
    /// Tile places in the run, ascending within a cell.
    ids: Vec<u32>,
}

/// Queries spanning at most this many cells use the grid, larger ones the boxes.
const GRID_CELLS: usize = 16;

impl RunGrid {
    /// The grid of `centres` in the box `bbox` that holds them: cells of side 2 (a new
    /// tile's neighbourhood spans at most two by two), or wider when the box is large for the
    /// run (a sparse run keeps about one cell per tile).
    fn new(centres: &[Point], bbox: &Rect) -> RunGrid {
        let n = centres.len();
        if n == 0 {
            return RunGrid {
                x0: 0.0,
                y0: 0.0,
                inv: 1.0,
                nx: 0,
                ny: 0,
                start: vec![0],
                ids: Vec::new(),
            };
        }
        let (w, h) = (bbox.x1 - bbox.x0, bbox.y1 - bbox.y0);
        let side = 2f64.max((w * h / n as f64).sqrt());
        let inv = 1.0 / side;
        // cells are at most (w / side + 1) (h / side + 1) <= n + 2 sqrt(n) + 1 when the side
        // is the wider one; a non-finite box (no tile can have one) leaves a single cell
        let span = |d: f64| {
            let c = (d * inv).floor();
            if c.is_finite() && c >= 0.0 {
                c as usize + 1
            } else {
                1
            }
        };
        let (nx, ny) = (span(w), span(h));
        let grid = RunGrid {
            x0: bbox.x0,
            y0: bbox.y0,
            inv,
            nx,
            ny,
            start: Vec::new(),
            ids: Vec::new(),
        };
        let cells: Vec<usize> = centres.iter().map(|&c| grid.cell(c)).collect();
        let mut start = vec![0u32; nx * ny + 1];
        for &c in &cells {
            start[c + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut fill = start.clone();
        let mut ids = vec![0u32; n];
        for (t, &c) in cells.iter().enumerate() {
            ids[fill[c] as usize] = t as u32;
            fill[c] += 1;
        }
        RunGrid { start, ids, ..grid }
    }

    /// The column (or row) of coordinate `v` from the grid's origin `o`, clamped to `0..n`.
    fn index(&self, v: f64, o: f64, n: usize) -> usize {
        // truncation is the floor of a non-negative value (and NaN takes the first)
        let c = (v - o) * self.inv;
        if c >= 0.0 {
            (c as usize).min(n - 1)
        } else {
            0
        }
    }

    /// The cell of a centre of the run.
    fn cell(&self, c: Point) -> usize {
        self.index(c.y, self.y0, self.ny) * self.nx + self.index(c.x, self.x0, self.nx)
    }

    /// The cell ranges `(columns, rows)` a query meets (it meets the grid's box), or `None`
    /// when they are more than [`GRID_CELLS`] cells.
    fn cells_of(
        &self,
        q: &Rect,
    ) -> Option<(
        std::ops::RangeInclusive<usize>,
        std::ops::RangeInclusive<usize>,
    )> {
        let (i0, i1) = (
            self.index(q.x0, self.x0, self.nx),
            self.index(q.x1, self.x0, self.nx),
        );
        let (j0, j1) = (
            self.index(q.y0, self.y0, self.ny),
            self.index(q.y1, self.y0, self.ny),
        );
        ((i1 - i0 + 1) * (j1 - j0 + 1) <= GRID_CELLS).then_some((i0..=i1, j0..=j1))
    }
}

fn closed_contains(r: &Rect, c: Point) -> bool {
    c.x >= r.x0 && c.x <= r.x1 && c.y >= r.y0 && c.y <= r.y1
}

/// The f64 screen of the exact overlap test: centres farther apart than this on an axis
/// cannot overlap (see `lattice::clearly_apart`).
const AXIS: f64 = 1.0 + 1e-6;
/// The screen along a diagonal.
const DIAGONAL: f64 = std::f64::consts::SQRT_2 + 1e-6;

/// Whether tile `t` of `run` overlaps a tile before it in the final shape (exactly, as
/// [`super::final_overlap`]), among the tiles of `near` (runs before `run` that may hold
/// one, the latest first; the run's own pairs are [`overlaps_within`]'s).
fn overlaps_before(near: &[&Run], run: &Run, t: usize) -> bool {
    let j = run.first + t;
    if j == 0 {
        return false;
    }
    let (c, p) = (run.centres[t], run.poses[t]);
    let query = Rect::new(c.x - AXIS, c.y - AXIS, c.x + AXIS, c.y + AXIS);
    let mut visit =
        |_, ci: Point, pi: ExactPose| !apart(c, ci) && lattice_overlap(pi.centre, p.centre);
    near.iter()
        .any(|r| r.for_each_in(j - 1, &query, &mut visit))
}

/// Whether the centres `a` and `b` are too far apart on an axis or a diagonal for their
/// tiles to overlap (the f64 screen of the exact test).
fn apart(a: Point, b: Point) -> bool {
    let (dx, dy) = (a.x - b.x, a.y - b.y);
    dx.abs() > AXIS || dy.abs() > AXIS || (dx + dy).abs() > DIAGONAL || (dx - dy).abs() > DIAGONAL
}

/// Whether two tiles of `run` overlap in the final shape (exactly, as
/// [`super::final_overlap`]): the same pairs [`overlaps_before`] asks of the run's own tiles,
/// each screened once, cell by cell of the run's grid. Centres that pass the screen are at
/// most [`AXIS`] apart on either axis, less than a cell's side (at least 2), so they lie in
/// the same cell or in neighbouring ones: each cell's pairs and those with the cells right,
/// above and diagonally above it cover them all.
fn overlaps_within(run: &Run) -> bool {
    let g = &run.grid;
    let tiles = |i: usize, j: usize| {
        &g.ids[g.start[j * g.nx + i] as usize..g.start[j * g.nx + i + 1] as usize]
    };
    let meet = |a: u32, b: u32| {
        let (a, b) = (a as usize, b as usize);
        !apart(run.centres[a], run.centres[b])
            && lattice_overlap(run.poses[a].centre, run.poses[b].centre)
    };
    for j in 0..g.ny {
        for i in 0..g.nx {
            let here = tiles(i, j);
            if here.is_empty() {
                continue;
            }
            for (n, &a) in here.iter().enumerate() {
                if here[n + 1..].iter().any(|&b| meet(a, b)) {
                    return true;
                }
            }
            // the neighbours not yet visited: right, and the row above from left to right
            let right = (i + 1 < g.nx).then(|| tiles(i + 1, j));
            let above = (j + 1 < g.ny).then(|| {
                (i.saturating_sub(1)..=(i + 1).min(g.nx - 1)).map(move |k| tiles(k, j + 1))
            });
            let others = right.into_iter().chain(above.into_iter().flatten());
            for other in others {
                if here.iter().any(|&a| other.iter().any(|&b| meet(a, b))) {
                    return true;
                }
            }
        }
    }
    false
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
        let grid = RunGrid::new(&centres, &bbox);
        Run {
            first,
            poses,
            centres,
            into,
            leaves,
            groups,
            bbox,
            grid,
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
        match self.grid.cells_of(query) {
            Some(cells) => self.for_each_in_cells(end, query, cells, visit),
            None => self.for_each_in_boxes(end, query, visit),
        }
    }

    /// [`Run::for_each_in`] over the tiles of the grid cells `(columns, rows)` that a small
    /// query meets (a centre in the closed query lies in one of them: the cell of a
    /// coordinate is monotone in it), for the run's tiles before place `end`.
    fn for_each_in_cells(
        &self,
        end: usize,
        query: &Rect,
        (cols, rows): (RangeInclusive<usize>, RangeInclusive<usize>),
        visit: &mut impl FnMut(usize, Point, ExactPose) -> bool,
    ) -> bool {
        let g = &self.grid;
        for j in rows {
            for i in cols.clone() {
                let c = j * g.nx + i;
                let ids = &g.ids[g.start[c] as usize..g.start[c + 1] as usize];
                for &t in ids.iter().take_while(|&&t| (t as usize) < end) {
                    let t = t as usize;
                    let c = self.centres[t];
                    if closed_contains(query, c) && visit(self.first + t, c, self.poses[t]) {
                        return true;
                    }
                }
            }
        }
        false
    }

    /// [`Run::for_each_in`] by the boxes of the run's groups and leaves, for the run's tiles
    /// before place `end`.
    fn for_each_in_boxes(
        &self,
        end: usize,
        query: &Rect,
        visit: &mut impl FnMut(usize, Point, ExactPose) -> bool,
    ) -> bool {
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
        let run = Arc::new(Run::new(first, poses, into));
        self.runs.push(Arc::clone(&run));
        self.tiles += run.poses.len();
        for (t, &f) in run.into.iter().enumerate() {
            let j = first + t;
            if j > 0 && f != Fold::S {
                // a tail of no tiles is clear
                self.clear.push(Reverse((j, j - 1, NEVER)));
            }
        }
        if !self.collided {
            // only the runs whose box comes near the new run's can hold a tile it overlaps
            let reach = run.bbox.inflate(AXIS, AXIS);
            // the run's own pairs by its grid, then each tile against the runs before it
            let near: Vec<&Run> = self.runs[..self.runs.len() - 1]
                .iter()
                .rev()
                .filter(|r| meets(&r.bbox, &reach))
                .map(|r| &**r)
                .collect();
            self.collided = overlaps_within(&run)
                || (!near.is_empty()
                    && (0..run.poses.len()).any(|t| overlaps_before(&near, &run, t)));
        }
    }

    /// Extends the cleared tails of the joints so far to a chain of `tiles` tiles (each at
    /// least doubled), recording the joints the memo says meet. A state that will be cloned
    /// for several extensions does this once, for the longest, so that the clones share it.
    pub fn clear_to(&mut self, tiles: usize) {
        let memo = Arc::clone(&self.memo);
        let mut memo = lock(&memo);
        self.clear_with(tiles, &mut memo, false);
    }

    /// [`PrefixCheck::clear_to`] with the memo locked. With `sweep`, each joint the memo
    /// says meets within `tiles` tiles is swept as soon as it is found, and the first that
    /// meets ends the clearing: the chain collides (and stays colliding), so the joints left
    /// need not be looked at; returns whether one met.
    fn clear_with(&mut self, tiles: usize, memo: &mut Memo, sweep: bool) -> bool {
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
                Some(m) if m <= to => {
                    self.meets.push((k + 1 + m, k));
                    if sweep && k + 1 + m <= tiles && self.sweep_meets(k, &memo.tile) {
                        return true;
                    }
                }
                m => {
                    let m = m.map_or(NEVER, |m| u32::try_from(m).unwrap_or(NEVER));
                    self.clear.push(Reverse((k + 1 + to, k, m)));
                }
            }
        }
        false
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
        // a tile this far from the hinge is met, if at all, no sooner than the best so far
        // (the distance is worked out once per best, not a bound per tile)
        let mut beyond = best.map_or(f64::INFINITY, |b| hits.no_sooner_than(b));
        self.for_each_in(k, &query, |_, ci, pi| {
            let d = (ci - pivot).hypot();
            if d >= beyond
                || d > reach
                || scanned.is_some_and(|(q, r)| d <= r && closed_contains(&q, ci))
            {
                return false;
            }
            let m = hits.get(canonical_offset(pi.centre, at, fold)) as usize;
            if best.is_none_or(|b| m < b) {
                best = Some(m);
                beyond = hits.no_sooner_than(m);
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
        // the joints flagged before are swept first, then the others as the clearing finds
        // them: the same sweeps in the same order as clearing first and sweeping every
        // flagged joint after, but a chain that collides is left at its first colliding joint
        let met = (0..self.meets.len()).any(|i| {
            let (from, k) = self.meets[i];
            from <= n && self.sweep_meets(k, &memo.tile)
        });
        if met || self.clear_with(n, &mut memo, true) {
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

    /// A long run's grid lists the same tiles as its boxes, for small queries all over it
    /// and every prefix end.
    #[test]
    fn the_grid_and_the_boxes_list_the_same_tiles() {
        let mut next = super::super::xorshift(0x2545_F491_4F6C_DD1D);
        // a serpentine of 40 rows of 30 tiles with stray folds, and a staircase (a sparse box)
        let mut serp = Vec::new();
        for r in 0..40 {
            serp.extend(std::iter::repeat_n(Fold::S, 30));
            let f = if r % 2 == 0 { Fold::L } else { Fold::R };
            serp.extend([f, f]);
        }
        for _ in 0..6 {
            let at = (next() % serp.len() as u64) as usize;
            serp[at] = [Fold::L, Fold::R][(next() % 2) as usize];
        }
        let stairs: Vec<Fold> = (0..600)
            .map(|i| if i % 2 == 0 { Fold::L } else { Fold::R })
            .collect();
        for word in [serp, stairs] {
            let mut chain = PrefixCheck::new();
            chain.push(&word);
            let run = &chain.runs[0];
            let b = run.bbox;
            let mut gridded = 0;
            for _ in 0..400 {
                let x = b.x0 - 2.0 + (b.x1 - b.x0 + 4.0) * (next() % 1000) as f64 / 1000.0;
                let y = b.y0 - 2.0 + (b.y1 - b.y0 + 4.0) * (next() % 1000) as f64 / 1000.0;
                let r = 0.5 + (next() % 40) as f64 / 10.0;
                let q = Rect::new(x - r, y - r, x + r, y + r);
                let end = 1 + (next() % run.centres.len() as u64) as usize;
                let list = |by_grid: bool| {
                    let mut seen = Vec::new();
                    let mut visit = |i: usize, _, _| {
                        seen.push(i);
                        false
                    };
                    match run.grid.cells_of(&q) {
                        Some(cells) if by_grid => {
                            run.for_each_in_cells(end, &q, cells, &mut visit);
                        }
                        _ => {
                            run.for_each_in_boxes(end, &q, &mut visit);
                        }
                    }
                    seen.sort_unstable();
                    seen
                };
                if run.grid.cells_of(&q).is_some() && meets(&b, &q) {
                    gridded += 1;
                    assert_eq!(list(true), list(false), "{q:?} end {end}");
                }
            }
            assert!(gridded > 50, "{gridded}");
        }
    }

    /// The final shape's overlaps found as runs are pushed (each run's own pairs cell by cell
    /// of its grid, each of its tiles against the runs before it) are those that the whole
    /// check finds in the final shape of the word, whether it comes in one run or in many.
    #[test]
    fn pushed_runs_overlap_as_the_whole_shape_does() {
        let mut next = super::super::xorshift(0xD1B5_4A32_D192_ED03);
        let (mut clean, mut overlapping, mut alone) = (0, 0, 0);
        for round in 0..600 {
            let letters = [Fold::L, Fold::R, Fold::S, Fold::S, Fold::S];
            let w: Vec<Fold> = if round % 3 == 2 {
                // a staircase with stray letters: a sparse box for the grid
                (0..20 + next() % 200)
                    .map(|i| match next() % 16 {
                        0 => letters[(next() % 5) as usize],
                        _ if i % 2 == 0 => Fold::L,
                        _ => Fold::R,
                    })
                    .collect()
            } else {
                (0..2 + next() % 150)
                    .map(|_| letters[(next() % 5) as usize])
                    .collect()
            };
            let mut state = PrefixCheck::new();
            state.push(&[]);
            let mut at = 0;
            while at < w.len() {
                // every third word in one run
                let step = if round % 3 == 0 {
                    w.len()
                } else {
                    1 + (next() % 60) as usize
                };
                let end = (at + step).min(w.len());
                state.push(&w[at..end]);
                at = end;
            }
            let poses: Vec<ExactPose> = state.runs.iter().flat_map(|r| r.poses.clone()).collect();
            assert_eq!(poses.len(), w.len() + 1);
            let expected = super::super::final_overlap(&poses).is_some();
            assert_eq!(state.collided, expected, "round {round}: {w:?}");
            if expected {
                overlapping += 1;
                alone += usize::from(round % 3 == 0);
            } else {
                clean += 1;
            }
        }
        assert!(
            clean > 100 && overlapping > 100 && alone > 50,
            "{clean} {overlapping} {alone}"
        );
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
