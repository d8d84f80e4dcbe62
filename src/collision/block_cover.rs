//! A rigid block of a segment (a run of tiles with no moving joint inside) as the nodes of
//! the chain tree that make it up, placed in the frame of its first tile, with a disc and a
//! box holding it in that frame. The covers are kept from one segment to the next while the
//! block's run and the angles inside it stay as they are ([`BlockCache`]), so a segment
//! places each block in the world by one motion (its first tile's) instead of descending the
//! tree for every block; the tree's angles of the moving joints are then never needed, and a
//! segment need not update the tree for them ([`super::advancement`]).

use std::rc::Rc;

use kurbo::Point;

use super::chain_tree::{enclose, ChainTree, Rigid};

/// One block's cover, in the frame of its first tile.
#[derive(Clone, Debug)]
pub(super) struct BlockCover {
    /// First and last tile.
    pub lo: usize,
    /// Last tile.
    pub hi: usize,
    /// The nodes making up the run, in tile order, each with its first tile's pose.
    pub nodes: Vec<(usize, Rigid)>,
    /// The pose of the last tile.
    pub last: Rigid,
    /// A disc holding the block.
    pub centre: Point,
    /// Its radius.
    pub radius: f64,
    /// Corners of a box holding the block's inset outlines.
    pub boxed: (Point, Point),
}

impl BlockCover {
    /// The cover of tiles `lo..=hi` of `tree` (every joint inside at its angle in the tree).
    pub fn new(tree: &ChainTree, lo: usize, hi: usize) -> BlockCover {
        let mut ids = Vec::new();
        tree.cover_nodes(lo, hi, &mut ids);
        let mut nodes = Vec::with_capacity(ids.len());
        let mut at = Rigid::IDENTITY;
        let mut last = Rigid::IDENTITY;
        for (i, &p) in ids.iter().enumerate() {
            nodes.push((p, at));
            last = tree.last_pose(p, &at);
            if i + 1 < ids.len() {
                at = last.then(&tree.turn(tree.last(p)));
            }
        }
        let mut disc: Option<(Point, f64)> = None;
        let (mut lo_box, mut hi_box) = (
            Point::new(f64::MAX, f64::MAX),
            Point::new(f64::MIN, f64::MIN),
        );
        for &(p, at) in &nodes {
            let (c, r) = tree.disc(p);
            let d = (at.apply(c), r);
            disc = Some(disc.map_or(d, |e| enclose(e, d)));
            let (a, b) = tree.bounds(p);
            for c in [a, Point::new(b.x, a.y), b, Point::new(a.x, b.y)] {
                let c = at.apply(c);
                (lo_box.x, lo_box.y) = (lo_box.x.min(c.x), lo_box.y.min(c.y));
                (hi_box.x, hi_box.y) = (hi_box.x.max(c.x), hi_box.y.max(c.y));
            }
        }
        // grown by a hair over the rounding of the turned corners
        let m = lo_box
            .x
            .abs()
            .max(lo_box.y.abs())
            .max(hi_box.x.abs())
            .max(hi_box.y.abs());
        let grow = 1e-12 * (1.0 + m);
        let (centre, radius) = disc.unwrap_or((Point::ORIGIN, 0.0));
        BlockCover {
            lo,
            hi,
            nodes,
            last,
            centre,
            radius,
            boxed: (
                Point::new(lo_box.x - grow, lo_box.y - grow),
                Point::new(hi_box.x + grow, hi_box.y + grow),
            ),
        }
    }
}

/// The blocks of the last segment, kept for the next while their runs and the angles of the
/// joints inside them stay as they are.
#[derive(Default)]
pub(super) struct BlockCache {
    /// By first tile, increasing.
    blocks: Vec<Rc<BlockCover>>,
}

impl BlockCache {
    /// Joint `k`'s angle in the tree changed: the block holding it is made again.
    pub fn turned(&mut self, k: usize) {
        let i = self.blocks.partition_point(|b| b.hi <= k);
        if self.blocks.get(i).is_some_and(|b| b.lo <= k && k < b.hi) {
            self.blocks.remove(i);
        }
    }

    /// The covers of the runs of tiles from tile 0 that end at `ends` (increasing, the last
    /// the chain's last tile), kept or made.
    pub fn covers(&mut self, tree: &ChainTree, ends: &[usize]) -> Vec<Rc<BlockCover>> {
        let mut out = Vec::with_capacity(ends.len());
        let mut lo = 0;
        let mut i = 0;
        for &hi in ends {
            while i < self.blocks.len() && self.blocks[i].lo < lo {
                i += 1;
            }
            match self.blocks.get(i).filter(|b| b.lo == lo && b.hi == hi) {
                Some(b) => out.push(b.clone()),
                None => out.push(Rc::new(BlockCover::new(tree, lo, hi))),
            }
            lo = hi + 1;
        }
        self.blocks.clone_from(&out);
        out
    }
}
