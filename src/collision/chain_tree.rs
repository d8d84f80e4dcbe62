//! A hierarchy of bounding discs over runs of consecutive tiles at arbitrary joint angles, for
//! the timed schedule check (after Lotan et al.'s ChainTree for protein chains).
//!
//! Node `p` of a complete binary tree over the tile indices holds, in the frame of the first
//! tile of its run: the pose of its last tile, the pose of its right child's first tile, and a
//! disc holding every outline of the run. A joint's new angle changes only the nodes whose run
//! holds both of its tiles, one path to the root: O(log n) per joint, so a schedule that turns
//! a few joints at a time never recomputes the whole chain. A run with no turning joint inside
//! is rigid, and its disc moves with its first tile.

use kurbo::{Point, Vec2};

use crate::{Octagon, Pose};

/// A rigid motion: rotation with cosine `c` and sine `s`, then translation `(x, y)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rigid {
    c: f64,
    s: f64,
    x: f64,
    y: f64,
}

impl Rigid {
    /// No motion.
    pub const IDENTITY: Rigid = Rigid {
        c: 1.0,
        s: 0.0,
        x: 0.0,
        y: 0.0,
    };

    /// The motion of a pose (its frame placed in the world).
    #[cfg(test)]
    pub fn from_pose(p: &Pose) -> Rigid {
        let (s, c) = p.angle.sin_cos();
        Rigid {
            c,
            s,
            x: p.x,
            y: p.y,
        }
    }

    /// Rotation by `angle` (radians, counter-clockwise) about `centre`.
    pub fn rotation_about(centre: Point, angle: f64) -> Rigid {
        let (s, c) = angle.sin_cos();
        Rigid {
            c,
            s,
            x: centre.x - (c * centre.x - s * centre.y),
            y: centre.y - (s * centre.x + c * centre.y),
        }
    }

    /// `self` after `o`: the motion that applies `o`, then `self`.
    pub fn then(&self, o: &Rigid) -> Rigid {
        Rigid {
            c: self.c * o.c - self.s * o.s,
            s: self.s * o.c + self.c * o.s,
            x: self.c * o.x - self.s * o.y + self.x,
            y: self.s * o.x + self.c * o.y + self.y,
        }
    }

    /// The image of `p`.
    pub fn apply(&self, p: Point) -> Point {
        Point::new(
            self.c * p.x - self.s * p.y + self.x,
            self.s * p.x + self.c * p.y + self.y,
        )
    }

    /// The same motion as a pose.
    pub fn to_pose(self) -> Pose {
        Pose::new(self.x, self.y, self.s.atan2(self.c))
    }
}

/// The transform across a joint at `angle`, tile width 1.
pub(super) fn turn_of(angle: f64) -> Rigid {
    // `kinematics::joint_transform` with one sine and cosine for the pose and its rotation
    let (hx, hy) = Octagon::new(1.0).hinge(angle >= 0.0);
    let (s, c) = angle.sin_cos();
    let (dx, dy) = (0.5, -hy);
    Rigid {
        c,
        s,
        x: hx + c * dx - s * dy,
        y: hy + s * dx + c * dy,
    }
}

/// The smallest disc holding two discs.
pub(super) fn enclose(a: (Point, f64), b: (Point, f64)) -> (Point, f64) {
    let d = (b.0 - a.0).hypot();
    if d + b.1 <= a.1 {
        return a;
    }
    if d + a.1 <= b.1 {
        return b;
    }
    let r = 0.5 * (d + a.1 + b.1);
    let along: Vec2 = (b.0 - a.0) * ((r - a.1) / d);
    // grown by a hair so that rounding never leaves an outline poking out
    (a.0 + along, r * (1.0 + 1e-12))
}

#[derive(Clone, Copy, Debug)]
struct Node {
    /// Pose of the right child's first tile in this node's first tile's frame.
    to_right: Rigid,
    /// Pose of the last tile in this node's first tile's frame.
    to_last: Rigid,
    /// Disc holding the run's outlines, in the first tile's frame; radius `-1` for no tiles.
    centre: Point,
    radius: f64,
    /// Every joint inside the run stands at exactly 0: the run is a straight row of tiles.
    straight: bool,
    /// Corners of a box holding the run's inset outlines, in the first tile's frame: exactly
    /// the row's outer faces for a straight run.
    lo: Point,
    hi: Point,
}

const EMPTY: Node = Node {
    to_right: Rigid::IDENTITY,
    to_last: Rigid::IDENTITY,
    centre: Point::ORIGIN,
    radius: -1.0,
    straight: true,
    lo: Point::ORIGIN,
    hi: Point::ORIGIN,
};

/// Poses and bounding discs of every aligned run of tiles (tile width 1).
#[derive(Clone, Debug)]
pub(super) struct ChainTree {
    tiles: usize,
    /// Leaves (a power of two); tile `i` is node `leaves + i`.
    leaves: usize,
    nodes: Vec<Node>,
    angles: Vec<f64>,
    /// Each joint's transform at its angle (one sine and cosine per new angle, not one per
    /// node above it).
    turns: Vec<Rigid>,
    /// [`ChainTree::set_angles`]'s scratch: the nodes queued (stamped with the call's
    /// generation), by depth.
    stamp: Vec<u32>,
    generation: u32,
    levels: Vec<Vec<usize>>,
}

impl ChainTree {
    /// The tree of a chain whose joints stand at `angles` (radians, positive = left), its
    /// boxes holding the outlines inset by `inset` (tile widths).
    pub fn new(angles: Vec<f64>, inset: f64) -> ChainTree {
        let tiles = angles.len() + 1;
        let leaves = tiles.next_power_of_two();
        let mut nodes = vec![EMPTY; 2 * leaves];
        let radius = Octagon::new(1.0).circumradius();
        let h = 0.5 - inset;
        for node in &mut nodes[leaves..leaves + tiles] {
            node.radius = radius;
            node.lo = Point::new(-h, -h);
            node.hi = Point::new(h, h);
        }
        let turns = angles.iter().map(|&a| turn_of(a)).collect();
        let mut tree = ChainTree {
            tiles,
            leaves,
            nodes,
            angles,
            turns,
            stamp: vec![0; 2 * leaves],
            generation: 0,
            levels: Vec::new(),
        };
        for p in (1..leaves).rev() {
            tree.merge(p);
        }
        tree
    }

    /// The number of tiles.
    pub fn tiles(&self) -> usize {
        self.tiles
    }

    /// Recomputes node `p` from its children.
    fn merge(&mut self, p: usize) {
        let (l, r) = (self.nodes[2 * p], self.nodes[2 * p + 1]);
        if r.radius < 0.0 {
            self.nodes[p] = l;
            return;
        }
        let joint = self.first(2 * p + 1) - 1;
        let turn = self.turns[joint];
        let to_right = l.to_last.then(&turn);
        let (centre, radius) = enclose((l.centre, l.radius), (to_right.apply(r.centre), r.radius));
        let (mut lo, mut hi) = (l.lo, l.hi);
        for (x, y) in [
            (r.lo.x, r.lo.y),
            (r.hi.x, r.lo.y),
            (r.hi.x, r.hi.y),
            (r.lo.x, r.hi.y),
        ] {
            let c = to_right.apply(Point::new(x, y));
            (lo.x, lo.y) = (lo.x.min(c.x), lo.y.min(c.y));
            (hi.x, hi.y) = (hi.x.max(c.x), hi.y.max(c.y));
        }
        let straight = l.straight && r.straight && self.angles[joint] == 0.0;
        if !straight {
            // grown by a hair over the rounding of the turned corners (a straight row's
            // corners are exact: its tiles sit at whole widths)
            let grow = 1e-12 * (1.0 + lo.x.abs().max(lo.y.abs()).max(hi.x.abs()).max(hi.y.abs()));
            (lo.x, lo.y, hi.x, hi.y) = (lo.x - grow, lo.y - grow, hi.x + grow, hi.y + grow);
        }
        self.nodes[p] = Node {
            to_right,
            to_last: to_right.then(&r.to_last),
            centre,
            radius,
            straight,
            lo,
            hi,
        };
    }

    #[cfg(test)]
    /// Turns joint `k` to `angle`, updating the nodes above it.
    pub fn set_angle(&mut self, k: usize, angle: f64) {
        self.set_angles(std::iter::once((k, angle)));
    }

    /// The first tile of node `p`'s run.
    pub fn first(&self, p: usize) -> usize {
        let depth = usize::BITS - 1 - p.leading_zeros();
        (p - (1 << depth)) * (self.leaves >> depth)
    }

    /// The last tile of node `p`'s run (runs past the chain's end are cut).
    pub fn last(&self, p: usize) -> usize {
        let depth = usize::BITS - 1 - p.leading_zeros();
        (self.first(p) + (self.leaves >> depth) - 1).min(self.tiles - 1)
    }

    /// The tile of leaf `p`, or `None` for an inner node.
    pub fn tile(&self, p: usize) -> Option<usize> {
        (p >= self.leaves).then(|| p - self.leaves)
    }

    /// Whether node `p`'s run is a straight row (every joint inside at exactly 0).
    pub fn straight(&self, p: usize) -> bool {
        self.nodes[p].straight
    }

    /// Corners of node `p`'s box, in the frame of its first tile.
    pub fn bounds(&self, p: usize) -> (Point, Point) {
        (self.nodes[p].lo, self.nodes[p].hi)
    }

    /// Node `p`'s disc, in the frame of its first tile.
    pub fn disc(&self, p: usize) -> (Point, f64) {
        (self.nodes[p].centre, self.nodes[p].radius)
    }

    /// The children of inner node `p` that hold tiles, each with the pose of its first tile
    /// given the pose `at` of `p`'s first tile.
    pub fn children(&self, p: usize, at: &Rigid) -> impl Iterator<Item = (usize, Rigid)> {
        let right = (self.nodes[2 * p + 1].radius >= 0.0)
            .then(|| (2 * p + 1, at.then(&self.nodes[p].to_right)));
        std::iter::once((2 * p, *at)).chain(right)
    }

    /// The nodes whose runs make up tiles `lo..=hi`, fewest first-to-last, each with the world
    /// pose of its first tile (tile 0 at the origin heading +x), appended to `out`.
    #[cfg(test)]
    pub fn cover(&self, lo: usize, hi: usize, out: &mut Vec<(usize, Rigid)>) {
        let mut stack = vec![(1usize, Rigid::IDENTITY)];
        while let Some((p, at)) = stack.pop() {
            let (first, last) = (self.first(p), self.last(p));
            if first > hi || last < lo || self.nodes[p].radius < 0.0 {
                continue;
            }
            if lo <= first && last <= hi {
                out.push((p, at));
                continue;
            }
            // right child first: the left one is taken next
            if self.nodes[2 * p + 1].radius >= 0.0 {
                stack.push((2 * p + 1, at.then(&self.nodes[p].to_right)));
            }
            stack.push((2 * p, at));
        }
    }

    /// The nodes whose runs make up tiles `lo..=hi` (`hi` within the chain), fewest, in
    /// tile order, appended to `out`.
    pub fn cover_nodes(&self, lo: usize, hi: usize, out: &mut Vec<usize>) {
        // a run to the chain's end takes the nodes past it too (they hold no tiles)
        let end = if hi + 1 >= self.tiles {
            self.leaves
        } else {
            hi + 1
        };
        let (mut l, mut r) = (lo + self.leaves, end + self.leaves);
        let mut right = Vec::new();
        while l < r {
            if l & 1 == 1 {
                out.push(l);
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                right.push(r);
            }
            l /= 2;
            r /= 2;
        }
        out.extend(right.into_iter().rev());
        out.retain(|&p| self.nodes[p].radius >= 0.0);
    }

    /// The world pose of tile `i` (tile 0 at the origin heading +x): down from the root,
    /// O(log n).
    pub fn tile_pose(&self, i: usize) -> Rigid {
        let mut at = Rigid::IDENTITY;
        let (mut p, mut width) = (1usize, self.leaves);
        while width > 1 {
            width /= 2;
            let right = 2 * p + 1;
            if i >= self.first(right) {
                at = at.then(&self.nodes[p].to_right);
                p = right;
            } else {
                p *= 2;
            }
        }
        debug_assert_eq!(p, self.leaves + i);
        at
    }

    /// Joint `k`'s angle in the tree.
    pub fn angle(&self, k: usize) -> f64 {
        self.angles[k]
    }

    /// The transform across joint `k` at its angle in the tree.
    pub fn turn(&self, k: usize) -> Rigid {
        self.turns[k]
    }

    /// The pose of node `p`'s last tile, given the pose `at` of its first.
    pub fn last_pose(&self, p: usize, at: &Rigid) -> Rigid {
        at.then(&self.nodes[p].to_last)
    }

    /// Turns each joint `k` of `angles` (`(k, angle)`) to its angle, then updates every node
    /// above them once, deepest first: the same nodes as [`ChainTree::set_angle`] one by
    /// one, each merged once.
    pub fn set_angles(&mut self, angles: impl Iterator<Item = (usize, f64)>) {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.stamp.fill(0);
            self.generation = 1;
        }
        let mut levels = std::mem::take(&mut self.levels);
        for (k, angle) in angles {
            if self.angles[k] == angle {
                continue;
            }
            self.angles[k] = angle;
            self.turns[k] = turn_of(angle);
            let (mut a, mut b) = (self.leaves + k, self.leaves + k + 1);
            while a != b {
                a /= 2;
                b /= 2;
            }
            // up to the first node already queued (its ancestors are too)
            while a >= 1 && self.stamp[a] != self.generation {
                self.stamp[a] = self.generation;
                let depth = (usize::BITS - 1 - a.leading_zeros()) as usize;
                if levels.len() <= depth {
                    levels.resize_with(depth + 1, Vec::new);
                }
                levels[depth].push(a);
                a /= 2;
            }
        }
        for level in levels.iter_mut().rev() {
            for &p in level.iter() {
                self.merge(p);
            }
            level.clear();
        }
        self.levels = levels;
    }

    #[cfg(test)]
    /// The world pose of tile `i`.
    pub fn pose_of(&self, i: usize) -> Rigid {
        let mut out = Vec::with_capacity(1);
        self.cover(i, i, &mut out);
        out.first().map_or(Rigid::IDENTITY, |&(_, at)| at)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Point, b: (f64, f64)) -> bool {
        (a.x - b.0).abs() < 1e-9 && (a.y - b.1).abs() < 1e-9
    }

    fn angles(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * std::f64::consts::PI
            })
            .collect()
    }

    #[test]
    fn poses_and_discs_follow_the_kinematics() {
        // a chain of 77 tiles at random angles, then some joints turned: every tile's pose is
        // the kinematics' one, and every node's disc holds its tiles' outlines
        let mut a = angles(76, 42);
        let mut tree = ChainTree::new(a.clone(), 1e-7);
        let r = Octagon::new(1.0).circumradius();
        for round in 0..4 {
            let poses = crate::kinematics::poses_at_angles(&a, 1.0);
            for (i, p) in poses.iter().enumerate() {
                let at = tree.pose_of(i);
                assert_eq!(tree.tile_pose(i), at, "tile {i}");
                assert!(close(at.apply(Point::ORIGIN), (p.x, p.y)), "tile {i}");
                let ahead = at.apply(Point::new(1.0, 0.0));
                assert!(close(ahead, p.transform_point((1.0, 0.0))), "tile {i}");
            }
            for p in 1..2 * tree.leaves {
                if tree.nodes[p].radius < 0.0 {
                    continue;
                }
                let mut cover = Vec::new();
                tree.cover(tree.first(p), tree.last(p), &mut cover);
                assert_eq!(cover.len(), 1, "node {p}");
                let (centre, radius) = tree.disc(p);
                let c = cover[0].1.apply(centre);
                for q in &poses[tree.first(p)..=tree.last(p)] {
                    assert!((c - Point::new(q.x, q.y)).hypot() + r <= radius + 1e-9);
                }
            }
            // one joint at a time, or all at once (each node above them merged once)
            for k in [0, 5 + round, 40, 75] {
                a[k] = -a[k] * 0.5;
                if round % 2 == 0 {
                    tree.set_angle(k, a[k]);
                }
            }
            if round % 2 == 1 {
                tree.set_angles([0, 5 + round, 40, 75].into_iter().map(|k| (k, a[k])));
            }
        }
    }

    #[test]
    fn cover_is_a_few_runs_in_order() {
        let tree = ChainTree::new(vec![0.0; 999], 1e-7);
        let mut cover = Vec::new();
        tree.cover(3, 871, &mut cover);
        let mut next = 3;
        for &(p, _) in &cover {
            assert_eq!(tree.first(p), next);
            next = tree.last(p) + 1;
        }
        assert_eq!(next, 872);
        assert!(cover.len() <= 2 * 10, "{}", cover.len());
        // straight chain: tile i at (i, 0)
        for &(p, at) in &cover {
            assert!(close(at.apply(Point::ORIGIN), (tree.first(p) as f64, 0.0)));
        }
    }

    #[test]
    fn block_covers_in_their_first_tiles_frame() {
        use crate::collision::block_cover::BlockCover;
        let angles: Vec<f64> = (0..600)
            .map(|k| 0.01 * ((k * 7919) % 13) as f64 - 0.06)
            .collect();
        let tree = ChainTree::new(angles, 1e-7);
        for (lo, hi) in [(0, 600), (0, 0), (5, 6), (7, 300), (301, 599), (600, 600)] {
            let cover = BlockCover::new(&tree, lo, hi);
            let mut nodes = Vec::new();
            tree.cover(lo, hi, &mut nodes);
            assert_eq!(cover.nodes.len(), nodes.len(), "{lo}..={hi}");
            let base = tree.pose_of(lo);
            for (&(p, rel), &(q, world)) in cover.nodes.iter().zip(&nodes) {
                assert_eq!(p, q);
                let (a, b) = (
                    base.then(&rel).apply(Point::ORIGIN),
                    world.apply(Point::ORIGIN),
                );
                assert!(close(a, (b.x, b.y)), "{lo}..={hi}");
            }
            let last = base.then(&cover.last).apply(Point::ORIGIN);
            let want = tree.pose_of(hi).apply(Point::ORIGIN);
            assert!(close(last, (want.x, want.y)), "{lo}..={hi}");
            // every tile inside the block's disc and box
            for i in lo..=hi {
                let c = tree.pose_of(i).apply(Point::ORIGIN);
                // back into the block's frame: the inverse rotation of the offset
                let (o, u) = (base.apply(Point::ORIGIN), base.apply(Point::new(1.0, 0.0)));
                let (dx, dy, ux, uy) = (c.x - o.x, c.y - o.y, u.x - o.x, u.y - o.y);
                let (x, y) = (ux * dx + uy * dy, -uy * dx + ux * dy);
                let r = (Point::new(x, y) - cover.centre).hypot();
                assert!(r + Octagon::new(1.0).circumradius() <= cover.radius + 1e-9);
                let (a, b) = cover.boxed;
                assert!(a.x <= x - 0.49 && x + 0.49 <= b.x && a.y <= y - 0.49 && y + 0.49 <= b.y);
            }
        }
    }

    #[test]
    fn a_turn_is_the_joint_transform() {
        for a in [
            -std::f64::consts::FRAC_PI_2,
            -0.7,
            -1e-9,
            0.0,
            3e-5,
            0.4,
            std::f64::consts::FRAC_PI_2,
        ] {
            let (t, k) = (
                turn_of(a),
                Rigid::from_pose(&crate::kinematics::joint_transform(a, 1.0)),
            );
            assert_eq!(
                [t.c, t.s, t.x, t.y].map(f64::to_bits),
                [k.c, k.s, k.x, k.y].map(f64::to_bits)
            );
        }
    }

    #[test]
    fn rotation_about_a_point() {
        let r = Rigid::rotation_about(Point::new(1.0, 1.0), std::f64::consts::FRAC_PI_2);
        assert!(close(r.apply(Point::new(2.0, 1.0)), (1.0, 2.0)));
        let back = Rigid::rotation_about(Point::new(1.0, 1.0), -std::f64::consts::FRAC_PI_2);
        assert!(close(
            back.then(&r).apply(Point::new(5.0, -3.0)),
            (5.0, -3.0)
        ));
    }
}
