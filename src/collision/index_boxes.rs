//! Boxes over runs of consecutive tiles, for finding the placed tiles near a swept region.
//!
//! A chain is spatially coherent: consecutive tiles touch, so the centres of any run of
//! consecutive tiles lie in a box about as small as the run. [`RangeBoxes`] keeps the box of
//! every run of `LEAF * 2^j` tiles aligned to a multiple of its length (a complete binary tree
//! over the chain's index, built once in O(n) from the final centres), and
//! [`RangeBoxes::for_each_in`] lists the tiles of a prefix `0..=last` whose centres lie in a
//! query rectangle, skipping every run whose box misses it. In the sequential check the placed
//! tiles are always such a prefix, so nothing is inserted or rebuilt while folding.

use kurbo::{Point, Rect};

/// Tiles per leaf: the leaf's tiles are tested one by one.
const LEAF: usize = 8;

/// The box of every aligned run of tiles.
#[derive(Clone, Debug)]
pub(super) struct RangeBoxes {
    /// Leaves in the tree (a power of two).
    leaves: usize,
    /// Heap layout: node `p` has children `2p` and `2p + 1`; leaf `l` is node `leaves + l`.
    /// An empty run has an empty (inverted) box.
    boxes: Vec<Rect>,
}

/// A box that contains nothing and meets nothing.
pub(crate) const EMPTY: Rect = Rect::new(
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
);

/// Do the closed boxes `a` and `b` meet (an empty box meets nothing)?
pub(crate) fn meets(a: &Rect, b: &Rect) -> bool {
    a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1
}

/// The smallest box holding `a` and `b` (either may be [`EMPTY`]).
pub(crate) fn union(a: Rect, b: Rect) -> Rect {
    Rect::new(
        a.x0.min(b.x0),
        a.y0.min(b.y0),
        a.x1.max(b.x1),
        a.y1.max(b.y1),
    )
}

/// The smallest box holding `b` (which may be [`EMPTY`]) and point `c`.
pub(crate) fn union_pt(b: Rect, c: Point) -> Rect {
    Rect::new(b.x0.min(c.x), b.y0.min(c.y), b.x1.max(c.x), b.y1.max(c.y))
}

impl RangeBoxes {
    /// The boxes of `centres`' runs.
    pub fn new(centres: &[Point]) -> RangeBoxes {
        let leaves = centres.len().div_ceil(LEAF).max(1).next_power_of_two();
        let mut boxes = vec![EMPTY; 2 * leaves];
        for (l, run) in centres.chunks(LEAF).enumerate() {
            boxes[leaves + l] = run.iter().fold(EMPTY, |b, &c| union_pt(b, c));
        }
        for p in (1..leaves).rev() {
            boxes[p] = union(boxes[2 * p], boxes[2 * p + 1]);
        }
        RangeBoxes { leaves, boxes }
    }

    /// Calls `visit(i)` for every tile `i <= last` whose centre lies in `query` (closed), in
    /// increasing order of `i`, until `visit` returns `true`; returns whether it did.
    pub fn for_each_in(
        &self,
        centres: &[Point],
        last: usize,
        query: &Rect,
        mut visit: impl FnMut(usize) -> bool,
    ) -> bool {
        // depth-first, left child first; the stack never holds more than two nodes a level
        let mut stack: Vec<(usize, usize)> = Vec::with_capacity(64);
        stack.push((1, 0));
        while let Some((p, first)) = stack.pop() {
            if first > last || !meets(&self.boxes[p], query) {
                continue;
            }
            if p >= self.leaves {
                let end = (first + LEAF).min(last + 1).min(centres.len());
                for (i, c) in centres.iter().enumerate().take(end).skip(first) {
                    if closed_contains(query, *c) && visit(i) {
                        return true;
                    }
                }
                continue;
            }
            // tiles per child at this level
            let span = LEAF * (self.leaves >> (usize::BITS - 1 - p.leading_zeros())) / 2;
            stack.push((2 * p + 1, first + span));
            stack.push((2 * p, first));
        }
        false
    }
}

/// Whether `c` lies in `r`, edges included (`Rect::contains` leaves out the far edges).
fn closed_contains(r: &Rect, c: Point) -> bool {
    c.x >= r.x0 && c.x <= r.x1 && c.y >= r.y0 && c.y <= r.y1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_exactly_the_prefix_tiles_in_the_box() {
        // a spiral-ish walk of 1,000 points, queried with many boxes and prefixes: the same
        // tiles as a plain scan, in the same order
        let mut centres = Vec::new();
        let (mut x, mut y) = (0.0f64, 0.0f64);
        for i in 0..1000 {
            let a = (i as f64).sqrt();
            x += a.cos();
            y += a.sin();
            centres.push(Point::new(x, y));
        }
        let boxes = RangeBoxes::new(&centres);
        for q in 0..200 {
            let (cx, cy) = (centres[q * 5].x, centres[q * 5].y);
            let h = 1.0 + (q % 7) as f64 * 3.0;
            let query = Rect::new(cx - h, cy - h * 0.5, cx + h * 0.7, cy + h);
            let last = (q * 37) % 1000;
            let mut got = Vec::new();
            boxes.for_each_in(&centres, last, &query, |i| {
                got.push(i);
                false
            });
            let want: Vec<usize> = (0..=last)
                .filter(|&i| closed_contains(&query, centres[i]))
                .collect();
            assert_eq!(got, want, "query {q}");
        }
    }

    #[test]
    fn stops_when_asked() {
        let centres: Vec<Point> = (0..100).map(|i| Point::new(i as f64, 0.0)).collect();
        let boxes = RangeBoxes::new(&centres);
        let mut seen = 0;
        let everything = Rect::new(-1.0, -1.0, 200.0, 1.0);
        assert!(boxes.for_each_in(&centres, 99, &everything, |i| {
            seen += 1;
            i == 41
        }));
        assert_eq!(seen, 42);
    }
}
