//! Which pairs of tiles can come within a cutoff of each other over a timed fold schedule,
//! found without visiting every pair: the candidates the clearance measurement
//! ([`super::clearance`]) follows exactly.
//!
//! The schedule's time is cut at every breakpoint of every track, so that within a segment
//! each joint turns at a constant rate. A tree of bounding discs over runs of consecutive
//! tiles ([`ChainTree`], updated in O(log n) per joint that changes) holds the chain at the
//! segment's start. Only pairs of runs with a joint between them (or inside them) that turns
//! in the segment, or whose angle changed at its start, are looked at: every other pair keeps
//! its shape and was looked at when it last changed (the whole chain is looked at once, at
//! the schedule's start). Over a segment of length `dt` a point of tile `q` moves, seen from
//! tile `p`, at most `dt sum_k |rate_k| 2 R (q - k)` over the joints `p <= k < q` that turn
//! (`R` the circumradius: a point of tile `q` lies within `2 R (q - k)` of joint `k`'s
//! hinge, [`super::clearance`]); two runs whose discs are further apart than the cutoff
//! plus both runs' motion are dropped together, the others are split down to pairs of
//! tiles. The cost is the number of runs near the turning joints, times the segments: about
//! linear in the chain, times the joints turning at once.

use kurbo::Point;
use rustc_hash::FxHashSet;

use super::chain_tree::{ChainTree, Rigid};
use super::JointTrack;
use crate::Octagon;

/// Slack on the pruning test, tile widths: far above the rounding of world coordinates
/// (1e-10 w at a million tiles), so a pair dropped is one that cannot come within the cutoff.
const SLACK: f64 = 1e-7;

/// The most a joint turns over one step of the search, radians: a run of tiles `m` widths
/// along the chain from a turning joint moves at most about `m` times this over a step, so
/// the runs far along a swinging tail stay clear of what lies near its hinge.
const STEP_TURN: f64 = 1.0 / 32.0;

/// The most steps one segment is cut into (a segment turning a joint by a quarter turn takes
/// about 50).
const MAX_STEPS: f64 = 4096.0;

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
) -> Option<Vec<(usize, usize)>> {
    let joints = tiles.saturating_sub(1);
    let tracks: Vec<&JointTrack> = track_of.iter().flatten().copied().collect();
    let mut breakpoints: Vec<f64> = tracks
        .iter()
        .flat_map(|t| t.times.iter().copied())
        .collect();
    breakpoints.sort_by(f64::total_cmp);
    breakpoints.dedup();
    let angles: Vec<f64> = (0..joints)
        .map(|k| track_of[k].map_or(0.0, |t| t.angle_at(t0)))
        .collect();
    let mut search = Search {
        tree: ChainTree::new(angles, 0.0),
        radius: Octagon::new(1.0).circumradius(),
        cutoff,
        budget,
        work: 0,
        found: FxHashSet::default(),
        active: Vec::new(),
        spin: Vec::new(),
        moment: Vec::new(),
    };
    // the whole chain at the start
    let all: Vec<(usize, f64)> = (0..joints).map(|k| (k, 0.0)).collect();
    search.look(&all, 0.0)?;
    let mut order: Vec<&JointTrack> = tracks.clone();
    order.sort_by(|a, b| a.times[0].total_cmp(&b.times[0]));
    let mut next = 0;
    let mut running: Vec<(&JointTrack, usize)> = Vec::new();
    let mut changed: Vec<(usize, f64)> = Vec::new();
    let mut moving: Vec<(usize, f64)> = Vec::new();
    let mut turning: Vec<(usize, f64, f64)> = Vec::new();
    for seg in breakpoints.windows(2) {
        let (ta, tb) = (seg[0], seg[1]);
        if tb <= ta {
            continue;
        }
        while next < order.len() && order[next].times[0] < tb {
            running.push((order[next], 0));
            next += 1;
        }
        changed.clear();
        moving.clear();
        turning.clear();
        let tree = &search.tree;
        running.retain_mut(|(tr, hint)| {
            let (a0, rate) = tr.chord_at(ta, hint);
            if tree.angle(tr.joint) != a0 {
                changed.push((tr.joint, a0));
            }
            if rate != 0.0 {
                moving.push((tr.joint, rate.abs()));
                turning.push((tr.joint, a0, rate));
            } else if tree.angle(tr.joint) != a0 {
                moving.push((tr.joint, 0.0));
            }
            tr.times[tr.times.len() - 1] > ta
        });
        search.tree.set_angles(changed.iter().copied());
        if moving.is_empty() {
            continue;
        }
        moving.sort_by_key(|m| m.0);
        // in steps over which no joint turns more than STEP_TURN
        let dt = tb - ta;
        let turn = turning.iter().map(|m| m.2.abs() * dt).fold(0.0, f64::max);
        let steps = (turn / STEP_TURN).ceil().clamp(1.0, MAX_STEPS) as usize;
        let h = dt / steps as f64;
        search.look(&moving, h)?;
        if steps > 1 {
            moving.retain(|m| m.1 != 0.0);
            for u in 1..steps {
                let at = h * u as f64;
                search
                    .tree
                    .set_angles(turning.iter().map(|&(k, a0, rate)| (k, a0 + rate * at)));
                search.look(&moving, h)?;
            }
        }
    }
    // the last angles (a jump at the schedule's end)
    changed.clear();
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
    let mut pairs: Vec<(usize, usize)> = search.found.into_iter().collect();
    pairs.sort_unstable();
    Some(pairs)
}

/// The search's state: the chain at a segment's start and the pairs found.
struct Search {
    tree: ChainTree,
    radius: f64,
    cutoff: f64,
    budget: usize,
    work: usize,
    found: FxHashSet<(usize, usize)>,
    /// The joints looked at in the segment (ascending), with prefix sums of their `|rate|`
    /// and of `|rate| k`.
    active: Vec<usize>,
    spin: Vec<f64>,
    moment: Vec<f64>,
}

/// A run of tiles placed in the world: its node and its first tile's pose.
#[derive(Clone, Copy)]
struct Run {
    node: usize,
    pose: Rigid,
}

impl Search {
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
        let root = Run {
            node: 1,
            pose: Rigid::IDENTITY,
        };
        // (p, q, whether p == q)
        let mut stack: Vec<(Run, Run, bool)> = vec![(root, root, true)];
        while let Some((p, q, same)) = stack.pop() {
            self.work += 1;
            if self.work > self.budget {
                return None;
            }
            let (pf, pl) = (self.tree.first(p.node), self.tree.last(p.node));
            let ql = self.tree.last(q.node);
            if same {
                if self.tree.tile(p.node).is_some() || !self.any(pf, pl) {
                    continue;
                }
                let kids: Vec<Run> = self
                    .tree
                    .children(p.node, &p.pose)
                    .map(|(node, pose)| Run { node, pose })
                    .collect();
                for (x, &a) in kids.iter().enumerate() {
                    stack.push((a, a, true));
                    for &b in &kids[x + 1..] {
                        stack.push((a, b, false));
                    }
                }
                continue;
            }
            if !self.any(pf, ql) {
                continue;
            }
            let (cp, rp) = self.disc(&p);
            let (cq, rq) = self.disc(&q);
            // how far q moves seen from p's first tile, and p's tiles seen from it
            let reach = 2.0 * self.radius * dt * (self.lever(pf, ql, ql) + self.lever(pf, pl, pl));
            let gap = (cp - cq).hypot() - rp - rq - reach;
            let round = SLACK + 1e-12 * (cp.to_vec2().hypot() + cq.to_vec2().hypot());
            if gap - round > self.cutoff {
                continue;
            }
            match (self.tree.tile(p.node), self.tree.tile(q.node)) {
                (Some(i), Some(j)) => {
                    if j >= i + 2 {
                        self.found.insert((i, j));
                    }
                }
                (pt, qt) => {
                    let split_p = qt.is_some() || (pt.is_none() && rp >= rq);
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
        Some(())
    }

    /// Whether a joint looked at lies in `lo..hi`.
    fn any(&self, lo: usize, hi: usize) -> bool {
        let a = self.active.partition_point(|&k| k < lo);
        a < self.active.len() && self.active[a] < hi
    }

    /// `sum |rate_k| (to - k)` over the joints looked at in `lo..hi`.
    fn lever(&self, lo: usize, hi: usize, to: usize) -> f64 {
        let a = self.active.partition_point(|&k| k < lo);
        let b = self.active.partition_point(|&k| k < hi);
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
