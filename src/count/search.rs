//! The depth-first search over fold words, with one integer budget per word.
//!
//! A node of the search is a valid word: tiles `0..=d` placed at their final poses. Under
//! sequential folding the tail behind a folding joint is straight whatever letters follow, so
//! each fold `j` of a word caps the length of every extension at `j + k`, `k` being the first
//! tail tile that would hit a tile already in place ([`FirstHits`]). A node keeps the smallest
//! cap, its budget: a straight letter keeps it (O(1)); a fold looks up the placed tiles near
//! its swept quarter annulus ([`TailWindow`]) and lowers it. A word is valid exactly when every
//! tail tile it has is below every cap, so an invalid prefix is cut and every valid word is
//! visited once; final-shape overlaps are the ends of sweeps and need no separate test. With
//! `final_only` the sweeps are skipped and each new tile is tested against the placed ones
//! exactly (the collision module's lattice test).
//!
//! Mirror images (L and R swapped) fold alike, so only words whose first turn is L are
//! searched and those with a turn are counted twice. The tree is cut at [`PREFIX_JOINTS`]
//! joints (deeper for many shards): the words there are shared out to shards (every `m`-th)
//! and to threads (one worker per thread, each with its own memo, taking the next prefix when
//! it is done).

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

use crate::collision::lattice_overlap;
use crate::exact::ExactPose;
use crate::Fold;

use super::first_hit::{FirstHits, TailWindow, NEVER};
use super::lattice::{canonical_offset, Steps};

/// The depth (joints) at which the search is shared out, at least.
const PREFIX_JOINTS: usize = 9;

/// Words at the cut per shard, at least (when the words are that many): the parts' sizes
/// differ by the sizes of their words' subtrees, and more words even them out.
const PARTS_PER_SHARD: usize = 16;

/// What one search looks for.
#[derive(Clone, Copy, Debug)]
pub(super) struct Scope {
    /// The longest chain, in tiles (at least 1).
    pub tiles: usize,
    /// Words with adjacent opposite folds are searched too.
    pub allow_opposite: bool,
    /// Only final shapes are tested.
    pub final_only: bool,
    /// The random-chain weights are summed too.
    pub weigh: bool,
    /// Touching tolerance, tile widths.
    pub tolerance: f64,
    /// Part `k` (1-based) of `m`.
    pub shard: (usize, usize),
}

/// Per-length tallies of one search.
#[derive(Clone, Debug)]
pub(super) struct Tally {
    /// Valid words per number of tiles, mirror images included (at most `3^39 < 2^64`).
    pub valid: Vec<u64>,
    /// Per number of tiles, the sum over valid words of `5^(straight joints)` (with `weigh`).
    pub weight: Vec<u128>,
}

impl Tally {
    fn new(tiles: usize) -> Tally {
        Tally {
            valid: vec![0; tiles + 1],
            weight: vec![0; tiles + 1],
        }
    }

    fn add(&mut self, o: &Tally) {
        for (a, b) in self.valid.iter_mut().zip(&o.valid) {
            *a += b;
        }
        for (a, b) in self.weight.iter_mut().zip(&o.weight) {
            *a += b;
        }
    }
}

/// A valid word, as the search sees it.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// Joints: tiles `0..=joints` are placed.
    joints: usize,
    /// The most tiles any extension may have (at most the scope's).
    budget: usize,
    /// The last letter (S for the one-tile word: nothing is opposite to it).
    last: Fold,
    /// Whether the word has a turn (then its mirror image is counted with it).
    turned: bool,
    /// Straight joints.
    straight: usize,
}

impl Node {
    fn root(tiles: usize) -> Node {
        Node {
            joints: 0,
            budget: tiles,
            last: Fold::S,
            turned: false,
            straight: 0,
        }
    }

    fn child(&self, f: Fold, budget: usize) -> Node {
        Node {
            joints: self.joints + 1,
            budget,
            last: f,
            turned: self.turned || f != Fold::S,
            straight: self.straight + usize::from(f == Fold::S),
        }
    }

    /// Whether another tile fits.
    fn has_room(&self) -> bool {
        self.joints + 2 <= self.budget
    }
}

/// A word where the tree is cut, searched further by a worker.
#[derive(Clone, Debug)]
struct Prefix {
    letters: Vec<Fold>,
    node: Node,
}

/// The first hits of the folding tile and of the one or two tiles before it: their offsets
/// depend only on the last letters, so they are looked up once, by letters.
#[derive(Clone, Copy, Debug)]
struct RecentHits {
    /// Per fold (index by `Fold as usize`): the folding tile alone (the one-tile word).
    zero: [u8; 3],
    /// Per last letter and fold: the folding tile and the one before.
    one: [[u8; 3]; 3],
    /// Per last two letters and fold: the folding tile and the two before.
    two: [[[u8; 3]; 3]; 3],
}

impl RecentHits {
    fn new(hits: &mut FirstHits, steps: &Steps) -> RecentHits {
        // the smallest first hit over the tiles of `letters` seen from its last tile
        let mut least = |letters: &[Fold], f: Fold| -> u8 {
            let mut poses = vec![ExactPose::default()];
            for &l in letters {
                let last = poses[poses.len() - 1];
                poses.push(steps.next(last, l));
            }
            let at = poses[poses.len() - 1];
            let offsets = poses.iter().map(|p| canonical_offset(p.centre, at, f));
            offsets.map(|o| hits.get(o)).min().unwrap_or(NEVER)
        };
        let mut t = RecentHits {
            zero: [NEVER; 3],
            one: [[NEVER; 3]; 3],
            two: [[[NEVER; 3]; 3]; 3],
        };
        for f in [Fold::L, Fold::R] {
            t.zero[f as usize] = least(&[], f);
            for a in Fold::ALL {
                t.one[a as usize][f as usize] = least(&[a], f);
                for b in Fold::ALL {
                    t.two[a as usize][b as usize][f as usize] = least(&[a, b], f);
                }
            }
        }
        t
    }
}

/// One depth-first walker: the placed tiles of the current word, a memo and tallies.
struct Walker {
    scope: Scope,
    hits: FirstHits,
    window: TailWindow,
    steps: Steps,
    /// The first tail tile that meets the folding tile or one of the two before it.
    recent: RecentHits,
    poses: Vec<ExactPose>,
    /// Tile centres in `f32` (tile widths) for screening (see [`TailWindow`]), summed step by
    /// step; indexed modulo [`SLOTS`] (tile indices stay below it), which spares the bounds
    /// checks in the inner loop.
    xs: Box<[f32; SLOTS]>,
    ys: Box<[f32; SLOTS]>,
    letters: Vec<Fold>,
    tally: Tally,
    pow5: Vec<u128>,
}

/// Room for the centres of the longest chain, a power of two.
const SLOTS: usize = 64;
const _: () = assert!(super::MAX_COUNT_TILES < SLOTS);

/// Centres screened together.
const LANES: usize = 16;

/// The unit vector of a quarter-turn heading.
const UNIT: [(f32, f32); 4] = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];

impl Walker {
    fn new(scope: &Scope, mut hits: FirstHits) -> Walker {
        let n = scope.tiles;
        let mut pow5 = vec![1u128; n];
        for i in 1..n {
            pow5[i] = pow5[i - 1] * 5;
        }
        let steps = Steps::new();
        Walker {
            scope: *scope,
            window: *hits.window(),
            recent: RecentHits::new(&mut hits, &steps),
            hits,
            steps,
            poses: vec![ExactPose::default(); n],
            xs: Box::new([0.0; SLOTS]),
            ys: Box::new([0.0; SLOTS]),
            letters: vec![Fold::S; n],
            tally: Tally::new(n),
            pow5,
        }
    }

    /// Puts tile `j` after joint `j - 1` folded `f`.
    fn place(&mut self, j: usize, f: Fold) {
        let before = self.poses[j - 1];
        let (dx, dy) = self.steps.delta(before, f);
        self.poses[j] = self.steps.next(before, f);
        self.xs[j % SLOTS] = self.xs[(j - 1) % SLOTS] + dx;
        self.ys[j % SLOTS] = self.ys[(j - 1) % SLOTS] + dy;
        self.letters[j - 1] = f;
    }

    fn record(&mut self, node: &Node) {
        let tiles = node.joints + 1;
        let mult = if node.turned { 2 } else { 1 };
        self.tally.valid[tiles] += mult;
        if self.scope.weigh {
            self.tally.weight[tiles] += u128::from(mult) * self.pow5[node.straight];
        }
    }

    /// Searches below `node` (valid, recorded, with room for another tile), recording every
    /// valid word; words of `split` joints are collected in `prefixes` instead of searched.
    fn dfs(&mut self, node: Node, split: usize, prefixes: &mut Vec<Prefix>) {
        if node.joints == split {
            prefixes.push(Prefix {
                letters: self.letters[..split].to_vec(),
                node,
            });
            return;
        }
        for f in Fold::ALL {
            let mirror = f == Fold::R && !node.turned;
            let opposite = !self.scope.allow_opposite && node.last.is_opposite(f);
            if mirror || opposite {
                continue;
            }
            let Some(budget) = self.child_budget(&node, f) else {
                continue;
            };
            let child = node.child(f, budget);
            self.record(&child);
            if child.has_room() {
                self.place(child.joints, f);
                self.dfs(child, split, prefixes);
            }
        }
    }

    /// The budget after appending `f` to `node`, or `None` if the new tile collides.
    #[inline]
    fn child_budget(&mut self, node: &Node, f: Fold) -> Option<usize> {
        let d = node.joints;
        if self.scope.final_only {
            let c = self.steps.next(self.poses[d], f).centre;
            let (x, y) = c.to_f64(1.0);
            // overlapping lattice tiles are less than w / cos(pi/8) < 1.1 w apart
            let near = |i: &usize| {
                let (xi, yi) = (self.xs[*i % SLOTS], self.ys[*i % SLOTS]);
                (f64::from(xi) - x).powi(2) + (f64::from(yi) - y).powi(2) < 1.2
            };
            let hit = (0..d)
                .filter(near)
                .any(|i| lattice_overlap(self.poses[i].centre, c));
            return (!hit).then_some(node.budget);
        }
        match f {
            Fold::S => Some(node.budget),
            _ => self.fold_budget(d, node.budget, f),
        }
    }

    /// The budget after folding joint `d` with `f` (budget `cap` before it), or `None` if
    /// tile `d + 1` itself is hit.
    #[inline]
    fn fold_budget(&mut self, d: usize, cap: usize, f: Fold) -> Option<usize> {
        let at = self.poses[d];
        let (ux, uy) = UNIT[usize::from(at.heading.get())];
        let side: f32 = if f == Fold::L { 1.0 } else { -1.0 };
        let w = &self.window;
        // the hinge in the world
        let (xd, yd) = (self.xs[d % SLOTS], self.ys[d % SLOTS]);
        let hx = xd + ux * w.hinge.0 - side * uy * w.hinge.1;
        let hy = yd + uy * w.hinge.0 + side * ux * w.hinge.1;
        // the folding tile and the two before it, whose offsets the last letters fix
        let recent = match d {
            0 => self.recent.zero[f as usize],
            1 => self.recent.one[self.letters[0] as usize][f as usize],
            _ => {
                let (a, b) = (self.letters[d - 2], self.letters[d - 1]);
                self.recent.two[a as usize][b as usize][f as usize]
            }
        };
        let mut cap = cap.min(d + usize::from(recent));
        if cap < d + 2 {
            return None;
        }
        // the other placed tiles within reach of the hinge, as a bit set (no branches: one
        // pass over the centres)
        let reach2 = w.reach2(cap - d - 1);
        let end = d.saturating_sub(2);
        let mut mask = 0u64;
        for base in (0..end).step_by(LANES) {
            // a fixed number of lanes, so that the compiler vectorises; the slots past `end`
            // hold stale centres and are masked off below
            let mut bits = 0u64;
            for lane in 0..LANES {
                let i = (base + lane) % SLOTS;
                let (rx, ry) = (self.xs[i] - hx, self.ys[i] - hy);
                bits |= u64::from(rx * rx + ry * ry <= reach2) << lane;
            }
            mask |= bits << base;
        }
        mask &= (1u64 << end) - 1;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            // the placed centre in the canonical frame, relative to the hinge
            let (rx, ry) = (self.xs[i % SLOTS] - hx, self.ys[i % SLOTS] - hy);
            let a = ux * rx + uy * ry;
            let c = side * (ux * ry - uy * rx);
            if a < w.min_x || c < w.min_y {
                continue;
            }
            let k = usize::from(self.hits.get(canonical_offset(self.poses[i].centre, at, f)));
            if d + k < cap {
                if k == 1 {
                    return None;
                }
                cap = d + k;
            }
        }
        Some(cap)
    }

    /// Places the tiles of a prefix.
    fn replay(&mut self, p: &Prefix) {
        for (j, &f) in p.letters.iter().enumerate() {
            self.place(j + 1, f);
        }
    }
}

/// Runs the search of `scope`. `progress(done, total)` is called as prefixes finish.
pub(super) fn search(scope: &Scope, progress: &(dyn Fn(u64, u64) + Sync)) -> Tally {
    let n = scope.tiles;
    let (k, m) = scope.shard;
    let root = Node::root(n);
    // cut at PREFIX_JOINTS, or deeper until every part has some PARTS_PER_SHARD words to
    // share out (the cut depends on the number of parts only, so all parts agree on it)
    let mut hits = FirstHits::new(scope.tolerance);
    let mut cut = PREFIX_JOINTS;
    let (top, prefixes) = loop {
        let mut top = Walker::new(scope, hits);
        top.record(&root);
        let mut prefixes = Vec::new();
        if root.has_room() {
            top.dfs(root, cut, &mut prefixes);
        }
        if prefixes.len() >= PARTS_PER_SHARD * m || cut + 1 >= n {
            break (top, prefixes);
        }
        hits = top.hits;
        cut += 1;
    };
    // lengths up to the cut are counted by the first shard alone
    let mut tally = if k == 1 {
        top.tally.clone()
    } else {
        Tally::new(n)
    };
    let mine: Vec<&Prefix> = prefixes.iter().skip(k - 1).step_by(m).collect();
    let total = mine.len() as u64;
    let next = AtomicUsize::new(0);
    let done = AtomicU64::new(0);
    let top = &top;
    let parts = rayon::broadcast(|_| {
        let mut w = Walker::new(scope, top.hits.clone());
        while let Some(p) = mine.get(next.fetch_add(1, Ordering::Relaxed)) {
            w.replay(p);
            w.dfs(p.node, usize::MAX, &mut Vec::new());
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
        }
        w.tally
    });
    for t in &parts {
        tally.add(t);
    }
    tally
}
