//! Which pairs of a segment's blocks can meet within it, found without visiting every pair.
//!
//! A long chain folding at many places at once has many blocks (a hundred joints turning
//! at once on a 300,000-tile serpentine) and most pairs of them are far apart: visiting every
//! pair in every segment costs the square of the blocks, segment after segment. Here the
//! blocks are grouped by index in a balanced tree, each group with a disc holding its blocks'
//! discs, and two groups are dropped together when their discs are further apart than any
//! point of the later group can move relative to any block of the earlier one within the
//! segment: the joints between turn at most by the sum of their `|rate|`, about hinges that
//! lie within the distance along the moving hinges of each other ([`super::blocks`] bounds a
//! single pair the same way). Groups that may meet are split, down to pairs of blocks.

use kurbo::Point;

use super::blocks::Segment;
use super::chain_tree::enclose;

/// A range of blocks `lo..hi` with a disc holding them and the largest distance of a point
/// of one of them from its block's first hinge.
#[derive(Clone, Copy)]
struct Group {
    lo: usize,
    hi: usize,
    centre: Point,
    radius: f64,
    reach: f64,
}

/// Calls `f(a, b)` for every pair of blocks `a + 2 <= b` of `segment` that may meet within
/// it (a superset of the pairs that do).
pub(super) fn near_pairs(segment: &Segment, mut f: impl FnMut(usize, usize)) {
    let n = segment.blocks();
    if n < 3 {
        return;
    }
    let mut groups: Vec<(Option<(usize, usize)>, Group)> = Vec::with_capacity(2 * n);
    let root = build(segment, 0, n, &mut groups);
    let dt = segment.span_time();
    let mut stack = vec![(root, root)];
    while let Some((i, j)) = stack.pop() {
        let (g, h) = (groups[i].1, groups[j].1);
        if i == j {
            if let Some((l, r)) = groups[i].0 {
                stack.push((l, l));
                stack.push((l, r));
                stack.push((r, r));
            }
            continue;
        }
        // g before h, disjoint; two blocks: neighbours turn about one hinge (checked apart)
        if g.hi - g.lo == 1 && h.hi - h.lo == 1 {
            if h.lo >= g.lo + 2 {
                f(g.lo, h.lo);
            }
            continue;
        }
        // any a in g, b in h: the joints between are among g.lo..h.hi-1; a point of b lies
        // within h.reach of hinge b-1, and hinge b-1 within the chain of any hinge l >= g.lo
        let (spin, chain) = segment.spin_and_chain(g.lo, h.hi - 1);
        let speed = spin * (h.reach + chain) * (1.0 + 1e-9);
        let gap = (g.centre - h.centre).hypot() - g.radius - h.radius;
        if gap > 0.0 && gap > speed * dt {
            continue;
        }
        let (split_g, kids) = if g.hi - g.lo >= h.hi - h.lo {
            (true, groups[i].0)
        } else {
            (false, groups[j].0)
        };
        if let Some((l, r)) = kids {
            if split_g {
                stack.push((l, j));
                stack.push((r, j));
            } else {
                stack.push((i, l));
                stack.push((i, r));
            }
        }
    }
}

/// The groups of blocks `lo..hi`, children before parents: index of the group of the range.
fn build(
    segment: &Segment,
    lo: usize,
    hi: usize,
    groups: &mut Vec<(Option<(usize, usize)>, Group)>,
) -> usize {
    if hi - lo == 1 {
        let (centre, radius, reach) = segment.block_disc(lo);
        groups.push((
            None,
            Group {
                lo,
                hi,
                centre,
                radius,
                reach,
            },
        ));
        return groups.len() - 1;
    }
    let mid = lo + (hi - lo) / 2;
    let (l, r) = (
        build(segment, lo, mid, groups),
        build(segment, mid, hi, groups),
    );
    let (a, b) = (groups[l].1, groups[r].1);
    let (centre, radius) = enclose((a.centre, a.radius), (b.centre, b.radius));
    groups.push((
        Some((l, r)),
        Group {
            lo,
            hi,
            centre,
            radius,
            reach: a.reach.max(b.reach),
        },
    ));
    groups.len() - 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::block_cover::BlockCache;
    use crate::collision::chain_tree::ChainTree;
    use crate::Octagon;

    #[test]
    fn pairs_left_out_do_not_meet() {
        // chains of 300 tiles crumpled at random, 40 joints turning at random rates: every
        // pair of blocks that meets within the segment is among the near pairs, and over a
        // third of the pairs are not (crumpled chains are compact; a serpentine's far rows
        // are left out by whole groups)
        let mut bits = super::super::xorshift(0xB10C_5EED_0000_0001);
        let mut next = move || (bits() >> 11) as f64 / (1u64 << 53) as f64;
        let shape = Octagon::new(1.0).to_parry(1e-7).unwrap();
        let (mut met, mut left_out, mut all) = (0, 0, 0);
        for _ in 0..20 {
            let angles: Vec<f64> = (0..299)
                .map(|_| {
                    if next() < 0.7 {
                        0.0
                    } else {
                        (next() - 0.5) * 2.0
                    }
                })
                .collect();
            let tree = ChainTree::new(angles.clone(), 1e-7);
            let mut joints: Vec<usize> = (0..40).map(|_| (next() * 299.0) as usize).collect();
            joints.sort_unstable();
            joints.dedup();
            let moving: Vec<(usize, f64, f64, f64)> = joints
                .iter()
                .map(|&k| {
                    let a = angles[k];
                    // turning away from straight, so no hinge changes side
                    let rate = if a >= 0.0 { 0.3 } else { -0.3 } * (0.2 + next());
                    (k, a, rate, f64::INFINITY)
                })
                .collect();
            let ends: Vec<usize> = joints.iter().copied().chain([299]).collect();
            let covers = BlockCache::default().covers(&tree, &ends);
            let seg = Segment::new(&tree, covers, 0.0, 0.05 + next() * 0.3, &moving, 1e-7);
            let mut near = Vec::new();
            near_pairs(&seg, |a, b| near.push((a, b)));
            for a in 0..seg.blocks() {
                for b in a + 2..seg.blocks() {
                    all += 1;
                    let mut best = None;
                    let mut work = 0;
                    let tb = seg.span_time();
                    seg.advance(a, b, &shape, tb, &mut best, &mut work, usize::MAX)
                        .unwrap();
                    if best.is_some() {
                        met += 1;
                        assert!(near.contains(&(a, b)), "({a}, {b}) meet but were left out");
                    }
                    if !near.contains(&(a, b)) {
                        left_out += 1;
                    }
                }
            }
        }
        assert!(met > 10, "{met}");
        assert!(left_out * 3 > all, "{left_out} of {all}");
    }
}
