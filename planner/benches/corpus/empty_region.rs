//! The largest empty region a plan leaves, measured independently of the planner (issue 26):
//! the part of the shape at least `w / 2` from its outline (`w` the tile width) that lies
//! farther than `0.95 w` from every tile centre, split into connected regions on a square
//! grid of spacing `w / 8` (four-neighbour connectivity); the largest region's area in tile
//! areas (a tile's octagon has area `2 (sqrt 2 - 1) w^2`). For a drawing with islands,
//! which the planner leaves out by design, the pieces that hold no tile centre are left out
//! of the measure and their area reported apart ([`measure`]).
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

/// What [`measure`] finds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measure {
    /// The largest empty region of the parts measured.
    pub largest: Option<EmptyRegion>,
    /// The area (tile areas) of the separate parts left out of the measure: pieces of the
    /// shape (four-neighbour connected on the grid, no margin) that hold no tile centre.
    pub left_out_tiles: f64,
}

/// The largest empty region of a plan with tile width `w` and tile centres `centres_svg`
/// (SVG user units, y down) over `shape` (y up), `None` when no point is empty. With
/// `islands`, a separate piece of the shape that holds no tile centre (none lies in one of
/// its grid squares; a centre across a strait narrower than a tile does not count) is left
/// out of the measure and its area reported apart: for the drawings the corpus README marks
/// `islands`, whose islands the planner leaves out by design (with a warning naming them),
/// so that they are measured over what is planned. Never for a drawing in one piece: there
/// a piece joined by a hairline that holds no tile is a part left empty.
pub fn measure(shape: &Shape, centres_svg: &[(f64, f64)], w: f64, islands: bool) -> Measure {
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
    // inside the shape (margin or not); holding a tile centre in its square
    let mut inside_pts = vec![false; nx * ny];
    let mut holds = vec![false; nx * ny];
    for &(x, y) in centres_svg {
        let (i, j) = (((x - b.x0) / h).floor(), ((-y - b.y0) / h).floor());
        if i >= 0.0 && j >= 0.0 && (i as usize) < nx && (j as usize) < ny {
            holds[j as usize * nx + i as usize] = true;
        }
    }
    for j in 0..ny {
        let y = b.y0 + (j as f64 + 0.5) * h;
        let inside = shape.intervals_at(y);
        for i in 0..nx {
            let x = b.x0 + (i as f64 + 0.5) * h;
            if !inside.iter().any(|&(a, c)| a <= x && x <= c) {
                continue;
            }
            let p = Point::new(x, y);
            let covered = tiles.at(p).iter().any(|&c| (c - p).hypot() <= reach);
            inside_pts[j * nx + i] = true;
            let near_edge = edges
                .at(p)
                .iter()
                .any(|&(a, c)| segment_distance(p, a, c) < margin);
            if near_edge {
                continue;
            }
            empty[j * nx + i] = !covered;
        }
    }
    let mut left_out = 0usize;
    if islands {
        for piece in regions(&inside_pts, nx, ny) {
            if !piece.iter().any(|&k| holds[k]) {
                left_out += piece.len();
                for k in piece {
                    empty[k] = false;
                }
            }
        }
    }
    let cell = h * h / (tile_area() * w * w);
    let left_out_tiles = left_out as f64 * cell;
    let mut best: Option<(usize, f64, f64)> = None;
    for region in regions(&empty, nx, ny) {
        let count = region.len();
        if best.is_none_or(|(c, _, _)| count > c) {
            let (sx, sy) = region.iter().fold((0.0, 0.0), |(sx, sy), &k| {
                let (i, j) = (k % nx, k / nx);
                (
                    sx + b.x0 + (i as f64 + 0.5) * h,
                    sy + b.y0 + (j as f64 + 0.5) * h,
                )
            });
            best = Some((count, sx / count as f64, sy / count as f64));
        }
    }
    Measure {
        largest: best.map(|(count, cx, cy)| EmptyRegion {
            tiles: count as f64 * cell,
            centre: (cx, -cy),
        }),
        left_out_tiles,
    }
}

/// The connected regions (four neighbours) of the set grid points of an `nx` by `ny` grid,
/// each as its points' indices, in the order of their first point; by an explicit stack.
fn regions(set: &[bool], nx: usize, ny: usize) -> Vec<Vec<usize>> {
    let mut seen = vec![false; nx * ny];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..nx * ny {
        if !set[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut region = Vec::new();
        while let Some(k) = stack.pop() {
            let (i, j) = (k % nx, k / nx);
            region.push(k);
            let mut visit = |n: usize| {
                if set[n] && !seen[n] {
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
        out.push(region);
    }
    out
}
