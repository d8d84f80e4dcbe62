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

use crate::check::check_folds;
use crate::plan::{Metrics, PlanPose};
use crate::{Plan, PlanError, PlanOptions, Shape, Turns, DEFAULT_TILES};

/// Offsets across a row (tile widths) at which the shape is sampled for row costs.
const ROW_SAMPLES: [f64; 3] = [-0.3, 0.0, 0.3];
/// Horizontal and vertical phases tried, as shares of a column and of a row pitch.
const PHASES: [f64; 3] = [0.0, 1.0 / 3.0, 2.0 / 3.0];
/// At most this many row directions are compared by full planning.
const MAX_DIRECTIONS: usize = 16;
/// Above this many tiles the direction is chosen on a coarser plan of this many tiles.
const COARSE_TILES: usize = 3000;
/// A shape monotone in no direction is planned as one serpentine that bridges its gaps
/// only while at most this share of the chain lies outside it; beyond, it is unplannable.
const MAX_OUTSIDE_NON_MONOTONE: f64 = 0.10;
/// Plans tried (best first) until one passes the collision check.
const MAX_CHECKED: usize = 8;

/// The geometry of one turn style, in tile widths.
#[derive(Clone, Copy, Debug)]
struct Style {
    turns: Turns,
    /// Distance between consecutive rows.
    pitch: f64,
    /// Heights of the turn tiles above the row they leave.
    turn_heights: &'static [f64],
}

const TIGHT: Style = Style {
    turns: Turns::Tight,
    pitch: SQRT_2,
    turn_heights: &[FRAC_1_SQRT_2],
};
const LOOSE: Style = Style {
    turns: Turns::Loose,
    pitch: 1.0 + SQRT_2,
    turn_heights: &[FRAC_1_SQRT_2, FRAC_1_SQRT_2 + 1.0],
};

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

/// Per-row data: target length and prefix overlaps at column boundaries.
struct RowData {
    /// Mean length of the shape along the row.
    len: f64,
    /// `hi[j]`: mean measure of the shape on (-inf, x_j + 1/2].
    hi: Vec<f64>,
    /// `lo[j]`: mean measure of the shape on (-inf, x_j - 1/2].
    lo: Vec<f64>,
    /// Turn cost leaving this row at column j (outward side known from the row's parity).
    turn: Vec<f64>,
}

/// Measure of `iv` on (-inf, x].
fn measure_below(iv: &[(f64, f64)], x: f64) -> f64 {
    iv.iter().map(|&(a, b)| (b.min(x) - a).max(0.0)).sum()
}

/// Solves the serpentine for a work-frame shape at unit tile width.
fn solve(work: &Shape, style: Style, xp: f64, yp: f64, orient: Orientation) -> Option<Serpentine> {
    let (xmin, ymin, xmax, ymax) = work.bbox();
    let p = style.pitch;
    let x0 = xmin.floor() - 2.0 + xp;
    let cols = ((xmax - x0).ceil() as usize) + 3;
    let y0 = ymin + 0.5 + (yp - 1.0) * p;
    let nrows = (((ymax - y0) / p).ceil() as usize) + 2;
    let mut rows: Vec<RowData> = Vec::with_capacity(nrows);
    for k in 0..nrows {
        let y = y0 + k as f64 * p;
        let ivs: Vec<Vec<(f64, f64)>> = ROW_SAMPLES
            .iter()
            .map(|d| work.intervals_at(y + d))
            .collect();
        let ns = ROW_SAMPLES.len() as f64;
        let len = ivs.iter().flatten().map(|(a, b)| b - a).sum::<f64>() / ns;
        let mean_below = |x: f64| ivs.iter().map(|iv| measure_below(iv, x)).sum::<f64>() / ns;
        let hi: Vec<f64> = (0..cols).map(|j| mean_below(x0 + j as f64 + 0.5)).collect();
        let lo: Vec<f64> = (0..cols).map(|j| mean_below(x0 + j as f64 - 0.5)).collect();
        let dir = if k % 2 == 0 { 1.0 } else { -1.0 };
        let turn_ivs: Vec<Vec<(f64, f64)>> = style
            .turn_heights
            .iter()
            .map(|h| work.intervals_at(y + h))
            .collect();
        let turn: Vec<f64> = (0..cols)
            .map(|j| {
                let x = x0 + j as f64 + dir * FRAC_1_SQRT_2;
                turn_ivs
                    .iter()
                    .map(|iv| 1.0 - (measure_below(iv, x + 0.5) - measure_below(iv, x - 0.5)))
                    .sum()
            })
            .collect();
        rows.push(RowData { len, hi, lo, turn });
    }
    let total: f64 = rows.iter().map(|r| r.len).sum();
    let inf = f64::INFINITY;
    let mut dp = vec![vec![inf; cols]; nrows];
    // back[k][e] = (start column, whether row k is the first row)
    let mut back = vec![vec![(0usize, true); cols]; nrows];
    let mut before = 0.0;
    let mut best: Option<(f64, usize, usize)> = None;
    let mut after = total;
    for k in 0..nrows {
        after -= rows[k].len;
        let r = &rows[k];
        let prev = if k > 0 {
            Some((&dp[k - 1], &rows[k - 1]))
        } else {
            None
        };
        let mut cur = vec![inf; cols];
        let mut bk = vec![(0usize, true); cols];
        if k % 2 == 0 {
            // rightward: cost(s, e) = (e + 1) + len - 2 hi[e] + (2 lo[s] - s)
            let mut first_min = (inf, 0usize);
            let mut cont_min = (inf, 0usize);
            for e in 0..cols {
                let term_s = 2.0 * r.lo[e] - e as f64;
                if before + term_s < first_min.0 {
                    first_min = (before + term_s, e);
                }
                let base = (e as f64 + 1.0) + r.len - 2.0 * r.hi[e];
                let cf = base + first_min.0;
                if cf < cur[e] {
                    cur[e] = cf;
                    bk[e] = (first_min.1, true);
                }
                if let Some((pd, pr)) = prev {
                    // continuation needs s < e: cont_min holds s <= e - 1
                    let cc = base + cont_min.0;
                    if cc < cur[e] {
                        cur[e] = cc;
                        bk[e] = (cont_min.1, false);
                    }
                    let v = pd[e] + pr.turn[e] + term_s;
                    if v < cont_min.0 {
                        cont_min = (v, e);
                    }
                }
            }
        } else {
            // leftward from s down to e: cost = (s + 1) + len - 2 hi[s] + (2 lo[e] - e)
            let mut first_min = (inf, 0usize);
            let mut cont_min = (inf, 0usize);
            for e in (0..cols).rev() {
                let term_s = (e as f64 + 1.0) - 2.0 * r.hi[e];
                if before + term_s < first_min.0 {
                    first_min = (before + term_s, e);
                }
                let base = r.len + 2.0 * r.lo[e] - e as f64;
                let cf = base + first_min.0;
                if cf < cur[e] {
                    cur[e] = cf;
                    bk[e] = (first_min.1, true);
                }
                if let Some((pd, pr)) = prev {
                    let cc = base + cont_min.0;
                    if cc < cur[e] {
                        cur[e] = cc;
                        bk[e] = (cont_min.1, false);
                    }
                    let v = pd[e] + pr.turn[e] + term_s;
                    if v < cont_min.0 {
                        cont_min = (v, e);
                    }
                }
            }
        }
        for (e, &c) in cur.iter().enumerate() {
            let t = c + after;
            if best.is_none_or(|b| t < b.0) {
                best = Some((t, k, e));
            }
        }
        dp[k] = cur;
        back[k] = bk;
        before += r.len;
    }
    let (cost, mut k, mut e) = best?;
    let mut out = Vec::new();
    loop {
        let (s, first) = back[k][e];
        out.push((k, s as i64, e as i64));
        if first || k == 0 {
            break;
        }
        k -= 1;
        e = s;
    }
    out.reverse();
    Some(Serpentine {
        orient,
        cost,
        x0,
        y0,
        pitch: p,
        rows: out,
    })
}

impl Serpentine {
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
struct Affine {
    l: [f64; 4],
    t: (f64, f64),
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

/// A checked candidate, ready to become a plan.
struct Candidate {
    serp: Serpentine,
    style: Style,
    w: f64,
    word: FoldWord,
}

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
    let styles: Vec<Style> = match opts.turns {
        Turns::Tight => vec![TIGHT],
        Turns::Loose => vec![LOOSE],
        Turns::Auto => vec![TIGHT, LOOSE],
    };
    let monotone = shape.monotone_row_angles();
    let directions = pick_directions(shape, &monotone);
    let mut best: Option<(Plan, f64)> = None;
    let mut failures: Vec<String> = Vec::new();
    for style in styles {
        match plan_style(shape, opts, style, &directions, name) {
            Ok(plan) => {
                let score = plan.metrics.fit_error();
                if best.as_ref().is_none_or(|b| score < b.1) {
                    best = Some((plan, score));
                }
            }
            Err(e) => failures.push(e),
        }
    }
    let Some((mut plan, _)) = best else {
        return Err(PlanError::Unplannable {
            name: name.into(),
            reason: failures.join("; "),
        });
    };
    plan.cells = 1;
    if monotone.is_empty() {
        // a single serpentine over a shape that is monotone in no direction: say so
        let pieces = (0..12)
            .map(|i| shape.rotated(-(i as f64) * PI / 12.0).max_pieces())
            .min()
            .unwrap_or(2);
        if plan.metrics.outside_share > MAX_OUTSIDE_NON_MONOTONE {
            return Err(PlanError::Unplannable {
                name: name.into(),
                reason: format!(
                    "the shape is monotone in no direction (lines along every row direction meet it in {pieces} or more pieces), and one serpentine covers only {:.0}% of it with {:.0}% of the chain outside; it needs splitting into monotone cells joined by 90-degree turns",
                    100.0 * plan.metrics.covered_share,
                    100.0 * plan.metrics.outside_share
                ),
            });
        }
    }
    Ok(plan)
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

/// The best checked plan for one turn style.
fn plan_style(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    directions: &[f64],
    name: &str,
) -> Result<Plan, String> {
    let area = shape.area();
    // area taken by one tile of a serpentine: one column of width w times the pitch
    let w_for = |n: usize| (area / (n as f64 * style.pitch)).sqrt();
    if let Some(w) = opts.tile_size {
        let dirs = if (area / (w * w * style.pitch)) as usize > COARSE_TILES {
            coarse_direction(shape, style, directions, w_for(COARSE_TILES))
        } else {
            directions.to_vec()
        };
        let c = best_checked(shape, style, &dirs, w)?;
        return Ok(to_plan(shape, c, name));
    }
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let dirs = if target > COARSE_TILES {
        coarse_direction(shape, style, directions, w_for(COARSE_TILES))
    } else {
        directions.to_vec()
    };
    let mut w = w_for(target);
    let mut best: Option<(usize, Candidate)> = None;
    let mut last_err = String::new();
    let mut tried: Vec<f64> = Vec::new();
    // secant-like steps on sqrt(tiles), then a few small steps around the best size: the
    // count jumps by whole rows, so the nearest count may lie between two steps
    let nudges = [0.98, 1.02, 0.96, 1.04, 0.99, 1.01, 0.97, 1.03];
    for step in 0..16 {
        if step >= 8 {
            match &best {
                Some((0, _)) | None => break,
                Some((_, c)) => w = c.w * nudges[step - 8],
            }
        } else if tried.iter().any(|&t| (t - w).abs() < 1e-12 * t) {
            continue;
        }
        tried.push(w);
        match best_unchecked(shape, style, &dirs, w) {
            Ok(c) => {
                let n = c.word.tiles();
                let miss = n.abs_diff(target);
                let better = best.as_ref().is_none_or(|(m, b)| {
                    miss < *m || (miss == *m && c.serp.cost * c.w < b.serp.cost * b.w)
                });
                if step < 8 {
                    w *= (n as f64 / target as f64).sqrt();
                }
                if better {
                    best = Some((miss, c));
                }
                if miss == 0 {
                    break;
                }
            }
            Err(e) => {
                last_err = e;
                w *= 0.97;
            }
        }
    }
    match best {
        // the size is settled on unchecked plans (the check is the costly part on long
        // chains); the plans at that size are now checked, best first
        Some((_, c)) => Ok(to_plan(
            shape,
            best_checked(shape, style, &dirs, c.w)?,
            name,
        )),
        None => Err(last_err),
    }
}

/// The lowest-cost serpentine at tile width `w`, not yet checked for collisions.
fn best_unchecked(
    shape: &Shape,
    style: Style,
    directions: &[f64],
    w: f64,
) -> Result<Candidate, String> {
    let serp = solve_all(shape, style, directions, w)
        .into_iter()
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .ok_or_else(|| String::from("no serpentine found"))?;
    let word = serp.word(style);
    Ok(Candidate {
        serp,
        style,
        w,
        word,
    })
}

/// The best direction on a coarse plan, for large plans.
fn coarse_direction(shape: &Shape, style: Style, directions: &[f64], w: f64) -> Vec<f64> {
    let mut all = solve_all(shape, style, directions, w);
    all.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    match all.first() {
        Some(s) => vec![s.orient.angle],
        None => directions.to_vec(),
    }
}

/// Every serpentine over directions, corners and phases at tile width `w`.
fn solve_all(shape: &Shape, style: Style, directions: &[f64], w: f64) -> Vec<Serpentine> {
    let mut out = Vec::new();
    for &angle in directions {
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            let orient = Orientation { angle, sx, sy };
            let work = shape.rotated(-angle).mirrored(sx, sy).scaled(1.0 / w);
            for xp in PHASES {
                for yp in PHASES {
                    if let Some(s) = solve(&work, style, xp, yp, orient) {
                        out.push(s);
                    }
                }
            }
        }
    }
    out
}

/// The lowest-cost serpentine at tile width `w` that folds without collision.
fn best_checked(
    shape: &Shape,
    style: Style,
    directions: &[f64],
    w: f64,
) -> Result<Candidate, String> {
    let mut all = solve_all(shape, style, directions, w);
    all.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    let mut why = String::from("no serpentine found");
    for serp in all.into_iter().take(MAX_CHECKED) {
        let word = serp.word(style);
        match check_folds(&word) {
            Ok(()) => {
                return Ok(Candidate {
                    serp,
                    style,
                    w,
                    word,
                })
            }
            Err(e) => why = format!("every candidate chain collides when folded (first: {e})"),
        }
    }
    Err(why)
}

/// Turns a checked candidate into the plan: poses from the exact kinematics, mapped into
/// the drawing, and the fit measured on them.
fn to_plan(shape: &Shape, c: Candidate, name: &str) -> Plan {
    let o = c.serp.orient;
    let w = c.w;
    let (l, t) = c.serp.chain_to_work();
    let c2w = Affine { l, t };
    let w2s = work_to_svg(o, w);
    let c2s = w2s.after(&c2w);
    let exact = kinematics::final_poses(&c.word);
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
    let work = shape.rotated(-o.angle).mirrored(o.sx, o.sy).scaled(1.0 / w);
    let metrics = measure(&work, &work_centres, w);
    let chain = c.word.to_chain();
    let bom = BillOfMaterials::from_chain(&chain)
        .parts
        .into_iter()
        .map(|(p, n)| (p.to_string(), n))
        .collect();
    let u_turns = c.serp.rows.len().saturating_sub(1);
    // the stacking axis: plan +y, in SVG coordinates
    let (s, co) = o.angle.sin_cos();
    let axis = (-co).atan2(-s).to_degrees().rem_euclid(180.0);
    let axis = if axis >= 180.0 - 1e-9 { 0.0 } else { axis };
    Plan {
        source: name.to_string(),
        tiles: c.word.tiles(),
        tile_list: chain.to_tile_list(),
        word: c.word.to_compact_string(),
        axis_deg: (axis * 1e9).round() / 1e9 + 0.0,
        tile_size: w,
        turns: c.style.turns,
        u_turns,
        quarter_turns: 0,
        cells: 1,
        bom,
        metrics,
        chain_to_svg: [c2s.l[0], c2s.l[2], c2s.l[1], c2s.l[3], c2s.t.0, c2s.t.1],
        poses,
    }
}

/// Octagon of across-flats width 1 centred at the origin: |x|, |y| <= 1/2 and
/// |x| + |y| <= 1/sqrt2 (its faces are axis-aligned and diagonal at every heading the
/// chain takes).
fn in_octagon(dx: f64, dy: f64) -> bool {
    dx.abs() <= 0.5 && dy.abs() <= 0.5 && dx.abs() + dy.abs() <= FRAC_1_SQRT_2
}

/// The fit measures (see [`Metrics`]) in the work frame (unit tiles), areas scaled by `w^2`.
fn measure(work: &Shape, centres: &[(f64, f64)], w: f64) -> Metrics {
    let mut cache: HashMap<i64, Vec<(f64, f64)>> = HashMap::new();
    let mut inside = |x: f64, y: f64| {
        let key = (y * 1e7).round() as i64;
        let iv = cache.entry(key).or_insert_with(|| work.intervals_at(y));
        iv.iter().any(|&(a, b)| a <= x && x <= b)
    };
    let offs = [-0.4, -0.2, 0.0, 0.2, 0.4];
    let (mut total, mut out) = (0usize, 0usize);
    for &(x, y) in centres {
        for dy in offs {
            for dx in offs {
                if in_octagon(dx, dy) {
                    total += 1;
                    if !inside(x + dx, y + dy) {
                        out += 1;
                    }
                }
            }
        }
    }
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, &(x, y)) in centres.iter().enumerate() {
        grid.entry((x.floor() as i64, y.floor() as i64))
            .or_default()
            .push(i);
    }
    let (xmin, ymin, xmax, ymax) = work.bbox();
    let step = ((xmax - xmin) * (ymax - ymin) / 250_000.0).sqrt().max(1e-9);
    let (mut in_shape, mut covered) = (0usize, 0usize);
    let mut y = ymin + 0.5 * step;
    while y < ymax {
        let iv = work.intervals_at(y);
        for &(a, b) in &iv {
            let mut x = xmin + ((a - xmin) / step).ceil() * step + 0.5 * step;
            while x <= b {
                in_shape += 1;
                let (cx, cy) = (x.floor() as i64, y.floor() as i64);
                let hit = (-1..=1).any(|i| {
                    (-1..=1).any(|j| {
                        grid.get(&(cx + i, cy + j)).is_some_and(|v| {
                            v.iter()
                                .any(|&t| in_octagon(x - centres[t].0, y - centres[t].1))
                        })
                    })
                });
                if hit {
                    covered += 1;
                }
                x += step;
            }
        }
        y += step;
    }
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
