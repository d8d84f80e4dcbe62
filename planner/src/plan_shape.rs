//! The planner's top level: checks the options, plans the shape as one serpentine
//! ([`crate::serpentine`]) and, where the shape splits into cells, by cells
//! ([`crate::cell_plan`]), each with the asked turn styles, and keeps the best fit that folds
//! without collision; or says why the shape cannot be planned.

use std::f64::consts::PI;

use rayon::prelude::*;

use crate::cap_plan::plan_by_caps;
use crate::caps;
use crate::cell_plan::{axes, CellFailure};
use crate::empty::note_empty;
use crate::error::{PlanError, Rejected};
use crate::fit::plan_score;
use crate::options::{PlanOptions, Turns, DEFAULT_TILES};
use crate::plan::Plan;
use crate::rows::{Style, LOOSE, TIGHT};
use crate::serpentine::{pick_directions, size_style, Sized};
use crate::shape::Shape;
use crate::sizing::{tiles_for, width_for};
use crate::Progress;

/// A shape monotone in no direction is planned as one serpentine that bridges its gaps
/// only while at most this share of the chain lies outside it; beyond, it is unplannable.
const MAX_OUTSIDE_NON_MONOTONE: f64 = 0.10;
/// Shapes monotone in some direction are also planned by cells up to this many tiles.
const MAX_CELL_TILES: usize = 20_000;

/// Plans a shape (physical frame); `name` names it in errors and in the plan.
pub(crate) fn plan_shape(
    shape: &Shape,
    opts: &PlanOptions,
    name: &str,
    progress: Progress<'_>,
) -> Result<Plan, PlanError> {
    opts.check(shape)?;
    let styles: Vec<Style> = match opts.turns {
        Turns::Tight => vec![TIGHT],
        Turns::Loose => vec![LOOSE],
        Turns::Auto => vec![TIGHT, LOOSE],
    }
    .into_iter()
    .map(|s| s.priced(opts.turn_cost))
    .collect();
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let tiles_est = opts
        .tile_size
        .map_or(target, |w| tiles_for(shape.area(), w, TIGHT.pitch));
    // one chain cannot cross a gap: a drawing in separate parts is refused at once
    let parts = separate_parts(shape, tiles_est);
    if parts.len() > 1 {
        let list: Vec<String> = parts
            .iter()
            .take(4)
            .map(|b| {
                format!(
                    "x {:.0} to {:.0}, y {:.0} to {:.0}",
                    b.x0, b.x1, -b.y1, -b.y0
                )
            })
            .collect();
        return Err(PlanError::Unplannable {
            name: name.into(),
            reason: format!(
                "the drawing is in {} separate parts ({}{}); one chain cannot cross the gaps between them: join the parts in the drawing, or plan each on its own",
                parts.len(),
                list.join("; "),
                if parts.len() > 4 { "; ..." } else { "" }
            ),
            rejected: None,
        });
    }
    let monotone = shape.monotone_row_angles();
    let directions = pick_directions(shape, &monotone);
    let mut failures: Vec<String> = Vec::new();
    let mut best = best_serpentine(
        shape,
        opts,
        &styles,
        &directions,
        name,
        &mut failures,
        progress,
    );
    // the best plan rejected for an empty part, for a preview of where
    let mut rejected: Option<Box<Rejected>> = None;
    let mut reject = |r: Box<Rejected>| {
        if rejected
            .as_ref()
            .is_none_or(|b| r.empty.tiles < b.empty.tiles)
        {
            rejected = Some(r);
        }
    };
    if let Some(p) = best.take() {
        match note_empty(shape, p, crate::empty::near(opts.turns)) {
            Ok(p) => best = Some(p),
            Err(e) => {
                let (part, p) = *e;
                failures.push(format!("one serpentine {part}"));
                reject(Box::new(Rejected {
                    plan: p,
                    empty: part,
                }));
            }
        }
    }
    if monotone.is_empty() {
        // one serpentine over a shape that is monotone in no direction (or in separate
        // parts) bridges its gaps: kept only while little of the chain lies outside
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
    // tiles by which a plan misses the asked count beyond the tolerance
    let tol = (opts.tiles_tolerance * target as f64) as usize;
    // (no count asked and no width: the default count, as the planners aim at it)
    let miss = |q: &Plan| match opts.tile_size {
        None => q.tiles.abs_diff(target).saturating_sub(tol),
        Some(_) => 0,
    };
    // plans are ranked: a count within the tolerance, then no part left empty, then fit
    let rank = |q: &Plan| {
        (
            miss(q),
            q.metrics.largest_empty_tiles > 0.0,
            OrdF64(plan_score(q, opts.turn_cost)),
        )
    };
    // caps joined by quarter turns, for shapes that are not one serpentine (and, up to
    // MAX_CELL_TILES tiles, for every shape: a monotone shape keeps the better of the two)
    if (monotone.is_empty() || tiles_est <= MAX_CELL_TILES) && splits_into_cells(shape, tiles_est) {
        progress("planning by caps", 0, 1);
        let by_caps: Vec<Result<Plan, CellFailure>> = styles
            .par_iter()
            .map(|&style| plan_by_caps(shape, opts, style, name))
            .collect();
        progress("planning by caps", 1, 1);
        for r in by_caps {
            match r {
                Ok(p) => {
                    // a count within the tolerance first, then the better fit
                    if best.as_ref().is_none_or(|b| rank(&p) < rank(b)) {
                        best = Some(p);
                    }
                }
                Err((e, r)) => {
                    failures.push(format!("by caps: {e}"));
                    if let Some(r) = r {
                        reject(r);
                    }
                }
            }
        }
    }
    best.ok_or_else(|| PlanError::Unplannable {
        name: name.into(),
        reason: unplannable_reason(shape, monotone.is_empty(), failures),
        rejected,
    })
}

/// The best serpentine over the turn styles that folds without collision: every style is
/// sized (in parallel) and its best unchecked plan measured, then the styles are checked best
/// fit first, so a long chain is checked once, not once per style. Failures are added to
/// `failures`.
fn best_serpentine(
    shape: &Shape,
    opts: &PlanOptions,
    styles: &[Style],
    directions: &[f64],
    name: &str,
    failures: &mut Vec<String>,
    progress: Progress<'_>,
) -> Option<Plan> {
    let sized: Vec<Result<Sized, String>> = styles
        .par_iter()
        .map(|&style| size_style(shape, opts, style, directions, progress))
        .collect();
    let mut scored: Vec<(f64, Plan, Sized)> = Vec::new();
    for r in sized {
        match r {
            Ok(sz) => {
                if let Some(plan) = sz.best_unchecked(shape, name) {
                    scored.push((plan.metrics.fit_error(), plan, sz));
                }
            }
            Err(e) => failures.push(e),
        }
    }
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    progress("checking the folds", 0, 1);
    for (_, plan, sz) in scored {
        match sz.best_checked(shape, plan, name) {
            Ok(p) => return Some(p),
            Err(e) => failures.push(e),
        }
    }
    None
}

/// Why no plan was found: what is wrong with the shape, then what each planner said.
fn unplannable_reason(shape: &Shape, nowhere_monotone: bool, mut failures: Vec<String>) -> String {
    let mut reason = String::new();
    if nowhere_monotone {
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
    reason
}

/// The separate parts of the shape at about `tiles` tiles, by their bounding boxes in the
/// physical frame (parts smaller than half a tile are not counted).
fn separate_parts(shape: &Shape, tiles: usize) -> Vec<kurbo::Rect> {
    let w = width_for(shape.area(), tiles.max(1), TIGHT.pitch);
    caps::parts(&shape.scaled(1.0 / w))
        .into_iter()
        .map(|b| kurbo::Rect::new(b.x0 * w, b.y0 * w, b.x1 * w, b.y1 * w))
        .collect()
}

/// True if along some sweep axis the cheapest cap decomposition at about `tiles` tiles has
/// more than one cell (a shape that one serpentine fills as well needs no caps).
fn splits_into_cells(shape: &Shape, tiles: usize) -> bool {
    let w = width_for(shape.area(), tiles.max(1), TIGHT.pitch);
    axes(shape).iter().any(|&a| {
        caps::cap_plans(&shape.rotated(-a).scaled(1.0 / w), TIGHT.pitch)
            .first()
            .is_some_and(|p| p.cells.len() > 1)
    })
}

/// An f64 ordered by `total_cmp`, for ranking keys.
#[derive(Clone, Copy, PartialEq)]
struct OrdF64(f64);

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
