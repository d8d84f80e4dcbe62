//! The target shape: the filled areas of an SVG drawing as polygons, and the queries the
//! planner asks of them (row intervals, point inside, monotone directions).
//!
//! Coordinates are held in the *physical* frame: SVG user units with y flipped (y up), so
//! that the drawing is seen from above in a right-handed frame and an L fold turns
//! counter-clockwise, as in `foldchain::kinematics`.

use usvg::tiny_skia_path::{PathSegment, Point};

use crate::PlanError;

/// Curve flattening tolerance, as a share of the larger side of the drawing's bounding box:
/// every flattened curve lies within this distance of the true curve. 1e-3 of the drawing is
/// under 0.5 percent of a tile for plans of up to about 200,000 tiles, far below what the
/// chain can resolve.
pub const FLATTEN_TOLERANCE: f64 = 1e-3;

/// A closed polygon (the last point joins the first).
#[derive(Clone, Debug, PartialEq)]
pub struct Ring {
    /// The vertices.
    pub points: Vec<(f64, f64)>,
}

/// One filled element: its rings and fill rule.
#[derive(Clone, Debug, PartialEq)]
struct FilledPath {
    rings: Vec<Ring>,
    even_odd: bool,
}

/// The target shape: the union of filled paths, each filled by its own rule.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    paths: Vec<FilledPath>,
    /// Bounding box `(xmin, ymin, xmax, ymax)`.
    bbox: (f64, f64, f64, f64),
}

impl Shape {
    /// Reads an SVG document; `name` names it in errors. Checks that it has filled area and
    /// that no outline crosses itself.
    pub fn from_svg_data(data: &[u8], name: &str) -> Result<Shape, PlanError> {
        let bad = |reason: String| PlanError::BadSvg {
            name: name.to_string(),
            reason,
        };
        let tree = usvg::Tree::from_data(data, &usvg::Options::default())
            .map_err(|e| bad(e.to_string()))?;
        let to_user = user_units_transform(data, &tree);
        let mut raw: Vec<(String, Vec<Vec<Seg>>, bool)> = Vec::new();
        collect_paths(tree.root(), &mut raw, to_user);
        if raw.is_empty() {
            return Err(PlanError::NoFilledArea {
                name: name.to_string(),
                reason: "no visible element with a fill (fill=\"none\" and strokes do not count)"
                    .into(),
            });
        }
        let mut lo = (f64::INFINITY, f64::INFINITY);
        let mut hi = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for (_, subpaths, _) in &raw {
            for sp in subpaths {
                for s in sp {
                    for &(x, y) in s.points() {
                        lo = (lo.0.min(x), lo.1.min(y));
                        hi = (hi.0.max(x), hi.1.max(y));
                    }
                }
            }
        }
        let size = (hi.0 - lo.0).max(hi.1 - lo.1);
        if !size.is_finite() || size <= 0.0 {
            return Err(PlanError::NoFilledArea {
                name: name.to_string(),
                reason: "the filled elements have zero size".into(),
            });
        }
        let tol = FLATTEN_TOLERANCE * size;
        let mut paths = Vec::new();
        for (element, subpaths, even_odd) in raw {
            let mut rings = Vec::new();
            for sp in subpaths {
                let ring = flatten(&sp, tol);
                if ring.points.len() >= 3 {
                    if let Some((i, j, p)) = self_intersection(&ring) {
                        return Err(PlanError::SelfIntersecting {
                            name: name.to_string(),
                            element: element.clone(),
                            first: i,
                            second: j,
                            x: p.0,
                            y: -p.1,
                        });
                    }
                    if ring_area(&ring).abs() > 1e-12 * size * size {
                        rings.push(ring);
                    }
                }
            }
            if !rings.is_empty() {
                paths.push(FilledPath { rings, even_odd });
            }
        }
        let shape = Shape::from_paths(paths);
        if shape.paths.is_empty() || shape.area() <= 1e-9 * size * size {
            return Err(PlanError::NoFilledArea {
                name: name.to_string(),
                reason: "the filled elements enclose no area".into(),
            });
        }
        Ok(shape)
    }

    /// A shape from rings in the physical frame (y up), all filled by the non-zero rule as
    /// one path: holes are rings wound the other way.
    pub fn from_rings(rings: Vec<Ring>) -> Shape {
        Shape::from_paths(vec![FilledPath {
            rings,
            even_odd: false,
        }])
    }

    fn from_paths(paths: Vec<FilledPath>) -> Shape {
        let mut b = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for p in &paths {
            for r in &p.rings {
                for &(x, y) in &r.points {
                    b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
                }
            }
        }
        Shape { paths, bbox: b }
    }

    /// The bounding box `(xmin, ymin, xmax, ymax)`.
    pub fn bbox(&self) -> (f64, f64, f64, f64) {
        self.bbox
    }

    /// Every ring, for drawing.
    pub fn rings(&self) -> impl Iterator<Item = &Ring> {
        self.paths.iter().flat_map(|p| p.rings.iter())
    }

    /// The number of polygon edges.
    pub fn edge_count(&self) -> usize {
        self.rings().map(|r| r.points.len()).sum()
    }

    /// The shape turned by `angle` radians counter-clockwise about the origin.
    pub fn rotated(&self, angle: f64) -> Shape {
        let (s, c) = angle.sin_cos();
        self.mapped(|(x, y)| (c * x - s * y, s * x + c * y))
    }

    /// The shape mirrored: x scaled by `sx`, y by `sy` (each +1 or -1).
    pub fn mirrored(&self, sx: f64, sy: f64) -> Shape {
        self.mapped(|(x, y)| (sx * x, sy * y))
    }

    /// The shape scaled by `k` about the origin.
    pub fn scaled(&self, k: f64) -> Shape {
        self.mapped(|(x, y)| (k * x, k * y))
    }

    /// The shape under the affine map `p -> L p + t` (`L` row-major).
    pub(crate) fn affine(&self, l: [f64; 4], t: (f64, f64)) -> Shape {
        self.mapped(|(x, y)| (l[0] * x + l[1] * y + t.0, l[2] * x + l[3] * y + t.1))
    }

    fn mapped(&self, f: impl Fn((f64, f64)) -> (f64, f64)) -> Shape {
        Shape::from_paths(
            self.paths
                .iter()
                .map(|p| FilledPath {
                    even_odd: p.even_odd,
                    rings: p
                        .rings
                        .iter()
                        .map(|r| Ring {
                            points: r.points.iter().map(|&q| f(q)).collect(),
                        })
                        .collect(),
                })
                .collect(),
        )
    }

    /// The intervals (sorted, disjoint) where the horizontal line at `y` lies inside the
    /// shape.
    pub fn intervals_at(&self, y: f64) -> Vec<(f64, f64)> {
        let mut all: Vec<(f64, f64)> = Vec::new();
        let mut crossings: Vec<(f64, i32)> = Vec::new();
        for p in &self.paths {
            crossings.clear();
            for r in &p.rings {
                let n = r.points.len();
                for i in 0..n {
                    let (x0, y0) = r.points[i];
                    let (x1, y1) = r.points[(i + 1) % n];
                    // half-open rule: counts each vertex once
                    if (y0 <= y) != (y1 <= y) {
                        let t = (y - y0) / (y1 - y0);
                        crossings.push((x0 + t * (x1 - x0), if y1 > y0 { 1 } else { -1 }));
                    }
                }
            }
            crossings.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut wind = 0i32;
            let mut start = 0.0;
            for &(x, d) in &crossings {
                let was = if p.even_odd { wind % 2 != 0 } else { wind != 0 };
                wind += d;
                let now = if p.even_odd { wind % 2 != 0 } else { wind != 0 };
                if !was && now {
                    start = x;
                } else if was && !now && x > start {
                    all.push((start, x));
                }
            }
        }
        union_intervals(all)
    }

    /// True if the point lies inside the shape.
    pub fn contains(&self, (x, y): (f64, f64)) -> bool {
        self.intervals_at(y).iter().any(|&(a, b)| a <= x && x <= b)
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

    fn vertex_heights(&self) -> Vec<f64> {
        let mut ys: Vec<f64> = self
            .rings()
            .flat_map(|r| r.points.iter().map(|p| p.1))
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
    fn first_split(&self, limit: usize) -> Option<(usize, f64)> {
        let ys = self.vertex_heights();
        let size = (self.bbox.2 - self.bbox.0).max(self.bbox.3 - self.bbox.1);
        let mut best: Option<(usize, f64)> = None;
        let mut seen = 0;
        for w in ys.windows(2) {
            if w[1] - w[0] <= 1e-12 * size {
                continue;
            }
            let y = 0.5 * (w[0] + w[1]);
            let iv = self.intervals_at(y);
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
                    break;
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
        use std::f64::consts::PI;
        let mut cands: Vec<f64> = (0..360).map(|i| i as f64 * PI / 360.0).collect();
        if self.edge_count() <= 400 {
            let mut e: Vec<f64> = Vec::new();
            for r in self.rings() {
                let n = r.points.len();
                for i in 0..n {
                    let (a, b) = (r.points[i], r.points[(i + 1) % n]);
                    e.push((b.1 - a.1).atan2(b.0 - a.0).rem_euclid(PI));
                }
            }
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
        use std::f64::consts::PI;
        let mut e: Vec<(f64, f64)> = Vec::new();
        for r in self.rings() {
            let n = r.points.len();
            for i in 0..n {
                let (a, b) = (r.points[i], r.points[(i + 1) % n]);
                let len = (b.0 - a.0).hypot(b.1 - a.1);
                e.push((len, (b.1 - a.1).atan2(b.0 - a.0).rem_euclid(PI)));
            }
        }
        e.sort_by(|a, b| b.0.total_cmp(&a.0));
        e.into_iter().take(count).map(|x| x.1).collect()
    }
}

/// Merges intervals into a sorted disjoint list.
pub(crate) fn union_intervals(mut v: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(v.len());
    for (a, b) in v {
        match out.last_mut() {
            Some(last) if a <= last.1 => last.1 = last.1.max(b),
            _ => out.push((a, b)),
        }
    }
    out
}

/// Signed area (counter-clockwise positive).
fn ring_area(r: &Ring) -> f64 {
    let n = r.points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (r.points[i], r.points[(i + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum::<f64>()
        * 0.5
}

/// A segment of a sub-path, already in the physical frame.
#[derive(Clone, Debug)]
enum Seg {
    Line([(f64, f64); 2]),
    Quad([(f64, f64); 3]),
    Cubic([(f64, f64); 4]),
}

impl Seg {
    fn points(&self) -> &[(f64, f64)] {
        match self {
            Seg::Line(p) => p,
            Seg::Quad(p) => p,
            Seg::Cubic(p) => p,
        }
    }
}

/// The transform from usvg's output coordinates back to the root element's user units:
/// usvg wraps everything in one group holding the viewBox mapping (and the root's own
/// transform), which is undone here so that plans are in the drawing's user units.
fn user_units_transform(data: &[u8], tree: &usvg::Tree) -> usvg::Transform {
    let id = usvg::Transform::identity();
    let Ok(text) = std::str::from_utf8(data) else {
        return id;
    };
    let Ok(doc) = usvg::roxmltree::Document::parse(text) else {
        return id;
    };
    let root = doc.root_element();
    let has_ts = root.attribute("transform").is_some();
    // usvg adds the wrapper only when the viewBox mapping is not the identity
    let size = tree.size();
    let vb_moves = root.attribute("viewBox").is_some_and(|vb| {
        let v: Vec<f64> = vb
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|t| !t.is_empty())
            .filter_map(|t| t.parse().ok())
            .collect();
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-6 * (1.0 + b.abs());
        !(v.len() == 4
            && same(v[0], 0.0)
            && same(v[1], 0.0)
            && same(v[2], size.width() as f64)
            && same(v[3], size.height() as f64))
    });
    let children = tree.root().children();
    if (vb_moves || has_ts) && children.len() == 1 {
        if let usvg::Node::Group(g) = &children[0] {
            let t = g.transform();
            if !t.is_identity() {
                return t.invert().unwrap_or(id);
            }
        }
    }
    id
}

fn collect_paths(
    group: &usvg::Group,
    out: &mut Vec<(String, Vec<Vec<Seg>>, bool)>,
    to_user: usvg::Transform,
) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => collect_paths(g, out, to_user),
            usvg::Node::Path(p) => {
                let Some(fill) = p.fill() else { continue };
                if !p.is_visible() {
                    continue;
                }
                let ts = p.abs_transform().post_concat(to_user);
                let map = |pt: Point| {
                    let mut q = pt;
                    ts.map_point(&mut q);
                    (q.x as f64, -(q.y as f64))
                };
                let mut subpaths: Vec<Vec<Seg>> = Vec::new();
                let mut cur: Vec<Seg> = Vec::new();
                let mut start = (0.0, 0.0);
                let mut last = (0.0, 0.0);
                for seg in p.data().segments() {
                    match seg {
                        PathSegment::MoveTo(a) => {
                            if !cur.is_empty() {
                                subpaths.push(std::mem::take(&mut cur));
                            }
                            start = map(a);
                            last = start;
                        }
                        PathSegment::LineTo(a) => {
                            let b = map(a);
                            cur.push(Seg::Line([last, b]));
                            last = b;
                        }
                        PathSegment::QuadTo(a, b) => {
                            let (a, b) = (map(a), map(b));
                            cur.push(Seg::Quad([last, a, b]));
                            last = b;
                        }
                        PathSegment::CubicTo(a, b, c) => {
                            let (a, b, c) = (map(a), map(b), map(c));
                            cur.push(Seg::Cubic([last, a, b, c]));
                            last = c;
                        }
                        PathSegment::Close => {
                            if last != start {
                                cur.push(Seg::Line([last, start]));
                            }
                            last = start;
                        }
                    }
                }
                if !cur.is_empty() {
                    subpaths.push(cur);
                }
                let element = if p.id().is_empty() {
                    format!("filled element #{}", out.len() + 1)
                } else {
                    format!("element id=\"{}\"", p.id())
                };
                let even_odd = fill.rule() == usvg::FillRule::EvenOdd;
                out.push((element, subpaths, even_odd));
            }
            _ => {}
        }
    }
}

/// Flattens a sub-path (closed implicitly, as a fill is) to a ring within `tol`.
fn flatten(segs: &[Seg], tol: f64) -> Ring {
    let mut pts: Vec<(f64, f64)> = Vec::new();
    let push = |pts: &mut Vec<(f64, f64)>, p: (f64, f64)| {
        if pts.last() != Some(&p) {
            pts.push(p);
        }
    };
    for s in segs {
        match s {
            Seg::Line([a, b]) => {
                push(&mut pts, *a);
                push(&mut pts, *b);
            }
            Seg::Quad([a, b, c]) => {
                // chord error <= |a - 2b + c| / (4 n^2)
                let d = (a.0 - 2.0 * b.0 + c.0).hypot(a.1 - 2.0 * b.1 + c.1);
                let n = ((d / (4.0 * tol)).sqrt().ceil() as usize).clamp(1, 10_000);
                push(&mut pts, *a);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    push(
                        &mut pts,
                        (
                            u * u * a.0 + 2.0 * u * t * b.0 + t * t * c.0,
                            u * u * a.1 + 2.0 * u * t * b.1 + t * t * c.1,
                        ),
                    );
                }
            }
            Seg::Cubic([a, b, c, d]) => {
                // chord error <= 0.75 * max|second differences| / n^2
                let d1 = (a.0 - 2.0 * b.0 + c.0).hypot(a.1 - 2.0 * b.1 + c.1);
                let d2 = (b.0 - 2.0 * c.0 + d.0).hypot(b.1 - 2.0 * c.1 + d.1);
                let n = ((0.75 * d1.max(d2) / tol).sqrt().ceil() as usize).clamp(1, 10_000);
                push(&mut pts, *a);
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    let u = 1.0 - t;
                    let (k0, k1, k2, k3) = (u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t);
                    push(
                        &mut pts,
                        (
                            k0 * a.0 + k1 * b.0 + k2 * c.0 + k3 * d.0,
                            k0 * a.1 + k1 * b.1 + k2 * c.1 + k3 * d.1,
                        ),
                    );
                }
            }
        }
    }
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    Ring { points: pts }
}

/// The first pair of non-adjacent edges of a ring that meet, with a meeting point.
fn self_intersection(r: &Ring) -> Option<(usize, usize, (f64, f64))> {
    let n = r.points.len();
    let seg = |i: usize| (r.points[i], r.points[(i + 1) % n]);
    // sort edges by min x, sweep
    let mut order: Vec<usize> = (0..n).collect();
    let minx = |i: usize| {
        let (a, b) = seg(i);
        a.0.min(b.0)
    };
    order.sort_by(|&i, &j| minx(i).total_cmp(&minx(j)));
    for (k, &i) in order.iter().enumerate() {
        let (a, b) = seg(i);
        let maxx = a.0.max(b.0);
        for &j in &order[k + 1..] {
            if minx(j) > maxx {
                break;
            }
            let adjacent = (i + 1) % n == j || (j + 1) % n == i;
            if adjacent || i == j {
                continue;
            }
            let (c, d) = seg(j);
            if let Some(p) = segments_meet(a, b, c, d) {
                return Some((i.min(j), i.max(j), p));
            }
        }
    }
    None
}

fn segments_meet(a: (f64, f64), b: (f64, f64), c: (f64, f64), d: (f64, f64)) -> Option<(f64, f64)> {
    let cross = |o: (f64, f64), p: (f64, f64), q: (f64, f64)| {
        (p.0 - o.0) * (q.1 - o.1) - (p.1 - o.1) * (q.0 - o.0)
    };
    let d1 = cross(c, d, a);
    let d2 = cross(c, d, b);
    let d3 = cross(a, b, c);
    let d4 = cross(a, b, d);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        let t = d1 / (d1 - d2);
        return Some((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
    }
    None
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn svg(body: &str) -> String {
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">{body}</svg>"#)
    }

    #[test]
    fn rect_area_and_intervals() {
        let s = Shape::from_svg_data(
            svg(r#"<rect x="10" y="20" width="30" height="40"/>"#).as_bytes(),
            "t",
        )
        .unwrap();
        assert!((s.area() - 1200.0).abs() < 1e-6, "{}", s.area());
        let iv = s.intervals_at(-30.0);
        assert_eq!(iv.len(), 1);
        assert!((iv[0].0 - 10.0).abs() < 1e-9 && (iv[0].1 - 40.0).abs() < 1e-9);
    }

    #[test]
    fn viewbox_gives_user_units() {
        let t = r#"<svg xmlns="http://www.w3.org/2000/svg" width="10cm" height="10cm" viewBox="0 0 10 10"><rect x="1" y="1" width="4" height="2"/></svg>"#;
        let s = Shape::from_svg_data(t.as_bytes(), "t").unwrap();
        assert!((s.area() - 8.0).abs() < 1e-4, "{}", s.area());
    }

    #[test]
    fn circle_area_within_tolerance() {
        let s = Shape::from_svg_data(svg(r#"<circle cx="50" cy="50" r="40"/>"#).as_bytes(), "t")
            .unwrap();
        let exact = std::f64::consts::PI * 1600.0;
        assert!((s.area() - exact).abs() / exact < 0.01, "{}", s.area());
    }

    #[test]
    fn evenodd_hole() {
        let t = svg(r#"<path fill-rule="evenodd" d="M0 0H90V90H0Z M30 30H60V60H30Z"/>"#);
        let s = Shape::from_svg_data(t.as_bytes(), "t").unwrap();
        assert!((s.area() - (8100.0 - 900.0)).abs() < 1e-6);
        assert!(!s.contains((45.0, -45.0)));
        assert!(s.contains((10.0, -45.0)));
        // nonzero with the same winding: no hole
        let t = svg(r#"<path d="M0 0H90V90H0Z M30 30H60V60H30Z"/>"#);
        let s = Shape::from_svg_data(t.as_bytes(), "t").unwrap();
        assert!(s.contains((45.0, -45.0)));
    }

    #[test]
    fn bowtie_is_self_intersecting() {
        let t = svg(r#"<polygon id="bow" points="0,0 50,50 50,0 0,50"/>"#);
        let e = Shape::from_svg_data(t.as_bytes(), "bow.svg").unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("bow.svg") && m.contains("bow") && m.contains("self-intersecting"),
            "{m}"
        );
        assert!(e.is_bad_input());
    }

    #[test]
    fn no_fill_and_bad_xml() {
        let t = svg(r#"<rect width="10" height="10" fill="none" stroke="black"/>"#);
        let e = Shape::from_svg_data(t.as_bytes(), "x.svg").unwrap_err();
        assert!(matches!(e, PlanError::NoFilledArea { .. }), "{e}");
        let e = Shape::from_svg_data(b"<svg><rect", "y.svg").unwrap_err();
        assert!(
            matches!(e, PlanError::BadSvg { .. }) && e.to_string().contains("y.svg"),
            "{e}"
        );
    }

    #[test]
    fn crescent_like_monotone_in_one_axis_only() {
        // a C open to the right: rows parallel to y (vertical) meet it in two pieces,
        // horizontal rows in one
        let t = svg(r#"<path d="M0 0H60V15H20V45H60V60H0Z"/>"#);
        let s = Shape::from_svg_data(t.as_bytes(), "t").unwrap();
        assert!(s.is_monotone_for_rows(0.0));
        assert!(!s.is_monotone_for_rows(std::f64::consts::FRAC_PI_2));
    }
}
