//! One segment of a timed schedule (every moving joint turning at a constant rate): the
//! moving joints cut the chain into rigid blocks, and every pair of blocks is checked on its
//! own.
//!
//! - Neighbouring blocks turn about one hinge relative to each other: their first contact is
//!   found exactly, as in sequential folding ([`super::sweep::TurningPair::first_contact`]), for the
//!   pairs of tiles that the descent through the two blocks' discs ([`ChainTree`]) cannot rule
//!   out: a disc turning about the hinge stays in its annulus and sweeps a known range of
//!   angles.
//! - Blocks two or more apart move by a composition of rotations: conservative advancement,
//!   each pair of parts on its own clock. A part of block `b` seen from block `a` moves no
//!   faster than the sum over the joints between of `|rate| * (distance from that hinge)`, and
//!   the distance from each hinge is bounded by the (fixed) distances between consecutive
//!   moving hinges plus the (fixed) distance from the last one. Two parts far apart for their
//!   size step by their disc distance over that speed; close ones are split into their
//!   children, down to pairs of tiles, which step by their exact distance. Parts that no
//!   contact can reach (the far end of a long tail) take one step for the whole segment.
//!   Besides its disc every part has a box ([`ChainTree::bounds`]; a whole block's in world
//!   coordinates): parts whose boxes are too far apart to meet are done, and two straight
//!   rows (or a row and a tile) close to each other step on their boxes' gap, which for rows
//!   lying face to face is their faces' gap: a serpentine's rows settling against each other
//!   at a U-turn cost one pair, not one pair per tile.
//! - A pair of blocks is advanced past the segment's end, up to the next breakpoint of a
//!   joint inside its span ([`super::windows`]), and reports until when it is clean.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::rc::Rc;

use kurbo::{Point, Vec2};
use parry2d_f64::query;
use parry2d_f64::shape::ConvexPolygon;

use crate::Octagon;

use super::block_cover::BlockCover;
use super::chain_tree::{turn_of, ChainTree, Rigid};
use super::sweep::TurningPair;
use super::{Collision, ScheduleError};

/// Distance (tile widths, between inset outlines) at which two tiles count as in contact.
const CONTACT: f64 = 1e-12;
/// Slack on the pruning tests, tile widths or radians: far above the rounding of world
/// coordinates (1e-10 w at a million tiles), so a pair pruned is one that cannot meet.
const SLACK: f64 = 1e-7;

/// The first contact found in a segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Contact {
    /// When.
    pub time: f64,
    /// The two tiles, lower first.
    pub tiles: (usize, usize),
    /// The moving joint reported: the highest joint between the tiles that turns in the
    /// segment and whose fold goes on, else the highest that turns (the one they turn
    /// about, for neighbouring blocks).
    pub joint: usize,
    /// That joint's angle at contact, degrees, unsigned.
    pub angle_deg: f64,
}

impl Contact {
    /// The contact as the check's error.
    pub(super) fn to_error(self) -> ScheduleError {
        ScheduleError::Collision(Collision {
            joint: Some(self.joint),
            angle_deg: self.angle_deg,
            time: Some(self.time),
            tiles: self.tiles,
        })
    }

    pub(super) fn earlier_than(&self, other: &Option<Contact>) -> bool {
        other.is_none_or(|o| (self.time, self.tiles) < (o.time, o.tiles))
    }
}

/// The conservative advancement ran past its work budget.
#[derive(Clone, Copy, Debug)]
pub(super) struct OverBudget {
    /// The time the stalled pair had reached.
    pub time: f64,
}

/// A rigid part of a block: a node of the tree, or the whole block (`node == 0`).
#[derive(Clone, Copy, Debug)]
struct Part {
    node: usize,
    block: usize,
    /// World pose at the segment's start of the node's first tile.
    pose: Rigid,
    /// World centre and radius of the disc holding the part, at the segment's start.
    centre: Point,
    radius: f64,
}

/// A segment's blocks, moving joints and hinges.
pub(super) struct Segment<'a> {
    tree: &'a ChainTree,
    ta: f64,
    tb: f64,
    /// Moving joints, increasing; block `b` starts after `joints[b - 1]`.
    joints: Vec<usize>,
    start: Vec<f64>,
    /// When each moving joint's fold ended (infinity when it has not).
    ended: Vec<f64>,
    rate: Vec<f64>,
    /// World hinge of each moving joint at the segment's start.
    hinges: Vec<Point>,
    /// Prefix sums over the moving joints `l' < l`: of `|rate|`; of the distances between
    /// consecutive hinges (`chain[l]`: from the first hinge to hinge `l` along the hinges);
    /// of `|rate| * chain`.
    spin: Vec<f64>,
    chain: Vec<f64>,
    spin_chain: Vec<f64>,
    /// Each block's cover, in the frame of its first tile.
    covers: Vec<Rc<BlockCover>>,
    /// Each whole block, placed in the world at the segment's start (`pose`: its first
    /// tile's; its box is its cover's, in that frame).
    roots: Vec<Part>,
    /// The tile's inset outline about its centre, and the full outline's circumradius.
    outline: [Point; 8],
    radius: f64,
}

impl<'a> Segment<'a> {
    /// The segment `[ta, tb]` in which joint `moving[l].0` turns from `moving[l].1` at the
    /// rate `moving[l].2` (joints increasing, every rate nonzero, no angle crossing zero
    /// before the joint's next breakpoint), its fold ended at `moving[l].3` (infinity when
    /// not); `covers` are its blocks (the runs between the moving joints, every joint inside
    /// at its angle of `ta`); outlines inset by `tolerance`.
    pub fn new(
        tree: &'a ChainTree,
        covers: Vec<Rc<BlockCover>>,
        ta: f64,
        tb: f64,
        moving: &[(usize, f64, f64, f64)],
        tolerance: f64,
    ) -> Segment<'a> {
        let o = Octagon::new(1.0);
        let span = (tb - ta).max(f64::MIN_POSITIVE);
        // each block placed by its first tile's pose: block 0's is the world's origin, and
        // block b + 1's is block b's last tile turned across moving joint b
        let mut places = Vec::with_capacity(covers.len());
        let mut hinges = Vec::with_capacity(moving.len());
        let mut at = Rigid::IDENTITY;
        for (b, cover) in covers.iter().enumerate() {
            places.push(at);
            if let Some(&(_, a0, rate, _)) = moving.get(b) {
                let last = at.then(&cover.last);
                let (x, y) = o.hinge(a0 + (a0 + rate * span) > 0.0);
                hinges.push(last.apply(Point::new(x, y)));
                at = last.then(&turn_of(a0));
            }
        }
        let roots: Vec<Part> = covers
            .iter()
            .zip(&places)
            .enumerate()
            .map(|(b, (cover, at))| Part {
                node: 0,
                block: b,
                pose: *at,
                centre: at.apply(cover.centre),
                radius: cover.radius,
            })
            .collect();
        let rate: Vec<f64> = moving.iter().map(|m| m.2).collect();
        let (mut spin, mut chain, mut spin_chain) = (vec![0.0], vec![0.0], vec![0.0]);
        for l in 0..rate.len() {
            let next: f64 = hinges
                .get(l + 1)
                .map_or(0.0, |h: &Point| (*h - hinges[l]).hypot());
            spin.push(spin[l] + rate[l].abs());
            spin_chain.push(spin_chain[l] + rate[l].abs() * chain[l]);
            chain.push(chain[l] + next);
        }
        Segment {
            tree,
            ta,
            tb,
            joints: moving.iter().map(|m| m.0).collect(),
            start: moving.iter().map(|m| m.1).collect(),
            ended: moving.iter().map(|m| m.3).collect(),
            rate,
            hinges,
            spin,
            chain,
            spin_chain,
            covers,
            roots,
            outline: o.inset_vertices(tolerance).map(Point::from),
            radius: o.circumradius(),
        }
    }

    /// The number of blocks.
    pub fn blocks(&self) -> usize {
        self.roots.len()
    }

    /// The segment's length, seconds.
    pub fn span_time(&self) -> f64 {
        self.tb - self.ta
    }

    /// Block `b`'s disc at the segment's start, and for `b >= 1` the distance from its first
    /// hinge (fixed in the block) that holds it.
    pub fn block_disc(&self, b: usize) -> (Point, f64, f64) {
        let r = &self.roots[b];
        let reach = match b.checked_sub(1) {
            Some(l) => (r.centre - self.hinges[l]).hypot() + r.radius,
            None => 0.0,
        };
        (r.centre, r.radius, reach)
    }

    /// The sum of `|rate|` over the moving joints `l0..l1`, and the distance along the moving
    /// hinges from hinge `l0` to hinge `l1 - 1` (0 for an empty range).
    pub fn spin_and_chain(&self, l0: usize, l1: usize) -> (f64, f64) {
        if l1 <= l0 {
            return (0.0, 0.0);
        }
        (
            self.spin[l1] - self.spin[l0],
            self.chain[l1 - 1] - self.chain[l0],
        )
    }

    /// Calls `f` with each part of `part` (none for a tile).
    fn each_child(&self, part: &Part, mut f: impl FnMut(Part)) {
        let child = |node: usize, pose: Rigid| {
            let (c, radius) = self.tree.disc(node);
            Part {
                node,
                block: part.block,
                pose,
                centre: pose.apply(c),
                radius,
            }
        };
        if part.node == 0 {
            for &(node, rel) in &self.covers[part.block].nodes {
                f(child(node, part.pose.then(&rel)));
            }
            return;
        }
        if self.tree.tile(part.node).is_some() {
            return;
        }
        for (node, pose) in self.tree.children(part.node, &part.pose) {
            f(child(node, pose));
        }
    }

    fn tile(&self, part: &Part) -> Option<usize> {
        if part.node == 0 {
            return None;
        }
        self.tree.tile(part.node)
    }

    fn outline_at(&self, pose: &Rigid) -> [Point; 8] {
        self.outline.map(|v| pose.apply(v))
    }

    /// Calls `f` with the pairs of parts to look into when `p` and `q` are too close to
    /// settle: the larger one split (never a tile).
    fn split_larger(&self, p: &Part, q: &Part, mut f: impl FnMut(Part, Part)) {
        let split_p = self.tile(q).is_some() || (self.tile(p).is_none() && p.radius >= q.radius);
        if split_p {
            self.each_child(p, |k| f(k, *q));
        } else {
            self.each_child(q, |k| f(*p, k));
        }
    }

    /// The first contact between blocks `b - 1` and `b`, which turn about the hinge of
    /// `joints[b - 1]` relative to each other, from the segment's start until `until` (at
    /// or after its end: no joint inside the two blocks changes its motion before), if
    /// earlier than `best`.
    pub fn rotation_contact(&self, b: usize, until: f64, best: &mut Option<Contact>) {
        let l = b - 1;
        let (k, pivot) = (self.joints[l], self.hinges[l]);
        let span = until.max(self.tb) - self.ta;
        let turn = self.rate[l] * span;
        // pairs are tested before they are stacked
        let mut stack = Vec::new();
        let (p0, q0) = (self.roots[b - 1], self.roots[b]);
        if rotation_may_meet(pivot, &p0, &q0, turn) {
            stack.push((p0, q0));
        }
        while let Some((p, q)) = stack.pop() {
            let (Some(i), Some(j)) = (self.tile(&p), self.tile(&q)) else {
                self.split_larger(&p, &q, |x, y| {
                    if rotation_may_meet(pivot, &x, &y, turn) {
                        stack.push((x, y));
                    }
                });
                continue;
            };
            if i == k && j == k + 1 {
                continue; // hinged neighbours
            }
            let (fixed, moving) = (self.outline_at(&p.pose), self.outline_at(&q.pose));
            let (cp, cq) = (p.pose.apply(Point::ORIGIN), q.pose.apply(Point::ORIGIN));
            let r = self.radius;
            let pair = TurningPair::new(&moving, cq, &fixed, cp, r, pivot);
            if let Some(phi) = pair.first_contact(turn) {
                let c = Contact {
                    time: self.ta + span * phi / turn.abs(),
                    tiles: (i, j),
                    joint: k,
                    angle_deg: (self.start[l] + turn.signum() * phi).abs().to_degrees(),
                };
                if c.earlier_than(best) {
                    *best = Some(c);
                }
            }
        }
    }

    /// The motion, from the segment's start to `t`, of block `b` seen from block `a`: the
    /// rotations about the hinges between, in world coordinates at the start.
    fn motion(&self, a: usize, b: usize, t: f64) -> Rigid {
        if t == self.ta {
            return Rigid::IDENTITY;
        }
        (a..b).fold(Rigid::IDENTITY, |g, l| {
            g.then(&Rigid::rotation_about(
                self.hinges[l],
                self.rate[l] * (t - self.ta),
            ))
        })
    }

    /// The runs of tiles of blocks `a` and `b`: first and last tile of each.
    pub fn span(&self, a: usize, b: usize) -> (usize, usize, usize, usize) {
        let first = |b: usize| if b == 0 { 0 } else { self.joints[b - 1] + 1 };
        let last = |b: usize| self.joints.get(b).copied().unwrap_or(self.tree.tiles() - 1);
        (first(a), last(a), first(b), last(b))
    }

    /// Conservative advancement of blocks `a` and `b` (`b >= a + 2`) from the segment's start
    /// until contact, `until` (at or after the segment's end: no joint between the two blocks
    /// or inside them changes its motion before it), or `best`'s time; a contact found earlier
    /// than `best` replaces it. Returns the time until which the pair is clean. `work` counts
    /// pair evaluations against `budget`.
    #[allow(clippy::too_many_arguments)]
    pub fn advance(
        &self,
        a: usize,
        b: usize,
        shape: &ConvexPolygon,
        until: f64,
        best: &mut Option<Contact>,
        work: &mut usize,
        budget: usize,
    ) -> Result<f64, OverBudget> {
        // speed of a point at distance rho from hinge b-1 (block b's first hinge):
        // w * rho + kk, from the fixed distances between consecutive moving hinges
        // (prefix sums: w = sum |rate_l|, kk = sum |rate_l| * (chain to hinge b-1 from l))
        let w = self.spin[b] - self.spin[a];
        let kk = (self.chain[b - 1] * w - (self.spin_chain[b] - self.spin_chain[a])).max(0.0);
        let hinge = self.hinges[b - 1];
        let mut stack = vec![(self.roots[a], self.roots[b], self.ta)];
        while let Some((p, q, mut t)) = stack.pop() {
            // grown by a hair over the rounding of the prefix sums
            let speed = (w * ((q.centre - hinge).hypot() + q.radius) + kk) * (1.0 + 1e-9);
            loop {
                let limit = best.map_or(until, |c| c.time.min(until));
                if t >= limit || speed <= 0.0 {
                    break;
                }
                *work += 1;
                if *work > budget {
                    return Err(OverBudget { time: t });
                }
                let g = self.motion(a, b, t);
                if let (Some(i), Some(j)) = (self.tile(&p), self.tile(&q)) {
                    let (pp, pq) = (p.pose.to_pose(), g.then(&q.pose).to_pose());
                    let d = query::distance(&pp.to_parry(), shape, &pq.to_parry(), shape)
                        .unwrap_or(0.0);
                    if d <= CONTACT {
                        let c = self.contact_at(t, i, j);
                        if c.earlier_than(best) {
                            *best = Some(c);
                        }
                        break;
                    }
                    t += (d / speed).max(1e-15 * (1.0 + t.abs()));
                    continue;
                }
                // parts that cannot meet before the limit are done; parts far apart for their
                // size step on their discs; close ones on their boxes when both are straight
                // rows or tiles (rows lying face to face, whose boxes' gap is their faces');
                // the rest are split
                let d = (p.centre - g.apply(q.centre)).hypot() - p.radius - q.radius;
                if d > 0.0 && t + d / speed >= limit {
                    break;
                }
                if d > p.radius.max(q.radius) {
                    t += d / speed;
                    continue;
                }
                let d = self.box_gap(&p, &q, &g);
                if d > 0.0 && t + d / speed >= limit {
                    break;
                }
                if d > CONTACT && self.straight(&p) && self.straight(&q) {
                    t += (d / speed).max(1e-15 * (1.0 + t.abs()));
                    continue;
                }
                self.split_larger(&p, &q, |x, y| stack.push((x, y, t)));
                break;
            }
        }
        Ok(best.map_or(until, |c| c.time.min(until)))
    }

    /// Whether a part is a straight row of tiles (or one tile).
    fn straight(&self, part: &Part) -> bool {
        part.node != 0 && self.tree.straight(part.node)
    }

    /// A part's box, in the frame of its first tile.
    fn bounds(&self, part: &Part) -> (Point, Point) {
        if part.node == 0 {
            self.covers[part.block].boxed
        } else {
            self.tree.bounds(part.node)
        }
    }

    /// A lower bound on the distance between the inset outlines of parts `p` (block `a`,
    /// unmoved) and `q` (moved by `g`): the widest gap between their boxes
    /// along one of the four box normals (separating axes), 0 when the boxes overlap.
    fn box_gap(&self, p: &Part, q: &Part, g: &Rigid) -> f64 {
        let gq = g.then(&q.pose);
        let boxes = [(p.pose, self.bounds(p)), (gq, self.bounds(q))];
        // each box: its world centre, unit axes and half sizes
        let frames = boxes.map(|(at, (lo, hi))| {
            let c = at.apply(lo.midpoint(hi));
            let o = at.apply(Point::ORIGIN);
            let u = at.apply(Point::new(1.0, 0.0)) - o;
            (
                c,
                u,
                Vec2::new(-u.y, u.x),
                0.5 * (hi.x - lo.x),
                0.5 * (hi.y - lo.y),
            )
        });
        let between = frames[1].0 - frames[0].0;
        let mut gap = 0.0f64;
        for f in &frames {
            for n in [f.1, f.2] {
                let reach: f64 = frames
                    .iter()
                    .map(|e| e.3 * e.1.dot(n).abs() + e.4 * e.2.dot(n).abs())
                    .sum();
                gap = gap.max(between.dot(n).abs() - reach);
            }
        }
        // the axes' rounding (a few 1e-16 of the coordinates) kept off the bound
        gap - 1e-15 * (1.0 + between.hypot())
    }

    /// A contact found by advancement at `t` between tiles `i < j`: reported with the fold
    /// front, the highest joint between them that turns in this segment and whose fold has
    /// not ended, or the highest that turns ([`super::Collision::joint`]).
    fn contact_at(&self, t: f64, i: usize, j: usize) -> Contact {
        // joints increase: the last one between the tiles whose fold goes on, else the last
        let between = |l: &usize| (i..j).contains(&self.joints[*l]);
        let l = (0..self.joints.len())
            .rev()
            .filter(between)
            .find(|&l| self.ended[l] > t)
            .or_else(|| (0..self.joints.len()).rev().find(between))
            .unwrap_or(0);
        Contact {
            time: t,
            tiles: (i, j),
            joint: self.joints[l],
            angle_deg: (self.start[l] + self.rate[l] * (t - self.ta))
                .abs()
                .to_degrees(),
        }
    }
}

/// Half the angle a disc of radius `radius` at distance `d` spans seen from the pivot, bounded
/// from above without `asin` (`asin x <= x pi/2` on `[0, 1]`); `PI` when the pivot is inside.
fn half_angle(d: f64, radius: f64) -> f64 {
    if d <= radius + SLACK {
        PI
    } else {
        (radius + SLACK) / d * FRAC_PI_2 + SLACK
    }
}

/// Whether part `q`, turning by `turn` about `pivot`, can meet part `p`: its disc moves no
/// further than its distance from the pivot times the turn, stays in its annulus about the
/// pivot, and sweeps a known range of angles.
fn rotation_may_meet(pivot: Point, p: &Part, q: &Part, turn: f64) -> bool {
    let (vp, vq) = (p.centre - pivot, q.centre - pivot);
    let (dp, dq) = (vp.hypot(), vq.hypot());
    let reach = p.radius + q.radius + SLACK;
    if (p.centre - q.centre).hypot() > reach + dq * turn.abs().min(2.0) || (dp - dq).abs() > reach {
        return false;
    }
    let (hp, hq) = (half_angle(dp, p.radius), half_angle(dq, q.radius));
    if hp >= PI || hq >= PI {
        return true;
    }
    // angles measured from p's direction: p spans [-hp, hp], q sweeps [q0, q1]
    let a = vp.cross(vq).atan2(vp.dot(vq));
    let (q0, q1) = (a - hq + turn.min(0.0), a + hq + turn.max(0.0));
    if q1 - q0 + 2.0 * hp >= TAU {
        return true;
    }
    // q's range shifted to start within one turn after -hp
    let s = -hp + (q0 + hp).rem_euclid(TAU);
    s <= hp || s + (q1 - q0) >= TAU - hp
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(x: f64, y: f64, radius: f64) -> Part {
        Part {
            node: 1,
            block: 0,
            pose: Rigid::IDENTITY,
            centre: Point::new(x, y),
            radius,
        }
    }

    #[test]
    fn rotation_pruning_keeps_what_the_sweep_reaches() {
        let o = Point::ORIGIN;
        // a disc at (5, 0) turning a quarter turn left reaches (0, 5), not (0, -5) or (9, 9)
        let q = part(5.0, 0.0, 0.6);
        assert!(rotation_may_meet(o, &part(0.0, 5.0, 0.6), &q, PI / 2.0));
        assert!(rotation_may_meet(o, &part(3.6, 3.6, 0.6), &q, PI / 2.0));
        assert!(!rotation_may_meet(o, &part(0.0, -5.0, 0.6), &q, PI / 2.0));
        assert!(rotation_may_meet(o, &part(0.0, -5.0, 0.6), &q, -PI / 2.0));
        assert!(!rotation_may_meet(o, &part(9.0, 9.0, 0.6), &q, PI / 2.0));
        // across the branch cut at +-pi
        let behind = part(-5.0, 0.1, 0.6);
        assert!(rotation_may_meet(o, &part(-5.0, -0.5, 0.6), &behind, 0.2));
        assert!(rotation_may_meet(
            o,
            &part(0.0, -5.0, 0.6),
            &behind,
            PI / 2.0
        ));
        // a disc over the pivot meets everything in its annulus
        assert!(rotation_may_meet(
            o,
            &part(0.0, -1.0, 0.6),
            &part(0.2, 0.0, 1.0),
            0.1
        ));
    }
}
