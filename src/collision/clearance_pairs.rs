//! Which pairs of tiles can come within a cutoff of each other over a timed fold schedule,
//! found without visiting every pair: the candidates the clearance measurement
//! ([`super::clearance`]) follows exactly.
//!
//! The schedule's time is cut into windows over which no joint turns much more than
//! [`WINDOW_TURN`], each joint's rate bounded by the fastest chord of its own track that the
//! window overlaps (`walk_windows`): the windows follow the fastest joint's clock, not the
//! union of every track's breakpoints, which for a long serpentine's U-turns folding at once
//! was some 140 segments a U-turn, each looking along the whole chain. A tree of bounding discs over runs of consecutive
//! tiles ([`ChainTree`], updated in O(log n) per joint that changes) holds the chain at the
//! segment's start. Only pairs of runs with a joint between them (or inside them) that turns
//! in the segment, or whose angle changed at its start, are looked at: every other pair keeps
//! its shape and was looked at when it last changed (the whole chain is looked at once, at
//! the schedule's start). Over a segment of length `dt` a point of tile `q` moves, seen from
//! tile `p`, at most `dt sum_k |rate_k| 2 R (q - k)` over the joints `p <= k < q` that turn
//! (`R` the circumradius: a point of tile `q` lies within `2 R (q - k)` of joint `k`'s
//! hinge, [`super::clearance`]), and at most `dt sum_k |rate_k| |x - H_k|` with `|x - H_k|`
//! the distance from the hinge, bounded from the runs' discs and the turning tiles' centres
//! plus what the step can add to it (`Search::reach`): far tighter for rows far along the
//! chain that fold back near each other. Two runs whose discs are further apart than the
//! cutoff plus both runs' motion are dropped together, the others are split down to pairs
//! of tiles. The cost is the number of runs near the turning joints, times the segments: about
//! linear in the chain, times the joints turning at once.

use std::sync::atomic::{AtomicUsize, Ordering};

use kurbo::Point;
use rustc_hash::FxHashSet;

use super::chain_tree::{ChainTree, Rigid};
use super::JointTrack;
use crate::Octagon;

/// Slack on the pruning test, tile widths: far above the rounding of world coordinates
/// (1e-10 w at a million tiles), so a pair dropped is one that cannot come within the cutoff.
const SLACK: f64 = 1e-7;

/// The most a joint turns over one window of the search, radians, from the fastest chord
/// of its track in the window (at most twice this): small, since a tile far along a row
/// moves by its distance from the turning hinge times this, and what it can reach over a
/// window is taken as found (on a 3,486-tile serpentine 1/32 found 12 times the pairs of
/// 0.004 and cost five times the CPU in all; 0.001 found half the pairs with four times the
/// windows and cost 1.5 times the CPU).
const WINDOW_TURN: f64 = 1.0 / 256.0;

/// The joints looked at are counted below every multiple of `1 << RANK_SHIFT` tiles once a
/// look ([`Search::rank`]): 64.
const RANK_SHIFT: u32 = 6;

/// A look's visits between two offers of its remaining pairs of runs to a second core: 1,024
/// (some tens of microseconds, far above what [`rayon::join`] costs).
const SPLIT_VISITS: usize = 1024;

/// The pairs `(i, j)`, `j >= i + 2`, ascending, that may come within `cutoff` tile widths
/// of each other (signed distance, negative for an overlap) at some moment from `t0` to the
/// last breakpoint, the joints of `track_of` following their tracks: a superset of those
/// that do. `None` when the search took more than `budget` steps.
pub(super) fn pairs_within(
    tiles: usize,
    track_of: &[Option<&JointTrack>],
    t0: f64,
    cutoff: f64,
    budget: usize,
) -> Option<Vec<(u32, u32)>> {
    // pairs are kept as two u32 (MAX_TILES is ten million)
    if u32::try_from(tiles).is_err() {
        return None;
    }
    let joints = tiles.saturating_sub(1);
    let tracks: Vec<&JointTrack> = track_of.iter().flatten().copied().collect();
    let angles: Vec<f64> = (0..joints)
        .map(|k| track_of[k].map_or(0.0, |t| t.angle_at(t0)))
        .collect();
    let mut search = Search::new(angles, cutoff, budget);
    // the whole chain at the start
    let all: Vec<(usize, f64)> = (0..joints).map(|k| (k, 0.0)).collect();
    search.look(&all, 0.0)?;
    walk_windows(&mut search, &tracks)?;
    // the last angles (a jump at the schedule's end)
    let mut changed: Vec<(usize, f64)> = Vec::new();
    for tr in &tracks {
        let a = tr.angles[tr.angles.len() - 1];
        if search.tree.angle(tr.joint) != a {
            changed.push((tr.joint, a));
        }
    }
    if !changed.is_empty() {
        search.tree.set_angles(changed.iter().copied());
        changed.sort_by_key(|c| c.0);
        let still: Vec<(usize, f64)> = changed.iter().map(|&(k, _)| (k, 0.0)).collect();
        search.look(&still, 0.0)?;
    }
    let mut pairs: Vec<u64> = search.found.into_iter().collect();
    pairs.sort_unstable();
    Some(
        pairs
            .into_iter()
            .map(|p| ((p >> 32) as u32, p as u32))
            .collect(),
    )
}

/// Follows the tracks from their first breakpoint to their last in windows, each one look
/// of the search: a window is cut so that no joint turns much more than [`WINDOW_TURN`] over
/// it (from the fastest chord of each joint's own track that it overlaps, so the bound on
/// every joint's rate holds over the whole window), and ends at every track's start and at
/// every jump of a track (a chord of no length). The windows follow the fastest joint's own
/// clock, not the union of every track's breakpoints: a long serpentine's U-turns, all
/// folding at once, each with some 140 breakpoints, no longer cut the time into that many
/// segments each looking along the whole chain.
fn walk_windows(search: &mut Search, tracks: &[&JointTrack]) -> Option<()> {
    // the times a window must end at: every track's start and every jump
    let mut hard: Vec<f64> = Vec::new();
    for tr in tracks {
        if let Some(&t) = tr.times.first() {
            hard.push(t);
        }
        for (i, w) in tr.times.windows(2).enumerate() {
            if w[1] <= w[0] && tr.angles[i + 1] != tr.angles[i] {
                hard.push(w[1]);
            }
        }
    }
    hard.sort_by(f64::total_cmp);
    hard.dedup();
    let end = tracks
        .iter()
        .filter_map(|t| t.times.last().copied())
        .fold(f64::NEG_INFINITY, f64::max);
    let Some(&start) = hard.first() else {
        return Some(());
    };
    let mut order: Vec<&JointTrack> = tracks.to_vec();
    order.sort_by(|a, b| a.times[0].total_cmp(&b.times[0]));
    let (mut next, mut next_hard) = (0, 0);
    let mut running: Vec<(&JointTrack, usize)> = Vec::new();
    let mut changed: Vec<(usize, f64)> = Vec::new();
    let mut moving: Vec<(usize, f64)> = Vec::new();
    let mut ta = start;
    while ta < end {
        while next < order.len() && order[next].times[0] <= ta {
            running.push((order[next], 0));
            next += 1;
        }
        while next_hard < hard.len() && hard[next_hard] <= ta {
            next_hard += 1;
        }
        let cap = hard.get(next_hard).map_or(end, |&t| t.min(end));
        changed.clear();
        let tree = &search.tree;
        let mut fastest: f64 = 0.0;
        let mut rest = cap;
        running.retain_mut(|(tr, hint)| {
            let (a0, rate) = tr.chord_at(ta, hint);
            if tree.angle(tr.joint) != a0 {
                changed.push((tr.joint, a0));
            }
            fastest = fastest.max(rate.abs());
            if let Some(&t) = tr.times.get(*hint) {
                rest = rest.min(t);
            }
            tr.times[tr.times.len() - 1] > ta
        });
        search.tree.set_angles(changed.iter().copied());
        // the window: WINDOW_TURN at the fastest rate now, halved while a joint's fastest
        // chord over it turns it more than twice that; at rest, to the next breakpoint
        let mut tb = if fastest > 0.0 {
            (ta + WINDOW_TURN / fastest).min(cap)
        } else {
            rest.max(ta).min(cap)
        };
        if tb <= ta {
            tb = cap;
        }
        for _ in 0..24 {
            window_rates(&running, ta, tb, &mut moving);
            let turn = moving.iter().map(|m| m.1).fold(0.0, f64::max) * (tb - ta);
            let half = ta + (tb - ta) / 2.0;
            if turn <= 2.0 * WINDOW_TURN || half <= ta || half >= tb {
                break;
            }
            tb = half;
        }
        for &(k, _) in &changed {
            if !moving.iter().any(|m| m.0 == k) {
                moving.push((k, 0.0));
            }
        }
        if !moving.is_empty() {
            moving.sort_by_key(|m| m.0);
            search.look(&moving, tb - ta)?;
        }
        ta = tb;
    }
    Some(())
}

/// The joints of `running` with the fastest `|rate|` of the chords of their tracks that
/// overlap `ta..tb` (those with a non-zero one), into `out`.
fn window_rates(running: &[(&JointTrack, usize)], ta: f64, tb: f64, out: &mut Vec<(usize, f64)>) {
    out.clear();
    for (tr, hint) in running {
        let (ts, a) = (&tr.times, &tr.angles);
        // `hint` counts the times at or before `ta`: chord `i` runs from ts[i - 1] to ts[i]
        let mut i = (*hint).max(1);
        let mut fastest: f64 = 0.0;
        while i < ts.len() && ts[i - 1] < tb {
            if ts[i] > ts[i - 1] && ts[i] > ta {
                fastest = fastest.max(((a[i] - a[i - 1]) / (ts[i] - ts[i - 1])).abs());
            }
            i += 1;
        }
        if fastest > 0.0 {
            out.push((tr.joint, fastest));
        }
    }
}

/// The pairs one look of the search finds on a chain at `angles` whose joints `joints`
/// (ascending, with their `|rate|`) turn for `dt`: the tests' view of one step.
#[cfg(test)]
pub(super) fn one_look(
    angles: Vec<f64>,
    joints: &[(usize, f64)],
    dt: f64,
    cutoff: f64,
) -> Vec<(u32, u32)> {
    let mut search = Search::new(angles, cutoff, usize::MAX);
    let _ = search.look(joints, dt);
    let mut pairs: Vec<u64> = search.found.into_iter().collect();
    pairs.sort_unstable();
    pairs
        .into_iter()
        .map(|p| ((p >> 32) as u32, p as u32))
        .collect()
}

/// The search's state: the chain at a segment's start and the pairs found.
struct Search {
    tree: ChainTree,
    radius: f64,
    cutoff: f64,
    budget: usize,
    work: usize,
    /// The pairs found, `i << 32 | j` (eight bytes a pair: a long serpentine's search finds
    /// millions).
    found: FxHashSet<u64>,
    /// The joints looked at in the segment (ascending), with prefix sums of their `|rate|`
    /// and of `|rate| k`.
    active: Vec<usize>,
    spin: Vec<f64>,
    moment: Vec<f64>,
    /// The world centre of the first tile of each joint looked at (its hinge lies within a
    /// circumradius of it).
    centres: Vec<Point>,
    /// How many joints looked at lie below tile `b << RANK_SHIFT`, for every `b`, the last
    /// entry all of them: a count below any tile is then a search among the few joints of
    /// one block, not among all (a look asks it eight times for every pair of runs it
    /// visits; the binary searches over all the joints were half of a 100,000-tile
    /// serpentine's search).
    ranks: Vec<u32>,
}

/// A run of tiles placed in the world: its node and its first tile's pose.
#[derive(Clone, Copy)]
struct Run {
    node: usize,
    pose: Rigid,
}

impl Search {
    /// A search over the chain at joint `angles` for pairs within `cutoff`, giving up past
    /// `budget` units of work.
    fn new(angles: Vec<f64>, cutoff: f64, budget: usize) -> Search {
        let blocks = ((angles.len() + 1) >> RANK_SHIFT) + 2;
        Search {
            ranks: vec![0; blocks],
            tree: ChainTree::new(angles, 0.0),
            radius: Octagon::new(1.0).circumradius(),
            cutoff,
            budget,
            work: 0,
            found: FxHashSet::default(),
            active: Vec::new(),
            spin: Vec::new(),
            moment: Vec::new(),
            centres: Vec::new(),
        }
    }

    /// Finds the pairs of tiles with one of `joints` (ascending, each with its `|rate|`)
    /// between them that may come within the cutoff over `dt` seconds from the tree's
    /// angles; `None` past the budget.
    fn look(&mut self, joints: &[(usize, f64)], dt: f64) -> Option<()> {
        self.active.clear();
        self.spin.clear();
        self.moment.clear();
        self.spin.push(0.0);
        self.moment.push(0.0);
        for &(k, r) in joints {
            self.active.push(k);
            let l = self.spin.len() - 1;
            self.spin.push(self.spin[l] + r);
            self.moment.push(self.moment[l] + r * k as f64);
        }
        let mut below = 0;
        let last = self.ranks.len() - 1;
        for (b, rank) in self.ranks[..last].iter_mut().enumerate() {
            let start = b << RANK_SHIFT;
            while below < self.active.len() && self.active[below] < start {
                below += 1;
            }
            *rank = below as u32;
        }
        self.ranks[last] = self.active.len() as u32;
        self.centres.clear();
        for &(k, _) in joints {
            let c = self.tree.tile_pose(k).apply(Point::ORIGIN);
            self.centres.push(c);
        }
        let root = Run {
            node: 1,
            pose: Rigid::IDENTITY,
        };
        let total = AtomicUsize::new(self.work);
        let mut found = std::mem::take(&mut self.found);
        let done = self.descend(vec![(root, root, true)], dt, &total, &mut found);
        self.found = found;
        self.work = total.into_inner();
        (done.is_some() && self.work <= self.budget).then_some(())
    }

    /// Adds to `found` the pairs of tiles found below the pairs of runs `stack` (`(p, q,
    /// whether p == q)`), each pair of runs visited counted into `total`; `None` once
    /// `total` passes the budget. Every [`SPLIT_VISITS`] visits the runs still to visit are
    /// dealt out to two halves visited by [`rayon::join`] (on a second core where there is
    /// one): which pairs of runs are visited, and so what is found and counted, does not
    /// depend on the order.
    fn descend(
        &self,
        mut stack: Vec<(Run, Run, bool)>,
        dt: f64,
        total: &AtomicUsize,
        found: &mut FxHashSet<u64>,
    ) -> Option<()> {
        let mut visits = 0;
        while let Some(entry) = stack.pop() {
            visits += 1;
            if visits == SPLIT_VISITS {
                let before = total.fetch_add(visits, Ordering::Relaxed);
                if before + visits > self.budget {
                    return None;
                }
                visits = 0;
                if stack.len() >= 2 && rayon::current_num_threads() > 1 {
                    self.visit(entry, dt, &mut stack, found);
                    // alternate entries: both halves take some of the runs near the root
                    let (mut a, mut b) = (Vec::new(), Vec::new());
                    for (x, e) in stack.drain(..).enumerate() {
                        if x % 2 == 0 {
                            a.push(e)
                        } else {
                            b.push(e)
                        }
                    }
                    let mut other = FxHashSet::default();
                    let (da, db) = rayon::join(
                        || self.descend(a, dt, total, found),
                        || self.descend(b, dt, total, &mut other),
                    );
                    found.extend(other);
                    return da.and(db);
                }
            }
            self.visit(entry, dt, &mut stack, found);
        }
        let before = total.fetch_add(visits, Ordering::Relaxed);
        (before + visits <= self.budget).then_some(())
    }

    /// Visits the pair of runs `(p, q, whether p == q)`: drops it, records it (two tiles
    /// not neighbours) into `found`, or pushes its halves onto `stack`.
    #[inline(always)]
    fn visit(
        &self,
        (p, q, same): (Run, Run, bool),
        dt: f64,
        stack: &mut Vec<(Run, Run, bool)>,
        found: &mut FxHashSet<u64>,
    ) {
        let (pf, pl) = (self.tree.first(p.node), self.tree.last(p.node));
        let (qf, ql) = (self.tree.first(q.node), self.tree.last(q.node));
        if same {
            if self.tree.tile(p.node).is_some() || !self.any(pf, pl) {
                return;
            }
            // an inner node's children: its left one and, unless past the chain's end, its
            // right one (no allocation: a look splits some hundreds of runs)
            let mut kids = self
                .tree
                .children(p.node, &p.pose)
                .map(|(node, pose)| Run { node, pose });
            if let Some(a) = kids.next() {
                stack.push((a, a, true));
                if let Some(b) = kids.next() {
                    stack.push((a, b, false));
                    stack.push((b, b, true));
                }
            }
            return;
        }
        // the joints looked at from p's first tile to q's last: active[a..d]
        let (a, d) = (self.rank(pf), self.rank(ql));
        if d <= a {
            return;
        }
        let (cp, rp) = self.disc(&p);
        let (cq, rq) = self.disc(&q);
        // the pair is dropped when it stays apart by more than the cutoff, never when the
        // discs come within it already (both bounds on the motion are at least 0): those
        // are told first without a square root (a split is always safe, so a pair on the
        // rounding's edge may be split where it could have been dropped)
        let near = rp + rq + SLACK + self.cutoff;
        let d2 = (cp - cq).hypot2();
        if !(near >= 0.0 && d2 <= near * near) {
            let dist = d2.sqrt();
            let round = SLACK + 1e-12 * (cp.to_vec2().hypot() + cq.to_vec2().hypot());
            let room = dist - rp - rq - round - self.cutoff;
            if room > 0.0 {
                let (b, c) = (self.rank(pl), self.rank(qf));
                // how far q moves seen from p's first tile, and p's tiles seen from it: along
                // the chain first, then from where the turning joints' hinges lie
                let (ep, eq) = (
                    2.0 * self.radius * dt * self.lever(a, b, pl),
                    2.0 * self.radius * dt * self.lever(a, d, ql),
                );
                if room > ep + eq {
                    return;
                }
                if self.reach([a, b, c, d], (rp, rq), (cq, dist), (ep, eq), dt) < room {
                    return;
                }
            }
        }
        match (self.tree.tile(p.node), self.tree.tile(q.node)) {
            (Some(i), Some(j)) => {
                if j >= i + 2 {
                    found.insert(((i as u64) << 32) | j as u64);
                }
            }
            (pt, qt) => {
                // where the joints looked at between p's first tile and q's last lie: all
                // inside q, the tiles of q before the first are rigid with p (a pair of them
                // is looked at when it changes), so q is split and its part before that
                // joint dropped; all inside p, likewise p and its part after the last. Else
                // the larger run is split.
                let split_p = if qt.is_none() && self.active[a] >= qf {
                    false
                } else if pt.is_none() && self.active[d - 1] < pl {
                    true
                } else {
                    qt.is_some() || (pt.is_none() && rp >= rq)
                };
                if split_p {
                    for (node, pose) in self.tree.children(p.node, &p.pose) {
                        stack.push((Run { node, pose }, q, false));
                    }
                } else {
                    for (node, pose) in self.tree.children(q.node, &q.pose) {
                        stack.push((p, Run { node, pose }, false));
                    }
                }
            }
        }
    }

    /// How far the tiles of run `q` can move towards those of run `p` over `dt` seconds
    /// (`p` before `q` along the chain: tiles `pf..=pl` and `qf..=ql`), from where the
    /// turning joints' hinges lie rather than from how far along the chain: joint `k` turning
    /// at `w_k` moves a point `x` at most `w_k |x - H_k|` seen from `p`'s first tile. At the
    /// step's start `|x - H_k|` is at most `2 r_q` for a joint inside `q` (both in its disc),
    /// `dist + r_p + r_q` for one inside `p`, and `|c_q - c_k| + r_q + R` for one between
    /// them (`c_k` the centre of tile `k`, whose vertex the hinge is); over the step it grows
    /// by at most twice the motion along the chain (`eq`: every point of the tiles up to the
    /// last of `q` moves at most that much seen from `p`'s first tile), and likewise for the
    /// joints inside `p` moving its own tiles. Each part is never taken above its bound along
    /// the chain (`ep`, `eq`); the joints between are summed only until that bound is
    /// reached. `[a, b, c, d]` are the ranks ([`Search::rank`]) of `pf`, `pl`, `qf`, `ql`.
    fn reach(
        &self,
        [a, b, c, d]: [usize; 4],
        (rp, rq): (f64, f64),
        (cq, dist): (Point, f64),
        (ep, eq): (f64, f64),
        dt: f64,
    ) -> f64 {
        // the joints inside p, between, inside q: active[a..b], [b..c], [c..d]
        let spin = |u: usize, v: usize| self.spin[v] - self.spin[u];
        let inside_p = spin(a, b) * (dist + rp + rq + 2.0 * eq);
        let inside_q = spin(c, d) * (2.0 * rq + 2.0 * eq);
        let mut between = 0.0;
        let cap = eq / dt.max(f64::MIN_POSITIVE);
        for x in b..c {
            let w = self.spin[x + 1] - self.spin[x];
            between += w * ((cq - self.centres[x]).hypot() + rq + self.radius + 2.0 * eq);
            if between + inside_p + inside_q >= cap {
                break;
            }
        }
        let q = (dt * (inside_p + between + inside_q)).min(eq);
        let p = (dt * spin(a, b) * (2.0 * rp + 2.0 * ep)).min(ep);
        q + p
    }

    /// How many joints looked at lie below tile `x`.
    fn rank(&self, x: usize) -> usize {
        let b = (x >> RANK_SHIFT).min(self.ranks.len() - 2);
        let (lo, hi) = (self.ranks[b] as usize, self.ranks[b + 1] as usize);
        lo + self.active[lo..hi].partition_point(|&k| k < x)
    }

    /// Whether a joint looked at lies in `lo..hi`.
    fn any(&self, lo: usize, hi: usize) -> bool {
        let a = self.rank(lo);
        a < self.active.len() && self.active[a] < hi
    }

    /// `sum |rate_k| (to - k)` over the joints looked at `active[a..b]` (those in `lo..hi`
    /// for `a` and `b` their ranks).
    fn lever(&self, a: usize, b: usize, to: usize) -> f64 {
        if b <= a {
            return 0.0;
        }
        let spin = self.spin[b] - self.spin[a];
        let moment = self.moment[b] - self.moment[a];
        (to as f64 * spin - moment).max(0.0)
    }

    /// A run's disc in the world.
    fn disc(&self, run: &Run) -> (Point, f64) {
        let (c, r) = self.tree.disc(run.node);
        (run.pose.apply(c), r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_below_a_tile_by_blocks_is_the_count_over_all_joints() {
        // sparse, dense, across block boundaries and at the chain's ends
        let tiles = 300;
        let sets: [Vec<usize>; 4] = [
            vec![],
            vec![0, 63, 64, 65, 127, 128, 200, 298],
            (0..tiles - 1).collect(),
            (5..tiles - 1).step_by(37).collect(),
        ];
        for set in sets {
            let mut search = Search::new(vec![0.0; tiles - 1], 0.5, usize::MAX);
            let joints: Vec<(usize, f64)> = set.iter().map(|&k| (k, 1.0)).collect();
            // a look of no time fills the counts (and finds what the start does)
            let _ = search.look(&joints, 0.0);
            for x in 0..tiles + 70 {
                let want = set.partition_point(|&k| k < x);
                assert_eq!(search.rank(x), want, "{set:?} below {x}");
                for hi in [x, x + 1, x + 64] {
                    let any = set.iter().any(|&k| k >= x && k < hi);
                    assert_eq!(search.any(x, hi), any, "{set:?} in {x}..{hi}");
                }
            }
        }
    }
}
