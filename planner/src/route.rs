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
//! in every cell so far); a route whose tile centres
//! come closer than one tile width (octagons of width 1 then overlap) is dropped.

use std::f64::consts::FRAC_1_SQRT_2;
use std::sync::Arc;

use foldchain::{Fold, FoldWord};
use kurbo::{Affine, Point, Vec2};

use crate::cells::Cells;
use crate::centre_grid::CentreGrid;
use crate::options::Turns;
use crate::rows::{solve_rows, Lattice, Serpentine, Solved, Style};
use crate::shape::Shape;

/// Partial routes kept at every depth of the beam search.
const BEAM: usize = 8;
/// Centres closer than this (tile widths) belong to overlapping tiles: every face of the
/// octagon is 1/2 from its centre, so two tiles closer than 1 overlap; the margin absorbs
/// rounding only (touching tiles are exactly 1 apart).
const MIN_GAP: f64 = 1.0 - 1e-6;

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

    /// The axis-frame shape in the cell frame (`d`, `n` orthonormal: the inverse is the
    /// transpose).
    fn work(self, s: &Shape) -> Shape {
        let o = self.o.to_vec2();
        s.transformed(Affine::new([
            self.d.x,
            self.n.x,
            self.d.y,
            self.n.y,
            -o.dot(self.d),
            -o.dot(self.n),
        ]))
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

/// The best ends of a solved programme: one whose last row runs +d, one -d.
fn ends(sol: &Solved) -> Vec<(f64, usize, usize)> {
    [0, 1]
        .iter()
        .filter_map(|&par| sol.best_end(|k| k % 2 == par))
        .collect()
}

/// True if some centre of `new` comes closer than [`MIN_GAP`] to a centre in `old`.
fn overlaps(old: &[Arc<Vec<Point>>], new: &[Point]) -> bool {
    let grid = CentreGrid::new(new);
    old.iter()
        .flat_map(|v| v.iter())
        .any(|&p| grid.any_near(p, |t| (new[t].x - p.x).hypot(new[t].y - p.y) < MIN_GAP))
}

/// The first leg: a free serpentine over the cell, rows along either axis, any corner and
/// phase; the best few by cost.
fn first_legs(shape: &Shape, style: Style) -> Vec<(f64, Leg)> {
    let p = style.pitch;
    let mut out = Vec::new();
    for d in [
        Vec2::new(1.0, 0.0),
        Vec2::new(-1.0, 0.0),
        Vec2::new(0.0, 1.0),
        Vec2::new(0.0, -1.0),
    ] {
        for n in [d.turn_90(), -d.turn_90()] {
            let frame = Frame {
                o: Point::ZERO,
                d,
                n,
            };
            let work = frame.work(shape);
            for lat in Lattice::phased(work.bbox(), p) {
                let sol = solve_rows(&work, style, lat, None);
                for (cost, k, e) in ends(&sol) {
                    let serp = sol.serpentine(lat, p, k, e);
                    out.push((
                        cost,
                        Leg {
                            frame,
                            serp,
                            join: Vec::new(),
                            quarter: false,
                        },
                    ));
                }
            }
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.truncate(BEAM);
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
/// with the best end of either parity, with the tiles the join lays.
fn next_legs(prev: &Leg, shape: &Shape, style: Style) -> Vec<(f64, Leg, Vec<Point>)> {
    let p = style.pitch;
    let (e, h, side) = prev.end();
    let mut out = Vec::new();
    for join in joins(e, h, side, style) {
        for &n in &join.sides {
            let frame = Frame {
                o: join.start,
                d: join.d,
                n,
            };
            let work = frame.work(shape);
            let (lat, c0) = Lattice::from_origin(work.bbox(), p);
            let sol = solve_rows(&work, style, lat, Some(c0));
            for (cost, k, end) in ends(&sol) {
                let leg = Leg {
                    frame,
                    serp: sol.serpentine(lat, p, k, end),
                    join: join.folds.clone(),
                    quarter: join.quarter,
                };
                out.push((cost, leg, join.tiles.clone()));
            }
        }
    }
    out
}

/// The best routes through the cells in `order`, cheapest first.
pub(crate) fn route_order(cells: &Cells, order: &[usize], style: Style) -> Vec<Route> {
    let mut beam: Vec<Route> = first_legs(&cells.cells[order[0]].shape, style)
        .into_iter()
        .map(|(cost, leg)| {
            let c = leg.centres(style);
            Route {
                cost,
                legs: vec![Arc::new(leg)],
                centres: vec![Arc::new(c)],
            }
        })
        .collect();
    for &cell in &order[1..] {
        let shape = &cells.cells[cell].shape;
        // every extension, cheapest first; the overlap test (the costly part) runs only
        // until the beam is full
        let mut cands: Vec<(f64, usize, Leg, Vec<Point>)> = Vec::new();
        for (i, r) in beam.iter().enumerate() {
            let Some(prev) = r.legs.last() else { continue };
            for (cost, leg, join_tiles) in next_legs(prev, shape, style) {
                cands.push((r.cost + cost, i, leg, join_tiles));
            }
        }
        cands.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut next: Vec<Route> = Vec::new();
        for (cost, i, leg, join_tiles) in cands {
            if next.len() >= BEAM {
                break;
            }
            let r = &beam[i];
            let mut c = join_tiles;
            c.extend(leg.centres(style));
            if overlaps(&r.centres, &c) {
                continue;
            }
            let mut legs = r.legs.clone();
            legs.push(Arc::new(leg));
            let mut centres = r.centres.clone();
            centres.push(Arc::new(c));
            next.push(Route {
                cost,
                legs,
                centres,
            });
        }
        beam = next;
        if beam.is_empty() {
            break;
        }
    }
    beam
}

impl Route {
    /// The route as a fold word with its frame and counts.
    pub(crate) fn to_routed(&self, style: Style) -> Option<Routed> {
        let first = self.legs.first()?;
        let mut folds = Vec::new();
        for leg in &self.legs {
            folds.extend(leg.join.iter().copied());
            leg.serp.folds(style, leg.frame.ccw(), &mut folds);
        }
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
