//! The row programme: the exact dynamic programme over row ends of a serpentine in a work
//! frame (rows along x at `y_k = y_0 + k p`, even rows running +x, odd rows -x, all tiles on
//! columns `x_j = x_0 + j`), shared by the monotone planner and the cell planner.
//!
//! The cost is area-true: the shape's area left uncovered plus the chain's area outside it
//! (weighted as the fit error weighs them), with the tiles as octagons (row tiles and U-turn
//! tiles alike) measured exactly along [`AREA_LINES`] lines across each tile, plus a price
//! per U-turn. Each tile adds its weighted area outside less the area of the shape it covers
//! (the shape's own area is a constant left out), so a turn
//! tile is credited for what it covers, not only charged for what lies outside, and the
//! shape between and beyond the rows counts as uncovered. The cost of a row from column
//! `s` to `e` splits into a term of `s` and a term of `e`, so the best predecessor of every
//! end column is a running minimum: the programme takes O(rows x columns) and is exact over
//! all row-length choices. Row tables cost O(intervals) per line (a difference array for
//! the columns wholly inside an interval), into flat buffers allocated once per programme.
//!
//! A solved programme is read back as a [`Serpentine`] ([`crate::row_chain`]): its rows in
//! chain order, their tile centres and their folds.

use std::cell::RefCell;
use std::f64::consts::{FRAC_1_SQRT_2, SQRT_2};

use kurbo::{Point, Rect};

use crate::centre_grid::{ceil_i64, floor_i64};
use crate::options::Turns;
pub(crate) use crate::row_chain::Serpentine;
use crate::shape::Shape;

/// Offsets across a tile (tile widths) of the lines on which the area of the shape under it
/// is measured: the midpoints of eight equal strips (the measure along each line is exact).
/// Fewer lines let the programme slide rows so that what lies outside falls between lines.
pub(crate) const AREA_LINES: [f64; 8] = [
    -0.4375, -0.3125, -0.1875, -0.0625, 0.0625, 0.1875, 0.3125, 0.4375,
];

/// Half the chord of the octagon of width 1 at height `dy` from its centre.
fn half_chord(dy: f64) -> f64 {
    0.5f64.min(FRAC_1_SQRT_2 - dy.abs()).max(0.0)
}

/// The area of a tile (octagon of width 1) by the quadrature of [`AREA_LINES`]: 0.8321,
/// against the exact 2 (sqrt2 - 1) = 0.8284. Costs use this value, so a tile wholly inside
/// the shape covers exactly its own area.
pub(crate) fn tile_area() -> f64 {
    AREA_LINES
        .iter()
        .map(|&dy| 2.0 * half_chord(dy))
        .sum::<f64>()
        / AREA_LINES.len() as f64
}

/// Horizontal and vertical phases of a free lattice, as shares of a column and of a row
/// pitch: the lattice is tried at each of the nine.
const PHASES: [f64; 3] = [0.0, 1.0 / 3.0, 2.0 / 3.0];

/// The geometry of one turn style, in tile widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Style {
    /// Tight or loose.
    pub turns: Turns,
    /// Distance between consecutive rows.
    pub pitch: f64,
    /// Heights of the turn tiles above the row they leave.
    pub turn_heights: &'static [f64],
    /// The price of a U-turn, in tile areas of misfit (see [`solve_rows`]).
    pub turn_price: f64,
    /// Whether the programme prices the lanes no row reaches ([`lane_half`]).
    pub lanes: bool,
}

impl Style {
    /// The weight of area outside the shape against area left uncovered: the fit error
    /// ([`crate::Metrics::fit_error`]) adds the uncovered share of the shape's area and the
    /// outside share of the chain's area, and a chain of this style covers about `a / pitch`
    /// of the shape (`a` the tile area), so an area outside weighs `pitch / a` times an area
    /// uncovered: 1.70 for tight turns, 2.90 for loose. A tile is then worth laying when
    /// more than `pitch / (a + pitch)` of it (63% tight, 74% loose) lies inside the shape.
    pub(crate) fn outside_weight(&self) -> f64 {
        self.pitch / tile_area()
    }

    /// The style with U-turns priced at `price` tile areas.
    pub(crate) fn priced(self, price: f64) -> Style {
        Style {
            turn_price: price,
            ..self
        }
    }

    /// The style whose programmes also price the lanes no row reaches ([`lane_half`]).
    pub(crate) fn with_lanes(self) -> Style {
        Style {
            lanes: true,
            ..self
        }
    }
}

/// One LL/RR tile per U-turn.
pub(crate) const TIGHT: Style = Style {
    turns: Turns::Tight,
    pitch: SQRT_2,
    turn_heights: &[FRAC_1_SQRT_2],
    turn_price: 0.0,
    lanes: false,
};
/// Fold, straight tile, fold.
pub(crate) const LOOSE: Style = Style {
    turns: Turns::Loose,
    pitch: 1.0 + SQRT_2,
    turn_heights: &[FRAC_1_SQRT_2, FRAC_1_SQRT_2 + 1.0],
    turn_price: 0.0,
    lanes: false,
};

/// The lattice of a programme: column `j` at `x0 + j`, row `k` at `y0 + k * pitch`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lattice {
    pub x0: f64,
    pub y0: f64,
    pub cols: usize,
    pub nrows: usize,
}

impl Lattice {
    /// The lattices of a free serpentine over a shape with bounding box `b` (unit tiles),
    /// one per phase pair (horizontal phase outer): two spare columns on either side, the
    /// first row half a tile above the bottom less the vertical phase.
    pub(crate) fn phased(b: Rect, pitch: f64) -> impl Iterator<Item = Lattice> {
        PHASES.iter().flat_map(move |&xp| {
            PHASES.iter().map(move |&yp| {
                let x0 = b.x0.floor() - 2.0 + xp;
                let y0 = b.y0 + 0.5 + (yp - 1.0) * pitch;
                Lattice {
                    x0,
                    y0,
                    cols: ((b.x1 - x0).ceil() as usize) + 3,
                    nrows: (((b.y1 - y0) / pitch).ceil() as usize) + 2,
                }
            })
        })
    }

    /// The lattice of a serpentine whose first tile is at the origin (unit tiles), over a
    /// shape with bounding box `b`, and the column of that first tile: row 0 at y = 0, the
    /// columns reaching at least two past the origin on either side.
    pub(crate) fn from_origin(b: Rect, pitch: f64) -> (Lattice, usize) {
        let x0 = (b.x0.floor() - 2.0).min(-2.0);
        let c0 = (-x0) as usize;
        let lat = Lattice {
            x0,
            y0: 0.0,
            cols: (((b.x1 - x0).ceil() as usize) + 3).max(c0 + 3),
            nrows: if b.y1 > 0.0 {
                ((b.y1 / pitch).ceil() as usize) + 2
            } else {
                1
            },
        };
        (lat, c0)
    }
}

/// A solved programme: the best cost of every row end, ready for back-tracking.
pub(crate) struct Solved {
    cols: usize,
    nrows: usize,
    /// `dp[k * cols + e]`: least cost of a chain whose last row is `k`, ending at `e`.
    dp: Vec<f64>,
    /// Start column of the row, and whether it is the first row.
    back: Vec<(u32, bool)>,
}

/// The buffers of a programme's tables (see [`Tables`]) and of its best costs, kept per
/// thread between programmes: a planner solves hundreds of thousands of programmes of a few
/// thousand row ends each, and buffers allocated afresh each time cost about a tenth of its
/// work (the allocator handing their pages back and faulting them in again). Every buffer
/// is filled before it is read, so what a programme computes does not depend on what a
/// buffer held before.
#[derive(Default)]
struct Tables {
    pre: Vec<f64>,
    turn: Vec<f64>,
    gaps: Vec<(f64, f64)>,
    /// Scratch of [`tile_cover`].
    cover: Vec<f64>,
    diff: Vec<f64>,
    /// A row's lanes ([`lane_cover`]): zeros where lanes are not priced.
    lane: Vec<f64>,
    /// The blocked row and U-turn sites ([`blocked_sites`]), empty when none is.
    blocked_rows: Vec<bool>,
    blocked_turns: Vec<bool>,
}

/// Best-cost buffers kept per thread: as many programmes as a caller holds at once.
const KEPT: usize = 4;

/// The buffers of a [`Solved`]'s best costs and back-pointers.
type BestCosts = (Vec<f64>, Vec<(u32, bool)>);

thread_local! {
    /// The table buffers of this thread's next programme.
    static TABLES: RefCell<Tables> = RefCell::new(Tables::default());
    /// Best-cost buffers given back by dropped [`Solved`]s.
    static KEPT_SOLVED: RefCell<Vec<BestCosts>> = const { RefCell::new(Vec::new()) };
}

/// `v` cleared and refilled with `len` copies of `x`.
fn refill<T: Copy>(mut v: Vec<T>, len: usize, x: T) -> Vec<T> {
    v.clear();
    v.resize(len, x);
    v
}

/// This thread's table buffers (empty ones if they are out).
fn take_tables() -> Tables {
    TABLES
        .try_with(|t| {
            t.try_borrow_mut()
                .map(|mut t| std::mem::take(&mut *t))
                .unwrap_or_default()
        })
        .unwrap_or_default()
}

/// Gives table buffers back to this thread.
fn give_tables(tables: Tables) {
    let _ = TABLES.try_with(|t| {
        if let Ok(mut t) = t.try_borrow_mut() {
            *t = tables;
        }
    });
}

/// Best-cost buffers given back on this thread, or empty ones.
fn take_solved() -> BestCosts {
    KEPT_SOLVED
        .try_with(|k| k.try_borrow_mut().ok().and_then(|mut k| k.pop()))
        .ok()
        .flatten()
        .unwrap_or_default()
}

impl Drop for Solved {
    fn drop(&mut self) {
        let pair = (std::mem::take(&mut self.dp), std::mem::take(&mut self.back));
        // a thread being torn down keeps nothing
        let _ = KEPT_SOLVED.try_with(|k| {
            if let Ok(mut k) = k.try_borrow_mut() {
                if k.len() < KEPT {
                    k.push(pair);
                }
            }
        });
    }
}

/// Keeps `(v, at)` in `min` if `v` is less than its value.
#[inline]
fn lower(min: &mut (f64, usize), v: f64, at: usize) {
    if v < min.0 {
        *min = (v, at);
    }
}

/// Lowers the best cost `cur` of a row end to `cost` if that is less, recording the start
/// column and whether the row is the chain's first.
#[inline]
fn relax(cur: &mut f64, back: &mut (u32, bool), cost: f64, (start, first): (usize, bool)) {
    if cost < *cur {
        *cur = cost;
        *back = (start as u32, first);
    }
}

/// Adds, for every column `j` of `out`, `weight` times the measure of the intervals `iv`
/// on `[x0 + j - hw, x0 + j + hw]` (`hw <= 1/2`): the columns wholly inside an interval get
/// `2 hw` through the difference array `diff` (`out.len() + 1` long, summed by the caller),
/// the at most two partial columns at either end their overlap, so a line costs
/// O(intervals), not O(columns).
fn add_tile_measures(
    iv: &[(f64, f64)],
    x0: f64,
    hw: f64,
    weight: f64,
    out: &mut [f64],
    diff: &mut [f64],
) {
    let cols = out.len() as i64;
    if cols == 0 {
        return;
    }
    let clamp = |j: i64| j.clamp(0, cols);
    for &(a, b) in iv {
        // columns whose whole span lies in [a, b]
        let f0 = clamp(ceil_i64((a + hw) - x0));
        let f1 = clamp(floor_i64((b - hw) - x0) + 1); // exclusive
                                                      // columns that touch [a, b] at all
        let t0 = clamp(floor_i64((a - hw) - x0));
        let t1 = clamp(ceil_i64((b + hw) - x0) + 1);
        let overlap = |j: i64| {
            let x = x0 + j as f64;
            (b.min(x + hw) - a.max(x - hw)).max(0.0)
        };
        if f0 < f1 {
            diff[f0 as usize] += weight * 2.0 * hw;
            diff[f1 as usize] -= weight * 2.0 * hw;
            // two plain loops (not a chained iterator): the same columns, each once
            for j in t0..f0 {
                out[j as usize] += weight * overlap(j);
            }
            for j in f1..t1 {
                out[j as usize] += weight * overlap(j);
            }
        } else {
            for j in t0..t1 {
                out[j as usize] += weight * overlap(j);
            }
        }
    }
}

/// Sets `out[j]` to the area of the shape under the tile centred at `(x0 + j, y)`, for
/// every column `j` (the quadrature of [`AREA_LINES`]), from the intervals `lines[i]` of
/// the shape along `y + AREA_LINES[i]`; `diff` is scratch of `out.len() + 1`.
fn tile_cover(lines: &RowLines, first: usize, x0: f64, out: &mut [f64], diff: &mut [f64]) {
    out.iter_mut().for_each(|v| *v = 0.0);
    diff.iter_mut().for_each(|v| *v = 0.0);
    let weight = 1.0 / AREA_LINES.len() as f64;
    for (i, dy) in AREA_LINES.into_iter().enumerate() {
        add_tile_measures(lines.line(first + i), x0, half_chord(dy), weight, out, diff);
    }
    let mut run = 0.0;
    for (o, d) in out.iter_mut().zip(diff.iter()) {
        run += d;
        *o += run;
    }
}

/// The intervals of a work shape along every line a programme with rows at
/// `y0 + k pitch` measures: for each row, the [`AREA_LINES`] across its tiles, the row's
/// own line (its ends' gaps to the outline), then the area lines across each of its U-turn
/// tiles. They depend on the rows' heights only, so the lattices of the three horizontal
/// phases share them ([`Phased`]).
pub(crate) struct RowLines {
    /// Lines per row.
    per_row: usize,
    /// Whether the rows' lanes are measured ([`lane_half`] above 0).
    lanes: bool,
    iv: Vec<(f64, f64)>,
    /// `iv[at[i]..at[i + 1]]`: the intervals of line `i`.
    at: Vec<usize>,
}

impl RowLines {
    /// The lines of `nrows` rows of `style` from `y0` over `work`.
    pub(crate) fn new(work: &Shape, style: Style, y0: f64, nrows: usize) -> RowLines {
        let lane = if style.lanes {
            lane_half(style.pitch)
        } else {
            0.0
        };
        let lane_lines = if lane > 0.0 { LANE_LINES } else { 0 };
        let per_row = (1 + style.turn_heights.len()) * AREA_LINES.len() + 1 + lane_lines;
        let mut iv = Vec::new();
        let mut at = Vec::with_capacity(nrows * per_row + 1);
        at.push(0);
        let mut line = Vec::new();
        let mut push = |y: f64| {
            work.intervals_into(y, &mut line);
            iv.extend_from_slice(&line);
            at.push(iv.len());
        };
        for k in 0..nrows {
            let y = y0 + k as f64 * style.pitch;
            for dy in AREA_LINES {
                push(y + dy);
            }
            push(y);
            for h in style.turn_heights {
                let yt = y + h;
                for dy in AREA_LINES {
                    push(yt + dy);
                }
            }
            for s in LANE_SAMPLES.iter().filter(|_| lane > 0.0) {
                let ys = y + s * lane;
                push(ys - EDGE);
                push(ys);
                push(ys + EDGE);
            }
        }
        RowLines {
            per_row,
            lanes: lane_lines > 0,
            iv,
            at,
        }
    }

    /// The intervals of line `i`.
    fn line(&self, i: usize) -> &[(f64, f64)] {
        &self.iv[self.at[i]..self.at[i + 1]]
    }

    /// The index of row `k`'s first line.
    fn row(&self, k: usize) -> usize {
        k * self.per_row
    }
}

/// The nine phased lattices of a free serpentine over a work shape ([`Lattice::phased`]),
/// with the lines of the three vertical phases, each shared by its three horizontal phases.
pub(crate) struct Phased {
    lats: Vec<Lattice>,
    /// The lines of `lats[i]` are `lines[i % PHASES.len()]`.
    lines: Vec<RowLines>,
}

impl Phased {
    /// The lattices over `work` and their lines.
    pub(crate) fn new(work: &Shape, style: Style) -> Phased {
        let lats: Vec<Lattice> = Lattice::phased(work.bbox(), style.pitch).collect();
        // the vertical phase is the inner one: the first three lattices hold one each
        let lines = lats
            .iter()
            .take(PHASES.len())
            .map(|l| RowLines::new(work, style, l.y0, l.nrows))
            .collect();
        Phased { lats, lines }
    }

    /// Each lattice (in [`Lattice::phased`]'s order) with its free programme solved.
    pub(crate) fn solve(&self, style: Style) -> impl Iterator<Item = (Lattice, Solved)> + '_ {
        self.lats.iter().enumerate().map(move |(i, &lat)| {
            let lines = &self.lines[i % PHASES.len()];
            (lat, solve_on(lines, style, lat, None, None, usize::MAX))
        })
    }
}

/// Vertical phases of the lattices of a serpentine that must span its shape
/// ([`solve_spanning`]), as shares of a row pitch: twice as fine as [`PHASES`].
const SPAN_PHASES: usize = 6;

/// The free programmes over `work` whose chain starts at the shape's near side, its first
/// row at most `y_max` high (a grown cell's lobes there, [`crate::lobes`]), on lattices of
/// [`SPAN_PHASES`] vertical and [`PHASES`] horizontal phases: where the rows must reach a
/// lobe, the phase at which they also cover the cell's own part is worth a finer search.
pub(crate) fn solve_spanning(work: &Shape, style: Style, y_max: f64) -> Vec<(Lattice, Solved)> {
    let b = work.bbox();
    let p = style.pitch;
    let mut out = Vec::new();
    for i in 0..SPAN_PHASES {
        let yp = i as f64 / SPAN_PHASES as f64;
        let y0 = b.y0 + 0.5 + (yp - 1.0) * p;
        let nrows = (((b.y1 - y0) / p).ceil() as usize) + 2;
        let rows = ((y_max - y0) / p).floor();
        if rows < 0.0 {
            continue;
        }
        let lines = RowLines::new(work, style, y0, nrows);
        for &xp in &PHASES {
            let x0 = b.x0.floor() - 2.0 + xp;
            let lat = Lattice {
                x0,
                y0,
                cols: ((b.x1 - x0).ceil() as usize) + 3,
                nrows,
            };
            let sol = solve_on(&lines, style, lat, None, None, rows as usize + 1);
            out.push((lat, sol));
        }
    }
    out
}

/// The farthest a row end may lie from the outline along its row (tile widths) for rows
/// `pitch` apart without leaving a strip of the shape that the empty-part measure
/// ([`crate::empty`], reach `near` = 0.95 for tight rows, 1.45 for loose) counts: beside
/// the end, half a row pitch across, at half a tile from the outline, lies a point
/// `sqrt(near^2 - (pitch / 2)^2)` beyond the end tile's centre. 1.134 for tight rows, 1.30
/// for loose.
fn gap_ok(pitch: f64) -> f64 {
    let near = crate::centre_grid::NEAR + (pitch - SQRT_2).max(0.0) / 2.0;
    0.5 + (near * near - pitch * pitch / 4.0).max(0.0).sqrt()
}

/// The lane of a row line (see [`lane_cover`]): the strip within this many tile widths of
/// the line, which no tile of the rows beside it reaches, for rows `pitch` apart: a point
/// of the strip is farther than the empty-part measure's reach ([`crate::centre_grid::NEAR`])
/// from both neighbouring lines. 0.46 for tight rows; 0 (no lanes priced) for loose rows,
/// whose gaps the measure does not reach across under `auto` turns anyway, rows or none.
fn lane_half(pitch: f64) -> f64 {
    if pitch > SQRT_2 + 1e-9 {
        return 0.0;
    }
    (pitch - crate::centre_grid::NEAR).clamp(0.0, pitch / 2.0)
}

/// Offsets (shares of [`lane_half`]) of the lines on which a lane is measured: the
/// midpoints of its two halves.
const LANE_SAMPLES: [f64; 2] = [-0.5, 0.5];
/// Lines per row for its lane: each sample line and the lines [`EDGE`] above and below it.
const LANE_LINES: usize = 3 * LANE_SAMPLES.len();
/// Only the shape at least this far (tile widths) inside its outline counts in a lane, as
/// in the empty-part measure ([`crate::empty::EDGE`]).
const EDGE: f64 = crate::empty::EDGE;
/// The price of a lane's area that no tile reaches, per unit of area (tile widths squared),
/// on top of its price as area uncovered: the empty-part measure counts what no tile centre
/// comes within its reach of, which the area alone prices no more than the corners between
/// an outline and its rows.
const LANE_PRICE: f64 = 1.0;

/// Intervals along a line, sorted and disjoint.
type Intervals = Vec<(f64, f64)>;

/// Sets `out` to the intervals of `a` and `b` both.
fn intersect_into(a: &[(f64, f64)], b: &[(f64, f64)], out: &mut Vec<(f64, f64)>) {
    out.clear();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let lo = a[i].0.max(b[j].0);
        let hi = a[i].1.min(b[j].1);
        if lo < hi {
            out.push((lo, hi));
        }
        if a[i].1 < b[j].1 {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// Sets `out[j]` to the area of row `k`'s lane ([`lane_half`]) under column `j` (centre
/// `x0 + j`, one tile width wide) that lies at least [`EDGE`] inside the shape, from the
/// row's lane lines (from `first`): measured along each sample line where it and the lines
/// [`EDGE`] above and below it lie inside the shape, less [`EDGE`] at either end. A row
/// whose tile covers column `j` reaches that area; where no tile of the row does, its
/// neighbours' tiles do not either. `diff` is scratch of `out.len() + 1`, `a` and `b` of
/// intervals.
fn lane_cover(
    lines: &RowLines,
    first: usize,
    x0: f64,
    half: f64,
    out: &mut [f64],
    diff: &mut [f64],
    (a, b): (&mut Intervals, &mut Intervals),
) {
    out.iter_mut().for_each(|v| *v = 0.0);
    diff.iter_mut().for_each(|v| *v = 0.0);
    let weight = half * 2.0 / LANE_SAMPLES.len() as f64;
    for i in 0..LANE_SAMPLES.len() {
        let at = first + 3 * i;
        intersect_into(lines.line(at), lines.line(at + 1), a);
        intersect_into(a, lines.line(at + 2), b);
        b.retain_mut(|v| {
            *v = (v.0 + EDGE, v.1 - EDGE);
            v.0 < v.1
        });
        add_tile_measures(b, x0, 0.5, weight, out, diff);
    }
    let mut run = 0.0;
    for (o, d) in out.iter_mut().zip(diff.iter()) {
        run += d;
        *o += run;
    }
}

/// Ends farther than this from the outline are priced by the uncovered area alone (the row
/// stops well inside the shape, and the area term sees it).
const GAP_MAX: f64 = 3.0;
/// The price of a row end that leaves such a strip, in tile areas: about the strip's area
/// over the row pitch beside it.
const GAP_PRICE: f64 = 1.0;

/// Sets `gaps[j]` to the prices of a row ending at column `j` (centre `x0 + j`) towards -x
/// and towards +x: [`GAP_PRICE`] where the outline along the row (the intervals `iv` of its
/// line) lies between [`gap_ok`] and [`GAP_MAX`] beyond the end tile's centre.
fn edge_gaps(iv: &[(f64, f64)], x0: f64, pitch: f64, gaps: &mut [(f64, f64)]) {
    let ok = gap_ok(pitch);
    let price = |gap: f64| {
        if gap > ok && gap < GAP_MAX {
            GAP_PRICE
        } else {
            0.0
        }
    };
    // the intervals are sorted and disjoint and the columns ascend: the one interval that
    // may hold column j is the first not ending before it
    let mut at = 0;
    for (j, g) in gaps.iter_mut().enumerate() {
        let x = x0 + j as f64;
        while at < iv.len() && iv[at].1 < x {
            at += 1;
        }
        *g = match iv.get(at) {
            Some(&(a, b)) if a <= x => (price(x - a), price(b - x)),
            _ => (0.0, 0.0),
        };
    }
}

/// The tiles (work frame) that would overlap tiles laid before, never outside `within` (a
/// box around the tiles laid near the cell): the lattice sites outside it are passed over
/// without asking.
#[derive(Clone, Copy)]
pub(crate) struct Blocked<'a> {
    /// No site outside this box (closed) is blocked.
    pub within: Rect,
    /// The tiles laid before: their centres in the work frame, to within far less than a
    /// tile width.
    pub tiles: &'a [Point],
    /// True if a tile centred at the point would overlap the `i`-th of `tiles`: a tile
    /// overlaps only tiles centred within a tile width of it on both axes, so only the
    /// lattice sites near each are asked of it ([`blocked_sites`]).
    pub test: &'a (dyn Fn(Point, usize) -> bool + Sync),
}

impl Blocked<'_> {
    /// True if `q` lies in `within`.
    #[inline]
    fn may_block(&self, q: Point) -> bool {
        let w = &self.within;
        q.x >= w.x0 && q.x <= w.x1 && q.y >= w.y0 && q.y <= w.y1
    }
}

/// Sets `rows[k * cols + j]` to whether the tile of row `k` in column `j` of `lat` (centre
/// `(x0 + j, y0 + k p)`) is blocked, and `turns[(k * heights + i) * cols + j]` to whether the
/// U-turn tile after row `k` at the style's `i`-th height is (centre `(x0 + j -+ 1/sqrt2,
/// y0 + k p + h)`, its side the row's direction). Each tile laid before is asked about the
/// sites within two tile widths of it on both axes only, not the lattice's every site: a
/// site farther from every tile on one axis than a tile width (however the maps between
/// the frames round, far below it) is blocked by none.
fn blocked_sites(
    lat: Lattice,
    style: Style,
    b: Blocked<'_>,
    rows: &mut [bool],
    turns: &mut [bool],
) {
    let Lattice {
        x0,
        y0,
        cols,
        nrows,
    } = lat;
    let p = style.pitch;
    let heights = style.turn_heights.len();
    let dir = |k: usize| if k % 2 == 0 { 1.0 } else { -1.0 };
    // the sites' centres, as the programme's tables place them
    let row_site = |k: usize, j: usize| Point::new(x0 + j as f64, y0 + k as f64 * p);
    let turn_site = |k: usize, h: f64, j: usize| {
        let xt = x0 + dir(k) * FRAC_1_SQRT_2;
        Point::new(xt + j as f64, (y0 + k as f64 * p) + h)
    };
    // the indices from floor(lo) to ceil(hi) that lie in 0..n (none when lo > hi)
    let span = |lo: f64, hi: f64, n: usize| {
        (floor_i64(lo).max(0)..=ceil_i64(hi).min(n as i64 - 1)).map(|v| v as usize)
    };
    for (t, c) in b.tiles.iter().enumerate() {
        let u = c.x - x0;
        for k in span((c.y - 2.0 - y0) / p, (c.y + 2.0 - y0) / p, nrows) {
            for j in span(u - 2.0, u + 2.0, cols) {
                let at = &mut rows[k * cols + j];
                let q = row_site(k, j);
                *at = *at || (b.may_block(q) && (b.test)(q, t));
            }
        }
        for (i, &h) in style.turn_heights.iter().enumerate() {
            for k in span((c.y - h - 2.0 - y0) / p, (c.y - h + 2.0 - y0) / p, nrows) {
                let v = u - dir(k) * FRAC_1_SQRT_2;
                for j in span(v - 2.0, v + 2.0, cols) {
                    let at = &mut turns[(k * heights + i) * cols + j];
                    let q = turn_site(k, h, j);
                    *at = *at || (b.may_block(q) && (b.test)(q, t));
                }
            }
        }
    }
}

/// The cost of a tile that overlaps one laid before (see [`solve_rows`]): more than any
/// chain's gain (a tile gains at most one tile area), finite so that prefix sums stay exact
/// enough.
const BLOCKED: f64 = 1e6;

/// Solves the programme on `work` (unit tiles). With `fixed_start = Some(c)` the chain must
/// begin in row 0 at column `c` running +x, and that row holds at least two tiles (a fold
/// before it may be opposite to the U-turn after it); otherwise the first row is free.
///
/// The cost of a chain is the area of the shape it leaves uncovered plus the area of the
/// chain outside the shape weighted by [`Style::outside_weight`], less the shape's area (a
/// constant): every tile, in a row or in a U-turn, adds its weighted area outside the shape
/// less the area of the shape it covers; every U-turn adds the style's `turn_price`.
///
/// Tiles where `blocked` holds (they would overlap tiles an earlier cell laid) cost
/// [`BLOCKED`]: rows stop short of them, so a cell's rows reach up to the rows of the cell
/// before, whatever the boundary between the two (a ring's top cell, in columns, begins
/// right above the last row of its side).
pub(crate) fn solve_rows(
    work: &Shape,
    style: Style,
    lat: Lattice,
    fixed_start: Option<usize>,
    blocked: Option<Blocked<'_>>,
) -> Solved {
    let lines = RowLines::new(work, style, lat.y0, lat.nrows);
    solve_on(&lines, style, lat, fixed_start, blocked, usize::MAX)
}

/// The row tables of the programme on `lat` from the shape's `lines` (see [`solve_rows`]),
/// into `t`'s buffers: `pre[k * (cols + 1) + m]`, the cost of the tiles in columns `0..m`
/// of row `k`; `turn[k * cols + j]`, the cost of the U-turn after row `k` ending at column
/// `j`; `gaps[k * cols + j]`, the prices of row `k` ending at column `j` towards -x and
/// towards +x. Returns the price of every row's lane ([`lane_cover`]) were no tile laid: a
/// chain's first row carries it, and each tile takes back the price of the lane it reaches.
fn tables(
    lines: &RowLines,
    style: Style,
    lat: Lattice,
    blocked: Option<Blocked<'_>>,
    t: &mut Tables,
) -> f64 {
    let Lattice {
        x0,
        y0: _,
        cols,
        nrows,
    } = lat;
    let p = style.pitch;
    let a = tile_area();
    let k_out = style.outside_weight();
    // a tile's cost: its area outside the shape, weighted, less the area it covers
    let tile_cost = |c: f64| k_out * (a - c) - c;
    let w1 = cols + 1;
    let mut pre = refill(std::mem::take(&mut t.pre), nrows * w1, 0.0);
    let mut turn = refill(std::mem::take(&mut t.turn), nrows * cols, 0.0);
    let mut gaps = refill(std::mem::take(&mut t.gaps), nrows * cols, (0.0, 0.0));
    let mut cover = refill(std::mem::take(&mut t.cover), cols, 0.0);
    let mut diff = refill(std::mem::take(&mut t.diff), w1, 0.0);
    let mut lane = refill(std::mem::take(&mut t.lane), cols, 0.0);
    let heights = style.turn_heights.len();
    let sites =
        |v: Vec<bool>, len: usize| refill(v, if blocked.is_some() { len } else { 0 }, false);
    let mut blocked_rows = sites(std::mem::take(&mut t.blocked_rows), nrows * cols);
    let mut blocked_turns = sites(std::mem::take(&mut t.blocked_turns), nrows * heights * cols);
    if let Some(b) = blocked {
        blocked_sites(lat, style, b, &mut blocked_rows, &mut blocked_turns);
    }
    // a site is blocked only where there are blocked sites
    let taken = |sites: &[bool], i: usize| !sites.is_empty() && sites[i];
    let (mut sa, mut sb) = (Vec::new(), Vec::new());
    let half = lane_half(p);
    let mut lanes = 0.0;
    for k in 0..nrows {
        let first = lines.row(k);
        tile_cover(lines, first, x0, &mut cover, &mut diff);
        if lines.lanes {
            let lane_at = first + lines.per_row - LANE_LINES;
            lane_cover(
                lines,
                lane_at,
                x0,
                half,
                &mut lane,
                &mut diff,
                (&mut sa, &mut sb),
            );
            lanes += LANE_PRICE * lane.iter().sum::<f64>();
        }
        let pr = &mut pre[k * w1..(k + 1) * w1];
        // the running sum in a register: pr[j + 1] = pr[j] + cost, the same additions
        let mut run = pr[0];
        for (j, (p, (&c, &l))) in pr[1..].iter_mut().zip(cover.iter().zip(&lane)).enumerate() {
            run += if taken(&blocked_rows, k * cols + j) {
                BLOCKED
            } else {
                tile_cost(c) - LANE_PRICE * l
            };
            *p = run;
        }
        let row_line = first + AREA_LINES.len();
        edge_gaps(
            lines.line(row_line),
            x0,
            p,
            &mut gaps[k * cols..(k + 1) * cols],
        );
        let dir = if k % 2 == 0 { 1.0 } else { -1.0 };
        let t = &mut turn[k * cols..(k + 1) * cols];
        t.iter_mut().for_each(|v| *v = style.turn_price);
        for i in 0..heights {
            let xt = x0 + dir * FRAC_1_SQRT_2;
            let at = row_line + 1 + i * AREA_LINES.len();
            tile_cover(lines, at, xt, &mut cover, &mut diff);
            for (j, (tj, c)) in t.iter_mut().zip(&cover).enumerate() {
                let taken = taken(&blocked_turns, (k * heights + i) * cols + j);
                *tj += if taken { BLOCKED } else { tile_cost(*c) };
            }
        }
    }
    *t = Tables {
        pre,
        turn,
        gaps,
        cover,
        diff,
        lane,
        blocked_rows,
        blocked_turns,
    };
    lanes
}

/// [`solve_rows`] with the shape's lines given (their rows those of `lat`); with a free
/// start, only rows below `first_rows` may be the chain's first.
fn solve_on(
    lines: &RowLines,
    style: Style,
    lat: Lattice,
    fixed_start: Option<usize>,
    blocked: Option<Blocked<'_>>,
    first_rows: usize,
) -> Solved {
    let Lattice { cols, nrows, .. } = lat;
    let w1 = cols + 1;
    let mut t = take_tables();
    let lanes = tables(lines, style, lat, blocked, &mut t);
    let Tables {
        pre, turn, gaps, ..
    } = &t;
    let inf = f64::INFINITY;
    let (dp, back) = take_solved();
    let mut dp = refill(dp, nrows * cols, inf);
    let mut back = refill(back, nrows * cols, (0u32, true));
    for k in 0..nrows {
        let pk = |m: usize| pre[k * w1 + m];
        let (done, todo) = dp.split_at_mut(k * cols);
        let cur = &mut todo[..cols];
        let bk = &mut back[k * cols..(k + 1) * cols];
        let prev = if k > 0 {
            Some((&done[(k - 1) * cols..], &turn[(k - 1) * cols..k * cols]))
        } else {
            None
        };
        if let (Some(_), Some((pd, pt))) = (fixed_start, prev) {
            // past a fixed first row no row starts a chain: its minimum would stay infinite
            // and never lower an end, so only the continuations are relaxed
            let rows = (
                &pre[k * w1..(k + 1) * w1],
                &gaps[k * cols..(k + 1) * cols],
                &pd[..cols],
                pt,
            );
            continue_row(cur, bk, rows, k % 2 == 0);
            continue;
        }
        // a first row may start here (free start: any row; fixed: row 0 at column c only)
        let first_ok = |s: usize| match fixed_start {
            None => k < first_rows,
            Some(c) => k == 0 && s == c,
        };
        let rightward = k % 2 == 0;
        // a fixed first row (rightward) needs s <= e - 1: its own column joins the minimum
        // only after it is used
        let first_after = rightward && fixed_start.is_some();
        let mut first_min = (inf, 0usize);
        let mut cont_min = (inf, 0usize);
        // e runs the way the row does, so the minima hold every start column behind it
        for i in 0..cols {
            let e = if rightward { i } else { cols - 1 - i };
            // the cost of a row from s to e is base(e) + term_s(s):
            // rightward: pre[e + 1] - pre[s]; leftward: pre[s + 1] - pre[e]
            let (gl, gr) = gaps[k * cols + e];
            let (term_s, base) = if rightward {
                (-pk(e) + gl, pk(e + 1) + gr)
            } else {
                (pk(e + 1) + gr, -pk(e) + gl)
            };
            if !first_after && first_ok(e) {
                lower(&mut first_min, term_s + lanes, e);
            }
            relax(
                &mut cur[e],
                &mut bk[e],
                base + first_min.0,
                (first_min.1, true),
            );
            if first_after && first_ok(e) {
                lower(&mut first_min, term_s + lanes, e);
            }
            if let Some((pd, pt)) = prev {
                // continuation needs s before e: cont_min holds the columns behind e
                let onward = pd[e] + pt[e] + term_s;
                continue_at((&mut cur[e], &mut bk[e]), &mut cont_min, base, (onward, e));
            }
        }
    }
    give_tables(t);
    Solved {
        cols,
        nrows,
        dp,
        back,
    }
}

/// A row's prefix costs and end gaps, the best costs of the row before and its U-turn
/// costs (see [`continue_row`]).
type RowData<'a> = (&'a [f64], &'a [(f64, f64)], &'a [f64], &'a [f64]);

/// The row of a programme after a fixed first row (see [`solve_on`]): each end `e` lowered
/// to the least continuation from the row before, `rows` the row's prefix costs and gaps,
/// the best costs of the row before and its U-turn costs; the same operations, in the same
/// order, as the general loop makes when no chain may start in the row.
fn continue_row(
    cur: &mut [f64],
    bk: &mut [(u32, bool)],
    (pre, gaps, pd, pt): RowData<'_>,
    rightward: bool,
) {
    let cols = cur.len();
    let mut cont_min = (f64::INFINITY, 0usize);
    for i in 0..cols {
        let e = if rightward { i } else { cols - 1 - i };
        let (gl, gr) = gaps[e];
        let (term_s, base) = if rightward {
            (-pre[e] + gl, pre[e + 1] + gr)
        } else {
            (pre[e + 1] + gr, -pre[e] + gl)
        };
        let onward = pd[e] + pt[e] + term_s;
        continue_at((&mut cur[e], &mut bk[e]), &mut cont_min, base, (onward, e));
    }
}

/// One end `e` of a row lowered to the best continuation from the row before (its start
/// column the one `cont_min` holds), then `cont_min` lowered to `onward`, the cost of
/// continuing from the row before at `e`.
#[inline]
fn continue_at(
    (cur, back): (&mut f64, &mut (u32, bool)),
    cont_min: &mut (f64, usize),
    base: f64,
    (onward, e): (f64, usize),
) {
    relax(cur, back, base + cont_min.0, (cont_min.1, false));
    lower(cont_min, onward, e);
}

impl Solved {
    /// The best end `(cost, row, column)` among rows that `row_ok` accepts.
    pub(crate) fn best_end(&self, row_ok: impl Fn(usize) -> bool) -> Option<(f64, usize, usize)> {
        let mut best: Option<(f64, usize, usize)> = None;
        for k in (0..self.nrows).filter(|&k| row_ok(k)) {
            let row = &self.dp[k * self.cols..(k + 1) * self.cols];
            for (e, &c) in row.iter().enumerate() {
                let t = c;
                if t.is_finite() && best.is_none_or(|b| t < b.0) {
                    best = Some((t, k, e));
                }
            }
        }
        best
    }

    /// The end `(cost, row, column)` among rows that `row_ok` accepts that minimises its
    /// cost plus `penalty(row, column)` (the cost returned leaves the penalty out), the first
    /// in the order of rows and columns where several do. `lower(row, column)` is a cheap
    /// bound, never negative, that the penalty never falls below: the penalty is not asked where the cost plus
    /// the bound cannot beat the best so far (floating-point addition is monotone, so the
    /// cost plus the penalty could not either).
    pub(crate) fn best_end_with(
        &self,
        row_ok: impl Fn(usize) -> bool,
        lower: impl Fn(usize, usize) -> f64,
        penalty: impl Fn(usize, usize) -> f64,
    ) -> Option<(f64, usize, usize)> {
        let mut best: Option<(f64, f64, usize, usize)> = None;
        for k in (0..self.nrows).filter(|&k| row_ok(k)) {
            let row = &self.dp[k * self.cols..(k + 1) * self.cols];
            for (e, &c) in row.iter().enumerate() {
                // the bound is never negative: a cost at or above the best so far cannot beat
                // it, whatever the bound (asked only below it)
                if !c.is_finite() || best.is_some_and(|b| c >= b.0 || c + lower(k, e) >= b.0) {
                    continue;
                }
                let t = c + penalty(k, e);
                if best.is_none_or(|b| t < b.0) {
                    best = Some((t, c, k, e));
                }
            }
        }
        best.map(|(_, c, k, e)| (c, k, e))
    }

    /// The least cost of a chain whose last row is `k`, ending at column `e` (None if no
    /// such chain, or `e` is off the lattice).
    pub(crate) fn end_cost(&self, k: usize, e: usize) -> Option<f64> {
        (k < self.nrows && e < self.cols)
            .then(|| self.dp[k * self.cols + e])
            .filter(|c| c.is_finite())
    }

    /// The number of columns of the lattice solved.
    pub(crate) fn cols(&self) -> usize {
        self.cols
    }

    /// The serpentine on `lat` that ends in row `k` at column `e`.
    pub(crate) fn serpentine(&self, lat: Lattice, pitch: f64, k: usize, e: usize) -> Serpentine {
        Serpentine {
            x0: lat.x0,
            y0: lat.y0,
            pitch,
            rows: self.rows_to(k, e),
        }
    }

    /// The rows `(row k, start column, end column)` in chain order of the chain ending in
    /// row `k` at column `e`.
    fn rows_to(&self, mut k: usize, mut e: usize) -> Vec<(usize, i64, i64)> {
        let mut out = Vec::new();
        loop {
            let (s, first) = self.back[k * self.cols + e];
            out.push((k, s as i64, e as i64));
            if first || k == 0 {
                break;
            }
            k -= 1;
            e = s as usize;
        }
        out.reverse();
        out
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::from_rings(vec![Ring::rect(x0, y0, x1, y1)])
    }

    /// The per-column tile measures match the overlap computed column by column.
    #[test]
    fn tile_measures_match_direct_overlaps() {
        let iv = [(0.3, 1.7), (2.5, 2.6), (4.0, 9.2), (9.9, 10.05)];
        for hw in [0.5, 0.3, 0.07] {
            let mut out = vec![0.0; 14];
            let mut diff = vec![0.0; 15];
            add_tile_measures(&iv, -0.25, hw, 1.0, &mut out, &mut diff);
            let mut run = 0.0;
            for (j, v) in out.iter().enumerate() {
                run += diff[j];
                let x = -0.25 + j as f64;
                let direct: f64 = iv
                    .iter()
                    .map(|&(a, b)| (b.min(x + hw) - a.max(x - hw)).max(0.0))
                    .sum();
                assert!(
                    (v + run - direct).abs() < 1e-12,
                    "{hw} {j}: {} vs {direct}",
                    v + run
                );
            }
        }
    }

    /// A row's lane (tight rows): in a wide band, the strip of 2 x 0.464 tile widths along
    /// the row under each column; nothing within half a tile of the outline; none for
    /// loose rows.
    #[test]
    fn lanes_lie_half_a_tile_inside_the_outline() {
        let s = rect(0.0, 0.0, 20.0, 3.0);
        let half = lane_half(TIGHT.pitch);
        assert!((half - (SQRT_2 - 0.95)).abs() < 1e-12);
        assert_eq!(lane_half(LOOSE.pitch), 0.0);
        let style = TIGHT.with_lanes();
        // rows at y = 1.5 (the middle) and y = 0.2 (within half a tile of the edge, so is
        // its whole lane)
        for (y0, want) in [(1.5, 2.0 * half), (0.2, 0.0)] {
            let lines = RowLines::new(&s, style, y0, 1);
            assert!(lines.lanes);
            let mut out = vec![0.0; 24];
            let mut diff = vec![0.0; 25];
            let (mut a, mut b) = (Vec::new(), Vec::new());
            let at = lines.per_row - LANE_LINES;
            lane_cover(
                &lines,
                at,
                -2.0,
                half,
                &mut out,
                &mut diff,
                (&mut a, &mut b),
            );
            // column j is centred at x = j - 2: columns 3..=19 lie wholly in x 0.5..19.5
            for (j, v) in out.iter().enumerate() {
                let expect = if (3..=19).contains(&j) {
                    want
                } else {
                    v.min(want)
                };
                assert!((v - expect).abs() < 1e-9, "{y0} {j}: {v} vs {expect}");
            }
        }
        assert!(!RowLines::new(&s, TIGHT, 1.5, 1).lanes);
    }

    /// Priced lanes never lower a programme's cost, and a lane no row can reach (its row
    /// blocked) adds its area: rows at y = 0, sqrt2 and 2 sqrt2 over a band whose inside
    /// holds the middle row's lane whole.
    #[test]
    fn a_lane_no_row_reaches_is_priced() {
        let s = rect(0.0, -0.5, 12.0, 2.0 * SQRT_2 + 0.5);
        let lat = Lattice {
            x0: -3.0,
            y0: 0.0,
            cols: 19,
            nrows: 3,
        };
        // tiles along the middle row, each blocking the sites of that row beside it
        let tiles: Vec<Point> = (-4..18).map(|x| Point::new(x as f64, SQRT_2)).collect();
        let middle =
            |q: Point, t: usize| (q.y - SQRT_2).abs() < 0.1 && (q.x - tiles[t].x).abs() < 0.5;
        let blocked = Blocked {
            within: Rect::new(-10.0, -10.0, 30.0, 10.0),
            tiles: &tiles,
            test: &middle,
        };
        let best = |style: Style, b: Option<Blocked<'_>>| {
            solve_rows(&s, style, lat, None, b)
                .best_end(|_| true)
                .unwrap()
                .0
        };
        for b in [None, Some(blocked)] {
            let (plain, laned) = (best(TIGHT, b), best(TIGHT.with_lanes(), b));
            assert!(laned >= plain - 1e-9, "{plain} {laned}");
        }
        // the middle row's lane, under the lattice's columns
        let half = lane_half(SQRT_2);
        let lines = RowLines::new(&s, TIGHT.with_lanes(), SQRT_2, 1);
        let (mut out, mut diff) = (vec![0.0; 19], vec![0.0; 20]);
        let (mut a, mut c) = (Vec::new(), Vec::new());
        let at = lines.per_row - LANE_LINES;
        lane_cover(
            &lines,
            at,
            -3.0,
            half,
            &mut out,
            &mut diff,
            (&mut a, &mut c),
        );
        let lane: f64 = out.iter().sum();
        assert!((lane - 2.0 * half * 11.0).abs() < 1e-9, "{lane}");
        let (plain, laned) = (
            best(TIGHT, Some(blocked)),
            best(TIGHT.with_lanes(), Some(blocked)),
        );
        assert!(
            laned >= plain + LANE_PRICE * lane - 1e-9,
            "{plain} {laned} {lane}"
        );
    }

    #[test]
    fn fixed_start_begins_where_asked_with_two_tiles() {
        let s = rect(-0.5, -0.5, 9.5, 6.0);
        let lat = Lattice {
            x0: -3.0,
            y0: 0.0,
            cols: 16,
            nrows: 6,
        };
        let sol = solve_rows(&s, TIGHT, lat, Some(3), None);
        let (_, k, e) = sol.best_end(|_| true).unwrap();
        let rows = sol.rows_to(k, e);
        assert_eq!(rows[0].0, 0);
        assert_eq!(rows[0].1, 3);
        assert!(rows[0].2 > 3);
        // the rectangle spans columns 3..=12 (x = 0..=9): rows fill it, a row coming back
        // stops one column short of the edge so that its U-turn tile lies inside
        assert!((3..=4).contains(&rows[1].2), "{rows:?}");
        assert!(
            rows.iter().all(|r| (3..=12).contains(&r.1.min(r.2))),
            "{rows:?}"
        );
        assert!(rows.len() >= 4, "{rows:?}");
    }
}
