//! Planning across monotone cells (thesis section 5.5, the key; SPEC section 5): the shape is
//! split into cells along an axis ([`crate::cells`]), the cells are visited in the order of a
//! Hamiltonian path of the cell graph, and each cell is filled with a serpentine whose first
//! row starts exactly where the join from the previous cell puts the chain.
//!
//! Frame: the *axis frame* is the physical frame turned by `-axis` and scaled to tile widths;
//! every tile heading in it is a quarter turn. A cell's serpentine runs in a *cell frame*
//! (origin, row direction `d`, stacking side `n`, both axis vectors), where the row programme
//! of [`crate::rows`] applies unchanged. Joins between cells, from the end of the last row
//! heading `h`:
//! - a quarter turn, one L or R fold: the next centre is `(h + h') / sqrt2` away and the rows
//!   of the next cell run along `h'` (orthogonal), stacked towards `h` or `-h`;
//! - a U-turn towards the stacking side (LL/RR, or fold, straight, fold for loose turns): the
//!   next cell continues the stacking with parallel rows;
//! - a straight tile: the row runs on into the next cell.
//!
//! A beam search keeps the cheapest partial routes (row cost of [`crate::rows`] in every
//! cell so far, plus the part of each cell behind its first row); a route whose tile centres
//! come closer than one tile width (octagons of width 1 then overlap) is dropped. The best
//! complete routes become fold words, which are checked by sequential folding like every
//! plan.

use std::f64::consts::{FRAC_1_SQRT_2, PI};
use std::sync::Arc;

use foldchain::{Fold, FoldWord};
use rayon::prelude::*;

use crate::cells::{decompose, Cells};
use crate::check::check_folds;
use crate::planner::{Affine, Assembly, CentreGrid};
use crate::rows::{solve_rows, Lattice, Solved, Style, ROW_SAMPLES};
use crate::{Plan, PlanOptions, Shape, Turns, DEFAULT_TILES};

type V = (f64, f64);

fn add(a: V, b: V) -> V {
    (a.0 + b.0, a.1 + b.1)
}
fn mul(a: V, k: f64) -> V {
    (a.0 * k, a.1 * k)
}
fn dot(a: V, b: V) -> f64 {
    a.0 * b.0 + a.1 * b.1
}
fn left(a: V) -> V {
    (-a.1, a.0)
}
fn neg(a: V) -> V {
    (-a.0, -a.1)
}

/// Size steps of the tile width search.
const SIZE_STEPS: usize = 5;
/// The size search stops once the count is within this share of the target (2%: a cell
/// route changes by whole rows in several cells at once).
const CELL_COUNT_TOLERANCE: f64 = 0.02;
/// Routes (cheapest first, over all axes) checked and measured.
const CHECKED_ROUTES: usize = 6;
/// Partial routes kept at every depth of the beam search.
const BEAM: usize = 8;
/// Hamiltonian paths tried per axis, and the search steps spent finding them.
const MAX_ORDERS: usize = 12;
const MAX_ORDER_STEPS: usize = 20_000;
/// Axes with more cells than this are not planned by cells.
pub(crate) const MAX_CELLS: usize = 12;
/// Complete routes per axis turned into words and checked.
const ROUTES_KEPT: usize = 4;
/// Centres closer than this (tile widths) belong to overlapping tiles: every face of the
/// octagon is 1/2 from its centre, so two tiles closer than 1 overlap; the margin absorbs
/// rounding only (touching tiles are exactly 1 apart).
const MIN_GAP: f64 = 1.0 - 1e-6;

/// A cell frame: `x = (q - o) . d`, `y = (q - o) . n` in the axis frame.
#[derive(Clone, Copy, Debug)]
struct Frame {
    o: V,
    d: V,
    n: V,
}

impl Frame {
    fn to_axis(self, x: f64, y: f64) -> V {
        add(self.o, add(mul(self.d, x), mul(self.n, y)))
    }
    fn work(self, s: &Shape) -> Shape {
        let l = [self.d.0, self.d.1, self.n.0, self.n.1];
        s.affine(l, (-dot(self.o, self.d), -dot(self.o, self.n)))
    }
    /// True if turning from `d` towards `n` is counter-clockwise (an L fold).
    fn ccw(self) -> bool {
        self.d.0 * self.n.1 - self.d.1 * self.n.0 > 0.0
    }
}

/// One cell's serpentine and the join that leads into it.
#[derive(Clone, Debug)]
struct Leg {
    frame: Frame,
    x0: f64,
    y0: f64,
    pitch: f64,
    rows: Vec<(usize, i64, i64)>,
    /// Folds from the previous leg's last tile to this leg's first (empty for the first).
    join: Vec<Fold>,
    quarter: bool,
}

impl Leg {
    fn centre(&self, k: usize, j: i64) -> V {
        self.frame
            .to_axis(self.x0 + j as f64, self.y0 + k as f64 * self.pitch)
    }
    /// The end pose: position, heading, stacking side.
    fn end(&self) -> (V, V, V) {
        let &(k, _, e) = self.rows.last().unwrap_or(&(0, 0, 0));
        let h = if k % 2 == 0 {
            self.frame.d
        } else {
            neg(self.frame.d)
        };
        (self.centre(k, e), h, self.frame.n)
    }
    fn start_heading(&self) -> V {
        let k = self.rows.first().map_or(0, |r| r.0);
        if k % 2 == 0 {
            self.frame.d
        } else {
            neg(self.frame.d)
        }
    }
    /// Every tile centre of the leg (rows and U-turn tiles), in chain order.
    fn centres(&self, style: Style) -> Vec<V> {
        let mut out = Vec::new();
        for (i, &(k, s, e)) in self.rows.iter().enumerate() {
            let step = if e >= s { 1 } else { -1 };
            let mut j = s;
            loop {
                out.push(self.centre(k, j));
                if j == e {
                    break;
                }
                j += step;
            }
            if i + 1 < self.rows.len() {
                let dir = if k % 2 == 0 { 1.0 } else { -1.0 };
                let x = self.x0 + e as f64 + dir * FRAC_1_SQRT_2;
                let y = self.y0 + k as f64 * self.pitch + FRAC_1_SQRT_2;
                out.push(self.frame.to_axis(x, y));
                if style.turns == Turns::Loose {
                    out.push(self.frame.to_axis(x, y + 1.0));
                }
            }
        }
        out
    }
    /// The folds of the leg's own rows and U-turns.
    fn folds(&self, style: Style, out: &mut Vec<Fold>) {
        let ccw = self.frame.ccw();
        for (i, &(k, s, e)) in self.rows.iter().enumerate() {
            out.extend(std::iter::repeat_n(
                Fold::S,
                (e - s).unsigned_abs() as usize,
            ));
            if i + 1 < self.rows.len() {
                let f = if (k % 2 == 0) == ccw {
                    Fold::L
                } else {
                    Fold::R
                };
                out.push(f);
                if style.turns == Turns::Loose {
                    out.push(Fold::S);
                }
                out.push(f);
            }
        }
    }
}

/// A partial or complete route.
#[derive(Clone)]
struct Route {
    cost: f64,
    legs: Vec<Arc<Leg>>,
    /// Tile centres so far, in pieces (shared between routes).
    centres: Vec<Arc<Vec<V>>>,
}

/// A complete route made concrete: the fold word and where its first tile lies.
pub(crate) struct Routed {
    pub word: FoldWord,
    /// First tile centre and heading in the axis frame.
    pub start: V,
    pub heading: V,
    /// Tile centres as the route lays them (the axis frame), for cross-checking.
    pub centres: Vec<V>,
    pub cells: usize,
    pub quarter_turns: usize,
    pub u_turns: usize,
    pub cost: f64,
}

/// Why an axis gave no route.
pub(crate) type Why = String;

/// The shape length of the rows of the cell behind its first row (never reached).
fn behind(work: &Shape, pitch: f64) -> f64 {
    let ymin = work.bbox().1;
    let ns = ROW_SAMPLES.len() as f64;
    let mut total = 0.0;
    let mut m = 1.0;
    while -m * pitch > ymin - 1.0 {
        for d in ROW_SAMPLES {
            total += work
                .intervals_at(-m * pitch + d)
                .iter()
                .map(|(a, b)| b - a)
                .sum::<f64>()
                / ns;
        }
        m += 1.0;
    }
    total
}

/// The best ends of a solved programme: one whose last row runs +d, one -d.
fn ends(sol: &Solved) -> Vec<(f64, usize, usize)> {
    [0, 1]
        .iter()
        .filter_map(|&par| sol.best_end(|k| k % 2 == par))
        .collect()
}

/// True if some centre of `new` comes closer than [`MIN_GAP`] to a centre in `old`.
fn overlaps(old: &[Arc<Vec<V>>], new: &[V]) -> bool {
    let grid = CentreGrid::new(new);
    old.iter().flat_map(|v| v.iter()).any(|&p| {
        let (cx, cy) = (p.0.floor() as i64, p.1.floor() as i64);
        (-1..=1).any(|i| {
            (-1..=1).any(|j| {
                grid.in_cell(cx + i, cy + j).iter().any(|&t| {
                    let q = new[t];
                    (q.0 - p.0).hypot(q.1 - p.1) < MIN_GAP
                })
            })
        })
    })
}

/// The first leg: a free serpentine over the cell, rows along either axis, any corner and
/// phase; the best few by cost.
fn first_legs(shape: &Shape, style: Style) -> Vec<(f64, Leg)> {
    let p = style.pitch;
    let mut frames = Vec::new();
    for d in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
        for n in [left(d), neg(left(d))] {
            frames.push(Frame {
                o: (0.0, 0.0),
                d,
                n,
            });
        }
    }
    let phases = [0.0, 1.0 / 3.0, 2.0 / 3.0];
    let mut out = Vec::new();
    for frame in frames {
        let work = frame.work(shape);
        let (xmin, ymin, xmax, ymax) = work.bbox();
        for xp in phases {
            for yp in phases {
                let x0 = xmin.floor() - 2.0 + xp;
                let y0 = ymin + 0.5 + (yp - 1.0) * p;
                let lat = Lattice {
                    x0,
                    y0,
                    cols: ((xmax - x0).ceil() as usize) + 3,
                    nrows: (((ymax - y0) / p).ceil() as usize) + 2,
                };
                let sol = solve_rows(&work, style, lat, None);
                for (cost, k, e) in ends(&sol) {
                    out.push((
                        cost,
                        Leg {
                            frame,
                            x0,
                            y0,
                            pitch: p,
                            rows: sol.rows_to(k, e),
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

/// The legs that can follow `prev` into `cell`: every join and stacking side, each with the
/// best end of either parity.
fn next_legs(prev: &Leg, shape: &Shape, style: Style) -> Vec<(f64, Leg, Vec<V>)> {
    let p = style.pitch;
    let (e, h, side) = prev.end();
    // (folds, tiles the join adds, first centre of the leg, its heading, stacking sides,
    // whether it is a quarter turn)
    type Join = (Vec<Fold>, Vec<V>, V, V, Vec<V>, bool);
    let mut joins: Vec<Join> = Vec::new();
    for (f, h2) in [(Fold::L, left(h)), (Fold::R, neg(left(h)))] {
        let start = add(e, mul(add(h, h2), FRAC_1_SQRT_2));
        joins.push((vec![f], Vec::new(), start, h2, vec![h, neg(h)], true));
    }
    {
        let f = if dot(side, left(h)) > 0.0 {
            Fold::L
        } else {
            Fold::R
        };
        let t1 = add(e, mul(add(h, side), FRAC_1_SQRT_2));
        let (folds, tiles, start) = if style.turns == Turns::Loose {
            let t2 = add(t1, side);
            (vec![f, Fold::S, f], vec![t1, t2], add(e, mul(side, p)))
        } else {
            (vec![f, f], vec![t1], add(e, mul(side, p)))
        };
        joins.push((folds, tiles, start, neg(h), vec![side], false));
    }
    joins.push((
        vec![Fold::S],
        Vec::new(),
        add(e, h),
        h,
        vec![left(h), neg(left(h))],
        false,
    ));
    let mut out = Vec::new();
    for (folds, tiles, start, d, sides, quarter) in joins {
        for n in sides {
            let frame = Frame { o: start, d, n };
            let work = frame.work(shape);
            let (xmin, _, xmax, ymax) = work.bbox();
            let x0 = (xmin.floor() - 2.0).min(-2.0);
            let c0 = (-x0) as usize;
            let cols = (((xmax - x0).ceil() as usize) + 3).max(c0 + 3);
            let nrows = if ymax > 0.0 {
                ((ymax / p).ceil() as usize) + 2
            } else {
                1
            };
            let lat = Lattice {
                x0,
                y0: 0.0,
                cols,
                nrows,
            };
            let sol = solve_rows(&work, style, lat, Some(c0));
            let back = behind(&work, p);
            for (cost, k, end) in ends(&sol) {
                out.push((
                    cost + back,
                    Leg {
                        frame,
                        x0,
                        y0: 0.0,
                        pitch: p,
                        rows: sol.rows_to(k, end),
                        join: folds.clone(),
                        quarter,
                    },
                    tiles.clone(),
                ));
            }
        }
    }
    out
}

/// The best routes through the cells in `order`.
fn route_order(cells: &Cells, order: &[usize], style: Style) -> Vec<Route> {
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
        let mut cands: Vec<(f64, usize, Leg, Vec<V>)> = Vec::new();
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
    fn to_routed(&self, style: Style) -> Option<Routed> {
        let first = self.legs.first()?;
        let mut folds = Vec::new();
        for leg in &self.legs {
            folds.extend(leg.join.iter().copied());
            leg.folds(style, &mut folds);
        }
        let (k, s, _) = *first.rows.first()?;
        let quarter_turns = self.legs.iter().filter(|l| l.quarter).count();
        let u_turns = self
            .legs
            .iter()
            .map(|l| l.rows.len().saturating_sub(1) + usize::from(l.join.len() > 1))
            .sum();
        Some(Routed {
            word: FoldWord::from_folds(folds),
            start: first.centre(k, s),
            heading: first.start_heading(),
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

/// The cell decomposition of the axis-frame shape at unit tiles.
pub(crate) fn cells_of(axis_shape: &Shape) -> Cells {
    // ends jumping by more than a tile start a new cell; cells under one tile are dropped
    decompose(axis_shape, 1.0, 1.0)
}

/// The best routes over the cells of `axis_shape` (axis frame, unit tiles), cheapest first,
/// or why there is none. `describe` names a cell for messages.
pub(crate) fn plan_cells(
    axis_shape: &Shape,
    style: Style,
    describe: &dyn Fn(&Shape) -> String,
) -> Result<Vec<Routed>, Why> {
    let cells = cells_of(axis_shape);
    let n = cells.cells.len();
    if n == 0 {
        return Err("no cell larger than a tile".into());
    }
    if n > MAX_CELLS {
        return Err(format!(
            "{n} cells (more than {MAX_CELLS}): the outline has too many steps and branches at this tile size"
        ));
    }
    let parts = cells.components();
    if parts > 1 {
        return Err(format!(
            "the shape is in {parts} separate parts at this tile size; one chain would have to cross the gap between them"
        ));
    }
    let orders = cells.orders(MAX_ORDERS, MAX_ORDER_STEPS);
    if orders.is_empty() {
        let (deg, c) = cells.max_degree();
        return Err(format!(
            "{n} cells and no order visits each once: cell {} ({}) touches {deg} others, more than a path through it can enter and leave; it needs splitting (Cheung et al.) or another axis",
            c,
            describe(&cells.cells[c].shape)
        ));
    }
    let mut routes: Vec<Route> = orders
        .par_iter()
        .flat_map_iter(|o| route_order(&cells, o, style).into_iter().take(2))
        .collect();
    if routes.is_empty() {
        return Err(format!(
            "{n} cells; every join between them ({} orders tried) lays tiles over earlier ones",
            orders.len()
        ));
    }
    routes.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    Ok(routes
        .iter()
        .take(ROUTES_KEPT)
        .filter_map(|r| r.to_routed(style))
        .collect())
}

/// Axes to sweep (radians, physical frame): the x and y axes and the long edge directions,
/// each with its orthogonal sweep.
pub(crate) fn axes(shape: &Shape) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    let mut push = |a: f64| {
        let a = a.rem_euclid(PI);
        if !out.iter().any(|&b| {
            let d = (a - b).rem_euclid(PI);
            d.min(PI - d) < 1e-6
        }) {
            out.push(a);
        }
    };
    for a in std::iter::once(0.0).chain(shape.long_edge_angles(3)) {
        push(a);
        push(a + PI / 2.0);
    }
    out.truncate(6);
    out
}

/// Plans `shape` by cells with one turn style: the tile width is searched like the
/// serpentine's (a few secant steps on the count), every axis is routed in parallel, and the
/// cheapest routes are checked by sequential folding; the best fit wins. The error says, per
/// axis, why no route was found.
pub(crate) fn plan_by_cells(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    name: &str,
) -> Result<Plan, String> {
    let area = shape.area();
    let w_for = |n: usize| (area / (n as f64 * style.pitch)).sqrt();
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let mut w = opts.tile_size.unwrap_or_else(|| w_for(target));
    let steps = if opts.tile_size.is_some() {
        1
    } else {
        SIZE_STEPS
    };
    let tolerance = ((CELL_COUNT_TOLERANCE * target as f64) as usize).max(1);
    let axes = axes(shape);
    // (miss, tile width, routes with their axis, cheapest first)
    type Sized = (usize, f64, Vec<(f64, Routed)>);
    let mut best: Option<Sized> = None;
    // reasons, each with the axes (SVG degrees) it holds for
    let mut why: Vec<(String, Vec<String>)> = Vec::new();
    for _ in 0..steps {
        let per_axis: Vec<(f64, Result<Vec<Routed>, Why>)> = axes
            .par_iter()
            .map(|&a| {
                let axis_shape = shape.rotated(-a).scaled(1.0 / w);
                let describe = |cell: &Shape| describe_cell(cell, a, w);
                (a, plan_cells(&axis_shape, style, &describe))
            })
            .collect();
        let mut routes: Vec<(f64, Routed)> = Vec::new();
        why.clear();
        for (a, r) in per_axis {
            match r {
                Ok(v) => routes.extend(v.into_iter().map(|x| (a, x))),
                Err(e) => {
                    let deg = format!("{:.0}", svg_axis_deg(a).round() % 180.0 + 0.0);
                    match why.iter_mut().find(|(r, _)| *r == e) {
                        Some((_, axes)) => axes.push(deg),
                        None => why.push((e, vec![deg])),
                    }
                }
            }
        }
        routes.sort_by(|x, y| x.1.cost.total_cmp(&y.1.cost));
        let Some(first) = routes.first() else {
            break;
        };
        let n = first.1.word.tiles();
        let miss = n.abs_diff(target);
        if best.as_ref().is_none_or(|b| miss < b.0) {
            best = Some((miss, w, routes));
        }
        if miss <= tolerance {
            break;
        }
        w *= (n as f64 / target as f64).sqrt();
    }
    let Some((_, w, routes)) = best else {
        let text: Vec<String> = why
            .iter()
            .map(|(r, axes)| format!("along axes {} deg: {r}", axes.join(", ")))
            .collect();
        return Err(text.join("; "));
    };
    let mut plans: Vec<Plan> = Vec::new();
    let mut collide = String::new();
    for (a, r) in routes.iter().take(CHECKED_ROUTES) {
        if let Err(e) = check_folds(&r.word) {
            collide = e;
            continue;
        }
        let h = r.heading;
        let work = shape.rotated(-a).scaled(1.0 / w);
        let (s, c) = a.sin_cos();
        let asm = Assembly {
            work: &work,
            chain_to_work: Affine {
                l: [h.0, -h.1, h.1, h.0],
                t: r.start,
            },
            work_to_svg: Affine {
                l: [w * c, -w * s, -w * s, -w * c],
                t: (0.0, 0.0),
            },
            row_angle: *a,
            style,
            w,
            u_turns: r.u_turns,
            quarter_turns: r.quarter_turns,
            cells: r.cells,
        };
        if !asm.agrees(&r.word, &r.centres) {
            collide =
                String::from("internal: the route's tile centres disagree with the kinematics");
            continue;
        }
        plans.push(asm.to_plan(&r.word, name));
    }
    plans
        .into_iter()
        .min_by(|x, y| x.metrics.fit_error().total_cmp(&y.metrics.fit_error()))
        .ok_or_else(|| format!("every cell route collides when folded (first: {collide})"))
}

/// The SVG direction (degrees in `[0, 180)`) of the sweep of row angle `a`.
fn svg_axis_deg(a: f64) -> f64 {
    let (s, c) = a.sin_cos();
    (-c).atan2(-s).to_degrees().rem_euclid(180.0)
}

/// A cell (axis frame of row angle `a`, tiles of width `w`) by its bounding box in SVG user
/// units.
fn describe_cell(cell: &Shape, a: f64, w: f64) -> String {
    let phys = cell.scaled(w).rotated(a);
    let (x0, y0, x1, y1) = phys.bbox();
    format!("x {x0:.0} to {x1:.0}, y {:.0} to {:.0}", -y1, -y0)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::rows::TIGHT;

    fn sample(name: &str) -> Shape {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shapes")
            .join(name);
        Shape::from_svg_data(&std::fs::read(path).unwrap(), name).unwrap()
    }

    /// The thesis key by cells: head and shaft as separate cells, every route folds.
    #[test]
    fn key_by_cells() {
        let opts = PlanOptions::default().with_tiles(171);
        let p = plan_by_cells(&sample("key.svg"), &opts, TIGHT, "key.svg").unwrap();
        eprintln!("key by cells: {}", p.summary());
        assert!(p.cells >= 2, "{}", p.summary());
        let w = p.fold_word().unwrap();
        assert!(w.first_opposite_pair().is_none());
        assert!(foldchain::collision::check_word(&w, &Default::default()).is_ok());
    }
}
