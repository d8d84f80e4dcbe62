//! Empty parts: a plan must not leave a part of the shape that a row could fill without a
//! tile (a ring's band below its hole skipped by one serpentine, a letter's crossbar, a
//! key's bits). The shape is sampled on a grid of an eighth of a tile width; points at
//! least [`EDGE`] inside the outline and farther than [`NEAR`] tile widths from every tile
//! centre are "empty", and a connected group of empty points (four-neighbour) larger than
//! [`MIN_EMPTY_TILES`] tile areas is an empty part (issue 26's measure).

use kurbo::{Point, Rect, Vec2};

use crate::centre_grid::{ceil_i64, floor_i64};
use crate::plan::Plan;
use crate::shape::Shape;

pub(crate) use crate::centre_grid::NEAR;

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
/// The price of one tile area of a part left empty beyond the [`MIN_EMPTY_TILES`]
/// allowance, in tile areas of misfit: ten turns at the default turn cost
/// ([`crate::options::DEFAULT_TURN_COST`], one tile area a turn). The one rule by which plans
/// trade empty area against turns and fit ([`plan_cost`]), in the cell router, the caps' width
/// search and the top level: a plan that fills the shape with a few more turns wins over one
/// that leaves a part half a tile area over the allowance, and one with a few tenths of a
/// tile area more empty and half the turns wins over a plan with twice its turns (the key at
/// 171 tiles: 2.4 tile areas empty in four cells with 12 turns rank before 2.1 in one
/// serpentine with 22 turns: 4 + 12 against 1 + 22). An estimate, like the turn cost: a
/// part left empty is what issue 26 measures a plan by, a turn what folding time and risk
/// grow with.
pub(crate) const EMPTY_PRICE: f64 = 10.0;

/// The tile areas of a largest empty part `tiles` beyond the [`MIN_EMPTY_TILES`] allowance
/// (0 for none: parts up to the allowance are not counted, so the price has no step there).
pub(crate) fn excess_empty(tiles: f64) -> f64 {
    (tiles - MIN_EMPTY_TILES).max(0.0)
}

/// The share of a plan's chain that may lie outside the shape before each tile beyond it
/// is priced like a tile area left empty ([`EMPTY_PRICE`], see [`plan_cost`]): the
/// area-true fit keeps plans within it (`plan_cells`' limit), and a smaller empty part
/// bought with much of the chain outside does not draw the shape better (the dog at 150
/// tiles: 13.9% outside). A price, not a tier: the frog at 300 tiles, one serpentine with
/// 9.6% outside and 4.5 tile areas empty, ranked after cells with 8.9% outside and 19.2
/// empty while plans over 9% outside ranked last.
pub(crate) const MAX_OUTSIDE_RANKED: f64 = 0.09;

/// The outside tier of a plan: 0 for a plan that leaves no part empty or has at most 5% of
/// its chain outside, 1 for one that leaves a part empty with more outside (a smaller empty
/// part is not bought with much of the chain outside: the ring at 200 tiles). Plans rank
/// by it first (after the count).
fn outside_tier(p: &Plan) -> u8 {
    u8::from(p.metrics.largest_empty_tiles > 0.0 && p.metrics.outside_share > 0.05)
}

/// A plan's cost, as a share of the shape's area: its fit and turns
/// ([`crate::fit::plan_score`]) plus [`EMPTY_PRICE`] tile areas per tile area of its largest
/// empty part beyond the allowance and per tile of its chain outside the shape beyond
/// [`MAX_OUTSIDE_RANKED`] of it. Lower is better.
pub(crate) fn plan_cost(p: &Plan, turn_cost: f64) -> f64 {
    let area_tiles = p.metrics.shape_area / (p.tile_size * p.tile_size);
    let outside = (p.metrics.outside_share - MAX_OUTSIDE_RANKED).max(0.0) * p.tiles as f64;
    let priced = if area_tiles > 0.0 {
        EMPTY_PRICE * (excess_empty(p.metrics.largest_empty_tiles) + outside) / area_tiles
    } else {
        0.0
    };
    crate::fit::plan_score(p, turn_cost) + priced
}

/// The key by which measured plans rank (least first), after the count: the outside tier
/// ([`outside_tier`]), then [`plan_cost`].
pub(crate) fn rank_key(p: &Plan, turn_cost: f64) -> (u8, OrdF64) {
    (outside_tier(p), OrdF64(plan_cost(p, turn_cost)))
}

/// The cost of a plan in the tile-width search (0 for one that leaves nothing empty, so
/// that the retries go on while the best plan leaves a part empty): the outside tier, then
/// the tile areas beyond the allowance. Among widths whose plans all leave a part empty the
/// least empty wins; a width's own plans were ranked by [`rank_key`].
pub(crate) fn empty_cost(p: &Plan) -> f64 {
    if p.metrics.largest_empty_tiles <= 0.0 {
        return 0.0;
    }
    // a part just over the allowance still costs something (the retries go on)
    1e-3 + excess_empty(p.metrics.largest_empty_tiles) + 1e6 * f64::from(outside_tier(p))
}

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
    largest(empty_parts(shape, plan, near), |p| p.tiles)
}

/// Every part of the shape that `plan` leaves empty with more than [`MIN_EMPTY_TILES`] tile
/// areas, as [`empty_part`] measures them, in the order they are found.
pub(crate) fn empty_parts(shape: &Shape, plan: &Plan, near: f64) -> Vec<EmptyPart> {
    let w = plan.tile_size;
    let work = shape.scaled(1.0 / w);
    let centres: Vec<Point> = plan
        .poses
        .iter()
        .map(|p| Point::new(p.x / w, -p.y / w))
        .collect();
    all_empty_parts(&work, &centres, near)
        .into_iter()
        .map(|(tiles, c, b)| EmptyPart {
            tiles,
            centre: Point::new(c.x * w, -c.y * w),
            bbox: Rect::new(b.x0 * w, -b.y1 * w, b.x1 * w, -b.y0 * w),
        })
        .collect()
}

/// The first of `items` with the largest `size`.
fn largest<T>(items: Vec<T>, size: impl Fn(&T) -> f64) -> Option<T> {
    items.into_iter().fold(None, |best, p| match best {
        Some(b) if size(&p) <= size(&b) => Some(b),
        _ => Some(p),
    })
}

/// The largest empty part of [`all_empty_parts`], if any.
pub(crate) fn largest_empty_part(
    work: &Shape,
    centres: &[Point],
    near: f64,
) -> Option<(f64, Point, Rect)> {
    largest(all_empty_parts(work, centres, near), |p| p.0)
}

/// The empty parts of the plan with tile centres `centres` over `work` (both in the work
/// frame, unit tiles) larger than [`MIN_EMPTY_TILES`], in the order they are found: each
/// one's area in tile areas, its centroid and its bounding box (of the sample points).
fn all_empty_parts(work: &Shape, centres: &[Point], near: f64) -> Vec<(f64, Point, Rect)> {
    if centres.is_empty() || centres.len() > MAX_CHECKED_TILES {
        return Vec::new();
    }
    let step = if centres.len() <= FINE_TILES {
        STEP
    } else {
        COARSE_STEP
    };
    let b = work.bbox();
    let nx = ((b.width() / step).ceil() as usize).max(1);
    let ny = ((b.height() / step).ceil() as usize).max(1);
    // state[i * nx + j] of the sample at column j, line i: REACHED when it lies within
    // `near` of a tile centre; each centre marks the samples of its disc, line by line (the
    // work grows with the tiles times the samples of one disc, not with the samples times a
    // neighbourhood search)
    let mut state = vec![FAR; nx * ny];
    let r2 = near * near;
    // the first sample index at or after `v` and the one after the last at or before `e`
    // (`ceil`/`floor` without libm: the values are finite)
    let first = |v: f64, o: f64| ceil_i64(((v - o) / step) - 0.5).max(0) as usize;
    let end = |v: f64, o: f64| (floor_i64(((v - o) / step) - 0.5) + 1).max(0) as usize;
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
                state[i * nx + j0..i * nx + j1].fill(REACHED);
            }
        }
    }
    // EMPTY: the sample lies inside the shape at least EDGE from its outline ([`DeepLine`])
    // and farther than `near` from every tile centre; `empties` lists them in ascending
    // order (lines up, intervals and columns left to right), the order the parts are
    // started from
    let mut empties: Vec<usize> = Vec::new();
    for i in 0..ny {
        let y = b.y0 + (i as f64 + 0.5) * step;
        // the line's chords, found the first time a sample on it is not reached
        let mut deep_line: Option<DeepLine> = None;
        for (a, e) in work.intervals_at(y) {
            let j0 = ceil_i64(((a - b.x0) / step) - 0.5).max(0) as usize;
            let j1 = (floor_i64(((e - b.x0) / step) - 0.5).max(-1) + 1) as usize;
            for j in j0..j1.min(nx) {
                let s = &mut state[i * nx + j];
                if *s == REACHED {
                    continue;
                }
                let deep = deep_line
                    .get_or_insert_with(|| DeepLine::new(work, y))
                    .deep(b.x0 + (j as f64 + 0.5) * step);
                *s = if deep { EMPTY } else { FAR };
                if deep {
                    empties.push(i * nx + j);
                }
            }
        }
    }
    // the parts: samples EMPTY joined by the four neighbours, each marked SEEN as it is
    // reached (the start samples in order, so the largest first found wins a tie)
    let mut parts: Vec<(f64, Point, Rect)> = Vec::new();
    let mut stack = Vec::new();
    for start in empties {
        if state[start] != EMPTY {
            continue;
        }
        state[start] = SEEN;
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
            four_neighbours(c, nx, ny, |n| {
                if state[n] == EMPTY {
                    state[n] = SEEN;
                    stack.push(n);
                }
            });
        }
        let area = count as f64 * step * step / tile_area_exact();
        if area > MIN_EMPTY_TILES {
            parts.push((area, (sum / count as f64).to_point(), bb));
        }
    }
    parts
}

/// A sample of [`all_empty_parts`] not known to be near a tile centre nor empty.
const FAR: u8 = 0;
/// A sample within `near` of a tile centre.
const REACHED: u8 = 1;
/// A sample deep inside the shape and far from every tile centre.
const EMPTY: u8 = 2;
/// An empty sample already joined to a part.
const SEEN: u8 = 3;

/// Calls `visit` on the four neighbours of cell `c` of a grid `nx` cells wide and `ny`
/// high, stored row by row: left, right, below, above.
pub(crate) fn four_neighbours(c: usize, nx: usize, ny: usize, mut visit: impl FnMut(usize)) {
    let (i, j) = (c % nx, c / nx);
    if i > 0 {
        visit(c - 1);
    }
    if i + 1 < nx {
        visit(c + 1);
    }
    if j > 0 {
        visit(c - nx);
    }
    if j + 1 < ny {
        visit(c + nx);
    }
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

/// An f64 ordered by `total_cmp`, for ranking keys.
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct OrdF64(pub(crate) f64);

impl Eq for OrdF64 {}

impl PartialOrd for OrdF64 {
    fn partial_cmp(&self, other: &OrdF64) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for OrdF64 {
    fn cmp(&self, other: &OrdF64) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
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

    /// Parts up to the allowance cost nothing, parts beyond it their excess, with no
    /// step at the allowance.
    #[test]
    fn empty_parts_cost_their_excess_over_the_allowance() {
        assert_eq!(excess_empty(0.0), 0.0);
        assert_eq!(excess_empty(MIN_EMPTY_TILES), 0.0);
        assert!((excess_empty(2.4) - 0.4).abs() < 1e-12);
        assert!(excess_empty(4.7) < excess_empty(5.4));
        // the key at 171 tiles: 2.4 tile areas in 12 turns before 2.1 in 22
        assert!(EMPTY_PRICE * excess_empty(2.4) + 12.0 < EMPTY_PRICE * excess_empty(2.1) + 22.0);
        // a fill with four more turns before half a tile area over the allowance
        assert!(16.0 < EMPTY_PRICE * excess_empty(2.5) + 12.0);
    }
}
