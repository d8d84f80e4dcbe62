//! Slabs cut into their pieces (issue 26, "each part swept along its own length"; the
//! boustrophedon cells of Bähnemann et al. 2019): a slab ([`crate::slabs`]) is all of the
//! shape between two cuts across one axis and must be one piece, so a slab beside a hole
//! holds both sides of it and a slab across an anchor holds its shank, crossbar and ring
//! together; the serpentine and the slabs then lay one interval on every line and the
//! other pieces on those lines get no row (BENCHMARKS, "What leaves a part empty at 1000
//! and 3000 tiles": 72% of the tile areas left empty at 3000 tiles).
//!
//! Here the shape is cut at every critical line of one axis ([`crate::slabs`]'s cuts) and
//! each slab that is not one piece is cut again, along the other axis, at the empty lines
//! between its pieces; each piece is a cell swept along its own length (the cheaper of its
//! two directions by the row programme). The cells are laid slab by slab along the axis, the
//! pieces of each slab in turn along the other axis, alternately forwards and backwards (a
//! boustrophedon over the pieces), in both orders; between pieces that do not touch, the
//! route's straight join runs the row on across the gap. Whether the chain folds is the
//! route's fold check's to say, whether the plan is better the rank's. A slab whose pieces
//! overlap along the other axis cannot be cut by a line between them: that decomposition is
//! not made.

use rayon::prelude::*;

use crate::caps::{CapCell, CapPlan, PBox, Raster, Search};
use crate::frame::Orientation;
use crate::rows::Style;
use crate::shape::Shape;
use crate::slabs::{critical_cuts, slab_price};

/// The most cells a piece decomposition may hold (the route's work grows with them).
const MAX_PIECES: usize = 16;
/// The sweep axes cut into pieces: the first of [`crate::cap_plan::cap_axes`] (cheapest by
/// their caps, else in [`crate::cell_plan::axes`]'s order: the drawing's axes first).
const AXES: usize = 6;

/// The piece decompositions of `axis_shape` (axis frame, unit tiles) for rows of `style`,
/// across each axis where some slab is more than one piece, each in both orders; empty
/// when the shape is not one piece.
pub(crate) fn piece_plans(axis_shape: &Shape, style: Style) -> Vec<CapPlan> {
    let r = Raster::new(axis_shape);
    let s = Search::new(&r, style.pitch);
    let Some(b) = s.whole() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for across_x in [true, false] {
        let (lo, hi) = if across_x { (b.x0, b.x1) } else { (b.y0, b.y1) };
        let mut edges = vec![lo];
        edges.extend(critical_cuts(&s, b, across_x, true));
        edges.push(hi);
        edges.dedup();
        let Some(cells) = pieces(axis_shape, &s, b, across_x, &edges, style) else {
            continue;
        };
        let plan = CapPlan {
            cells,
            cost: 0.0,
            slabs: true,
            joined: true,
        };
        let mut rev = plan.clone();
        rev.cells.reverse();
        out.extend([plan, rev]);
    }
    out
}

/// The cells of the slabs of `b` between consecutive `edges` (pixel columns if `across_x`,
/// else rows), each slab cut into its pieces, in boustrophedon order; None when no slab has
/// two pieces, a slab's pieces cannot be cut apart by lines, a piece has no direction whose
/// rows fit, or the pieces are more than [`MAX_PIECES`].
fn pieces(
    axis_shape: &Shape,
    s: &Search<'_>,
    b: PBox,
    across_x: bool,
    edges: &[usize],
    style: Style,
) -> Option<Vec<CapCell>> {
    let mut cells: Vec<CapCell> = Vec::new();
    let mut split = false;
    for (i, e) in edges.windows(2).enumerate() {
        let slab = if across_x {
            PBox {
                x0: e[0],
                x1: e[1],
                ..b
            }
        } else {
            PBox {
                y0: e[0],
                y1: e[1],
                ..b
            }
        };
        let Some(t) = s.tight(slab) else {
            continue;
        };
        let mut parts = apart(s, t, across_x)?;
        split |= parts.len() > 1;
        if i % 2 == 1 {
            parts.reverse();
        }
        for p in parts {
            let prices = slab_price(axis_shape, s, p, style);
            let n = prices
                .iter()
                .copied()
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map(|a| a.1)?;
            cells.push(CapCell {
                rect: s.rect(p),
                n,
                either_sign: true,
                spans: false,
            });
        }
        if cells.len() > MAX_PIECES {
            return None;
        }
    }
    (split && cells.len() > 1).then_some(cells)
}

/// The pieces of the slab `t` (a tight box), cut apart at the empty lines across the slab's
/// lines (pixel rows if `across_x`, else columns), in order; None when a part between two
/// empty lines is not one piece.
fn apart(s: &Search<'_>, t: PBox, across_x: bool) -> Option<Vec<PBox>> {
    if s.components(t) == 1 {
        return Some(vec![t]);
    }
    let (lo, hi, a0, a1) = if across_x {
        (t.y0, t.y1, t.x0, t.x1)
    } else {
        (t.x0, t.x1, t.y0, t.y1)
    };
    let mut out = Vec::new();
    let mut start: Option<usize> = None;
    for k in lo..=hi {
        let filled = k < hi && !s.runs(across_x, k, a0, a1).is_empty();
        match (filled, start) {
            (true, None) => start = Some(k),
            (false, Some(k0)) => {
                let part = if across_x {
                    PBox { y0: k0, y1: k, ..t }
                } else {
                    PBox { x0: k0, x1: k, ..t }
                };
                let part = s.tight(part)?;
                if s.components(part) != 1 {
                    return None;
                }
                out.push(part);
                start = None;
            }
            _ => {}
        }
    }
    (out.len() > 1).then_some(out)
}

/// The piece decompositions of the axes of `all_axes` (`(axis, decompositions, width)`, as
/// [`crate::cap_plan::cap_axes`] gives them) as one group to size, or None when no axis has
/// one.
pub(crate) fn piece_group(
    shape: &Shape,
    all_axes: &[(f64, Vec<CapPlan>, f64)],
    style: Style,
) -> Option<Vec<(f64, Vec<CapPlan>, f64)>> {
    let group: Vec<(f64, Vec<CapPlan>, f64)> = all_axes[..all_axes.len().min(AXES)]
        .par_iter()
        .map(|&(a, _, w)| {
            let axis_shape = Orientation::along(a).work_shape(shape, w);
            (a, piece_plans(&axis_shape, style), w)
        })
        .filter(|g| !g.1.is_empty())
        .collect();
    (!group.is_empty()).then_some(group)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::rows::TIGHT;
    use crate::shape::Ring;
    use crate::slabs::tests::poly;
    use kurbo::{Point, Rect};

    /// A square frame, 30 tile widths across around a hole of 10: the slabs beside the
    /// hole are cut into the parts above and below it, each a cell of its own, and the
    /// cells cover the frame once (no two overlap, none holds the hole).
    #[test]
    fn a_frame_is_cut_into_the_pieces_beside_its_hole() {
        let ring = |p: &[(f64, f64)]| Ring {
            points: p.iter().map(|&q| Point::from(q)).collect(),
        };
        let frame = Shape::from_rings(vec![
            ring(&[(0.0, 0.0), (30.0, 0.0), (30.0, 30.0), (0.0, 30.0)]),
            ring(&[(10.0, 10.0), (10.0, 20.0), (20.0, 20.0), (20.0, 10.0)]),
        ]);
        assert!((frame.area() - 800.0).abs() < 1e-6, "{}", frame.area());
        let plans = piece_plans(&frame, TIGHT);
        assert!(!plans.is_empty());
        for p in &plans {
            assert!(p.cells.len() >= 4, "{p:?}");
            let area: f64 = p.cells.iter().map(|c| frame.clipped(c.rect).area()).sum();
            assert!(
                (area - 800.0).abs() < 20.0,
                "the cells cover it once: {area} {p:?}"
            );
            for c in &p.cells {
                let hole = Rect::new(10.5, 10.5, 19.5, 19.5);
                assert!(c.rect.intersect(hole).area() < 1e-9, "{c:?}");
            }
        }
        // each decomposition in both orders
        let rev: Vec<_> = plans[1].cells.iter().rev().map(|c| c.rect).collect();
        let fwd: Vec<_> = plans[0].cells.iter().map(|c| c.rect).collect();
        assert_eq!(rev, fwd);
    }

    /// A convex shape has no slab of two pieces.
    #[test]
    fn a_square_has_no_pieces() {
        let s = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        assert!(piece_plans(&s, TIGHT).is_empty());
    }
}
