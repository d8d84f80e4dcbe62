//! The target shape: filled polygons, and the queries the planner asks of them (row
//! intervals, point inside, area, monotone directions, long edges). Reading a shape from an
//! SVG drawing is [`crate::drawing`]'s part.
//!
//! Coordinates are held in the *physical* frame: SVG user units with y flipped (y up), so
//! that the drawing is seen from above in a right-handed frame and an L fold turns
//! counter-clockwise, as in `foldchain::kinematics`. Points, boxes and maps are kurbo's
//! [`Point`], [`Rect`] and [`Affine`], the workspace's one 2-D vocabulary.

use std::f64::consts::PI;

use kurbo::{Affine, Point, Rect};

/// A closed polygon (the last point joins the first).
#[derive(Clone, Debug, PartialEq)]
pub struct Ring {
    /// The vertices.
    pub points: Vec<Point>,
}

impl Ring {
    /// The axis-aligned rectangle from `(x0, y0)` to `(x1, y1)` (tests).
    #[cfg(test)]
    pub(crate) fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Ring {
        Ring {
            points: vec![
                Point::new(x0, y0),
                Point::new(x1, y0),
                Point::new(x1, y1),
                Point::new(x0, y1),
            ],
        }
    }

    /// The edges `(from, to)`, the last one closing the ring.
    pub(crate) fn edges(&self) -> impl Iterator<Item = (Point, Point)> + '_ {
        let n = self.points.len();
        (0..n).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }

    /// Signed area (counter-clockwise positive).
    pub(crate) fn signed_area(&self) -> f64 {
        self.edges()
            .map(|(a, b)| a.x * b.y - b.x * a.y)
            .sum::<f64>()
            * 0.5
    }
}

/// One filled element: its rings and fill rule.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct FilledPath {
    pub rings: Vec<Ring>,
    pub even_odd: bool,
}

/// The target shape: the union of filled paths, each filled by its own rule.
#[derive(Clone, Debug)]
pub struct Shape {
    paths: Vec<FilledPath>,
    bbox: Rect,
    /// The edges bucketed by height, built on the first row query.
    index: std::sync::OnceLock<EdgeIndex>,
}

impl Shape {
    /// The shape bit for bit (each path's fill rule, rings and vertices): the same for two
    /// shapes only if every row query answers them alike.
    pub(crate) fn bits(&self) -> Vec<u64> {
        let mut out = Vec::new();
        for p in &self.paths {
            out.extend([u64::from(p.even_odd), p.rings.len() as u64]);
            for r in &p.rings {
                out.push(r.points.len() as u64);
                out.extend(r.points.iter().flat_map(|q| [q.x.to_bits(), q.y.to_bits()]));
            }
        }
        out
    }
}

impl PartialEq for Shape {
    fn eq(&self, other: &Shape) -> bool {
        self.paths == other.paths
    }
}

/// The edges of a shape bucketed by height: bucket `i` holds every edge (with the index of
/// its filled path) whose height range meets `[y0 + i h, y0 + (i + 1) h]`, so a row query
/// looks at the edges near its line only, not at every edge of the outline.
#[derive(Clone, Debug)]
struct EdgeIndex {
    y0: f64,
    /// Buckets per unit of height.
    per: f64,
    /// `edges[start[i]..start[i + 1]]`: bucket `i`, its edges in outline order.
    start: Vec<usize>,
    edges: Vec<(usize, Point, Point)>,
}

/// Bucket entries an [`EdgeIndex`] holds per edge at most, on average over the outline.
const SPANNED_PER_EDGE: f64 = 8.0;
/// Edge evaluations spent at most, over one sweep of [`Shape::first_split`], on lines at
/// heights where edges of overlapping rings cross (each line costs the edges across it):
/// rings given to [`Shape::from_rings`] may overlap, and an outline whose rings cross each
/// other everywhere has crossings as the square of its edges. Beyond it, slabs are tested
/// at their middle only.
const MAX_CROSSING_WORK: usize = 20_000_000;

impl EdgeIndex {
    fn new(paths: &[FilledPath], bbox: Rect) -> EdgeIndex {
        let edges: usize = paths
            .iter()
            .flat_map(|p| &p.rings)
            .map(|r| r.points.len())
            .sum();
        let h = bbox.height().max(1e-12);
        // the edges' heights together, in heights of the shape: an edge is put in every
        // bucket it spans
        let spans: f64 = paths
            .iter()
            .flat_map(|p| p.rings.iter().flat_map(Ring::edges))
            .map(|(a, b)| (a.y - b.y).abs() / h)
            .sum();
        // about two edges a bucket on average, at most 65,536 buckets, and at most
        // SPANNED_PER_EDGE bucket entries an edge over all (a fine zigzag of tall edges put
        // 200,000 edges in a thousand buckets each: 5 GB); the buckets only narrow what a
        // row query looks at, so their number changes no answer
        let n = (edges / 2)
            .min((SPANNED_PER_EDGE * edges as f64 / spans.max(1e-12)) as usize)
            .clamp(1, 1 << 16);
        let per = n as f64 / h;
        // each edge with the buckets it spans, in outline order; then the buckets laid out
        // one after another (compressed rows), each holding its edges in that order
        let spans = || {
            paths.iter().enumerate().flat_map(move |(pi, p)| {
                p.rings.iter().flat_map(Ring::edges).map(move |(a, b)| {
                    let lo = a.y.min(b.y);
                    let hi = a.y.max(b.y);
                    let i0 = (((lo - bbox.y0) * per).floor().max(0.0) as usize).min(n - 1);
                    let i1 = (((hi - bbox.y0) * per).floor().max(0.0) as usize).min(n - 1);
                    (pi, a, b, i0, i1)
                })
            })
        };
        let mut start = vec![0usize; n + 1];
        for (_, _, _, i0, i1) in spans() {
            for c in &mut start[i0 + 1..=i1 + 1] {
                *c += 1;
            }
        }
        for i in 1..=n {
            start[i] += start[i - 1];
        }
        let mut fill = start.clone();
        let mut edges = vec![(0, Point::ZERO, Point::ZERO); start[n]];
        for (pi, a, b, i0, i1) in spans() {
            for f in &mut fill[i0..=i1] {
                edges[*f] = (pi, a, b);
                *f += 1;
            }
        }
        EdgeIndex {
            y0: bbox.y0,
            per,
            start,
            edges,
        }
    }

    /// The edges (with their path) that may cross the line at `y`, grouped by path.
    fn near(&self, y: f64) -> &[(usize, Point, Point)] {
        let i = ((y - self.y0) * self.per).floor();
        if !(i >= 0.0 && (i as usize) + 1 < self.start.len()) {
            return &[];
        }
        let i = i as usize;
        &self.edges[self.start[i]..self.start[i + 1]]
    }
}

impl Shape {
    /// A shape from rings in the physical frame (y up), all filled by the non-zero rule as
    /// one path: holes are rings wound the other way.
    pub fn from_rings(rings: Vec<Ring>) -> Shape {
        Shape::from_paths(vec![FilledPath {
            rings,
            even_odd: false,
        }])
    }

    pub(crate) fn from_paths(paths: Vec<FilledPath>) -> Shape {
        let mut b = Rect::new(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for p in paths
            .iter()
            .flat_map(|p| p.rings.iter().flat_map(|r| &r.points))
        {
            b = Rect::new(b.x0.min(p.x), b.y0.min(p.y), b.x1.max(p.x), b.y1.max(p.y));
        }
        Shape {
            paths,
            bbox: b,
            index: std::sync::OnceLock::new(),
        }
    }

    /// The filled paths, each with its rings and fill rule.
    pub(crate) fn paths(&self) -> &[FilledPath] {
        &self.paths
    }

    /// Whether the shape has no filled path.
    pub(crate) fn is_empty(&self) -> bool {
        self.paths.is_empty()
    }

    /// The bounding box.
    pub fn bbox(&self) -> Rect {
        self.bbox
    }

    /// The larger side of the bounding box.
    pub(crate) fn size(&self) -> f64 {
        self.bbox.width().max(self.bbox.height())
    }

    /// Every ring, for drawing.
    pub fn rings(&self) -> impl Iterator<Item = &Ring> {
        self.paths.iter().flat_map(|p| p.rings.iter())
    }

    /// Every edge of every ring.
    fn edges(&self) -> impl Iterator<Item = (Point, Point)> + '_ {
        self.rings().flat_map(Ring::edges)
    }

    /// The number of polygon edges.
    pub fn edge_count(&self) -> usize {
        self.rings().map(|r| r.points.len()).sum()
    }

    /// The shape turned by `angle` radians counter-clockwise about the origin.
    pub fn rotated(&self, angle: f64) -> Shape {
        self.transformed(Affine::rotate(angle))
    }

    /// The shape mirrored: x scaled by `sx`, y by `sy` (each +1 or -1).
    pub fn mirrored(&self, sx: f64, sy: f64) -> Shape {
        self.transformed(Affine::scale_non_uniform(sx, sy))
    }

    /// The shape scaled by `k` about the origin.
    pub fn scaled(&self, k: f64) -> Shape {
        self.transformed(Affine::scale(k))
    }

    /// The shape under the affine map `a`.
    pub fn transformed(&self, a: Affine) -> Shape {
        Shape::from_paths(
            self.map_rings(|r| {
                Some(Ring {
                    points: r.points.iter().map(|&q| a * q).collect(),
                })
            })
            .collect(),
        )
    }

    /// The paths with each ring replaced by `f` of it (left out where `f` gives `None`), each
    /// path keeping its fill rule.
    fn map_rings<'a>(
        &'a self,
        f: impl Fn(&Ring) -> Option<Ring> + 'a,
    ) -> impl Iterator<Item = FilledPath> + 'a {
        self.paths.iter().map(move |p| FilledPath {
            even_odd: p.even_odd,
            rings: p.rings.iter().filter_map(&f).collect(),
        })
    }

    /// The shape clipped to the box `r` (each ring by Sutherland-Hodgman against the box's
    /// four sides: a ring that leaves the box and comes back keeps a stretch along the side,
    /// which has no area and adds no interval).
    pub(crate) fn clipped(&self, r: Rect) -> Shape {
        let clip = |pts: Vec<Point>,
                    inside: &dyn Fn(Point) -> bool,
                    cross: &dyn Fn(Point, Point) -> Point| {
            let n = pts.len();
            let mut out = Vec::with_capacity(n + 4);
            for i in 0..n {
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                match (inside(a), inside(b)) {
                    (true, true) => out.push(b),
                    (true, false) => out.push(cross(a, b)),
                    (false, true) => {
                        out.push(cross(a, b));
                        out.push(b);
                    }
                    (false, false) => {}
                }
            }
            out
        };
        let at_x = |x: f64| {
            move |a: Point, b: Point| {
                let t = (x - a.x) / (b.x - a.x);
                Point::new(x, a.y + t * (b.y - a.y))
            }
        };
        let at_y = |y: f64| {
            move |a: Point, b: Point| {
                let t = (y - a.y) / (b.y - a.y);
                Point::new(a.x + t * (b.x - a.x), y)
            }
        };
        Shape::from_paths(
            self.map_rings(|ring| {
                let mut pts = ring.points.clone();
                pts = clip(pts, &|q| q.x >= r.x0, &at_x(r.x0));
                pts = clip(pts, &|q| q.x <= r.x1, &at_x(r.x1));
                pts = clip(pts, &|q| q.y >= r.y0, &at_y(r.y0));
                pts = clip(pts, &|q| q.y <= r.y1, &at_y(r.y1));
                (pts.len() >= 3).then_some(Ring { points: pts })
            })
            .filter(|p| !p.rings.is_empty())
            .collect(),
        )
    }

    /// The intervals (sorted, disjoint) where the horizontal line at `y` lies inside the
    /// shape.
    pub fn intervals_at(&self, y: f64) -> Vec<(f64, f64)> {
        let mut out = Vec::new();
        self.intervals_into(y, &mut out);
        out
    }

    /// [`Shape::intervals_at`] into `out` (cleared first), so that a caller asking many lines
    /// reuses one buffer; the crossings are gathered in a buffer kept per thread.
    pub(crate) fn intervals_into(&self, y: f64, out: &mut Vec<(f64, f64)>) {
        out.clear();
        let index = self
            .index
            .get_or_init(|| EdgeIndex::new(&self.paths, self.bbox));
        self.intervals_of(index.near(y), y, out);
    }

    /// The intervals where the horizontal line at `y` lies inside the shape, from `edges`
    /// (with the index of their filled path, grouped by path, each path's in outline order):
    /// every edge of the shape that crosses the line must be among them; appended to `out`,
    /// which is then sorted and made disjoint.
    fn intervals_of(&self, edges: &[(usize, Point, Point)], y: f64, out: &mut Vec<(f64, f64)>) {
        thread_local! {
            static CROSSINGS: std::cell::RefCell<Vec<(f64, i32)>> =
                const { std::cell::RefCell::new(Vec::new()) };
        }
        if edges.is_empty() {
            return;
        }
        CROSSINGS.with_borrow_mut(|crossings| {
            let mut at = 0;
            while at < edges.len() {
                // the edges of one filled path lie together in the bucket
                let pi = edges[at].0;
                let mut end = at;
                crossings.clear();
                while end < edges.len() && edges[end].0 == pi {
                    let (_, a, b) = edges[end];
                    // half-open rule: counts each vertex once
                    if (a.y <= y) != (b.y <= y) {
                        let t = (y - a.y) / (b.y - a.y);
                        crossings.push((a.x + t * (b.x - a.x), if b.y > a.y { 1 } else { -1 }));
                    }
                    end += 1;
                }
                at = end;
                let even_odd = self.paths[pi].even_odd;
                crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
                let mut wind = 0i32;
                let mut start = 0.0;
                for &(x, d) in crossings.iter() {
                    let was = if even_odd { wind % 2 != 0 } else { wind != 0 };
                    wind += d;
                    let now = if even_odd { wind % 2 != 0 } else { wind != 0 };
                    if !was && now {
                        start = x;
                    } else if was && !now && x > start {
                        out.push((start, x));
                    }
                }
            }
        });
        union_in_place(out);
    }

    /// True if the point lies inside the shape.
    pub fn contains(&self, p: Point) -> bool {
        self.intervals_at(p.y)
            .iter()
            .any(|&(a, b)| a <= p.x && p.x <= b)
    }

    /// The area (by integrating row lengths across horizontal slabs between vertex heights,
    /// four Gauss-free midpoint samples a slab: exact for polygons whose outlines do not
    /// cross inside a slab, close otherwise).
    pub fn area(&self) -> f64 {
        let ys = self.vertex_heights();
        let mut a = 0.0;
        for w in ys.windows(2) {
            let h = w[1] - w[0];
            if h <= 0.0 {
                continue;
            }
            for k in 0..4 {
                let y = w[0] + h * (k as f64 + 0.5) / 4.0;
                a += self.intervals_at(y).iter().map(|(p, q)| q - p).sum::<f64>() * h / 4.0;
            }
        }
        a
    }

    /// The heights of all vertices, sorted, without repeats.
    pub(crate) fn vertex_heights(&self) -> Vec<f64> {
        let mut ys: Vec<f64> = self
            .rings()
            .flat_map(|r| r.points.iter().map(|p| p.y))
            .collect();
        ys.sort_by(f64::total_cmp);
        ys.dedup();
        ys
    }

    /// The largest number of pieces in which a horizontal line meets the shape, tested
    /// between consecutive vertex heights (exact for polygons). Gaps narrower than
    /// `1e-9` of the shape's size are not counted.
    pub fn max_pieces(&self) -> usize {
        self.first_split(usize::MAX).map_or(1, |(n, _)| n)
    }

    /// The first height at which a horizontal line meets the shape in more than one piece,
    /// with the number of pieces; stops after `limit` splits are counted (returns the
    /// largest seen).
    ///
    /// A sweep from the lowest vertex up: the edges that span each slab between vertex
    /// heights are kept as the line rises (added when it passes their lower end, dropped at
    /// their upper one), so each line looks only at the edges it crosses; the work is the
    /// sorting of the edges plus, per slab, the edges across it (two per slab for a shape a
    /// line meets once), not the edges times the slabs, and stopping at the first split costs
    /// nothing more. Lines meet the edges in the order [`Shape::intervals_at`] sees them, so
    /// the pieces are the same.
    fn first_split(&self, limit: usize) -> Option<(usize, f64)> {
        let ys = self.vertex_heights();
        let size = self.size();
        let mut best: Option<(usize, f64)> = None;
        let mut seen = 0;
        // every edge (outline order, with its path), by its lower end
        let edges: Vec<(usize, Point, Point)> = self
            .paths
            .iter()
            .enumerate()
            .flat_map(|(pi, p)| {
                p.rings
                    .iter()
                    .flat_map(Ring::edges)
                    .map(move |(a, b)| (pi, a, b))
            })
            .collect();
        let mut by_low: Vec<usize> = (0..edges.len()).collect();
        by_low.sort_by(|&i, &j| {
            edges[i]
                .1
                .y
                .min(edges[i].2.y)
                .total_cmp(&edges[j].1.y.min(edges[j].2.y))
        });
        let mut next = 0;
        // the edges across the current line, by their place in the outline
        let mut active: Vec<usize> = Vec::new();
        let mut across: Vec<(usize, Point, Point)> = Vec::new();
        let mut iv: Vec<(f64, f64)> = Vec::new();
        let (mut order, mut heights): (Vec<(f64, f64)>, Vec<f64>) = (Vec::new(), Vec::new());
        // the work spent on crossing heights (a bound for outlines whose rings cross
        // everywhere; beyond it, slabs are tested at their middle only)
        let mut budget = MAX_CROSSING_WORK;
        for w in ys.windows(2) {
            if w[1] - w[0] <= 1e-12 * size {
                continue;
            }
            let y = 0.5 * (w[0] + w[1]);
            while next < by_low.len() && {
                let (_, a, b) = edges[by_low[next]];
                a.y.min(b.y) < y
            } {
                active.push(by_low[next]);
                next += 1;
            }
            active.retain(|&i| edges[i].1.y.max(edges[i].2.y) > y);
            active.sort_unstable();
            across.clear();
            across.extend(active.iter().map(|&i| edges[i]));
            // where edges of overlapping rings cross inside the slab, the pieces change at
            // the crossings: a line between every two of them is tested too
            heights.clear();
            if budget > 0 {
                // each swap of the sort and each line costs about the edges across
                let k = across.len().max(1);
                crossing_heights(&across, (w[0], w[1]), budget / k, &mut order, &mut heights);
                heights.truncate(budget / k);
                budget -= (heights.len() * k).min(budget);
            }
            heights.push(w[0]);
            heights.push(w[1]);
            heights.sort_by(f64::total_cmp);
            let lines: Vec<f64> = if heights.len() == 2 {
                vec![y]
            } else {
                heights
                    .windows(2)
                    .filter(|h| h[1] - h[0] > 1e-12 * size)
                    .map(|h| 0.5 * (h[0] + h[1]))
                    .collect()
            };
            for y in lines {
                iv.clear();
                self.intervals_of(&across, y, &mut iv);
                let pieces = 1 + iv
                    .windows(2)
                    .filter(|p| p[1].0 - p[0].1 > 1e-9 * size)
                    .count();
                if pieces > 1 {
                    if best.is_none_or(|(n, _)| pieces > n) {
                        best = Some((pieces, y));
                    }
                    seen += 1;
                    if seen >= limit {
                        return best;
                    }
                }
            }
        }
        best
    }

    /// True if every line at angle `row_angle` (radians, physical frame) meets the shape in
    /// at most one piece: the shape is monotone to the direction orthogonal to it.
    pub fn is_monotone_for_rows(&self, row_angle: f64) -> bool {
        self.rotated(-row_angle).first_split(1).is_none()
    }

    /// Row angles in `[0, pi)` (physical frame) for which the shape is monotone: tested at a
    /// 0.5 degree grid and, for outlines of up to 400 edges, at every edge direction and
    /// between consecutive edge directions (the monotone directions form arcs whose ends are
    /// edge directions, so this finds every arc).
    pub fn monotone_row_angles(&self) -> Vec<f64> {
        let mut cands: Vec<f64> = (0..360).map(|i| i as f64 * PI / 360.0).collect();
        if self.edge_count() <= 400 {
            let mut e: Vec<f64> = self.edges().map(|(a, b)| edge_angle(a, b)).collect();
            e.sort_by(f64::total_cmp);
            e.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
            for i in 0..e.len() {
                let next = if i + 1 < e.len() { e[i + 1] } else { e[0] + PI };
                cands.push(e[i]);
                cands.push((0.5 * (e[i] + next)).rem_euclid(PI));
            }
        }
        cands.sort_by(f64::total_cmp);
        cands.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        cands
            .into_iter()
            .filter(|&a| self.is_monotone_for_rows(a))
            .collect()
    }

    /// The directions of the longest edges (row angles in `[0, pi)`), longest first: rows
    /// parallel to long straight sides fit them best.
    pub fn long_edge_angles(&self, count: usize) -> Vec<f64> {
        let mut e: Vec<(f64, f64)> = self
            .edges()
            .map(|(a, b)| ((b.x - a.x).hypot(b.y - a.y), edge_angle(a, b)))
            .collect();
        e.sort_by(|a, b| b.0.total_cmp(&a.0));
        e.into_iter().take(count).map(|x| x.1).collect()
    }
}

/// The direction of the edge from `a` to `b` as a row angle in `[0, pi)`.
fn edge_angle(a: Point, b: Point) -> f64 {
    (b.y - a.y).atan2(b.x - a.x).rem_euclid(PI)
}

/// The heights strictly inside the slab `(y0, y1)` at which two of `edges` (each spanning
/// the whole slab) cross, appended to `out`. Edges are ordered by where they meet the
/// slab's bottom and insertion-sorted by where they meet its top: every swap is one
/// crossing, so the work is the edges plus the crossings (none for rings that do not
/// overlap, whose edges meet only at vertices); it stops after `max` crossings. `order` is
/// scratch space.
fn crossing_heights(
    edges: &[(usize, Point, Point)],
    (y0, y1): (f64, f64),
    max: usize,
    order: &mut Vec<(f64, f64)>,
    out: &mut Vec<f64>,
) {
    let x_at = |a: Point, b: Point, y: f64| a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
    order.clear();
    order.extend(
        edges
            .iter()
            .map(|&(_, a, b)| (x_at(a, b, y0), x_at(a, b, y1))),
    );
    order.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.total_cmp(&q.1)));
    for i in 1..order.len() {
        let mut j = i;
        while j > 0 && order[j - 1].1 > order[j].1 {
            let (p, q) = (order[j - 1], order[j]);
            // x of p minus x of q goes from (p.0 - q.0) <= 0 at y0 to (p.1 - q.1) > 0 at y1
            let (d0, d1) = (p.0 - q.0, p.1 - q.1);
            let t = -d0 / (d1 - d0);
            let h = y0 + t * (y1 - y0);
            if h > y0 && h < y1 {
                out.push(h);
                if out.len() >= max {
                    return;
                }
            }
            order.swap(j - 1, j);
            j -= 1;
        }
    }
}

/// Merges intervals into a sorted disjoint list, in place.
fn union_in_place(v: &mut Vec<(f64, f64)>) {
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut len = 0;
    for i in 0..v.len() {
        let (a, b) = v[i];
        if len > 0 && a <= v[len - 1].1 {
            v[len - 1].1 = v[len - 1].1.max(b);
        } else {
            v[len] = (a, b);
            len += 1;
        }
    }
    v.truncate(len);
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, side: f64, ccw: bool) -> Ring {
        let mut points = vec![
            Point::new(x0, y0),
            Point::new(x0 + side, y0),
            Point::new(x0 + side, y0 + side),
            Point::new(x0, y0 + side),
        ];
        if !ccw {
            points.reverse();
        }
        Ring { points }
    }

    #[test]
    fn a_hole_wound_the_other_way_is_left_out() {
        let s = Shape::from_rings(vec![
            square(0.0, 0.0, 9.0, true),
            square(3.0, 3.0, 3.0, false),
        ]);
        assert!((s.area() - 72.0).abs() < 1e-9, "{}", s.area());
        assert_eq!(s.intervals_at(4.5), vec![(0.0, 3.0), (6.0, 9.0)]);
        assert!(!s.contains(Point::new(4.5, 4.5)) && s.contains(Point::new(1.0, 4.5)));
        assert_eq!(s.max_pieces(), 2);
        assert!((square(0.0, 0.0, 2.0, false).signed_area() + 4.0).abs() < 1e-12);
    }

    #[test]
    fn transforms_move_the_box() {
        let s = Shape::from_rings(vec![square(1.0, 2.0, 1.0, true)]);
        let r = s.rotated(PI / 2.0).bbox();
        assert!(
            (r.x0 + 3.0).abs() < 1e-12 && (r.y1 - 2.0).abs() < 1e-12,
            "{r:?}"
        );
        let m = s.mirrored(-1.0, 1.0).scaled(2.0).bbox();
        assert_eq!((m.x0, m.x1, m.y0, m.y1), (-4.0, -2.0, 4.0, 6.0));
    }

    /// A bar of length 100 and width 10 centred at the origin, turned by `deg` degrees
    /// (counter-clockwise ring).
    fn bar(deg: f64) -> Ring {
        let (sin, cos) = deg.to_radians().sin_cos();
        let points = [(-50.0, -5.0), (50.0, -5.0), (50.0, 5.0), (-50.0, 5.0)]
            .iter()
            .map(|&(x, y)| Point::new(x * cos - y * sin, x * sin + y * cos))
            .collect();
        Ring { points }
    }

    /// Two bars crossing as an X between two plates, given as four overlapping rings: the
    /// bars' vertices lie at the heights +-25 +-4.33 inside the plates (y 20 to 35 and -35
    /// to -20), so the slab between vertex heights -20 and 20 is one piece at its middle,
    /// where the bars cross, and two above and below the crossing; every other slab is one
    /// piece. The sweep tests a line between every two heights where edges cross too.
    #[test]
    fn overlapping_rings_split_between_vertex_heights() {
        let plate = |y0: f64| Ring::rect(-60.0, y0, 60.0, y0 + 15.0);
        let x = Shape::from_rings(vec![bar(30.0), bar(-30.0), plate(20.0), plate(-35.0)]);
        assert_eq!(x.intervals_at(0.0).len(), 1);
        assert_eq!(x.intervals_at(25.0).len(), 1);
        assert_eq!(x.intervals_at(15.0).len(), 2);
        assert!(!x.is_monotone_for_rows(0.0));
        assert_eq!(x.max_pieces(), 2);
        // along the bars' middle line the X is two pieces too; one bar alone is monotone
        let one = Shape::from_rings(vec![bar(30.0)]);
        assert!(one.is_monotone_for_rows(0.0));
        assert_eq!(one.max_pieces(), 1);
        // two squares at 5 degrees overlapping (last session's case) stay one piece at
        // every height, and the sweep says so
        let sq = Shape::from_rings(vec![square(0.0, 0.0, 10.0, true), {
            let (sin, cos) = 5f64.to_radians().sin_cos();
            let mut r = square(2.0, 2.0, 10.0, true);
            for p in &mut r.points {
                *p = Point::new(p.x * cos - p.y * sin, p.x * sin + p.y * cos);
            }
            r
        }]);
        let pieces = (1..200)
            .map(|i| sq.intervals_at(-1.0 + i as f64 * 0.07).len())
            .max()
            .unwrap();
        assert_eq!(sq.max_pieces(), pieces);
    }
}
