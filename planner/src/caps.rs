//! Cap decompositions: the order in which one chain can fill a shape so that it folds in
//! sequence from its first tile.
//!
//! While joint `k` folds, the rest of the chain is a straight tail that turns a quarter turn
//! about the hinge (SPEC section 3): it sweeps the quadrant ahead of the hinge on the fold
//! side, as far as the tail is long. A serpentine's U-turns therefore need everything laid
//! before them to lie behind the row they end (the two folds of a U-turn sweep the half-plane
//! beyond it), and a row may only end where nothing laid lies ahead of it. A chain whose cells
//! are each a *cap* meets both by construction: cell `i` is the part of what is left of the
//! shape beyond a line across one axis direction `n_i`, every line across `n_i` meets it in
//! one interval (it is one serpentine of rows across `n_i`, stacked towards `n_i`), and every
//! cell laid before it lies behind that line. Read from the chain's end, the cells peel the
//! shape: the last cell is a cap of the whole shape, the one before a cap of the rest, and so
//! on; what is left at every step lies in an axis box, so the search runs over boxes.
//!
//! Consecutive cells meet at a quarter turn: the last row of one runs towards the next cell's
//! line and turns along it. The search ([`cap_plans`]) prices a decomposition by its turns
//! (rows of every cell, one quarter turn per join) plus the length of the first row that a
//! join cannot reach, and returns the cheapest few; [`crate::route`] lays them out exactly and
//! the sequential fold check has the last word.
//!
//! The topology is read from a raster of the shape (pixels of a quarter tile, fewer for large
//! shapes), so the work grows with the shape's area in tiles, not with its outline.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use kurbo::{Rect, Vec2};

use crate::empty::DeepLine;
use crate::shape::Shape;

/// One of the four axis directions of the axis frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Dir {
    /// +x.
    PosX,
    /// -x.
    NegX,
    /// +y.
    PosY,
    /// -y.
    NegY,
}

impl Dir {
    pub(crate) const ALL: [Dir; 4] = [Dir::PosY, Dir::NegY, Dir::PosX, Dir::NegX];

    /// The unit vector.
    pub(crate) fn vec(self) -> Vec2 {
        match self {
            Dir::PosX => Vec2::new(1.0, 0.0),
            Dir::NegX => Vec2::new(-1.0, 0.0),
            Dir::PosY => Vec2::new(0.0, 1.0),
            Dir::NegY => Vec2::new(0.0, -1.0),
        }
    }

    /// True for the y directions.
    fn is_y(self) -> bool {
        matches!(self, Dir::PosY | Dir::NegY)
    }

    /// True for the positive directions.
    fn positive(self) -> bool {
        matches!(self, Dir::PosX | Dir::PosY)
    }
}

/// One cell of a cap decomposition, in the axis frame (unit tiles).
#[derive(Clone, Debug)]
pub(crate) struct CapCell {
    /// The cell's box: the cell is the shape inside it.
    pub rect: Rect,
    /// The direction its rows are stacked in (rows run across it).
    pub n: Dir,
    /// True if the opposite stacking direction will do as well (the first cell of a chain
    /// has nothing laid before it).
    pub either_sign: bool,
    /// True if its rows must span it (a cell grown over lobes, [`crate::lobes`]).
    pub spans: bool,
}

/// A cap decomposition in chain order, with its price.
#[derive(Clone, Debug)]
pub(crate) struct CapPlan {
    pub cells: Vec<CapCell>,
    /// Turns (U-turns and quarter turns) plus the join misses, in tile widths.
    pub cost: f64,
    /// True for a slab decomposition ([`crate::slabs`]): its cells need not be caps, and it
    /// is sized on its own.
    pub slabs: bool,
    /// True for the slab decomposition chosen by the price of its joins too
    /// ([`crate::slabs`]): sized in a slot of its own, its cost not comparable with the others'.
    pub joined: bool,
}

/// Cap decompositions kept per box and join requirement.
const KEEP: usize = 4;
/// Cuts tried per box and direction.
const CUTS: usize = 4;
/// The most cells a decomposition may hold.
const MAX_CELLS: usize = 16;
/// The most boxes the search visits (a bound on its work, whatever the shape).
const MAX_BOXES: usize = 1500;
/// The most pixels of the raster; a larger shape is read at a coarser pixel.
const MAX_PIXELS: usize = 40_000;
/// Price of one tile width of a first row that its join cannot reach, in tile areas (a strip
/// of the cell along the cut is then reached only by the next row, a row pitch away: about
/// two thirds of a tile width of it lies farther than 0.95 w from every tile).
const MISS_PRICE: f64 = 0.8;
/// Price of one tile width by which the runs of consecutive rows of a cell differ at an end
/// (see [`Search::steps`]): between a tile left uncovered (1 tile area) and one laid outside
/// (about 1.4).
const STEP_PRICE: f64 = 1.2;
/// Price per tile width of a cap's rows when their count has the wrong parity for the caps
/// either side of it (see [`Search::best`]): the row programme then leaves a row out or
/// lays one more than fits, about half a row's strip of misfit.
const PARITY_PRICE: f64 = 0.5;
/// Price of one unit of area (a tile width squared) of a cell that its rows leave to the
/// next cell's first row but that row does not reach ([`Search::dropped`]): an area left
/// empty, as the row programme prices a tile area left uncovered.
const DROP_PRICE: f64 = 1.0;
/// Price of a join that cannot be made.
const NO_JOIN: f64 = 1e3;
/// Price of one tile laid outside the shape to make a join (a round cell's last row ends
/// short of the next cell's line, and runs on outside the outline to reach it): a tile wholly
/// outside costs its area weighted as the row programme weighs it (about 1.4 tile areas,
/// [`crate::rows::Style::outside_weight`]).
const BRIDGE_PRICE: f64 = 1.4;

/// The shape as pixels: `inside[j * nx + i]` for the pixel whose centre is at
/// `(x0 + (i + 1/2) px, y0 + (j + 1/2) px)`.
pub(crate) struct Raster {
    nx: usize,
    ny: usize,
    x0: f64,
    y0: f64,
    px: f64,
    inside: Vec<bool>,
    /// The summed-area table of `inside` (see [`Raster::count`]).
    sat: Vec<u32>,
    /// The runs (half-open column ranges) of inside pixels of every pixel row.
    row_runs: Vec<Runs>,
    /// The runs (half-open row ranges) of inside pixels of every pixel column.
    col_runs: Vec<Runs>,
}

/// Drops the slivers from a raster (`inside`, `nx` by `ny` pixels of size `px` from `(x0,
/// y0)`, of `shape` in unit tiles): a group of touching inside pixels at least half a tile
/// in area (one that would count as a part of the shape) in which no pixel centre lies half
/// a tile inside the outline ([`DeepLine`], the empty-part measure's own test) is a sliver
/// narrower than a tile (a thin spit of a country's coast, the tip of a crescent) that the
/// raster sees cut off from the rest. No tile fits in it, so no chain needs to reach it: it
/// is neither a separate part nor a cell. Smaller groups are left as they are (the search
/// ignores them).
fn drop_slivers(shape: &Shape, inside: &mut [bool], nx: usize, ny: usize, o: (f64, f64, f64)) {
    let (x0, y0, px) = o;
    let min_px = (0.5 / (px * px)).max(1.0) as usize;
    // label the groups (four-neighbour), with their sizes
    let mut label = vec![u32::MAX; nx * ny];
    let mut sizes: Vec<usize> = Vec::new();
    let mut stack = Vec::new();
    for s in 0..nx * ny {
        if label[s] != u32::MAX || !inside[s] {
            continue;
        }
        let l = sizes.len() as u32;
        label[s] = l;
        stack.push(s);
        let mut size = 0;
        while let Some(c) = stack.pop() {
            size += 1;
            crate::empty::four_neighbours(c, nx, ny, |k| {
                if label[k] == u32::MAX && inside[k] {
                    label[k] = l;
                    stack.push(k);
                }
            });
        }
        sizes.push(size);
    }
    // the groups that count as parts and hold a pixel a tile fits around
    let mut holds_tile: Vec<bool> = sizes.iter().map(|&n| n < min_px).collect();
    for j in 0..ny {
        let y = y0 + (j as f64 + 0.5) * px;
        let mut line: Option<DeepLine> = None;
        for i in 0..nx {
            let l = label[j * nx + i];
            if l == u32::MAX || holds_tile[l as usize] {
                continue;
            }
            let x = x0 + (i as f64 + 0.5) * px;
            if line.get_or_insert_with(|| DeepLine::new(shape, y)).deep(x) {
                holds_tile[l as usize] = true;
            }
        }
    }
    for (v, &l) in inside.iter_mut().zip(&label) {
        if l != u32::MAX && !holds_tile[l as usize] {
            *v = false;
        }
    }
}

impl Raster {
    pub(crate) fn new(shape: &Shape) -> Raster {
        let b = shape.bbox();
        let area = (b.width() * b.height()).max(1e-9);
        // a quarter tile, or coarser so that the raster stays bounded
        let px = 0.25f64.max((area / MAX_PIXELS as f64).sqrt());
        let nx = ((b.width() / px).ceil() as usize).max(1);
        let ny = ((b.height() / px).ceil() as usize).max(1);
        let mut inside = vec![false; nx * ny];
        for j in 0..ny {
            let y = b.y0 + (j as f64 + 0.5) * px;
            for (a, e) in shape.intervals_at(y) {
                let i0 = (((a - b.x0) / px) - 0.5).ceil().max(0.0) as usize;
                let i1 = ((((e - b.x0) / px) - 0.5).floor() + 1.0).max(0.0) as usize;
                for i in i0..i1.min(nx) {
                    inside[j * nx + i] = true;
                }
            }
        }
        drop_slivers(shape, &mut inside, nx, ny, (b.x0, b.y0, px));
        // sat[(j * (nx + 1)) + i]: inside pixels with column < i and row < j
        let mut sat = vec![0u32; (nx + 1) * (ny + 1)];
        for j in 0..ny {
            let mut row = 0u32;
            for i in 0..nx {
                row += u32::from(inside[j * nx + i]);
                sat[(j + 1) * (nx + 1) + i + 1] = sat[j * (nx + 1) + i + 1] + row;
            }
        }
        let line_runs = |n: usize, len: usize, at: &dyn Fn(usize, usize) -> bool| -> Vec<Runs> {
            (0..n)
                .map(|k| {
                    let mut runs: Runs = Vec::new();
                    let mut start: Option<usize> = None;
                    for t in 0..len {
                        match (at(k, t), start) {
                            (true, None) => start = Some(t),
                            (false, Some(a)) => {
                                runs.push((a, t));
                                start = None;
                            }
                            _ => {}
                        }
                    }
                    if let Some(a) = start {
                        runs.push((a, len));
                    }
                    runs
                })
                .collect()
        };
        let row_runs = line_runs(ny, nx, &|j, i| inside[j * nx + i]);
        let col_runs = line_runs(nx, ny, &|i, j| inside[j * nx + i]);
        Raster {
            nx,
            ny,
            x0: b.x0,
            y0: b.y0,
            px,
            inside,
            sat,
            row_runs,
            col_runs,
        }
    }

    /// The runs of inside pixels of pixel row `j` (if `rows`) or column `j` within `lo..hi`.
    fn runs_within(&self, rows: bool, j: usize, lo: usize, hi: usize) -> Runs {
        let all = if rows {
            &self.row_runs[j]
        } else {
            &self.col_runs[j]
        };
        all.iter()
            .filter_map(|&(a, e)| {
                let (a, e) = (a.max(lo), e.min(hi));
                (a < e).then_some((a, e))
            })
            .collect()
    }

    /// The number of inside pixels in columns `x0..x1` and rows `y0..y1`.
    fn count(&self, x0: usize, x1: usize, y0: usize, y1: usize) -> u32 {
        let w = self.nx + 1;
        self.sat[y1 * w + x1] + self.sat[y0 * w + x0]
            - self.sat[y0 * w + x1]
            - self.sat[y1 * w + x0]
    }

    /// Pixels per tile width.
    pub(crate) fn per_tile(&self) -> f64 {
        1.0 / self.px
    }
}

/// A box of pixels, half-open: `x0..x1`, `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct PBox {
    pub x0: usize,
    pub x1: usize,
    pub y0: usize,
    pub y1: usize,
}

/// The runs (half-open pixel ranges) of one line of the raster inside a box, gaps and
/// runs shorter than `min` merged and dropped.
type Runs = Vec<(usize, usize)>;

/// The cheapest decompositions found per box, join requirement and cut side.
type Memo = HashMap<(PBox, Option<bool>, Option<Dir>), Rc<Vec<CapPlan>>>;

/// The search over boxes.
pub(crate) struct Search<'a> {
    r: &'a Raster,
    pitch: f64,
    /// Runs and gaps shorter than this many pixels do not count (half a tile).
    min: usize,
    memo: Memo,
    visited: usize,
    /// [`Search::components`] of the boxes asked about so far.
    components_memo: RefCell<HashMap<PBox, usize>>,
}

impl<'a> Search<'a> {
    /// A search over the raster `r` for rows of pitch `pitch` (tile widths).
    pub(crate) fn new(r: &'a Raster, pitch: f64) -> Search<'a> {
        Search {
            r,
            pitch,
            min: ((0.5 / r.px).round() as usize).max(1),
            memo: HashMap::new(),
            visited: 0,
            components_memo: RefCell::new(HashMap::new()),
        }
    }

    /// The raster searched.
    pub(crate) fn raster(&self) -> &Raster {
        self.r
    }

    /// The box of every inside pixel, if it is one piece.
    pub(crate) fn whole(&self) -> Option<PBox> {
        let all = PBox {
            x0: 0,
            x1: self.r.nx,
            y0: 0,
            y1: self.r.ny,
        };
        self.tight(all).filter(|&b| self.components(b) == 1)
    }

    /// The runs of line `k` (a pixel row if `rows`, else a pixel column) within `lo..hi`.
    pub(crate) fn runs(&self, rows: bool, k: usize, lo: usize, hi: usize) -> Runs {
        let raw = self.r.runs_within(rows, k, lo, hi);
        let mut out: Runs = Vec::new();
        for (a, b) in raw {
            match out.last_mut() {
                Some(last) if a - last.1 < self.min => last.1 = b,
                _ => out.push((a, b)),
            }
        }
        out.retain(|&(a, b)| b - a >= self.min);
        out
    }

    /// [`Search::runs`] of a line of a cell whose side `cut` meets the next cell: when the
    /// line meets the cell in several runs, those that reach that side are left out (a
    /// round hole's corner beside the next cell's first row: that row covers its edge, and
    /// what it does not reach the empty-part check reports).
    fn runs_cut(&self, rows: bool, k: usize, lo: usize, hi: usize, cut: Option<Dir>) -> Runs {
        let mut runs = self.runs(rows, k, lo, hi);
        let Some(c) = cut else { return runs };
        // the cut side lies at an end of this line only if the line runs along the cut's
        // direction
        if runs.len() < 2 || c.is_y() == rows {
            return runs;
        }
        let touches = |r: &(usize, usize)| {
            if c.positive() {
                r.1 + 1 >= hi
            } else {
                r.0 <= lo + 1
            }
        };
        if runs.iter().any(|r| !touches(r)) {
            runs.retain(|r| !touches(r));
        }
        runs
    }

    /// The box shrunk to the inside pixels it holds, or None if it holds none (each side
    /// moved in while the line along it is empty, each line counted in the summed-area
    /// table).
    pub(crate) fn tight(&self, b: PBox) -> Option<PBox> {
        let r = self.r;
        if b.x0 >= b.x1 || b.y0 >= b.y1 || r.count(b.x0, b.x1, b.y0, b.y1) == 0 {
            return None;
        }
        let PBox {
            mut x0,
            mut x1,
            mut y0,
            mut y1,
        } = b;
        while r.count(x0, x0 + 1, y0, y1) == 0 {
            x0 += 1;
        }
        while r.count(x1 - 1, x1, y0, y1) == 0 {
            x1 -= 1;
        }
        while r.count(x0, x1, y0, y0 + 1) == 0 {
            y0 += 1;
        }
        while r.count(x0, x1, y1 - 1, y1) == 0 {
            y1 -= 1;
        }
        Some(PBox { x0, x1, y0, y1 })
    }

    /// [`Search::count_components`], remembered per box (the cuts of a box and of the boxes
    /// around it ask about the same rests again and again).
    pub(crate) fn components(&self, b: PBox) -> usize {
        if let Some(&n) = self.components_memo.borrow().get(&b) {
            return n;
        }
        let n = self.count_components(b);
        self.components_memo.borrow_mut().insert(b, n);
        n
    }

    /// The number of groups of touching inside pixels in the box larger than half a tile:
    /// the runs of the box's pixel rows, joined where runs of neighbouring rows share a
    /// column (the work grows with the rows and their runs, not with the pixels).
    fn count_components(&self, b: PBox) -> usize {
        let min_px = (0.5 * self.r.per_tile() * self.r.per_tile()).max(1.0) as usize;
        let mut runs: Runs = Vec::new();
        let mut row_start: Vec<usize> = Vec::with_capacity(b.y1 - b.y0 + 1);
        for j in b.y0..b.y1 {
            row_start.push(runs.len());
            runs.extend(self.r.runs_within(true, j, b.x0, b.x1));
        }
        row_start.push(runs.len());
        let mut parent: Vec<usize> = (0..runs.len()).collect();
        fn root(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        for r in 1..row_start.len() - 1 {
            let (mut i, mut k) = (row_start[r - 1], row_start[r]);
            while i < row_start[r] && k < row_start[r + 1] {
                let ((a0, e0), (a1, e1)) = (runs[i], runs[k]);
                if a0 < e1 && a1 < e0 {
                    let (ri, rk) = (root(&mut parent, i), root(&mut parent, k));
                    parent[ri] = rk;
                }
                if e0 < e1 {
                    i += 1;
                } else {
                    k += 1;
                }
            }
        }
        let mut size = vec![0usize; runs.len()];
        for (i, &(a, e)) in runs.iter().enumerate() {
            let r = root(&mut parent, i);
            size[r] += e - a;
        }
        size.iter().filter(|&&n| n >= min_px).count()
    }

    /// The area (tile widths squared) that [`Search::runs_cut`] leaves out of the lines of
    /// the box across `y` (pixel rows if `y`, else columns) for a cell whose side `cut` meets
    /// the next cell, beyond the tile nearest that side (the next cell's first row reaches
    /// that far): no row of this cell covers it, so it is left empty. Priced in
    /// [`Search::best`] at [`DROP_PRICE`] per unit, so that the price grows with the tiles
    /// (a decomposition that leaves a round hole's corners to the next cell is cheap at a
    /// hundred tiles and costs tens of tile areas at thousands: more cells then cost less).
    fn dropped(&self, b: PBox, y: bool, cut: Option<Dir>) -> f64 {
        let Some(c) = cut else { return 0.0 };
        if c.is_y() == y {
            return 0.0;
        }
        let (k0, k1, lo, hi) = if y {
            (b.y0, b.y1, b.x0, b.x1)
        } else {
            (b.x0, b.x1, b.y0, b.y1)
        };
        let reach = self.r.per_tile();
        let mut px = 0.0;
        for k in k0..k1 {
            let all = self.runs(y, k, lo, hi);
            if all.len() < 2 {
                continue;
            }
            let kept = self.runs_cut(y, k, lo, hi, cut);
            for r in all.iter().filter(|r| !kept.contains(r)) {
                px += ((r.1 - r.0) as f64 - reach).max(0.0);
            }
        }
        DROP_PRICE * px * self.r.px * self.r.px
    }

    /// True if every line across `y` (pixel rows if `y`, else columns) meets the box's pixels
    /// in at most one run.
    fn monotone(&self, b: PBox, y: bool, cut: Option<Dir>) -> bool {
        if y {
            (b.y0..b.y1).all(|j| self.runs_cut(true, j, b.x0, b.x1, cut).len() <= 1)
        } else {
            (b.x0..b.x1).all(|i| self.runs_cut(false, i, b.y0, b.y1, cut).len() <= 1)
        }
    }

    /// The misfit of a serpentine stacked along `y` (pixel rows if `y`, else columns) over
    /// the box, in tile areas: where the run of one row and the next differ in an end, the
    /// U-turn between them either runs outside the shape or stops short of the shape, over
    /// the difference (a T's wide bar below its narrow stem: the U-turn at the bar's end is
    /// far from the stem). Rows are sampled a row pitch apart; each end changes its U-turn
    /// every other row, so half of both ends' changes are priced.
    pub(crate) fn steps(&self, b: PBox, y: bool) -> f64 {
        let tile = self.r.per_tile();
        let step = ((self.pitch * tile).round() as usize).max(1);
        let (k0, k1, lo, hi) = if y {
            (b.y0, b.y1, b.x0, b.x1)
        } else {
            (b.x0, b.x1, b.y0, b.y1)
        };
        let mut prev: Option<(usize, usize)> = None;
        let mut sum = 0.0;
        let mut k = k0 + step / 2;
        while k < k1 {
            let runs = self.runs(y, k, lo, hi);
            if let (Some(&(a, _)), Some(&(_, e))) = (runs.first(), runs.last()) {
                if let Some((pa, pe)) = prev {
                    sum += (a as f64 - pa as f64).abs() + (e as f64 - pe as f64).abs();
                }
                prev = Some((a, e));
            }
            k += step;
        }
        STEP_PRICE * 0.5 * sum / tile
    }

    /// Rows of a serpentine over an extent of `px` pixels.
    pub(crate) fn rows(&self, px: usize) -> f64 {
        (px as f64 * self.r.px / self.pitch).round().max(1.0)
    }

    /// The line of `b` farthest towards `d` and the lines across `d` in order from it
    /// inwards.
    fn lines(b: PBox, d: Dir) -> Vec<usize> {
        match d {
            Dir::PosY => (b.y0..b.y1).rev().collect(),
            Dir::NegY => (b.y0..b.y1).collect(),
            Dir::PosX => (b.x0..b.x1).rev().collect(),
            Dir::NegX => (b.x0..b.x1).collect(),
        }
    }

    /// The cap of `b` towards `d` holding the first `depth` lines, and the rest.
    fn split(b: PBox, d: Dir, depth: usize) -> (PBox, PBox) {
        let (mut cap, mut rest) = (b, b);
        let (lo, hi) = if d.is_y() { (b.y0, b.y1) } else { (b.x0, b.x1) };
        let at = if d.positive() { hi - depth } else { lo + depth };
        // the cap's inner edge and the rest's outer edge, both at `at`
        let (cap_edge, rest_edge) = match d {
            Dir::PosY => (&mut cap.y0, &mut rest.y1),
            Dir::NegY => (&mut cap.y1, &mut rest.y0),
            Dir::PosX => (&mut cap.x0, &mut rest.x1),
            Dir::NegX => (&mut cap.x1, &mut rest.x0),
        };
        *cap_edge = at;
        *rest_edge = at;
        (cap, rest)
    }

    /// The depths (lines) at which a cap towards `d` may be cut off `b`: every line of the
    /// cap meets the shape in one run, the runs of neighbouring lines overlap, and the rest
    /// is one piece. The deepest such cut first, then cuts at shoulders (where the run
    /// shrinks or grows by more than a tile from one line to the next), deepest first.
    fn cuts(&self, b: PBox, d: Dir, cut: Option<Dir>) -> Vec<usize> {
        let rows = d.is_y();
        let (lo, hi) = if d.is_y() { (b.x0, b.x1) } else { (b.y0, b.y1) };
        let lines = Self::lines(b, d);
        let mut prev: Option<(usize, usize)> = None;
        let mut valid = 0usize;
        let mut shoulders: Vec<usize> = Vec::new();
        let tile = self.r.per_tile();
        for (depth, &k) in lines.iter().enumerate() {
            let runs = self.runs_cut(rows, k, lo, hi, cut);
            if runs.len() > 1 {
                break;
            }
            let Some(&run) = runs.first() else {
                if prev.is_some() {
                    break;
                }
                continue;
            };
            if let Some(p) = prev {
                if run.1 <= p.0 || p.1 <= run.0 {
                    break;
                }
                let jump = (run.0 as f64 - p.0 as f64)
                    .abs()
                    .max((run.1 as f64 - p.1 as f64).abs());
                if jump > tile {
                    shoulders.push(depth);
                }
            }
            prev = Some(run);
            valid = depth + 1;
        }
        // at least a tile deep, and never the whole box
        let min_depth = tile.ceil() as usize;
        let total = lines.len();
        let mut out: Vec<usize> = Vec::new();
        let mut candidates: Vec<usize> = vec![valid];
        candidates.extend(shoulders.iter().rev().copied());
        // one row deep, where the side is a band of at most three rows: a side of a spiral
        // around a hole, or the row that fixes a band's row count
        let one_row = (self.pitch * tile).round() as usize;
        if one_row <= valid && (valid as f64) < 3.0 * self.pitch * tile {
            candidates.push(one_row.max(min_depth));
        }
        for depth in candidates {
            if out.len() >= CUTS {
                break;
            }
            if depth < min_depth || depth >= total || out.contains(&depth) {
                continue;
            }
            let (_, rest) = Self::split(b, d, depth);
            let Some(rest) = self.tight(rest) else {
                continue;
            };
            if self.components(rest) == 1 {
                out.push(depth);
            } else if depth == valid {
                // the deepest cap leaves separate pieces (a star's legs): step back towards
                // the extreme until the rest is one piece, a tile at a time
                let mut d2 = depth;
                while d2 > min_depth + tile as usize {
                    d2 -= tile.max(1.0) as usize;
                    let (_, rest) = Self::split(b, d, d2);
                    if let Some(rest) = self.tight(rest) {
                        if self.components(rest) == 1 {
                            out.push(d2);
                            break;
                        }
                    }
                }
            }
        }
        out
    }

    /// The extreme line of a cell towards `d` and its run across `d`.
    fn edge_run(&self, b: PBox, d: Dir) -> Option<(usize, (usize, usize))> {
        let rows = d.is_y();
        let (lo, hi) = if d.is_y() { (b.x0, b.x1) } else { (b.y0, b.y1) };
        for k in Self::lines(b, d) {
            if let Some(&run) = self.runs(rows, k, lo, hi).first() {
                return Some((k, run));
            }
        }
        None
    }

    /// The price of joining the last cell `last` (box `lb`) to the cap `cap` (box `cb`,
    /// stacked towards `cd`): the last cell's final row runs towards the cap (along `cd`) at
    /// the last cell's edge towards its stacking direction, and turns onto the cap's first
    /// row; the part of that row the turn cannot reach is priced. Returns the price and
    /// the stacking direction the last cell must take (for a first cell that may take either).
    fn join(&self, last: &CapCell, lb: PBox, cb: PBox, cd: Dir) -> (f64, Dir) {
        let Some((_, first)) = self.edge_run(cb, opposite(cd)) else {
            return (NO_JOIN, last.n);
        };
        let signs: Vec<Dir> = if last.either_sign {
            vec![last.n, opposite(last.n)]
        } else {
            vec![last.n]
        };
        let mut best = (NO_JOIN * 2.0, last.n);
        for s in signs {
            // the last row: the edge of the last cell towards s, a run along cd
            let Some((k, run)) = self.edge_run(lb, s) else {
                continue;
            };
            // does it reach the cap's line?
            let reach = if cd.positive() {
                let cut = if cd.is_y() { cb.y0 } else { cb.x0 };
                cut.abs_diff(run.1)
            } else {
                let cut = if cd.is_y() { cb.y1 } else { cb.x1 };
                cut.abs_diff(run.0)
            };
            let tile = self.r.per_tile();
            // a last row that ends short of the cap's line runs on outside the shape
            let mut price = BRIDGE_PRICE * (reach as f64 / tile - 1.0).max(0.0);
            // where the turn lands on the cap's first row (its line k across): outside the
            // row, the row begins outside the shape
            let m = k as f64 + 0.5;
            let (a, b) = (first.0 as f64, first.1 as f64);
            if m < a || m > b {
                price += BRIDGE_PRICE * ((a - m).max(m - b) / tile - 0.5).max(0.0);
            } else {
                let miss = (b - m).min(m - a);
                price += MISS_PRICE * miss / tile;
            }
            if price < best.0 {
                best = (price, s);
            }
        }
        best
    }

    /// The cheapest decompositions of the shape in `b` whose last cell's rows run along
    /// the y axis (`Some(true)`), the x axis (`Some(false)`) or either (`None`).
    fn best(
        &mut self,
        b: PBox,
        rows_along_y: Option<bool>,
        cut: Option<Dir>,
        depth: usize,
    ) -> Rc<Vec<CapPlan>> {
        let key = (b, rows_along_y, cut);
        if let Some(v) = self.memo.get(&key) {
            return v.clone();
        }
        self.visited += 1;
        let mut out = self.one_serpentine(b, rows_along_y, cut);
        if depth < MAX_CELLS && self.visited < MAX_BOXES {
            for d in Dir::ALL {
                // the cap is the last cell: its rows run across d
                if rows_along_y.is_some_and(|ry| ry == d.is_y()) {
                    continue;
                }
                for depth_px in self.cuts(b, d, cut) {
                    self.capped(b, d, depth_px, cut, depth, &mut out);
                }
            }
        }
        let v = Rc::new(Self::keep(out));
        self.memo.insert(key, v.clone());
        v
    }

    /// The plans of `b` as one serpentine over the whole box (rows along x are stacked
    /// along y), for the stacking directions `rows_along_y` allows.
    fn one_serpentine(
        &self,
        b: PBox,
        rows_along_y: Option<bool>,
        cut: Option<Dir>,
    ) -> Vec<CapPlan> {
        let mut out = Vec::new();
        for stack_y in [true, false] {
            if rows_along_y.is_some_and(|ry| ry == stack_y) {
                continue;
            }
            if self.monotone(b, stack_y, cut) {
                let extent = if stack_y { b.y1 - b.y0 } else { b.x1 - b.x0 };
                let n = if stack_y { Dir::PosY } else { Dir::PosX };
                out.push(CapPlan {
                    cells: vec![CapCell {
                        rect: self.rect(b),
                        n,
                        either_sign: true,
                        spans: false,
                    }],
                    cost: self.rows(extent) - 1.0
                        + self.steps(b, stack_y)
                        + self.dropped(b, stack_y, cut),
                    slabs: false,
                    joined: false,
                });
            }
        }
        out
    }

    /// Adds to `out` the plans of `b` whose last cell is the cap towards `d` holding its
    /// first `depth_px` lines, after the cheapest plans of the rest.
    fn capped(
        &mut self,
        b: PBox,
        d: Dir,
        depth_px: usize,
        cut: Option<Dir>,
        depth: usize,
        out: &mut Vec<CapPlan>,
    ) {
        let (cap, rest) = Self::split(b, d, depth_px);
        let (Some(cap), Some(rest)) = (self.tight(cap), self.tight(rest)) else {
            return;
        };
        // the cell before the cap has its rows along d
        let before = self.best(rest, Some(d.is_y()), Some(d), depth + 1);
        let extent = if d.is_y() {
            cap.y1 - cap.y0
        } else {
            cap.x1 - cap.x0
        };
        let cap_cost = self.rows(extent) - 1.0
            + 1.0
            + self.steps(cap, d.is_y())
            + self.dropped(cap, d.is_y(), cut);
        for p in before.iter() {
            let Some(last) = p.cells.last() else { continue };
            let lb = self.pbox(last.rect);
            let (price, sign) = self.join(last, lb, cap, d);
            if price >= NO_JOIN {
                continue;
            }
            let parity = self.parity(cap, d, extent, cut, sign);
            let mut cells = p.cells.clone();
            if let Some(l) = cells.last_mut() {
                l.n = sign;
                l.either_sign = false;
            }
            cells.push(CapCell {
                rect: self.rect(cap),
                n: d,
                either_sign: false,
                spans: false,
            });
            out.push(CapPlan {
                cells,
                cost: p.cost + cap_cost + price + parity,
                slabs: false,
                joined: false,
            });
        }
    }

    /// The price of a cap's row count: the cap's first row leaves the side of the cell
    /// before it (its stacking side `sign`), its last row must run towards the next cap
    /// (side `cut`): an odd number of rows if those sides differ.
    fn parity(&self, cap: PBox, d: Dir, extent: usize, cut: Option<Dir>, sign: Dir) -> f64 {
        match cut {
            Some(c) if ((self.rows(extent) as usize) % 2 == 1) == (c == sign) => {
                let len = if d.is_y() {
                    cap.x1 - cap.x0
                } else {
                    cap.y1 - cap.y0
                };
                PARITY_PRICE * len as f64 / self.r.per_tile()
            }
            _ => 0.0,
        }
    }

    /// The cheapest of `out`, at most [`KEEP`], one per cell count and cost.
    fn keep(mut out: Vec<CapPlan>) -> Vec<CapPlan> {
        out.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        let mut kept: Vec<CapPlan> = Vec::new();
        for p in out {
            if kept.len() >= KEEP {
                break;
            }
            // one per last-cell direction and cell count is enough variety
            if kept
                .iter()
                .any(|q| q.cells.len() == p.cells.len() && (q.cost - p.cost).abs() < 1e-9)
            {
                continue;
            }
            kept.push(p);
        }
        kept
    }

    /// The box in the axis frame (unit tiles).
    pub(crate) fn rect(&self, b: PBox) -> Rect {
        let px = self.r.px;
        Rect::new(
            self.r.x0 + b.x0 as f64 * px,
            self.r.y0 + b.y0 as f64 * px,
            self.r.x0 + b.x1 as f64 * px,
            self.r.y0 + b.y1 as f64 * px,
        )
    }

    /// The pixel box of a rectangle made by [`Search::rect`].
    fn pbox(&self, r: Rect) -> PBox {
        let px = self.r.px;
        let f = |v: f64, o: f64| ((v - o) / px).round().max(0.0) as usize;
        PBox {
            x0: f(r.x0, self.r.x0),
            x1: f(r.x1, self.r.x0),
            y0: f(r.y0, self.r.y0),
            y1: f(r.y1, self.r.y0),
        }
    }
}

/// The opposite direction.
pub(crate) fn opposite(d: Dir) -> Dir {
    match d {
        Dir::PosX => Dir::NegX,
        Dir::NegX => Dir::PosX,
        Dir::PosY => Dir::NegY,
        Dir::NegY => Dir::PosY,
    }
}

/// The bounding boxes of the separate parts of `axis_shape` (axis frame, unit tiles) larger
/// than half a tile area, as its raster sees them, largest first.
pub(crate) fn parts(axis_shape: &Shape) -> Vec<Rect> {
    let r = Raster::new(axis_shape);
    let (w, h) = (r.nx, r.ny);
    let min_px = (0.5 * r.per_tile() * r.per_tile()).max(1.0) as usize;
    let mut seen = vec![false; w * h];
    let mut out: Vec<(usize, Rect)> = Vec::new();
    let mut stack = Vec::new();
    for s in 0..w * h {
        if seen[s] || !r.inside[s] {
            continue;
        }
        seen[s] = true;
        stack.push(s);
        let (mut size, mut x0, mut x1, mut y0, mut y1) = (0, usize::MAX, 0, usize::MAX, 0);
        while let Some(c) = stack.pop() {
            size += 1;
            let (i, j) = (c % w, c / w);
            (x0, x1, y0, y1) = (x0.min(i), x1.max(i + 1), y0.min(j), y1.max(j + 1));
            crate::empty::four_neighbours(c, w, h, |k| {
                if !seen[k] && r.inside[k] {
                    seen[k] = true;
                    stack.push(k);
                }
            });
        }
        if size >= min_px {
            let px = r.px;
            out.push((
                size,
                Rect::new(
                    r.x0 + x0 as f64 * px,
                    r.y0 + y0 as f64 * px,
                    r.x0 + x1 as f64 * px,
                    r.y0 + y1 as f64 * px,
                ),
            ));
        }
    }
    out.sort_by_key(|p| std::cmp::Reverse(p.0));
    out.into_iter().map(|p| p.1).collect()
}

/// The cheapest cap decompositions of `axis_shape` (axis frame, unit tiles) for rows of
/// pitch `pitch`, cheapest first (at most [`KEEP`]); empty if the shape has no inside pixel.
pub(crate) fn cap_plans(axis_shape: &Shape, pitch: f64) -> Vec<CapPlan> {
    let r = Raster::new(axis_shape);
    let min = ((0.5 / r.px).round() as usize).max(1);
    let mut s = Search {
        r: &r,
        pitch,
        min,
        memo: HashMap::new(),
        visited: 0,
        components_memo: RefCell::new(HashMap::new()),
    };
    let all = PBox {
        x0: 0,
        x1: r.nx,
        y0: 0,
        y1: r.ny,
    };
    let Some(b) = s.tight(all) else {
        return Vec::new();
    };
    if s.components(b) != 1 {
        return Vec::new();
    }
    s.best(b, None, None, 0).as_ref().clone()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::shape::Ring;
    use crate::slabs::tests::poly;

    /// A U (two arms on a bar): the arms in columns along their length, the bar in rows,
    /// joined by two quarter turns, cheaper than columns across the whole U.
    #[test]
    fn a_u_is_arms_and_bar() {
        let u = poly(&[
            (0.0, 0.0),
            (30.0, 0.0),
            (30.0, 28.0),
            (22.0, 28.0),
            (22.0, 8.0),
            (8.0, 8.0),
            (8.0, 28.0),
            (0.0, 28.0),
        ]);
        let plans = cap_plans(&u, std::f64::consts::SQRT_2);
        let best = &plans[0];
        // the arms in columns (each in one cell), the bar in rows; at most one more cell
        // (a single row along a cut) than the three parts
        assert!((3..=4).contains(&best.cells.len()), "{best:?}");
        let arm = |x0: f64, x1: f64| {
            best.cells.iter().any(|c| {
                !c.n.is_y()
                    && c.rect.x0 <= x0
                    && c.rect.x1 >= x1
                    && c.rect.y1 >= 28.0
                    && c.rect.y0 <= 9.0
            })
        };
        assert!(arm(0.0, 8.0) && arm(22.0, 30.0), "{best:?}");
        assert!(
            best.cells
                .iter()
                .any(|c| c.n.is_y() && c.rect.width() >= 29.0 && c.rect.height() >= 6.0),
            "{best:?}"
        );
        assert!(best.cost < 20.0, "{}", best.cost);
    }

    /// A separate piece a third of a tile thick is a sliver (no tile fits in it): not a
    /// part; a separate piece two tiles wide is one.
    #[test]
    fn a_sliver_is_not_a_separate_part() {
        let square = Ring::rect(0.0, 0.0, 10.0, 10.0);
        let sliver = Ring::rect(11.0, 2.0, 11.35, 9.0);
        let block = Ring::rect(12.0, 2.0, 14.0, 9.0);
        assert_eq!(
            parts(&Shape::from_rings(vec![square.clone(), sliver.clone()])).len(),
            1
        );
        assert_eq!(
            parts(&Shape::from_rings(vec![square, sliver, block])).len(),
            2
        );
    }

    /// The run-based count of connected pieces agrees with a flood fill of the pixels, on
    /// every box of a grid of boxes over a shape with a hole and a notch.
    #[test]
    fn pieces_counted_from_runs_agree_with_a_flood_fill() {
        // holes wound the other way: a hole in the middle and a notch into the left edge
        let reversed = |r: Ring| Ring {
            points: r.points.into_iter().rev().collect(),
        };
        let shape = Shape::from_rings(vec![
            Ring::rect(0.0, 0.0, 12.0, 10.0),
            reversed(Ring::rect(4.0, 3.0, 8.0, 7.0)),
            reversed(Ring::rect(-1.0, 4.0, 3.0, 5.0)),
        ]);
        let r = Raster::new(&shape);
        let s = Search {
            r: &r,
            pitch: std::f64::consts::SQRT_2,
            min: 2,
            memo: HashMap::new(),
            visited: 0,
            components_memo: RefCell::new(HashMap::new()),
        };
        let min_px = (0.5 * r.per_tile() * r.per_tile()).max(1.0) as usize;
        let flood = |b: PBox| {
            let (w, h) = (b.x1 - b.x0, b.y1 - b.y0);
            let mut seen = vec![false; w * h];
            let mut count = 0;
            for start in 0..w * h {
                let at = |c: usize| r.inside[(b.y0 + c / w) * r.nx + b.x0 + c % w];
                if seen[start] || !at(start) {
                    continue;
                }
                seen[start] = true;
                let mut stack = vec![start];
                let mut size = 0;
                while let Some(c) = stack.pop() {
                    size += 1;
                    crate::empty::four_neighbours(c, w, h, |n| {
                        if !seen[n] && at(n) {
                            seen[n] = true;
                            stack.push(n);
                        }
                    });
                }
                if size >= min_px {
                    count += 1;
                }
            }
            count
        };
        let mut several = 0;
        for x0 in (0..r.nx).step_by(5) {
            for x1 in (x0 + 1..=r.nx).step_by(7) {
                for y0 in (0..r.ny).step_by(5) {
                    for y1 in (y0 + 1..=r.ny).step_by(7) {
                        let b = PBox { x0, x1, y0, y1 };
                        let n = s.count_components(b);
                        assert_eq!(n, flood(b), "{b:?}");
                        several += usize::from(n > 1);
                    }
                }
            }
        }
        assert!(several > 0, "no box with several pieces was tried");
    }

    /// A convex shape is one cell.
    #[test]
    fn a_square_is_one_cell() {
        let s = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        let plans = cap_plans(&s, std::f64::consts::SQRT_2);
        assert_eq!(plans[0].cells.len(), 1);
    }
}
