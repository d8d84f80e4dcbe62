//! Empty parts: a plan must not leave a part of the shape that a row could fill without a
//! tile (a ring's band below its hole skipped by one serpentine, a letter's crossbar, a
//! key's bits). The shape is sampled on a grid of an eighth of a tile width; points at
//! least [`EDGE`] inside the outline and farther than [`NEAR`] tile widths from every tile
//! centre are "empty", and a connected group of empty points (four-neighbour) larger than
//! [`MIN_EMPTY_TILES`] tile areas is an empty part (issue 26's measure).

use kurbo::{Point, Rect, Vec2};

use crate::plan::Plan;
use crate::shape::Shape;

/// Sample points farther than this (tile widths) from every tile centre are empty: tight
/// rows sqrt2 apart leave no point of the band between them farther than 0.71 from a
/// centre, and a row of tiles 1 apart none farther than 0.5 along it, so 0.95 flags only
/// what no row reaches (issue 26's measure).
pub(crate) const NEAR: f64 = 0.95;

/// [`NEAR`] for plans of the asked turn style `turns`: loose rows lie `1 + sqrt2` apart, a
/// tile width farther than tight ones, so when the user asks for loose turns their bands
/// reach half of that farther; under `auto` every plan is held to [`NEAR`], so that a loose
/// plan is chosen only where it leaves nothing empty by the measure.
pub(crate) fn near(turns: crate::Turns) -> f64 {
    match turns {
        crate::Turns::Loose => NEAR + 0.5,
        _ => NEAR,
    }
}
/// Only points at least this far (tile widths) inside the outline are sampled: a row along
/// an edge keeps its tile centres half a tile inside it, and slivers thinner than a tile
/// have no room for one.
pub(crate) const EDGE: f64 = 0.5;
/// A connected empty group larger than this many tile areas is an empty part (issue 26:
/// two tile areas; smaller groups are the corners between a round outline and its rows).
pub(crate) const MIN_EMPTY_TILES: f64 = 2.0;
/// A plan that leaves a part larger than this many tile areas empty is set aside, and
/// returned (with a warning saying where) only when no planner finds any other plan; one
/// that leaves a smaller part (but more than [`MIN_EMPTY_TILES`]) is returned only when no
/// plan leaves none, with a warning saying where.
pub(crate) const REFUSE_EMPTY_TILES: f64 = 20.0;
/// The sample spacing, tile widths: an eighth, as the corpus report measures (a coarser
/// grid splits a thin empty strip into pieces that each look small).
const STEP: f64 = 0.125;
/// The sample spacing for plans of more than [`FINE_TILES`] tiles (a bound on the work).
const COARSE_STEP: f64 = 0.25;
/// Plans up to this many tiles are sampled at [`STEP`].
const FINE_TILES: usize = 30_000;
/// Plans with more tiles than this are not checked (the grid would hold millions of
/// points; a part left empty at that size is a small share of the shape).
pub(crate) const MAX_CHECKED_TILES: usize = 200_000;

/// A part of the shape a plan leaves empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmptyPart {
    /// Its area in tile areas.
    pub tiles: f64,
    /// Its centroid, SVG user units.
    pub centre: Point,
    /// Its bounding box, SVG user units (y down).
    pub bbox: Rect,
}

impl std::fmt::Display for EmptyPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "leaves a part of the shape empty: about {:.0} tile areas without a tile, around ({:.0}, {:.0}) (x {:.0} to {:.0}, y {:.0} to {:.0})",
            self.tiles,
            self.centre.x,
            self.centre.y,
            self.bbox.x0,
            self.bbox.x1,
            self.bbox.y0,
            self.bbox.y1
        )
    }
}

/// The largest part of the shape that `plan` leaves empty (see this module's
/// documentation; points farther than `near` tile widths from every centre), in SVG user
/// units, if it has at least [`MIN_EMPTY_TILES`] tile areas.
pub(crate) fn empty_part(shape: &Shape, plan: &Plan, near: f64) -> Option<EmptyPart> {
    let w = plan.tile_size;
    let work = shape.scaled(1.0 / w);
    let centres: Vec<Point> = plan
        .poses
        .iter()
        .map(|p| Point::new(p.x / w, -p.y / w))
        .collect();
    let (tiles, c, b) = largest_empty_part(&work, &centres, near)?;
    Some(EmptyPart {
        tiles,
        centre: Point::new(c.x * w, -c.y * w),
        bbox: Rect::new(b.x0 * w, -b.y1 * w, b.x1 * w, -b.y0 * w),
    })
}

/// The largest empty part of the plan with tile centres `centres` over `work` (both in the
/// work frame, unit tiles): its area in tile areas, its centroid and its bounding box (of
/// the sample points), if it has at least [`MIN_EMPTY_TILES`].
pub(crate) fn largest_empty_part(
    work: &Shape,
    centres: &[Point],
    near: f64,
) -> Option<(f64, Point, Rect)> {
    if centres.is_empty() || centres.len() > MAX_CHECKED_TILES {
        return None;
    }
    let step = if centres.len() <= FINE_TILES {
        STEP
    } else {
        COARSE_STEP
    };
    let b = work.bbox();
    let nx = ((b.width() / step).ceil() as usize).max(1);
    let ny = ((b.height() / step).ceil() as usize).max(1);
    // reached[i * nx + j]: the sample at column j, line i lies within `near` of a tile
    // centre; each centre marks the samples of its disc, line by line (the work grows with
    // the tiles times the samples of one disc, not with the samples times a neighbourhood
    // search)
    let mut reached = vec![false; nx * ny];
    let r2 = near * near;
    // the first sample index at or after `v` and the one after the last at or before `e`
    let first = |v: f64, o: f64| (((v - o) / step) - 0.5).ceil().max(0.0) as usize;
    let end = |v: f64, o: f64| ((((v - o) / step) - 0.5).floor() + 1.0).max(0.0) as usize;
    for c in centres {
        for i in first(c.y - near, b.y0)..end(c.y + near, b.y0).min(ny) {
            let dy = b.y0 + (i as f64 + 0.5) * step - c.y;
            let h2 = r2 - dy * dy;
            if h2 < 0.0 {
                continue;
            }
            let h = h2.sqrt();
            let (j0, j1) = (first(c.x - h, b.x0), end(c.x + h, b.x0).min(nx));
            if j0 < j1 {
                reached[i * nx + j0..i * nx + j1].fill(true);
            }
        }
    }
    // empty[i * nx + j]: the sample at column j, line i lies inside the shape at least
    // EDGE from its outline ([`DeepLine`]) and farther than `near` from every tile centre
    let mut empty = vec![false; nx * ny];
    for i in 0..ny {
        let y = b.y0 + (i as f64 + 0.5) * step;
        // the line's chords, found the first time a sample on it is not reached
        let mut deep_line: Option<DeepLine> = None;
        for (a, e) in work.intervals_at(y) {
            let j0 = (((a - b.x0) / step) - 0.5).ceil().max(0.0) as usize;
            let j1 = ((((e - b.x0) / step) - 0.5).floor().max(-1.0) + 1.0) as usize;
            for j in j0..j1.min(nx) {
                if reached[i * nx + j] {
                    continue;
                }
                empty[i * nx + j] = deep_line
                    .get_or_insert_with(|| DeepLine::new(work, y))
                    .deep(b.x0 + (j as f64 + 0.5) * step);
            }
        }
    }
    let mut seen = vec![false; nx * ny];
    let mut best: Option<(f64, Point, Rect)> = None;
    let mut stack = Vec::new();
    for start in 0..nx * ny {
        if !empty[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut count = 0usize;
        let (mut sum, mut bb) = (
            Vec2::ZERO,
            Rect::new(f64::MAX, f64::MAX, f64::MIN, f64::MIN),
        );
        while let Some(c) = stack.pop() {
            count += 1;
            let (i, j) = (c / nx, c % nx);
            let p = Point::new(
                b.x0 + (j as f64 + 0.5) * step,
                b.y0 + (i as f64 + 0.5) * step,
            );
            sum += p.to_vec2();
            bb = bb.union_pt(p);
            let mut visit = |n: usize| {
                if empty[n] && !seen[n] {
                    seen[n] = true;
                    stack.push(n);
                }
            };
            if j > 0 {
                visit(c - 1);
            }
            if j + 1 < nx {
                visit(c + 1);
            }
            if i > 0 {
                visit(c - nx);
            }
            if i + 1 < ny {
                visit(c + nx);
            }
        }
        let area = count as f64 * step * step / tile_area_exact();
        if area > MIN_EMPTY_TILES && best.is_none_or(|(a, _, _)| area > a) {
            best = Some((area, (sum / count as f64).to_point(), bb));
        }
    }
    best
}

/// The exact area of a tile of width 1, `2 (sqrt2 - 1)`.
fn tile_area_exact() -> f64 {
    2.0 * (std::f64::consts::SQRT_2 - 1.0)
}

/// The points of one line across the shape (at height `y`, work frame) that lie at least
/// [`EDGE`] inside the outline: a point is that deep when the chords of a disc of radius
/// [`EDGE`] about it, on five lines across it, lie inside the shape. The empty-part measure
/// samples only such points; a part of the shape holding none is a sliver no tile fits in
/// ([`crate::caps`] drops those).
pub(crate) struct DeepLine {
    /// Each chord's half width and the shape's intervals on its line.
    lines: Vec<(f64, Vec<(f64, f64)>)>,
}

impl DeepLine {
    /// The line at height `y` across `work`.
    pub(crate) fn new(work: &Shape, y: f64) -> DeepLine {
        DeepLine {
            lines: [-1.0, -0.5, 0.0, 0.5, 1.0]
                .iter()
                .map(|&f: &f64| (EDGE * (1.0 - f * f).sqrt(), work.intervals_at(y + f * EDGE)))
                .collect(),
        }
    }

    /// True if the point at `x` on the line is at least [`EDGE`] inside the outline.
    pub(crate) fn deep(&self, x: f64) -> bool {
        self.lines
            .iter()
            .all(|(hw, iv)| iv.iter().any(|&(a, e)| a <= x - hw && x + hw <= e))
    }
}

/// Checks `plan` for an empty part (points farther than `near` tile widths from every
/// centre, see [`near`]): a part larger than [`REFUSE_EMPTY_TILES`] rejects it (returned with
/// the plan); a smaller one is noted in the plan's metrics and warnings.
pub(crate) fn note_empty(
    shape: &Shape,
    mut plan: Plan,
    near: f64,
) -> Result<Plan, Box<(EmptyPart, Plan)>> {
    match empty_part(shape, &plan, near) {
        None => Ok(plan),
        Some(part) if part.tiles > REFUSE_EMPTY_TILES => Err(Box::new((part, plan))),
        Some(part) => {
            plan.metrics.largest_empty_tiles = part.tiles;
            plan.warnings.push(format!("the plan {part}"));
            Ok(plan)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Ring {
        Ring::rect(x0, y0, x1, y1)
    }

    /// Rows filling the left half of a 20 x 10 rectangle leave the right half empty; rows
    /// over all of it leave nothing.
    #[test]
    fn a_half_filled_rectangle_has_an_empty_part() {
        let shape = Shape::from_rings(vec![rect(0.0, 0.0, 20.0, 10.0)]);
        let rows = |x1: usize| -> Vec<Point> {
            (0..7)
                .flat_map(|k| {
                    (0..x1).map(move |j| Point::new(j as f64 + 0.5, 0.7 + k as f64 * 1.41))
                })
                .collect()
        };
        let (area, p, b) =
            largest_empty_part(&shape, &rows(10), NEAR).expect("the right half is empty");
        assert!(area > 40.0 && p.x > 10.0, "{area} at {p:?}");
        assert!(b.x0 > 10.0 && b.x1 < 20.0 && b.height() > 8.0, "{b:?}");
        assert!(largest_empty_part(&shape, &rows(20), NEAR).is_none());
    }
}
