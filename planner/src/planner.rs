//! Serpentine planning (thesis section 5.5): rows of straight tiles orthogonal to a direction
//! in which the shape is monotone, joined by U-turns that alternate in direction.
//!
//! Frames: the *physical* frame is the drawing seen from above, y up (see [`crate::shape`]);
//! the *plan* frame is the physical one turned so that rows run along x; the *work* frame
//! mirrors the plan frame (x by `sx`, y by `sy`) so that the rows are stacked towards +y,
//! and is scaled to tile widths (w = 1). The dynamic programme runs in the work frame.
//!
//! Row `k` sits at `y_k = y_0 + k p` (p the row pitch) and runs +x for even `k`, -x for odd.
//! Every row starts in the column where the previous one ended (a U-turn brings the chain
//! back exactly above the last tile), so all row tiles sit on columns `x_j = x_0 + j` and a
//! plan is a sequence of row ends. The cost of a row is the length of the symmetric
//! difference between the span of its tiles and the shape along the row (averaged over three
//! lines across the tile), plus, for each turn tile, the part of it outside the shape. The
//! cost of a row from column `s` to `e` splits into a term of `s` and a term of `e`, so the
//! best predecessor of every end column is a running minimum: the programme takes O(rows x
//! columns) for each orientation, phase and start corner, and is exact over all row-length
//! choices (no row-by-row rounding).

use std::collections::HashMap;
use std::f64::consts::{FRAC_1_SQRT_2, PI, SQRT_2};

use foldchain::{kinematics, BillOfMaterials, Fold, FoldWord};

use rayon::prelude::*;

use crate::check::check_folds;
use crate::plan::{Metrics, PlanPose};
use crate::route;
use crate::rows::{solve_rows, Lattice, Style, LOOSE, TIGHT};
use crate::{Plan, PlanError, PlanOptions, Shape, Turns, DEFAULT_TILES};

/// Horizontal and vertical phases tried, as shares of a column and of a row pitch.
const PHASES: [f64; 3] = [0.0, 1.0 / 3.0, 2.0 / 3.0];
/// At most this many row directions are compared by full planning.
const MAX_DIRECTIONS: usize = 16;
/// Above this many tiles the direction is chosen on a coarser plan of this many tiles.
const COARSE_TILES: usize = 3000;
/// A shape monotone in no direction is planned as one serpentine that bridges its gaps
/// only while at most this share of the chain lies outside it; beyond, it is unplannable.
const MAX_OUTSIDE_NON_MONOTONE: f64 = 0.10;
/// Shapes monotone in some direction are also planned by cells up to this many tiles.
const MAX_CELL_TILES: usize = 20_000;
/// Plans tried (best first) until one passes the collision check.
const MAX_CHECKED: usize = 8;
/// The size search stops once the tile count is within this share of the target (0.1%:
/// 100 tiles in 100,000; below 1,000 tiles it must be met exactly, or as near as the steps
/// reach).
const COUNT_TOLERANCE: f64 = 1e-3;

/// One way to lay the serpentine: row direction and start corner.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Orientation {
    /// Row direction in the physical frame, radians.
    angle: f64,
    sx: f64,
    sy: f64,
}

/// A solved serpentine in the work frame.
#[derive(Clone, Debug)]
struct Serpentine {
    orient: Orientation,
    cost: f64,
    x0: f64,
    y0: f64,
    pitch: f64,
    /// (row index k, start column, end column) in chain order.
    rows: Vec<(usize, i64, i64)>,
}

/// Solves the serpentine for a work-frame shape at unit tile width.
fn solve(work: &Shape, style: Style, xp: f64, yp: f64, orient: Orientation) -> Option<Serpentine> {
    let (xmin, ymin, xmax, ymax) = work.bbox();
    let p = style.pitch;
    let x0 = xmin.floor() - 2.0 + xp;
    let cols = ((xmax - x0).ceil() as usize) + 3;
    let y0 = ymin + 0.5 + (yp - 1.0) * p;
    let nrows = (((ymax - y0) / p).ceil() as usize) + 2;
    let lat = Lattice {
        x0,
        y0,
        cols,
        nrows,
    };
    let sol = solve_rows(work, style, lat, None);
    let (cost, k, e) = sol.best_end(|_| true)?;
    Some(Serpentine {
        orient,
        cost,
        x0,
        y0,
        pitch: p,
        rows: sol.rows_to(k, e),
    })
}

impl Serpentine {
    /// The number of tiles of its chain.
    fn tiles(&self, style: Style) -> usize {
        let row_tiles: usize = self
            .rows
            .iter()
            .map(|&(_, s, e)| (e - s).unsigned_abs() as usize + 1)
            .sum();
        // a tight U-turn adds its LL/RR tile, a loose one that and a straight tile
        let turn_tiles = if style.turns == Turns::Loose { 2 } else { 1 };
        row_tiles + turn_tiles * self.rows.len().saturating_sub(1)
    }

    /// The fold word: rows of straight joints, U-turns between them.
    fn word(&self, style: Style) -> FoldWord {
        let proper = self.orient.sx * self.orient.sy > 0.0;
        let mut folds = Vec::new();
        for (i, &(k, s, e)) in self.rows.iter().enumerate() {
            let n = (e - s).unsigned_abs() as usize + 1;
            folds.extend(std::iter::repeat_n(Fold::S, n - 1));
            if i + 1 < self.rows.len() {
                // from a +x row, turning towards +y is counter-clockwise in the work frame
                let ccw = k % 2 == 0;
                let f = if ccw == proper { Fold::L } else { Fold::R };
                folds.push(f);
                if style.turns == Turns::Loose {
                    folds.push(Fold::S);
                }
                folds.push(f);
            }
        }
        FoldWord::from_folds(folds)
    }

    /// The affine map from the chain frame (w = 1) to the work frame: linear part
    /// (row-major 2x2) and translation.
    fn chain_to_work(&self) -> ([f64; 4], (f64, f64)) {
        let (k, s, _) = self.rows[0];
        let d0 = if k % 2 == 0 { 1.0 } else { -1.0 };
        let sigma = self.orient.sx * self.orient.sy;
        (
            [d0, 0.0, 0.0, d0 * sigma],
            (self.x0 + s as f64, self.y0 + k as f64 * self.pitch),
        )
    }
}

/// An affine map `p -> L p + t` with `L` row-major.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Affine {
    pub l: [f64; 4],
    pub t: (f64, f64),
}

impl Affine {
    fn apply(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (
            self.l[0] * x + self.l[1] * y + self.t.0,
            self.l[2] * x + self.l[3] * y + self.t.1,
        )
    }
    fn linear(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (self.l[0] * x + self.l[1] * y, self.l[2] * x + self.l[3] * y)
    }
    /// `self` after `first`.
    fn after(&self, first: &Affine) -> Affine {
        let a = self.l;
        let b = first.l;
        Affine {
            l: [
                a[0] * b[0] + a[1] * b[2],
                a[0] * b[1] + a[1] * b[3],
                a[2] * b[0] + a[3] * b[2],
                a[2] * b[1] + a[3] * b[3],
            ],
            t: self.apply(first.t),
        }
    }
}

/// work -> SVG user units.
fn work_to_svg(o: Orientation, w: f64) -> Affine {
    let (s, c) = o.angle.sin_cos();
    // work -> plan (mirror, scale w) -> physical (rotate) -> SVG (flip y)
    let l = [
        w * o.sx * c,
        -w * o.sy * s,
        -(w * o.sx * s),
        -(w * o.sy * c),
    ];
    Affine { l, t: (0.0, 0.0) }
}

/// The serpentines of one turn style at the tile width the size search settled on.
struct Sized {
    style: Style,
    w: f64,
    /// Every serpentine at that width, lowest cost first.
    all: Vec<Serpentine>,
}

/// The most tiles a plan may hold: two million, twice the largest plan benchmarked (a million
/// tiles in about 15 s); larger requests are refused up front instead of running for minutes.
pub const MAX_PLAN_TILES: usize = 2_000_000;

/// Plans a shape (physical frame).
pub(crate) fn plan_shape(shape: &Shape, opts: &PlanOptions, name: &str) -> Result<Plan, PlanError> {
    if let Some(w) = opts.tile_size {
        if !(w.is_finite() && w > 0.0) {
            return Err(PlanError::BadOption {
                option: "--tile-size",
                reason: format!("{w}: expected a positive number of SVG user units"),
            });
        }
    }
    if opts.tiles == Some(0) {
        return Err(PlanError::BadOption {
            option: "--tiles",
            reason: "0: expected at least 1".into(),
        });
    }
    // Guard against sizes no run can finish (or allocate): the chain may hold at most
    // MAX_PLAN_TILES tiles, asked for directly or implied by the tile size.
    if let Some(n) = opts.tiles.filter(|&n| n > MAX_PLAN_TILES) {
        return Err(PlanError::BadOption {
            option: "--tiles",
            reason: format!("{n}: expected at most {MAX_PLAN_TILES}"),
        });
    }
    if let Some(w) = opts.tile_size {
        // a tile covers w^2 (sqrt2 - 1) * 2 of area: about w^2 / 1.2; the estimate only has
        // to be right to a small factor
        let implied = shape.area() / (0.8 * w * w);
        if implied > MAX_PLAN_TILES as f64 {
            return Err(PlanError::BadOption {
                option: "--tile-size",
                reason: format!(
                    "{w}: the shape would take about {implied:.3e} tiles of that size, more than the {MAX_PLAN_TILES} a plan may hold"
                ),
            });
        }
    }
    let styles: Vec<Style> = match opts.turns {
        Turns::Tight => vec![TIGHT],
        Turns::Loose => vec![LOOSE],
        Turns::Auto => vec![TIGHT, LOOSE],
    };
    let monotone = shape.monotone_row_angles();
    let directions = pick_directions(shape, &monotone);
    // size every style (in parallel), measure the best unchecked plan of each, then check
    // the styles best fit first: a long chain is checked once, not once per style
    let sized: Vec<Result<Sized, String>> = styles
        .par_iter()
        .map(|&style| size_style(shape, opts, style, &directions))
        .collect();
    let mut failures: Vec<String> = Vec::new();
    let mut scored: Vec<(f64, Plan, Sized)> = Vec::new();
    for r in sized {
        match r {
            Ok(sz) => {
                if let Some(first) = sz.all.first() {
                    let word = first.word(sz.style);
                    let plan = to_plan(shape, first, sz.style, sz.w, &word, name);
                    scored.push((plan.metrics.fit_error(), plan, sz));
                }
            }
            Err(e) => failures.push(e),
        }
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best: Option<Plan> = None;
    for (_, plan, sz) in scored {
        match best_checked(&sz.all, sz.style) {
            Ok((0, _)) => best = Some(plan),
            Ok((i, word)) => best = Some(to_plan(shape, &sz.all[i], sz.style, sz.w, &word, name)),
            Err(e) => {
                failures.push(e);
                continue;
            }
        }
        break;
    }
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let tiles_est = opts.tile_size.map_or(target, |w| {
        (shape.area() / (w * w * std::f64::consts::SQRT_2)) as usize
    });
    let parts = separate_parts(shape, tiles_est);
    if monotone.is_empty() || parts > 1 {
        // one serpentine over a shape that is monotone in no direction (or in separate
        // parts) bridges its gaps:
        // kept only while little of the chain lies outside
        if let Some(p) = best.take() {
            if p.metrics.outside_share <= MAX_OUTSIDE_NON_MONOTONE {
                best = Some(p);
            } else {
                failures.push(format!(
                    "one serpentine covers {:.0}% of the shape with {:.0}% of the chain outside",
                    100.0 * p.metrics.covered_share,
                    100.0 * p.metrics.outside_share
                ));
            }
        }
    }
    // cells joined by turns, for shapes that split into several cells along some axis and
    // plans small enough to route (a monotone shape keeps the better fit of the two)
    if (monotone.is_empty() || tiles_est <= MAX_CELL_TILES) && splits_into_cells(shape, tiles_est) {
        let by_cells: Vec<Result<Plan, String>> = styles
            .par_iter()
            .map(|&style| route::plan_by_cells(shape, opts, style, name))
            .collect();
        for r in by_cells {
            match r {
                Ok(p) => {
                    if best
                        .as_ref()
                        .is_none_or(|b| p.metrics.fit_error() < b.metrics.fit_error())
                    {
                        best = Some(p);
                    }
                }
                Err(e) => failures.push(format!("by cells: {e}")),
            }
        }
    }
    match best {
        Some(plan) => Ok(plan),
        None => {
            let mut reason = String::new();
            if parts > 1 {
                reason = format!(
                    "the shape is in {parts} separate parts and one chain would have to bridge the gaps between them; "
                );
            } else if monotone.is_empty() {
                let pieces = (0..12)
                    .map(|i| shape.rotated(-(i as f64) * PI / 12.0).max_pieces())
                    .min()
                    .unwrap_or(2);
                reason = format!(
                    "the shape is monotone in no direction (lines along every row direction meet it in {pieces} or more pieces); "
                );
            }
            failures.dedup();
            reason.push_str(&failures.join("; "));
            Err(PlanError::Unplannable {
                name: name.into(),
                reason,
            })
        }
    }
}

/// The number of separate parts of the shape, at about `tiles` tiles (parts smaller than a
/// tile are not counted).
fn separate_parts(shape: &Shape, tiles: usize) -> usize {
    let w = (shape.area() / (tiles.max(1) as f64 * std::f64::consts::SQRT_2)).sqrt();
    route::cells_of(&shape.scaled(1.0 / w)).components()
}

/// True if some sweep axis splits the shape into two or more cells at about `tiles` tiles.
fn splits_into_cells(shape: &Shape, tiles: usize) -> bool {
    let w = (shape.area() / (tiles.max(1) as f64 * std::f64::consts::SQRT_2)).sqrt();
    route::axes(shape).iter().any(|&a| {
        route::cells_of(&shape.rotated(-a).scaled(1.0 / w))
            .cells
            .len()
            > 1
    })
}

/// Row directions to compare: the long-edge directions and the SVG axes where the shape is
/// monotone for them, then an even spread over the monotone directions; every direction
/// (a 15 degree spread) when there is none.
fn pick_directions(shape: &Shape, monotone: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    let near = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(PI);
        d.min(PI - d) < 1e-6
    };
    let push = |out: &mut Vec<f64>, a: f64| {
        if out.len() < MAX_DIRECTIONS && !out.iter().any(|&b| near(a, b)) {
            out.push(a);
        }
    };
    if monotone.is_empty() {
        for a in shape.long_edge_angles(4) {
            push(&mut out, a);
        }
        for i in 0..12 {
            push(&mut out, i as f64 * PI / 12.0);
        }
        return out;
    }
    for a in shape.long_edge_angles(6) {
        if shape.is_monotone_for_rows(a) {
            push(&mut out, a);
        }
    }
    for a in [0.0, PI / 2.0] {
        if monotone.iter().any(|&m| near(m, a)) {
            push(&mut out, a);
        }
    }
    let n = monotone.len();
    let slots = MAX_DIRECTIONS.saturating_sub(out.len()).max(1);
    for i in 0..slots {
        push(&mut out, monotone[i * n / slots]);
    }
    out
}

/// The tile width for one turn style, with every serpentine at that width (best first),
/// not yet checked for collisions.
fn size_style(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    directions: &[f64],
) -> Result<Sized, String> {
    let area = shape.area();
    // area taken by one tile of a serpentine: one column of width w times the pitch
    let w_for = |n: usize| (area / (n as f64 * style.pitch)).sqrt();
    let tiles_at = |w: f64| (area / (w * w * style.pitch)) as usize;
    if let Some(w) = opts.tile_size {
        let dirs = if tiles_at(w) > COARSE_TILES {
            coarse_direction(shape, style, directions, w_for(COARSE_TILES))
        } else {
            directions.to_vec()
        };
        let all = solve_all(shape, style, &dirs, w);
        return Ok(Sized { style, w, all });
    }
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let dirs = if target > COARSE_TILES {
        coarse_direction(shape, style, directions, w_for(COARSE_TILES))
    } else {
        directions.to_vec()
    };
    let tolerance = (COUNT_TOLERANCE * target as f64) as usize;
    let mut w = w_for(target);
    // (miss, cost in user units, tile width, every serpentine at that width, best first)
    let mut best: Option<(usize, f64, f64, Vec<Serpentine>)> = None;
    let mut tried: Vec<f64> = Vec::new();
    // secant-like steps on sqrt(tiles), then a few small steps around the best size: the
    // count jumps by whole rows, so the nearest count may lie between two steps
    let nudges = [0.98, 1.02, 0.96, 1.04, 0.99, 1.01, 0.97, 1.03];
    for step in 0..16 {
        if step >= 8 {
            match &best {
                None => break,
                Some((m, ..)) if *m <= tolerance => break,
                Some((_, _, bw, _)) => w = bw * nudges[step - 8],
            }
        } else if tried.iter().any(|&t| (t - w).abs() < 1e-12 * t) {
            continue;
        }
        tried.push(w);
        let all = solve_all(shape, style, &dirs, w);
        let Some(first) = all.first() else {
            w *= 0.97;
            continue;
        };
        let n = first.tiles(style);
        let miss = n.abs_diff(target);
        let cost = first.cost * w;
        if step < 8 {
            w *= (n as f64 / target as f64).sqrt();
        }
        if best
            .as_ref()
            .is_none_or(|(m, c, ..)| miss < *m || (miss == *m && cost < *c))
        {
            best = Some((miss, cost, tried[tried.len() - 1], all));
        }
        if miss <= tolerance {
            break;
        }
    }
    match best {
        // the size is settled on unchecked plans (the check is the costly part on long
        // chains); the caller checks the plans at that size, best first
        Some((_, _, w, all)) => Ok(Sized { style, w, all }),
        None => Err(String::from("no serpentine found")),
    }
}

/// The best direction on a coarse plan, for large plans.
fn coarse_direction(shape: &Shape, style: Style, directions: &[f64], w: f64) -> Vec<f64> {
    match solve_all(shape, style, directions, w).first() {
        Some(s) => vec![s.orient.angle],
        None => directions.to_vec(),
    }
}

/// Every serpentine over directions, corners and phases at tile width `w`, lowest cost
/// first (solved in parallel; the order is deterministic).
fn solve_all(shape: &Shape, style: Style, directions: &[f64], w: f64) -> Vec<Serpentine> {
    let mut tasks = Vec::new();
    for &angle in directions {
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            tasks.push(Orientation { angle, sx, sy });
        }
    }
    let mut out: Vec<Serpentine> = tasks
        .par_iter()
        .flat_map_iter(|&orient| {
            let work = shape
                .rotated(-orient.angle)
                .mirrored(orient.sx, orient.sy)
                .scaled(1.0 / w);
            PHASES
                .iter()
                .flat_map(|&xp| PHASES.iter().map(move |&yp| (xp, yp)))
                .filter_map(|(xp, yp)| solve(&work, style, xp, yp, orient))
                .collect::<Vec<_>>()
        })
        .collect();
    out.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    out
}

/// The first serpentine of `all` (sorted, best first) that folds without collision: its
/// index and fold word.
fn best_checked(all: &[Serpentine], style: Style) -> Result<(usize, FoldWord), String> {
    let mut why = String::from("no serpentine found");
    for (i, serp) in all.iter().enumerate().take(MAX_CHECKED) {
        let word = serp.word(style);
        match check_folds(&word) {
            Ok(()) => return Ok((i, word)),
            Err(e) => why = format!("every candidate chain collides when folded (first: {e})"),
        }
    }
    Err(why)
}

/// Turns a checked serpentine into the plan.
fn to_plan(
    shape: &Shape,
    serp: &Serpentine,
    style: Style,
    w: f64,
    word: &FoldWord,
    name: &str,
) -> Plan {
    let o = serp.orient;
    let (l, t) = serp.chain_to_work();
    let work = shape.rotated(-o.angle).mirrored(o.sx, o.sy).scaled(1.0 / w);
    let shape_plan = Assembly {
        work: &work,
        chain_to_work: Affine { l, t },
        work_to_svg: work_to_svg(o, w),
        row_angle: o.angle,
        style,
        w,
        u_turns: serp.rows.len().saturating_sub(1),
        quarter_turns: 0,
        cells: 1,
    };
    shape_plan.to_plan(word, name)
}

/// What turns a checked fold word into a plan: the frames and the counts.
pub(crate) struct Assembly<'a> {
    /// The shape in the work frame (unit tiles), where the fit is measured.
    pub work: &'a Shape,
    pub chain_to_work: Affine,
    pub work_to_svg: Affine,
    /// The row direction of the stacking axis (physical frame, radians).
    pub row_angle: f64,
    pub style: Style,
    pub w: f64,
    pub u_turns: usize,
    pub quarter_turns: usize,
    pub cells: usize,
}

impl Assembly<'_> {
    /// True if the exact kinematics of `word` put the tile centres where `centres` (work
    /// frame) says, within 1e-6 tile widths.
    pub(crate) fn agrees(&self, word: &FoldWord, centres: &[(f64, f64)]) -> bool {
        let exact = kinematics::final_poses(word);
        exact.len() == centres.len()
            && exact.iter().zip(centres).all(|(p, &(x, y))| {
                let (u, v) = self.chain_to_work.apply(p.centre.to_f64(1.0));
                (u - x).abs() < 1e-6 && (v - y).abs() < 1e-6
            })
    }

    /// The plan: poses from the exact kinematics, mapped into the drawing, and the fit
    /// measured on them.
    pub(crate) fn to_plan(&self, word: &FoldWord, name: &str) -> Plan {
        let c2w = self.chain_to_work;
        let c2s = self.work_to_svg.after(&c2w);
        let exact = kinematics::final_poses(word);
        let work_centres: Vec<(f64, f64)> = exact
            .iter()
            .map(|p| c2w.apply(p.centre.to_f64(1.0)))
            .collect();
        let poses: Vec<PlanPose> = exact
            .iter()
            .map(|p| {
                let (x, y) = c2s.apply(p.centre.to_f64(1.0));
                let a = p.heading.to_radians();
                let (dx, dy) = c2s.linear((a.cos(), a.sin()));
                let mut h = dy.atan2(dx).to_degrees().rem_euclid(360.0);
                if h >= 360.0 - 1e-9 {
                    h = 0.0;
                }
                PlanPose {
                    x,
                    y,
                    heading_deg: (h * 1e9).round() / 1e9 + 0.0,
                }
            })
            .collect();
        let metrics = measure(self.work, &work_centres, self.w);
        let chain = word.to_chain();
        let bom = BillOfMaterials::from_chain(&chain)
            .parts
            .into_iter()
            .map(|(p, n)| (p.to_string(), n))
            .collect();
        // the stacking axis: plan +y, in SVG coordinates
        let (s, co) = self.row_angle.sin_cos();
        let axis = (-co).atan2(-s).to_degrees().rem_euclid(180.0);
        let axis = if axis >= 180.0 - 1e-9 { 0.0 } else { axis };
        Plan {
            source: name.to_string(),
            tiles: word.tiles(),
            tile_list: chain.to_tile_list(),
            word: word.to_compact_string(),
            axis_deg: (axis * 1e9).round() / 1e9 + 0.0,
            tile_size: self.w,
            turns: self.style.turns,
            u_turns: self.u_turns,
            quarter_turns: self.quarter_turns,
            cells: self.cells,
            bom,
            metrics,
            chain_to_svg: [c2s.l[0], c2s.l[2], c2s.l[1], c2s.l[3], c2s.t.0, c2s.t.1],
            poses,
        }
    }
}

/// Octagon of across-flats width 1 centred at the origin: |x|, |y| <= 1/2 and
/// |x| + |y| <= 1/sqrt2 (its faces are axis-aligned and diagonal at every heading the
/// chain takes).
fn in_octagon(dx: f64, dy: f64) -> bool {
    dx.abs() <= 0.5 && dy.abs() <= 0.5 && dx.abs() + dy.abs() <= FRAC_1_SQRT_2
}

/// Tile centres bucketed by unit cell (compressed rows), for "which tiles are near".
pub(crate) struct CentreGrid {
    x0: i64,
    y0: i64,
    nx: i64,
    ny: i64,
    /// `start[c]..start[c + 1]` indexes `ids` for cell `c`.
    start: Vec<usize>,
    ids: Vec<usize>,
}

impl CentreGrid {
    pub(crate) fn new(centres: &[(f64, f64)]) -> CentreGrid {
        let cell = |&(x, y): &(f64, f64)| (x.floor() as i64, y.floor() as i64);
        let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for c in centres.iter().map(cell) {
            (x0, y0, x1, y1) = (x0.min(c.0), y0.min(c.1), x1.max(c.0), y1.max(c.1));
        }
        let (nx, ny) = if centres.is_empty() {
            (0, 0)
        } else {
            (x1 - x0 + 1, y1 - y0 + 1)
        };
        let index = |(cx, cy): (i64, i64)| ((cy - y0) * nx + (cx - x0)) as usize;
        let mut start = vec![0usize; (nx * ny) as usize + 1];
        for c in centres.iter().map(cell) {
            start[index(c) + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut fill = start.clone();
        let mut ids = vec![0usize; centres.len()];
        for (i, c) in centres.iter().map(cell).enumerate() {
            let k = index(c);
            ids[fill[k]] = i;
            fill[k] += 1;
        }
        CentreGrid {
            x0,
            y0,
            nx,
            ny,
            start,
            ids,
        }
    }

    /// The tiles whose centre lies in the cell `(cx, cy)`.
    pub(crate) fn in_cell(&self, cx: i64, cy: i64) -> &[usize] {
        let (i, j) = (cx - self.x0, cy - self.y0);
        if i < 0 || j < 0 || i >= self.nx || j >= self.ny {
            return &[];
        }
        let k = (j * self.nx + i) as usize;
        &self.ids[self.start[k]..self.start[k + 1]]
    }
}

/// The fit measures (see [`Metrics`]) in the work frame (unit tiles), areas scaled by `w^2`.
pub(crate) fn measure(work: &Shape, centres: &[(f64, f64)], w: f64) -> Metrics {
    let offs = [-0.4, -0.2, 0.0, 0.2, 0.4];
    // chunks of consecutive tiles share rows, so each chunk caches the lines it asks for
    let (total, out) = centres
        .par_chunks(4096)
        .map(|chunk| {
            let mut cache: HashMap<i64, Vec<(f64, f64)>> = HashMap::new();
            let (mut total, mut out) = (0usize, 0usize);
            for &(x, y) in chunk {
                for dy in offs {
                    let yy = y + dy;
                    let key = (yy * 1e7).round() as i64;
                    let iv = cache.entry(key).or_insert_with(|| work.intervals_at(yy));
                    for dx in offs {
                        if in_octagon(dx, dy) {
                            total += 1;
                            let xx = x + dx;
                            if !iv.iter().any(|&(a, b)| a <= xx && xx <= b) {
                                out += 1;
                            }
                        }
                    }
                }
            }
            (total, out)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    let grid = CentreGrid::new(centres);
    let (xmin, ymin, xmax, ymax) = work.bbox();
    let step = ((xmax - xmin) * (ymax - ymin) / 250_000.0).sqrt().max(1e-9);
    let lines = ((ymax - ymin) / step - 0.5).ceil().max(0.0) as usize;
    let (in_shape, covered) = (0..lines)
        .into_par_iter()
        .map(|i| {
            let y = ymin + (i as f64 + 0.5) * step;
            let (mut in_shape, mut covered) = (0usize, 0usize);
            for (a, b) in work.intervals_at(y) {
                let mut x = xmin + ((a - xmin) / step).ceil() * step + 0.5 * step;
                while x <= b {
                    in_shape += 1;
                    let (cx, cy) = (x.floor() as i64, y.floor() as i64);
                    let hit = (-1..=1).any(|i| {
                        (-1..=1).any(|j| {
                            grid.in_cell(cx + i, cy + j)
                                .iter()
                                .any(|&t| in_octagon(x - centres[t].0, y - centres[t].1))
                        })
                    });
                    if hit {
                        covered += 1;
                    }
                    x += step;
                }
            }
            (in_shape, covered)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    let oct_area = 2.0 * (SQRT_2 - 1.0);
    Metrics {
        covered_share: if in_shape > 0 {
            covered as f64 / in_shape as f64
        } else {
            0.0
        },
        outside_share: if total > 0 {
            out as f64 / total as f64
        } else {
            0.0
        },
        shape_area: work.area() * w * w,
        chain_area: centres.len() as f64 * oct_area * w * w,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::Ring;

    #[test]
    fn tile_count_matches_the_word() {
        let disc = Shape::from_rings(vec![Ring {
            points: (0..64)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / 64.0;
                    (10.0 * a.cos(), 10.0 * a.sin())
                })
                .collect(),
        }]);
        for style in [TIGHT, LOOSE] {
            let all = solve_all(&disc, style, &[0.0, 0.7], 1.0);
            assert!(!all.is_empty());
            for s in &all {
                assert_eq!(s.tiles(style), s.word(style).tiles());
            }
            assert!(all.windows(2).all(|p| p[0].cost <= p[1].cost));
        }
    }
}
