//! The largest empty region a plan leaves, measured independently of the planner (issue 26):
//! the part of the shape at least `w / 2` from its outline (`w` the tile width) that lies
//! farther than `0.95 w` from every tile centre, split into connected regions on a square
//! grid of spacing `w / 8` (four-neighbour connectivity); the largest region's area in tile
//! areas (a tile's octagon has area `2 (sqrt 2 - 1) w^2`).
//!
//! Frames: a [`Shape`] is held y-up (SVG user units with y negated), a plan's poses are SVG
//! user units with y down; the poses are mapped into the shape's frame here.
//!
//! Each grid point stands for the `(w/8)^2` square around it, so an area is good to about
//! one grid spacing times the region's perimeter. Used by the corpus report and tested in
//! `planner/tests/corpus.rs`.

use foldchain_planner::kurbo::Point;
use foldchain_planner::Shape;

/// Grid spacing, in tile widths.
pub const STEP: f64 = 1.0 / 8.0;
/// A point is covered when a tile centre is within this many tile widths.
pub const REACH: f64 = 0.95;
/// Only points at least this many tile widths inside the outline are measured.
pub const MARGIN: f64 = 0.5;

/// The area of one tile (a regular octagon of width 1 across flats), in units of `w^2`.
pub fn tile_area() -> f64 {
    2.0 * (2f64.sqrt() - 1.0)
}

/// The largest empty region.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmptyRegion {
    /// Its area in tile areas.
    pub tiles: f64,
    /// Its centroid, SVG user units (y down).
    pub centre: (f64, f64),
}

/// A uniform bucket grid of points or segments, for "is anything within r of p" queries.
struct Buckets<T> {
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    items: Vec<Vec<T>>,
}

impl<T: Copy> Buckets<T> {
    fn new(x0: f64, y0: f64, x1: f64, y1: f64, cell: f64) -> Self {
        let nx = (((x1 - x0) / cell).ceil() as usize).max(1);
        let ny = (((y1 - y0) / cell).ceil() as usize).max(1);
        Buckets {
            x0,
            y0,
            cell,
            nx,
            ny,
            items: vec![Vec::new(); nx * ny],
        }
    }

    fn index(&self, v: f64, lo: f64, n: usize) -> usize {
        (((v - lo) / self.cell).floor().max(0.0) as usize).min(n - 1)
    }

    /// Adds `item` to every cell that the box `[a, b]` meets.
    fn insert_box(&mut self, a: Point, b: Point, item: T) {
        let (i0, i1) = (
            self.index(a.x, self.x0, self.nx),
            self.index(b.x, self.x0, self.nx),
        );
        let (j0, j1) = (
            self.index(a.y, self.y0, self.ny),
            self.index(b.y, self.y0, self.ny),
        );
        for j in j0..=j1 {
            for i in i0..=i1 {
                self.items[j * self.nx + i].push(item);
            }
        }
    }

    fn at(&self, p: Point) -> &[T] {
        let i = self.index(p.x, self.x0, self.nx);
        let j = self.index(p.y, self.y0, self.ny);
        &self.items[j * self.nx + i]
    }
}

/// Distance from `p` to the segment `ab`.
fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.hypot2();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).hypot()
}

/// The largest empty region of a plan with tile width `w` and tile centres `centres_svg`
/// (SVG user units, y down) over `shape` (y up); `None` when no point is empty.
pub fn largest_empty_region(
    shape: &Shape,
    centres_svg: &[(f64, f64)],
    w: f64,
) -> Option<EmptyRegion> {
    assert!(w > 0.0 && w.is_finite(), "tile width {w}");
    let b = shape.bbox();
    let h = STEP * w;
    let margin = MARGIN * w;
    let reach = REACH * w;
    // the outline's edges, bucketed by their boxes grown by the margin
    let mut edges = Buckets::new(b.x0, b.y0, b.x1, b.y1, margin.max(h));
    for ring in shape.rings() {
        let n = ring.points.len();
        for k in 0..n {
            let (p, q) = (ring.points[k], ring.points[(k + 1) % n]);
            let lo = Point::new(p.x.min(q.x) - margin, p.y.min(q.y) - margin);
            let hi = Point::new(p.x.max(q.x) + margin, p.y.max(q.y) + margin);
            edges.insert_box(lo, hi, (p, q));
        }
    }
    // tile centres in the shape's frame, bucketed by cells of the reach
    let mut tiles = Buckets::new(
        b.x0 - reach,
        b.y0 - reach,
        b.x1 + reach,
        b.y1 + reach,
        reach,
    );
    for &(x, y) in centres_svg {
        let c = Point::new(x, -y);
        tiles.insert_box(
            Point::new(c.x - reach, c.y - reach),
            Point::new(c.x + reach, c.y + reach),
            c,
        );
    }
    // grid points at the centres of h x h squares over the box
    let nx = ((b.width() / h).ceil() as usize).max(1);
    let ny = ((b.height() / h).ceil() as usize).max(1);
    let mut empty = vec![false; nx * ny];
    for j in 0..ny {
        let y = b.y0 + (j as f64 + 0.5) * h;
        let inside = shape.intervals_at(y);
        for i in 0..nx {
            let x = b.x0 + (i as f64 + 0.5) * h;
            if !inside.iter().any(|&(a, c)| a <= x && x <= c) {
                continue;
            }
            let p = Point::new(x, y);
            let near_edge = edges
                .at(p)
                .iter()
                .any(|&(a, c)| segment_distance(p, a, c) < margin);
            if near_edge {
                continue;
            }
            let covered = tiles.at(p).iter().any(|&c| (c - p).hypot() <= reach);
            empty[j * nx + i] = !covered;
        }
    }
    // connected regions (four neighbours), by an explicit stack
    let mut seen = vec![false; nx * ny];
    let mut best: Option<(usize, f64, f64)> = None;
    let mut stack = Vec::new();
    for start in 0..nx * ny {
        if !empty[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let (mut count, mut sx, mut sy) = (0usize, 0.0, 0.0);
        while let Some(k) = stack.pop() {
            let (i, j) = (k % nx, k / nx);
            count += 1;
            sx += b.x0 + (i as f64 + 0.5) * h;
            sy += b.y0 + (j as f64 + 0.5) * h;
            let mut visit = |n: usize| {
                if empty[n] && !seen[n] {
                    seen[n] = true;
                    stack.push(n);
                }
            };
            if i > 0 {
                visit(k - 1);
            }
            if i + 1 < nx {
                visit(k + 1);
            }
            if j > 0 {
                visit(k - nx);
            }
            if j + 1 < ny {
                visit(k + nx);
            }
        }
        if best.is_none_or(|(c, _, _)| count > c) {
            best = Some((count, sx / count as f64, sy / count as f64));
        }
    }
    best.map(|(count, cx, cy)| EmptyRegion {
        tiles: count as f64 * h * h / (tile_area() * w * w),
        centre: (cx, -cy),
    })
}
