//! Cell routes (thesis section 5.5, the key; SPEC section 5): one chain through monotone
//! cells ([`crate::cells`]) in a given order, each cell filled with a serpentine whose first
//! row starts exactly where the join from the previous cell puts the chain.
//!
//! Frame: the *axis frame* is the physical frame turned by `-axis` and scaled to tile widths
//! ([`crate::frame`]); every tile heading in it is a quarter turn. A cell's serpentine runs in
//! a *cell frame* (origin, row direction `d`, stacking side `n`, both axis vectors), where
//! the row programme of [`crate::rows`] applies unchanged. Joins between cells, from the end
//! of the last row heading `h`:
//! - a quarter turn, one L or R fold: the next centre is `(h + h') / sqrt2` away and the rows
//!   of the next cell run along `h'` (orthogonal), stacked towards `h` or `-h`;
//! - a U-turn towards the stacking side (LL/RR, or fold, straight, fold for loose turns): the
//!   next cell continues the stacking with parallel rows;
//! - a straight tile: the row runs on into the next cell.
//!
//! A beam search keeps the cheapest partial routes (the area-true cost of [`crate::rows`]
//! in every cell so far, turns priced, ranked with a look-ahead: how far each cell's exit
//! lies from the next cell); a route whose tile centres come closer than one tile width
//! (octagons of width 1 then overlap), or whose prefix collides when folded in sequence
//! from tile 0, is dropped as it grows.

use std::collections::{HashMap, HashSet};
use std::f64::consts::FRAC_1_SQRT_2;
use std::sync::{Arc, Mutex};

use foldchain::collision::PrefixCheck;
use foldchain::{Fold, FoldWord};
use kurbo::{Affine, Point, Rect, Vec2};

use crate::centre_grid::CentreGrid;
use crate::check::CheckMemo;
use crate::options::Turns;
use crate::rows::{
    solve_rows, solve_spanning, tile_area, Blocked, Lattice, Phased, Serpentine, Solved, Style,
};
use crate::shape::Shape;

/// Partial routes kept at every depth of the beam search.
const BEAM: usize = 24;
/// Centres closer than this (tile widths) belong to overlapping tiles: every face of the
/// octagon is 1/2 from its centre, so two tiles closer than 1 overlap; the margin absorbs
/// rounding only (touching tiles are exactly 1 apart).
const MIN_GAP: f64 = 1.0 - 1e-6;
/// The widening (tile widths) of the box outside which no lattice site of a cell is blocked
/// ([`Blocked::within`]): far more than the rounding of the maps between the frames.
const WITHIN_MARGIN: f64 = 1e-3;

/// A cell frame: `x = (q - o) . d`, `y = (q - o) . n` in the axis frame.
#[derive(Clone, Copy, Debug)]
struct Frame {
    o: Point,
    d: Vec2,
    n: Vec2,
}

impl Frame {
    /// The map from the cell frame to the axis frame.
    fn to_axis(self) -> Affine {
        Affine::new([self.d.x, self.d.y, self.n.x, self.n.y, self.o.x, self.o.y])
    }

    /// The map from the axis frame to the cell frame (`d`, `n` orthonormal: the inverse is
    /// the transpose).
    fn axis_to_cell(self) -> Affine {
        let o = self.o.to_vec2();
        Affine::new([
            self.d.x,
            self.n.x,
            self.d.y,
            self.n.y,
            -o.dot(self.d),
            -o.dot(self.n),
        ])
    }

    /// The axis-frame shape in the cell frame.
    fn work(self, s: &Shape) -> Shape {
        s.transformed(self.axis_to_cell())
    }

    /// True if turning from `d` towards `n` is counter-clockwise (an L fold).
    fn ccw(self) -> bool {
        self.d.cross(self.n) > 0.0
    }
}

/// One cell's serpentine and the join that leads into it.
#[derive(Clone, Debug)]
struct Leg {
    frame: Frame,
    serp: Serpentine,
    /// Folds from the previous leg's last tile to this leg's first (empty for the first).
    join: Vec<Fold>,
    quarter: bool,
}

impl Leg {
    /// The direction, in the axis frame, in which row `k` runs.
    fn heading(&self, k: usize) -> Vec2 {
        self.frame.d * Serpentine::runs(k)
    }

    /// The end pose: position, heading, stacking side.
    fn end(&self) -> (Point, Vec2, Vec2) {
        let (k, e) = self.serp.last();
        (
            self.frame.to_axis() * self.serp.centre(k, e),
            self.heading(k),
            self.frame.n,
        )
    }

    /// Every tile centre of the leg (rows and U-turn tiles), in chain order, axis frame.
    fn centres(&self, style: Style) -> Vec<Point> {
        let to_axis = self.frame.to_axis();
        self.serp
            .centres(style)
            .into_iter()
            .map(|c| to_axis * c)
            .collect()
    }
}

/// A partial or complete route.
#[derive(Clone)]
pub(crate) struct Route {
    pub cost: f64,
    legs: Vec<Arc<Leg>>,
    /// Tile centres so far, in pieces (shared between routes).
    centres: Vec<Arc<Vec<Point>>>,
    /// The bounding box of each piece of `centres`: the tests of a new leg pass over the
    /// pieces far from it (see [`far_apart`]).
    boxes: Vec<Rect>,
    /// The sequential fold check of the route so far (its tiles shared between routes).
    check: PrefixCheck,
    /// Each leg as [`LegMemo`] knows it: the call that offered it and its place among the
    /// offers.
    ids: Vec<(u64, usize)>,
}

/// A complete route made concrete: the fold word and where its first tile lies.
pub(crate) struct Routed {
    pub word: FoldWord,
    /// The map from the chain frame (w = 1) to the axis frame: tile 0 on the first row's
    /// start, heading along it.
    pub chain_to_axis: Affine,
    /// Tile centres as the route lays them (the axis frame), for cross-checking.
    pub centres: Vec<Point>,
    pub cells: usize,
    pub quarter_turns: usize,
    pub u_turns: usize,
    pub cost: f64,
}

/// The ends of a solved programme (on `lat`, cell frame `frame`) the route tries: the best
/// one whose last row runs +d and the best one running -d, and, when there is a next cell
/// (its bounding box `toward`, axis frame), for each parity the best end counting its
/// distance from that box: the exit of a cell is chosen with the entry of the next (the head of
/// a key ends its last column where the shaft begins, not at a corner).
///
/// The distance is priced at what it may cost the next cell: every tile width between the
/// end and the box is a strip of the cell (as long as the box's longer side) that the chain
/// cannot reach without crossing what it has laid, and rows hold `a / pitch` tile areas
/// per unit of area (`a` the tile area). A ring's top cell filled in rows ends a cell's
/// height away from the last cell and loses all of it; in columns it ends beside it.
///
/// Returned without and with the spread exits: the cheapest other exits of the near end's
/// row beside the next cell (see [`beside`]). An end's cost and look-ahead are those of its
/// row and column, so the ends of the first are among those of the second.
fn ends(
    sol: &Solved,
    lat: Lattice,
    pitch: f64,
    frame: Frame,
    toward: Option<Rect>,
    far_y: Option<f64>,
) -> [Vec<(f64, f64, usize, usize)>; 2] {
    let to_axis = frame.to_axis();
    // the distance penalty of an end: a look-ahead for ranking, not part of the cost
    let apart = |t: Rect, k: usize, e: usize| {
        let q = to_axis * Point::new(lat.x0 + e as f64, lat.y0 + k as f64 * pitch);
        let dx = (t.x0 - q.x).max(q.x - t.x1).max(0.0);
        let dy = (t.y0 - q.y).max(q.y - t.y1).max(0.0);
        (t.width().max(t.height()) * tile_area() / pitch, dx, dy)
    };
    let look = |k: usize, e: usize| match toward {
        Some(t) => {
            let (strip, dx, dy) = apart(t, k, e);
            strip * dx.hypot(dy)
        }
        None => 0.0,
    };
    // a bound the look-ahead never falls below, without the libm call: the hypotenuse is
    // at least the longer leg (faithfully rounded too: that leg is a float below it), less a
    // relative 1e-12 that covers the rounding of the products
    let look_lower = |k: usize, e: usize| match toward {
        Some(t) => {
            let (strip, dx, dy) = apart(t, k, e);
            strip * dx.max(dy) * (1.0 - 1e-12)
        }
        None => 0.0,
    };
    let mut out: [Vec<(f64, f64, usize, usize)>; 2] = [Vec::new(), Vec::new()];
    for par in [0, 1] {
        let plain = sol.best_end(|k| k % 2 == par);
        let near = toward.and_then(|_| sol.best_end_with(|k| k % 2 == par, look_lower, look));
        // and the other exits of the near end's row that lie beside the next cell: where
        // along the last row the chain leaves sets the phase of the next cell's rows (a
        // key's head ends its last column where the shaft's first row runs along the
        // shaft's middle, so that the rows below it can reach into the teeth), which the
        // look-ahead cannot see; the route's cost chooses among them
        let others = match (toward, near) {
            (Some(t), Some((_, k, _))) => beside(sol, lat, pitch, frame, t, k),
            _ => Vec::new(),
        };
        // and, for a cell whose rows must span it (`far_y`, a grown cell's lobes beyond its
        // rows, [`crate::lobes`]), the best end in the farthest row of this parity whose
        // line lies at most `far_y` high: the serpentine that reaches the cell's far side,
        // which the area alone may not choose
        let far = far_y.and_then(|y| {
            let top = ((y - lat.y0) / pitch).floor();
            if top < 0.0 {
                return None;
            }
            let top = top as usize;
            let k = if top % 2 == par {
                top
            } else {
                top.checked_sub(1)?
            };
            sol.best_end_with(|r| r == k, |_, _| 0.0, look)
        });
        // (only those, when asked)
        let (plain, near) = if far_y.is_some() {
            (None, None)
        } else {
            (plain, near)
        };
        for (spread, out) in out.iter_mut().enumerate() {
            let others = if spread == 1 { &others[..] } else { &[] };
            let found = plain.into_iter().chain(near).chain(others.iter().copied());
            for (c, k, e) in found.chain(far) {
                if !out.iter().any(|o| o.2 == k && o.3 == e) {
                    out.push((c, look(k, e), k, e));
                }
            }
        }
    }
    out
}

/// What a cell offers the routes that reach it ([`first_legs`], [`next_legs`]): its legs,
/// and the order in which a routing without and with the spread exits ([`ends`]) takes them.
struct Offers<T> {
    legs: Vec<T>,
    ways: [Vec<usize>; 2],
}

impl<T> Default for Offers<T> {
    fn default() -> Offers<T> {
        Offers {
            legs: Vec::new(),
            ways: [Vec::new(), Vec::new()],
        }
    }
}

impl<T> Offers<T> {
    /// Adds the ends of one programme ([`ends`]), each end once, as `leg` makes it.
    fn add(
        &mut self,
        found: [Vec<(f64, f64, usize, usize)>; 2],
        leg: impl Fn(f64, f64, usize, usize) -> T,
    ) {
        let [plain, spread] = found;
        let at = self.legs.len();
        for &(c, look, k, e) in &spread {
            self.ways[1].push(self.legs.len());
            self.legs.push(leg(c, look, k, e));
        }
        // each end of the first is one of the second (the same row and column)
        for &(c, look, k, e) in &plain {
            let i = match spread.iter().position(|o| o.2 == k && o.3 == e) {
                Some(i) => at + i,
                None => {
                    self.legs.push(leg(c, look, k, e));
                    self.legs.len() - 1
                }
            };
            self.ways[0].push(i);
        }
    }
}

/// Exits tried per row beside the next cell (see [`ends`]): a bound on the route's work.
const SPREAD: usize = 4;

/// The ends `(cost, row, column)` of row `k` of a solved programme whose tile centres lie
/// beside the box `t` (axis frame): their coordinate along the row within the box's extent
/// in that direction, at most [`SPREAD`], the cheapest.
fn beside(
    sol: &Solved,
    lat: Lattice,
    pitch: f64,
    frame: Frame,
    t: Rect,
    k: usize,
) -> Vec<(f64, usize, usize)> {
    let to_axis = frame.to_axis();
    let along_x = frame.d.x.abs() > 0.5;
    let (lo, hi) = if along_x { (t.x0, t.x1) } else { (t.y0, t.y1) };
    let mut found: Vec<(f64, usize, usize)> = (0..sol.cols())
        .filter_map(|e| {
            let q = to_axis * Point::new(lat.x0 + e as f64, lat.y0 + k as f64 * pitch);
            let v = if along_x { q.x } else { q.y };
            if v < lo || v > hi {
                return None;
            }
            sol.end_cost(k, e).map(|c| (c, k, e))
        })
        .collect();
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    found.truncate(SPREAD);
    found
}

/// The bounding box of `pts` (inverted, and so [`far_apart`] from every box, when empty).
fn bbox_of(pts: &[Point]) -> Rect {
    pts.iter().fold(
        Rect::new(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ),
        |b, &q| Rect::new(b.x0.min(q.x), b.y0.min(q.y), b.x1.max(q.x), b.y1.max(q.y)),
    )
}

/// True if every point of box `a` lies more than `gap` from every point of box `b` along x
/// or along y (a point of one then lies farther than `gap` from any point of the other).
fn far_apart(a: Rect, b: Rect, gap: f64) -> bool {
    a.x0 > b.x1 + gap || b.x0 > a.x1 + gap || a.y0 > b.y1 + gap || b.y0 > a.y1 + gap
}

/// True if some centre of `new` comes closer than [`MIN_GAP`] to a centre in `old` (pieces
/// with bounding boxes `boxes`): only the pieces whose box comes within a tile of `new`'s
/// are looked at, the same verdict as testing every centre.
fn overlaps(old: &[Arc<Vec<Point>>], boxes: &[Rect], new: &[Point]) -> bool {
    let reach = bbox_of(new);
    let mut near = old
        .iter()
        .zip(boxes)
        .filter(|(_, &b)| !far_apart(b, reach, 1.0))
        .peekable();
    if near.peek().is_none() {
        return false;
    }
    let grid = CentreGrid::new(new);
    near.flat_map(|(v, _)| v.iter())
        .any(|&p| grid.any_near(p, |t| (new[t].x - p.x).hypot(new[t].y - p.y) < MIN_GAP))
}

/// A leg with its cost and look-ahead.
type FirstLeg = (f64, f64, Leg);
/// A leg with its cost and look-ahead, and the tiles its join lays.
type NextLeg = (f64, f64, Leg, Vec<Point>);

/// The first leg: a free serpentine over the cell, rows along either axis, any corner and
/// phase; the best few by cost, for either routing ([`ends`]).
fn first_legs(
    shape: &Shape,
    style: Style,
    toward: Option<Rect>,
    need: Need,
    span: bool,
) -> Offers<FirstLeg> {
    let p = style.pitch;
    let mut out = Offers::default();
    for d in [
        Vec2::new(1.0, 0.0),
        Vec2::new(-1.0, 0.0),
        Vec2::new(0.0, 1.0),
        Vec2::new(0.0, -1.0),
    ] {
        for n in [d.turn_90(), -d.turn_90()] {
            if !allows(need, n) {
                continue;
            }
            let frame = Frame {
                o: Point::ZERO,
                d,
                n,
            };
            let work = frame.work(shape);
            // a cell whose rows must span it starts at its near side
            let solved: Vec<(Lattice, Solved)> = if span {
                solve_spanning(&work, style, work.bbox().y0 + 0.5 + p / 6.0)
            } else {
                Phased::new(&work, style).solve(style).collect()
            };
            for (lat, sol) in solved {
                let found = ends(&sol, lat, p, frame, toward, None);
                out.add(found, |cost, look, k, e| {
                    let serp = sol.serpentine(lat, p, k, e);
                    let join = Vec::new();
                    let leg = Leg {
                        frame,
                        serp,
                        join,
                        quarter: false,
                    };
                    (cost, look, leg)
                });
            }
        }
    }
    let legs = &out.legs;
    for way in &mut out.ways {
        way.sort_by(|&a, &b| (legs[a].0 + legs[a].1).total_cmp(&(legs[b].0 + legs[b].1)));
        way.truncate(BEAM);
    }
    out
}

/// A way from the end of one leg into the next cell.
struct Join {
    folds: Vec<Fold>,
    /// Tiles the join lays between the legs (U-turn tiles).
    tiles: Vec<Point>,
    /// The first centre of the next leg and the direction of its first row.
    start: Point,
    d: Vec2,
    /// The stacking sides the next leg may take.
    sides: Vec<Vec2>,
    quarter: bool,
}

/// The joins from a leg ending at `e` heading `h` with stacking side `side`.
fn joins(e: Point, h: Vec2, side: Vec2, style: Style) -> Vec<Join> {
    let mut out: Vec<Join> = Vec::new();
    for (f, h2) in [(Fold::L, h.turn_90()), (Fold::R, -h.turn_90())] {
        out.push(Join {
            folds: vec![f],
            tiles: Vec::new(),
            start: e + (h + h2) * FRAC_1_SQRT_2,
            d: h2,
            sides: vec![h, -h],
            quarter: true,
        });
    }
    let f = if side.dot(h.turn_90()) > 0.0 {
        Fold::L
    } else {
        Fold::R
    };
    let t1 = e + (h + side) * FRAC_1_SQRT_2;
    let (folds, tiles) = if style.turns == Turns::Loose {
        (vec![f, Fold::S, f], vec![t1, t1 + side])
    } else {
        (vec![f, f], vec![t1])
    };
    out.push(Join {
        folds,
        tiles,
        start: e + side * style.pitch,
        d: -h,
        sides: vec![side],
        quarter: false,
    });
    out.push(Join {
        folds: vec![Fold::S],
        tiles: Vec::new(),
        start: e + h,
        d: h,
        sides: vec![h.turn_90(), -h.turn_90()],
        quarter: false,
    });
    out
}

/// The legs that can follow `prev` into the cell `shape`: every join and stacking side, each
/// with the best end of either parity, with the tiles the join lays; for either routing
/// ([`ends`]).
fn next_legs(
    prev: &Leg,
    laid: &[Point],
    shape: &Shape,
    style: Style,
    toward: Option<Rect>,
    need: Need,
    span: bool,
) -> Offers<NextLeg> {
    // only tiles near the cell can block its rows
    let cell_box = shape.bbox().inflate(2.0, 2.0);
    let laid: Vec<Point> = laid
        .iter()
        .copied()
        .filter(|&q| cell_box.contains(q))
        .collect();
    let laid = &laid[..];
    let p = style.pitch;
    let (e, h, side) = prev.end();
    let mut out = Offers::default();
    for join in joins(e, h, side, style) {
        let near_box = laid
            .iter()
            .chain(&join.tiles)
            .fold(Rect::from_points(e, e), |b, &q| b.union_pt(q));
        for &n in &join.sides {
            if !allows(need, n) {
                continue;
            }
            let frame = Frame {
                o: join.start,
                d: join.d,
                n,
            };
            let work = frame.work(shape);
            let (lat, c0) = Lattice::from_origin(work.bbox(), p);
            // tiles of the leg may not overlap those laid before, nor the join's (a box
            // around them rejects most lattice tiles at once); each is asked only about the
            // lattice sites near it (see [`Blocked::test`])
            let to_axis = frame.to_axis();
            let reach = near_box.inflate(1.0, 1.0);
            let tiles: Vec<Point> = laid.iter().chain(&join.tiles).copied().collect();
            let test = |q: Point, t: usize| {
                let q = to_axis * q;
                reach.contains(q) && tiles[t].distance(q) < MIN_GAP
            };
            let cell_tiles: Vec<Point> = tiles.iter().map(|&q| frame.axis_to_cell() * q).collect();
            // `reach` in the cell frame, widened far beyond the rounding of either map: the
            // sites outside it are not blocked, so the test is not asked there
            let within = frame
                .axis_to_cell()
                .transform_rect_bbox(reach)
                .inflate(WITHIN_MARGIN, WITHIN_MARGIN);
            let blocked = Blocked {
                within,
                tiles: &cell_tiles,
                test: &test,
            };
            let sol = solve_rows(&work, style, lat, Some(c0), Some(blocked));
            let far = span.then(|| work.bbox().y1 - 0.5);
            let found = ends(&sol, lat, p, frame, toward, far);
            out.add(found, |cost, look, k, end| {
                let leg = Leg {
                    frame,
                    serp: sol.serpentine(lat, p, k, end),
                    join: join.folds.clone(),
                    quarter: join.quarter,
                };
                let price = if join.quarter || join.folds.len() > 1 {
                    style.turn_price
                } else {
                    0.0
                };
                (cost + price, look, leg, join.tiles.clone())
            });
        }
    }
    out
}

/// A leg's end pose (position to 1/1000 tile, heading, stacking side), for merging routes
/// that end alike.
type EndKey = [i64; 6];

fn end_key(leg: &Leg) -> EndKey {
    let (e, h, side) = leg.end();
    let r = |v: f64| (v * 1000.0).round() as i64;
    [r(e.x), r(e.y), r(h.x), r(h.y), r(side.x), r(side.y)]
}

/// The stacking side a cell's rows must take (`Some((n, either))`: `n`, or `-n` too when
/// `either`), or any (`None`).
pub(crate) type Need = Option<(Vec2, bool)>;

/// True if a cell whose rows are stacked towards `n` meets `need`.
fn allows(need: Need, n: Vec2) -> bool {
    match need {
        None => true,
        Some((m, either)) => (n - m).hypot() < 1e-9 || (either && (n + m).hypot() < 1e-9),
    }
}

/// The legs the cells offer at one tile width, by what fixes them, kept for both routings
/// there ([`route_sequence`] without and with the spread exits): where the cheapest routes
/// leave a part empty, the second routing meets the first's first legs, and many of its
/// next ones, again. A call is known by its cell (bit for bit), the style, what the cell needs,
/// the next cell's box and, after the first cell, the route's legs so far, each known by
/// the call that offered it and its place among the offers: they fix the tiles laid before
/// and where the route ends, and so the legs offered. The extensions the first routing
/// tried are kept too ([`extended`]: the fold check of the longer route and its verdict),
/// and given up as the second meets them. The first routing keeps, the second reads: what
/// is kept lasts one width. It only saves work.
#[derive(Default)]
pub(crate) struct LegMemo {
    kept: Mutex<Kept>,
}

/// Calls by their bits (see [`LegMemo`]), each with its id and offers.
type Calls<T> = HashMap<Vec<u64>, (u64, Arc<Offers<T>>)>;

/// What a [`LegMemo`] holds: cells by their bits, and the offers of each call with its id.
#[derive(Default)]
struct Kept {
    cells: HashMap<Vec<u64>, u64>,
    first: Calls<FirstLeg>,
    next: Calls<NextLeg>,
    calls: u64,
    /// Each route (its legs' ids) with a leg added, as [`extended`] found it.
    tried: HashMap<Vec<u64>, Extended>,
}

impl LegMemo {
    fn kept(&self) -> std::sync::MutexGuard<'_, Kept> {
        // a thread that panicked left whole entries only
        self.kept.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The id of the cell `shape` (the same for shapes the same bit for bit).
    fn cell(&self, shape: &Shape) -> u64 {
        let bits = shape.bits();
        let mut kept = self.kept();
        let n = kept.cells.len() as u64;
        *kept.cells.entry(bits).or_insert(n)
    }

    /// The offers of the call `key` (see [`LegMemo`]) and its id: kept, or made and kept.
    /// The offers of the call `key` (see [`LegMemo`]) and its id: kept, or made (and kept
    /// with `keep`; made and not kept, they take an id no call kept has).
    fn offers<T>(
        &self,
        (key, keep): (Vec<u64>, bool),
        map: fn(&mut Kept) -> &mut Calls<T>,
        make: impl FnOnce() -> Offers<T>,
    ) -> (u64, Arc<Offers<T>>) {
        {
            let mut kept = self.kept();
            if let Some(found) = map(&mut kept).get(&key) {
                return (found.0, Arc::clone(&found.1));
            }
        }
        let made = Arc::new(make());
        let mut kept = self.kept();
        let id = kept.calls;
        kept.calls += 1;
        if !keep {
            return (id, made);
        }
        // another thread may have made them meanwhile: the same offers, its id kept
        map(&mut kept).entry(key).or_insert((id, made)).clone()
    }

    /// [`extended`] of the route whose legs' ids, and the added leg's, are `key`: kept, or
    /// worked out (the tiles, the fold check and its verdict are those of the legs, which
    /// the ids fix). With `keep` what is worked out is kept; without, what was kept is
    /// given up (each extension is tried once a routing).
    fn tried(&self, (key, keep): (Vec<u64>, bool), make: impl FnOnce() -> Extended) -> Extended {
        if keep {
            if let Some(found) = self.kept().tried.get(&key) {
                return found.clone();
            }
            let made = make();
            return self.kept().tried.entry(key).or_insert(made).clone();
        }
        let found = self.kept().tried.remove(&key);
        found.unwrap_or_else(make)
    }
}

/// The bits of what fixes a cell's offers besides the route before it (see [`LegMemo`]).
fn call_key(
    kind: u64,
    cell: u64,
    style: Style,
    toward: Option<Rect>,
    need: Need,
    span: bool,
) -> Vec<u64> {
    let mut key = vec![kind, cell, style.turns as u64, style.pitch.to_bits()];
    key.extend(style.turn_heights.iter().map(|h| h.to_bits()));
    key.extend([
        style.turn_price.to_bits(),
        u64::from(style.lanes),
        u64::from(span),
    ]);
    match toward {
        Some(t) => key.extend([
            1,
            t.x0.to_bits(),
            t.y0.to_bits(),
            t.x1.to_bits(),
            t.y1.to_bits(),
        ]),
        None => key.push(0),
    }
    match need {
        Some((n, either)) => key.extend([1, n.x.to_bits(), n.y.to_bits(), u64::from(either)]),
        None => key.push(0),
    }
    key
}

/// The best routes through the cells `seq` in this order, each cell's rows stacked as its
/// [`Need`] says (and, where its flag is set, also made to span it: started at its near
/// side if first, ended at its far side, see [`ends`]), cheapest first; with `spread`, each cell followed by another also tries
/// the other exits of its last row beside that cell ([`ends`]): more ways, found by the same
/// bounded beam, that replace some of the cheapest (the caller routes both ways where the
/// cheapest leave a part of the shape empty).
pub(crate) fn route_sequence(
    seq: &[(&Shape, Need, bool)],
    style: Style,
    (memo, legs): (&CheckMemo, &LegMemo),
    spread: bool,
) -> Vec<Route> {
    let Some(&(first, need0, span0)) = seq.first() else {
        return Vec::new();
    };
    let root = memo.take();
    let beam = route_beam(seq, (first, need0, span0), style, (&root, legs), spread);
    memo.give(root);
    beam
}

/// The routes of one leg each through the first cell (`shape`, its id in `memo`, what it
/// needs and whether its rows span it), the next cell's box `toward`; see [`first_legs`].
fn first_beam(
    (shape, cell, need, span): (&Shape, u64, Need, bool),
    toward: Option<Rect>,
    style: Style,
    (root, memo): (&PrefixCheck, &LegMemo),
    spread: bool,
) -> Vec<Route> {
    let key = call_key(0, cell, style, toward, need, span);
    let (call, offers) = memo.offers(
        (key, !spread),
        |k| &mut k.first,
        || first_legs(shape, style, toward, need, span),
    );
    offers.ways[usize::from(spread)]
        .iter()
        .map(|&i| {
            let (cost, _, leg) = &offers.legs[i];
            let c = leg.centres(style);
            let mut check = root.emptied();
            check.push(&leg_folds(leg, style));
            Route {
                cost: *cost,
                legs: vec![Arc::new(leg.clone())],
                boxes: vec![bbox_of(&c)],
                centres: vec![Arc::new(c)],
                check,
                ids: vec![(call, i)],
            }
        })
        .collect()
}

/// [`route_sequence`] with an empty fold check whose memo the routes share.
fn route_beam(
    seq: &[(&Shape, Need, bool)],
    (first, need0, span0): (&Shape, Need, bool),
    style: Style,
    (root, memo): (&PrefixCheck, &LegMemo),
    spread: bool,
) -> Vec<Route> {
    let centre = |i: usize| seq.get(i).map(|c| c.0.bbox());
    let way = usize::from(spread);
    let cells: Vec<u64> = seq.iter().map(|c| memo.cell(c.0)).collect();
    // the first routing keeps what it finds, the second (with the spread exits) reads it
    let keep = !spread;
    let mut beam = first_beam(
        (first, cells[0], need0, span0),
        centre(1),
        style,
        (root, memo),
        spread,
    );
    for (at, &(shape, need, span)) in seq.iter().enumerate().skip(1) {
        let toward = centre(at + 1);
        // only tiles near the cell can block its rows (see [`next_legs`]): the pieces of a
        // route far from it are passed over whole
        let cell_box = shape.bbox().inflate(2.0, 2.0);
        // every extension, cheapest first; the overlap test (the costly part) runs only
        // until the beam is full
        let key = call_key(1, cells[at], style, toward, need, span);
        // each route's offers (with their call's id), and every extension: (cost, look-ahead,
        // route, offer)
        let mut offered: Vec<(u64, Arc<Offers<NextLeg>>)> = Vec::new();
        let mut cands: Vec<(f64, f64, usize, usize)> = Vec::new();
        for (i, r) in beam.iter().enumerate() {
            let Some(prev) = r.legs.last() else {
                offered.push((u64::MAX, Arc::new(Offers::default())));
                continue;
            };
            let mut key = key.clone();
            key.extend(r.id_bits());
            let (call, offers) = memo.offers(
                (key, keep),
                |k| &mut k.next,
                || {
                    next_legs(
                        prev,
                        &r.laid_near(cell_box),
                        shape,
                        style,
                        toward,
                        need,
                        span,
                    )
                },
            );
            for &j in &offers.ways[way] {
                let (cost, look, ..) = offers.legs[j];
                cands.push((r.cost + cost, look, i, j));
            }
            offered.push((call, offers));
        }
        // ranked with the look-ahead to the next cell; the route keeps the cost alone
        cands.sort_by(|a, b| (a.0 + a.1).total_cmp(&(b.0 + b.1)));
        let mut next: Vec<Route> = Vec::new();
        let mut seen: HashSet<EndKey> = HashSet::new();
        for (cost, _, i, j) in cands {
            if next.len() >= BEAM {
                break;
            }
            let (call, offers) = &offered[i];
            let (_, _, leg, join_tiles) = &offers.legs[j];
            // routes that end in the same pose have the same ways on; the cheapest is kept
            // (near-copies would fill the beam with one end: a ring's top cell all in rows
            // ending far from the last cell, none in columns ending at it)
            let key = end_key(leg);
            if seen.contains(&key) {
                continue;
            }
            let r = &mut beam[i];
            let mut tried = r.id_bits();
            tried.extend([*call, j as u64]);
            let extend = || extended(r, leg, join_tiles, style);
            let Some(took) = memo.tried((tried, keep), extend) else {
                continue;
            };
            let (check, c, b) = &*took;
            let mut legs = r.legs.clone();
            legs.push(Arc::new(leg.clone()));
            seen.insert(key);
            let mut boxes = r.boxes.clone();
            boxes.push(*b);
            let mut centres = r.centres.clone();
            centres.push(Arc::clone(c));
            let mut ids = r.ids.clone();
            ids.push((*call, j));
            next.push(Route {
                cost,
                legs,
                boxes,
                centres,
                check: check.clone(),
                ids,
            });
        }
        beam = next;
        if beam.is_empty() {
            break;
        }
    }
    beam
}

/// What route `r` becomes with `leg` (and its join's tiles) added: the fold check of the
/// longer chain and the leg's tiles with their box; `None` where the leg's tiles overlap
/// the route's or the longer chain collides when folded in sequence.
type Extended = Option<Arc<(PrefixCheck, Arc<Vec<Point>>, Rect)>>;

/// [`Extended`] worked out.
fn extended(r: &mut Route, leg: &Leg, join_tiles: &[Point], style: Style) -> Extended {
    let mut c = join_tiles.to_vec();
    c.extend(leg.centres(style));
    if overlaps(&r.centres, &r.boxes, &c) {
        return None;
    }
    // folding is sequential from tile 0: a prefix that collides stays colliding, so routes
    // are checked as they grow, not only when complete; the check of the route so far is
    // kept, and only what the leg changes is checked (the parent's joints are cleared for
    // the longer chain first, once for all its extensions)
    let folds = leg_folds(leg, style);
    r.check.clear_to(r.check.tiles() + folds.len());
    let mut check = r.check.clone();
    check.push(&folds);
    if !check.folds_cleanly() {
        return None;
    }
    let b = bbox_of(&c);
    Some(Arc::new((check, Arc::new(c), b)))
}

/// The folds of a leg, its join included.
fn leg_folds(leg: &Leg, style: Style) -> Vec<Fold> {
    let mut folds = leg.join.clone();
    leg.serp.folds(style, leg.frame.ccw(), &mut folds);
    folds
}

/// The folds of a route's legs, joins included.
fn route_folds(legs: &[Arc<Leg>], style: Style) -> Vec<Fold> {
    let mut folds = Vec::new();
    for leg in legs {
        folds.extend(leg_folds(leg, style));
    }
    folds
}

impl Route {
    /// The tiles of the pieces of the route whose box meets `near`.
    fn laid_near(&self, near: Rect) -> Vec<Point> {
        self.centres
            .iter()
            .zip(&self.boxes)
            .filter(|(_, &b)| !far_apart(b, near, 0.0))
            .flat_map(|(v, _)| v.iter().copied())
            .collect()
    }

    /// The ids of the route's legs ([`LegMemo`]) as bits.
    fn id_bits(&self) -> Vec<u64> {
        self.ids.iter().flat_map(|&(c, j)| [c, j as u64]).collect()
    }

    /// The route as a fold word with its frame and counts.
    pub(crate) fn to_routed(&self, style: Style) -> Option<Routed> {
        let first = self.legs.first()?;
        let folds = route_folds(&self.legs, style);
        let (k, s) = first.serp.first();
        let start = first.frame.to_axis() * first.serp.centre(k, s);
        let h = first.heading(k);
        let quarter_turns = self.legs.iter().filter(|l| l.quarter).count();
        let u_turns = self
            .legs
            .iter()
            .map(|l| l.serp.u_turns() + usize::from(l.join.len() > 1))
            .sum();
        Some(Routed {
            word: FoldWord::from_folds(folds),
            chain_to_axis: Affine::new([h.x, h.y, -h.y, h.x, start.x, start.y]),
            centres: self
                .centres
                .iter()
                .flat_map(|v| v.iter().copied())
                .collect(),
            cells: self.legs.len(),
            quarter_turns,
            u_turns,
            cost: self.cost,
        })
    }
}
