//! An SVG path as the planner reads it: its sub-paths as kurbo segments in the physical
//! frame ([`path_segments`]), each flattened to a ring within a tolerance ([`flatten`]), by
//! the rules the recorded plans were made with. Read by the drawing ([`crate::drawing`]) and
//! by its clip paths and masks ([`crate::clip`]).

use kurbo::{CubicBez, Line, ParamCurve, PathSeg, Point, QuadBez, Vec2};
use usvg::tiny_skia_path::PathSegment;

use crate::shape::Ring;

/// The sub-paths of `p` under the transform `ts` (usvg's `f32` arithmetic), as kurbo
/// segments in the physical frame (y negated).
pub(crate) fn path_segments(p: &usvg::Path, ts: usvg::Transform) -> Vec<Vec<PathSeg>> {
    let map = |mut q: usvg::tiny_skia_path::Point| {
        ts.map_point(&mut q);
        Point::new(q.x as f64, -(q.y as f64))
    };
    let mut subpaths: Vec<Vec<PathSeg>> = Vec::new();
    let mut cur: Vec<PathSeg> = Vec::new();
    let mut start = Point::ZERO;
    let mut last = Point::ZERO;
    for seg in p.data().segments() {
        let next = match seg {
            PathSegment::MoveTo(a) => {
                if !cur.is_empty() {
                    subpaths.push(std::mem::take(&mut cur));
                }
                start = map(a);
                last = start;
                continue;
            }
            PathSegment::LineTo(a) => PathSeg::Line(Line::new(last, map(a))),
            PathSegment::QuadTo(a, b) => PathSeg::Quad(QuadBez::new(last, map(a), map(b))),
            PathSegment::CubicTo(a, b, c) => {
                PathSeg::Cubic(CubicBez::new(last, map(a), map(b), map(c)))
            }
            PathSegment::Close => {
                let close = last != start;
                let line = Line::new(last, start);
                last = start;
                if !close {
                    continue;
                }
                PathSeg::Line(line)
            }
        };
        last = next.end();
        cur.push(next);
    }
    if !cur.is_empty() {
        subpaths.push(cur);
    }
    subpaths
}

/// Flattens a sub-path (closed implicitly, as a fill is) to a ring within `tol`.
///
/// Each curve is cut into `n` equal steps of its parameter, `n` from the bound on the chord
/// error by the second differences of its control points (quadratic: `|p0 - 2 p1 + p2| /
/// (4 n^2)`; cubic: `0.75 max |second differences| / n^2`). This is the planner's rule from
/// before the refactor to kurbo, kept on purpose: kurbo's own adaptive flattening
/// (`kurbo::flatten`) places fewer, different points, which changes the polygons and so the
/// plans recorded in tests/golden.
pub(crate) fn flatten(segs: &[PathSeg], tol: f64) -> Ring {
    let mut pts: Vec<Point> = Vec::new();
    let push = |pts: &mut Vec<Point>, p: Point| {
        if pts.last() != Some(&p) {
            pts.push(p);
        }
    };
    // |a - 2b + c|: the second difference of three control points
    let second = |a: Point, b: Point, c: Point| {
        let v: Vec2 = a.to_vec2() - b.to_vec2() * 2.0 + c.to_vec2();
        v.x.hypot(v.y)
    };
    for s in segs {
        let n = match *s {
            PathSeg::Line(_) => 1,
            PathSeg::Quad(q) => {
                let d = second(q.p0, q.p1, q.p2);
                ((d / (4.0 * tol)).sqrt().ceil() as usize).clamp(1, 10_000)
            }
            PathSeg::Cubic(c) => {
                let d = second(c.p0, c.p1, c.p2).max(second(c.p1, c.p2, c.p3));
                ((0.75 * d / tol).sqrt().ceil() as usize).clamp(1, 10_000)
            }
        };
        push(&mut pts, s.start());
        if let PathSeg::Line(l) = s {
            push(&mut pts, l.p1);
            continue;
        }
        for i in 1..=n {
            push(&mut pts, bernstein(s, i as f64 / n as f64));
        }
    }
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    Ring { points: pts }
}

/// The point at `t` of a curve, by its Bernstein form summed term by term. kurbo's `eval`
/// (a Horner-like form) differs from it in the last bit, which moves a flattened circle's
/// bounding box and with it the fit's sample grid: the plans recorded before the refactor
/// (tests/golden) were made with this form.
fn bernstein(s: &PathSeg, t: f64) -> Point {
    let u = 1.0 - t;
    let mix = |terms: &[(f64, Point)]| {
        let sum = |f: fn(Point) -> f64| {
            terms
                .iter()
                .map(|&(k, p)| k * f(p))
                .reduce(|a, b| a + b)
                .unwrap_or(0.0)
        };
        Point::new(sum(|p| p.x), sum(|p| p.y))
    };
    match *s {
        PathSeg::Line(l) => mix(&[(u, l.p0), (t, l.p1)]),
        PathSeg::Quad(q) => mix(&[(u * u, q.p0), (2.0 * u * t, q.p1), (t * t, q.p2)]),
        PathSeg::Cubic(c) => mix(&[
            (u * u * u, c.p0),
            (3.0 * u * u * t, c.p1),
            (3.0 * u * t * t, c.p2),
            (t * t * t, c.p3),
        ]),
    }
}
