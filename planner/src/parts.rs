//! The separate parts of a drawing, decided once from its outline and so the same at every
//! tile count (issue 26: if a drawing plans at N tiles, it plans at every count above).
//!
//! - A *part* is a connected piece of the filled area (the union of the filled elements, as
//!   `i_overlay` groups an outer contour with its holes); pieces closer than [`GAP`] of the
//!   drawing's size (the reading's precision: each curve is flattened within half of it)
//!   are one part, so a hairline a tracing left between two pieces, or two pieces touching
//!   at a point, does not split a drawing.
//! - The *islands* are the smallest parts, as many as are together under [`ISLAND_SHARE`] of
//!   the drawing's filled area: they are left out of the plan, with a warning naming them,
//!   at every count (one chain cannot reach them; a map's islets, a logo's dot). A budget
//!   for them together, not a share each, so that a drawing of many small pieces (a stipple,
//!   a logo's letters) is not planned as its largest piece alone.
//! - A drawing with two or more parts besides is refused, at every count, naming them.
//!
//! Before, a part counted only where it held half a tile at the asked count, so a drawing
//! with islands planned at low counts (the islands under a tile, dropped) and was refused at
//! high ones (mapsicon's Russia, Ecuador, Kuwait, Sint Maarten at 100 and 300 tiles against
//! 1000).

use kurbo::{Line, ParamCurveNearest, Point, Rect};

use crate::clip::filled_pieces;
use crate::drawing::FLATTEN_TOLERANCE;
use crate::shape::{FilledPath, Ring, Shape};

/// Pieces of the filled area closer than this share of the drawing's larger side are one
/// part: twice the flattening tolerance, the most by which two curves drawn touching can
/// come apart when each is flattened.
pub(crate) const GAP: f64 = 2.0 * FLATTEN_TOLERANCE;

/// The smallest parts, together under this share of the drawing's filled area, are islands,
/// left out.
pub(crate) const ISLAND_SHARE: f64 = 0.05;

/// A separate part of a drawing.
#[derive(Clone, Debug)]
pub(crate) struct Part {
    /// Its contours (physical frame), filled by the even-odd rule.
    pub(crate) rings: Vec<Ring>,
    /// Its area.
    pub(crate) area: f64,
    /// Its bounding box (physical frame).
    pub(crate) bbox: Rect,
}

/// What a drawing's parts allow.
#[derive(Debug)]
pub(crate) enum Parts {
    /// One part (islands aside): the shape to plan (`None`: the drawing as read, for a
    /// drawing in one piece), and the islands left out, largest first.
    One {
        /// The shape without its islands, if it has any.
        shape: Option<Shape>,
        /// The islands left out.
        islands: Vec<Part>,
    },
    /// Two or more parts besides the islands (largest first), and the islands.
    Several {
        /// The large parts.
        large: Vec<Part>,
        /// The islands.
        islands: Vec<Part>,
    },
}

/// The shape's parts (see the module doc).
pub(crate) fn split(shape: &Shape) -> Parts {
    let mut parts = parts(shape);
    if parts.len() < 2 {
        return Parts::One {
            shape: None,
            islands: Vec::new(),
        };
    }
    let total: f64 = parts.iter().map(|p| p.area).sum();
    // the smallest parts, while together under the budget
    let mut left_out = 0.0;
    let n_islands = parts
        .iter()
        .rev()
        .take_while(|p| {
            left_out += p.area;
            left_out < ISLAND_SHARE * total
        })
        .count()
        .min(parts.len() - 1);
    let n_large = parts.len() - n_islands;
    let islands = parts.split_off(n_large);
    if parts.len() > 1 {
        return Parts::Several {
            large: parts,
            islands,
        };
    }
    let kept = parts.remove(0);
    Parts::One {
        shape: Some(Shape::from_paths(vec![FilledPath {
            rings: kept.rings,
            even_odd: true,
        }])),
        islands,
    }
}

/// The separate parts of the shape, largest first (pieces within [`GAP`] of each other
/// joined).
pub(crate) fn parts(shape: &Shape) -> Vec<Part> {
    let pieces: Vec<Part> = filled_pieces(shape.paths())
        .into_iter()
        .map(|rings| {
            let area = rings.iter().map(Ring::signed_area).sum::<f64>().abs();
            let bbox = bounds(&rings);
            Part { rings, area, bbox }
        })
        .collect();
    let gap = GAP * shape.size();
    // union-find over the pieces: joined where any two of their edges come within `gap`
    let mut root: Vec<usize> = (0..pieces.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for i in 0..pieces.len() {
        for j in i + 1..pieces.len() {
            let (ri, rj) = (find(&mut root, i), find(&mut root, j));
            if ri != rj && near(&pieces[i], &pieces[j], gap) {
                root[ri] = rj;
            }
        }
    }
    let mut joined: Vec<Option<Part>> = vec![None; pieces.len()];
    for (i, p) in pieces.into_iter().enumerate() {
        let r = find(&mut root, i);
        match &mut joined[r] {
            Some(q) => {
                q.area += p.area;
                q.bbox = q.bbox.union(p.bbox);
                q.rings.extend(p.rings);
            }
            slot => *slot = Some(p),
        }
    }
    let mut out: Vec<Part> = joined.into_iter().flatten().collect();
    out.sort_by(|a, b| b.area.total_cmp(&a.area));
    out
}

/// The bounding box of the rings' points.
fn bounds(rings: &[Ring]) -> Rect {
    let mut points = rings.iter().flat_map(|r| r.points.iter().copied());
    let first = points.next().unwrap_or_default();
    points.fold(Rect::from_points(first, first), |b, p| b.union_pt(p))
}

/// Whether two pieces (whose areas do not overlap) come within `gap` of each other: only
/// the edges that meet both boxes grown by `gap` are compared.
fn near(a: &Part, b: &Part, gap: f64) -> bool {
    let (ga, gb) = (a.bbox.inflate(gap, gap), b.bbox.inflate(gap, gap));
    let r = Rect::new(
        ga.x0.max(gb.x0),
        ga.y0.max(gb.y0),
        ga.x1.min(gb.x1),
        ga.y1.min(gb.y1),
    );
    if r.x0 > r.x1 || r.y0 > r.y1 {
        return false;
    }
    let meets = |(p, q): &(Point, Point)| {
        p.x.max(q.x) >= r.x0 && p.x.min(q.x) <= r.x1 && p.y.max(q.y) >= r.y0 && p.y.min(q.y) <= r.y1
    };
    let edges = |part: &Part| -> Vec<(Point, Point)> {
        part.rings
            .iter()
            .flat_map(Ring::edges)
            .filter(|e| meets(e))
            .collect()
    };
    let (ea, eb) = (edges(a), edges(b));
    ea.iter().any(|&(p, q)| {
        eb.iter().any(|&(s, t)| {
            // segments that do not cross are nearest at an end of one of them
            seg_dist(p, s, t)
                .min(seg_dist(q, s, t))
                .min(seg_dist(s, p, q))
                .min(seg_dist(t, p, q))
                <= gap
        })
    })
}

/// The distance from `p` to the segment `a`-`b`.
fn seg_dist(p: Point, a: Point, b: Point) -> f64 {
    Line::new(a, b).nearest(p, 0.0).distance_sq.sqrt()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Ring {
        Ring::rect(x, y, x + s, y + s)
    }

    /// A drawing in one piece is planned as read; a small piece apart is an island, left
    /// out; two large pieces are several parts; pieces a hairline apart are one part.
    #[test]
    fn parts_islands_and_hairlines() {
        let one = Shape::from_rings(vec![square(0.0, 0.0, 100.0)]);
        assert!(matches!(split(&one), Parts::One { shape: None, .. }));
        // an island of 4% of the area
        let isle = Shape::from_rings(vec![square(0.0, 0.0, 100.0), square(120.0, 0.0, 20.8)]);
        match split(&isle) {
            Parts::One {
                shape: Some(s),
                islands,
            } => {
                assert_eq!(islands.len(), 1);
                assert!((s.area() - 10_000.0).abs() < 1e-2, "{}", s.area());
                assert!((islands[0].bbox.x0 - 120.0).abs() < 1e-3);
            }
            other => panic!("{other:?}"),
        }
        // two islands of 2% each: left out together
        let two_isles = Shape::from_rings(vec![
            square(0.0, 0.0, 100.0),
            square(120.0, 0.0, 14.5),
            square(120.0, 50.0, 14.5),
        ]);
        assert!(matches!(split(&two_isles), Parts::One { islands, .. } if islands.len() == 2));
        // three of 2% each, 6% together: the smallest two left out, the drawing refused
        let three = Shape::from_rings(vec![
            square(0.0, 0.0, 100.0),
            square(120.0, 0.0, 14.5),
            square(120.0, 30.0, 14.4),
            square(120.0, 60.0, 14.3),
        ]);
        match split(&three) {
            Parts::Several { large, islands } => {
                assert_eq!((large.len(), islands.len()), (2, 2));
                assert!((large[1].bbox.y0 - 0.0).abs() < 1e-3, "{:?}", large[1].bbox);
            }
            other => panic!("{other:?}"),
        }
        // a second part of 6%: refused, whatever the count
        let two = Shape::from_rings(vec![square(0.0, 0.0, 100.0), square(120.0, 0.0, 25.0)]);
        match split(&two) {
            Parts::Several { large, islands } => {
                assert_eq!((large.len(), islands.len()), (2, 0));
            }
            other => panic!("{other:?}"),
        }
        // a hairline (0.1 of a 145-unit drawing: under GAP) between two large pieces
        let hair = Shape::from_rings(vec![square(0.0, 0.0, 100.0), square(100.1, 0.0, 45.0)]);
        assert!(matches!(split(&hair), Parts::One { islands, .. } if islands.is_empty()));
        assert_eq!(parts(&hair).len(), 1);
        // two squares touching at a corner
        let corner = Shape::from_rings(vec![square(0.0, 0.0, 50.0), square(50.0, 50.0, 50.0)]);
        assert_eq!(parts(&corner).len(), 1);
    }
}
