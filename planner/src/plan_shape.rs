//! The planner's top level: checks the options, plans the shape as one serpentine
//! ([`crate::serpentine`]) and, where the shape splits into cells, by cells
//! ([`crate::cell_plan`]), each with the asked turn styles, and keeps the best fit that folds
//! without collision; or says why the shape cannot be planned.

use rayon::prelude::*;

use crate::cap_plan::{cap_axes, centres_inside, plan_by_caps, start_width};
use crate::caps::{self, CapPlan};
use crate::cell_plan::CellFailure;
use crate::check::check_folds;
use crate::empty::{note_empty, rank_key, EmptyPart};
use crate::error::{PlanError, Rejected};
use crate::narrow;
use crate::options::{PlanOptions, Turns, DEFAULT_TILES, MAX_PLAN_TILES};
use crate::parts::{self, Parts};
use crate::plan::Plan;
use crate::rank::Asked;
use crate::refusal;
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
/// Factors on the width of a serpentine that leaves a large part empty, tried in turn
/// ([`serpentine_at_other_widths`]).
const SERPENTINE_RETRIES: [f64; 4] = [1.01, 0.99, 1.02, 0.98];
/// The share of the asked count (in tile areas) that the part a serpentine leaves empty
/// must exceed for [`SERPENTINE_RETRIES`] to be tried.
const RETRY_EMPTY_SHARE: f64 = 0.05;

/// Under `auto`, the loose pass is skipped after a tight route within the count that leaves
/// at most this share of the asked count empty, in the asked chain's tile areas
/// ([`tight_holds_count`]). A thin ring (hole 0.9 of its diameter) at 1000 tiles, whose
/// tight routes leave a whole side empty (962 of their tile areas, 40% of the count), plans
/// loose leaving 679 of its own (21%); on the corpus the tight routes that the loose pass did
/// not beat left at most 21% (libsi-Q at 3000 tiles).
const LOOSE_AFTER_EMPTY_SHARE: f64 = 0.25;

/// Plans a shape (physical frame); `name` names it in errors and in the plan.
/// `mm_per_unit` (the drawing's millimetres per user unit) only words a refusal; `retry`
/// lets a refusal try fewer tiles (when a count was asked) to name one that plans.
pub(crate) fn plan_shape(
    shape: &Shape,
    opts: &PlanOptions,
    name: &str,
    mm_per_unit: f64,
    retry: bool,
    progress: Progress<'_>,
) -> Result<Plan, PlanError> {
    opts.check(shape)?;
    let (kept, island_warning) = without_islands(shape, name, mm_per_unit)?;
    let shape = kept.as_ref().unwrap_or(shape);
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
    refuse_at_once(shape, opts, name, mm_per_unit, tiles_est)?;
    let monotone = shape.monotone_row_angles();
    let directions = pick_directions(shape, &monotone);
    // tiles by which a plan misses the asked count beyond the tolerance
    let tol = (opts.tiles_tolerance * target as f64) as usize;
    // (no count asked and no width: the default count, as the planners aim at it)
    let miss = |q: &Plan| match opts.tile_size {
        None => q.tiles.abs_diff(target).saturating_sub(tol),
        Some(_) => 0,
    };
    let mut found = Found {
        asked: Asked::new(opts, shape.area(), tiles_est),
        ..Found::default()
    };
    // under `auto`, loose turns are planned only when tight ones give no plan with a count
    // within the tolerance: loose rows lie a tile width farther apart than the empty-part
    // measure reaches under `auto` ([`crate::empty::near`]), so a loose plan with rows
    // longer than about three tiles leaves a strip between every two rows empty (at least
    // 0.5 w wide: 0.6 tile areas per tile of row), more than a tight plan leaves
    let groups: Vec<&[Style]> = if opts.turns == Turns::Auto {
        styles.chunks(1).collect()
    } else {
        vec![&styles[..]]
    };
    for group in groups {
        plan_styles(
            shape,
            opts,
            group,
            (&monotone, &directions),
            tiles_est,
            name,
            progress,
            &mut found,
            &miss,
        );
        if found.best.as_ref().is_some_and(|b| miss(b) == 0)
            || tight_holds_count(&found, &miss, tiles_est)
        {
            break;
        }
    }
    walks(shape, opts, tiles_est, name, &miss, &mut found);
    let Found {
        best,
        failures,
        rejected,
        bridging,
        asked,
    } = found;
    // one chain can fill the shape, only not without leaving a part of it empty: the plan
    // that leaves the least empty, with a warning saying where, rather than no plan (issue
    // 26: a drawing is refused only when one chain cannot do it); a serpentine bridging the
    // gaps of a shape monotone in no direction with much of the chain outside is never
    // returned (it only words the refusal), but a plan by caps is, whatever lies outside
    // returned in place of a plan off the count too, when nearer the count and less short
    // of the asked chain ([`Asked::prefers_rejected`])
    let returned = |r: Box<Rejected>| {
        let Rejected { mut plan, empty } = *r;
        plan.metrics.largest_empty_tiles = empty.tiles;
        plan.warnings.push(format!("the plan {empty}"));
        Some(plan)
    };
    let (best, rejected) = match (best, rejected) {
        (None, Some(r)) => (returned(r), None),
        (Some(b), Some(r)) if asked.prefers_rejected(&r, &b) => (returned(r), None),
        (best, None) => (best, bridging),
        other => other,
    };
    let Some(plan) = best else {
        progress("looking for a tile count that plans", 0, 1);
        let plans_at = |n: usize| {
            let fewer = opts.clone().with_tiles(n);
            plan_shape(shape, &fewer, name, mm_per_unit, false, &|_, _, _| {})
                .ok()
                .map(|p| p.tiles)
        };
        let retry = retry && opts.tile_size.is_none();
        return Err(refusal::no_plan(
            name,
            tiles_est,
            monotone.is_empty(),
            failures,
            rejected,
            mm_per_unit,
            retry.then_some(refusal::Retry {
                plans_at: &plans_at,
                tolerance: opts.tiles_tolerance,
            }),
        ));
    };
    // U-turns pushed into the parts left empty at row ends ([`crate::pockets`])
    let mut plan = crate::pockets::fill_row_ends(shape, plan, opts);
    plan.warnings.extend(count_warning(opts, plan.tiles));
    plan.warnings.extend(island_warning);
    Ok(plan)
}

/// Single-file walks along thin strokes ([`crate::walk`]), tried where the plans found fall
/// short of the asked chain by more than [`WALK_SHORTFALL_SHARE`] of it (a count far off, or
/// a large part left empty: a thin ring or letter at a low count), for counts up to
/// [`crate::walk::MAX_WALK_TILES`]; the best walk is offered as the other plans are.
fn walks(
    shape: &Shape,
    opts: &PlanOptions,
    tiles_est: usize,
    name: &str,
    miss: &dyn Fn(&Plan) -> usize,
    found: &mut Found,
) {
    if opts.tile_size.is_some() || tiles_est > crate::walk::MAX_WALK_TILES {
        return;
    }
    let short = found
        .best
        .iter()
        .map(|b| found.asked.plan_shortfall(b))
        .chain(
            found
                .rejected
                .iter()
                .map(|r| found.asked.rejected_shortfall(r)),
        )
        .fold(f64::INFINITY, f64::min);
    if short <= WALK_SHORTFALL_SHARE * tiles_est as f64 {
        return;
    }
    let Some(p) = crate::walk::best_walk(shape, tiles_est, &found.asked, name) else {
        return;
    };
    // a walk draws the shape no worse than the plans found (the area-true fit: a single
    // file along one edge of a band three tiles wide splits what it leaves empty into
    // smaller parts, but covers less of the shape)
    let fit = found
        .best
        .iter()
        .chain(found.rejected.iter().map(|r| &r.plan))
        .map(|q| q.metrics.fit_error())
        .fold(f64::INFINITY, f64::min);
    // nor misses the count by more than they do (issue 26: the count within the tolerance)
    let least_miss = found
        .best
        .iter()
        .chain(found.rejected.iter().map(|r| &r.plan))
        .map(miss)
        .min()
        .unwrap_or(usize::MAX);
    if miss(&p) > least_miss {
        found.failures.push(format!(
            "a walk along the strokes lays {} tiles, further from the count",
            p.tiles
        ));
        return;
    }
    if p.metrics.fit_error() > fit {
        found.failures.push(format!(
            "a walk along the strokes fits worse ({:.0}% of the shape covered, {:.0}% of the chain outside)",
            100.0 * p.metrics.covered_share,
            100.0 * p.metrics.outside_share
        ));
        return;
    }
    // the plan's word read back and checked from scratch, as every plan returned is (a word
    // that does not read back is no plan)
    if p.fold_word().map_or(true, |w| check_folds(&w).is_err()) {
        found
            .failures
            .push("a walk along the strokes does not fold".into());
        return;
    }
    match note_empty(shape, p, crate::empty::near(opts.turns)) {
        Ok(p) => {
            let rank = |q: &Plan| (miss(q), rank_key(q, opts.turn_cost));
            if found.best.as_ref().is_none_or(|b| rank(&p) < rank(b)) {
                found.best = Some(p);
            }
        }
        Err(e) => {
            let (part, plan) = *e;
            found.reject(Box::new(Rejected { plan, empty: part }));
        }
    }
}

/// Walks are tried where the plans found fall short of the asked chain ([`Asked::shortfall`])
/// by more than this share of the count.
const WALK_SHORTFALL_SHARE: f64 = 0.1;

/// Under `auto`, whether the tight plans found leave the loose ones nothing to win: no plan
/// kept, but a route rejected for an empty part with a count within the tolerance that
/// leaves at most [`LOOSE_AFTER_EMPTY_SHARE`] of the asked count empty (in the asked
/// chain's tile areas, [`Asked::shortfall`]). A loose route could replace it only by
/// falling less short of the asked chain ([`Asked::before`]), and loose rows under `auto`
/// leave a strip between every two rows empty (0.6 tile areas per tile of row, see
/// [`plan_shape`]). On the corpus (71 one-piece drawings at 100, 300, 1000 and 3000 tiles)
/// the loose pass after such a route found no kept plan and its best rejected route ranked
/// first once (letter C at 3000: 92 of its tile areas empty against the tight route's 57,
/// 1.2% of the count), while it took a third of the CPU at 3000 tiles. Where the tight pass
/// found nothing within the count, or leaves more empty (a whole side of a thin ring), the
/// loose pass runs as before.
fn tight_holds_count(found: &Found, miss: &dyn Fn(&Plan) -> usize, tiles: usize) -> bool {
    found.best.is_none()
        && found.rejected.as_ref().is_some_and(|r| {
            miss(&r.plan) == 0
                && found.asked.rejected_shortfall(r) <= LOOSE_AFTER_EMPTY_SHARE * tiles as f64
        })
}

/// The drawing's parts, the same at every count ([`crate::parts`]): a drawing of several
/// large parts is refused; otherwise the shape without its islands (`None`: the drawing as
/// read) and the warning that names them.
fn without_islands(
    shape: &Shape,
    name: &str,
    mm_per_unit: f64,
) -> Result<(Option<Shape>, Option<String>), PlanError> {
    match parts::split(shape) {
        Parts::Several { large, islands } => {
            Err(refusal::separate_parts(name, &large, &islands, mm_per_unit))
        }
        Parts::One {
            shape: kept,
            islands,
        } => {
            let total = kept.as_ref().map_or(0.0, Shape::area)
                + islands.iter().map(|p| p.area).sum::<f64>();
            let warning = refusal::islands_left_out(&islands, total, mm_per_unit);
            Ok((kept, warning))
        }
    }
}

/// The refusal made before any search: a drawing (of one part, [`crate::parts`]) in which
/// no tile fits at the width `tiles_est` tiles give.
fn refuse_at_once(
    shape: &Shape,
    opts: &PlanOptions,
    name: &str,
    mm_per_unit: f64,
    tiles_est: usize,
) -> Result<(), PlanError> {
    // the raster found no part that holds half a tile: unless a finer look finds one, no
    // chain can fill the drawing at this tile width, refused at once (searching widths at
    // which every row sticks out of it took minutes)
    let w = opts
        .tile_size
        .unwrap_or_else(|| width_for(shape.area(), tiles_est.max(1), TIGHT.pitch));
    if caps::parts(&shape.scaled(1.0 / w)).is_empty()
        && !narrow::fits_a_tile(&shape.scaled(1.0 / w))
    {
        let min_w = width_for(shape.area(), MAX_PLAN_TILES, TIGHT.pitch);
        return Err(refusal::too_narrow(
            name,
            tiles_est,
            w,
            opts.tile_size.is_some(),
            narrow::fitting_width(shape, w, min_w),
            mm_per_unit,
        ));
    }
    Ok(())
}

/// The warning for a plan of `tiles` tiles whose count misses the asked count by more than
/// the tolerance (none when no count was asked: a tile width, or the default count).
fn count_warning(opts: &PlanOptions, tiles: usize) -> Option<String> {
    let asked = opts.tiles.filter(|_| opts.tile_size.is_none())?;
    let tol = (opts.tiles_tolerance * asked as f64) as usize;
    if tiles.abs_diff(asked) <= tol {
        return None;
    }
    let share = 100.0 * tiles.abs_diff(asked) as f64 / asked as f64;
    Some(format!(
        "the plan has {tiles} tiles, {share:.1}% {} than the {asked} asked (tolerance {:.1}%): no plan nearer that count was found that folds and fills the shape",
        if tiles < asked { "fewer" } else { "more" },
        100.0 * opts.tiles_tolerance
    ))
}

/// What the planners found so far: the best plan, what each planner said when it failed, the
/// best plan rejected for an empty part (returned with a warning when nothing else plans),
/// and the best serpentine rejected for an empty part that also bridges the gaps of a shape
/// monotone in no direction with more than [`MAX_OUTSIDE_NON_MONOTONE`] of the chain outside
/// (never returned: it only words a refusal and its preview).
#[derive(Default)]
struct Found {
    best: Option<Plan>,
    failures: Vec<String>,
    rejected: Option<Box<Rejected>>,
    bridging: Option<Box<Rejected>>,
    /// The asked chain, by which rejected plans rank ([`Asked::before`]).
    asked: Asked,
}

impl Found {
    /// Keeps `r` if it falls less short of the asked chain than the one kept.
    fn reject(&mut self, r: Box<Rejected>) {
        keep_least_short(&mut self.rejected, r, &self.asked);
    }
}

/// Puts `r` in `slot` if the slot is empty or `r` falls less short of the asked chain.
fn keep_least_short(slot: &mut Option<Box<Rejected>>, r: Box<Rejected>, asked: &Asked) {
    if asked.before(&r, slot.as_deref()) {
        *slot = Some(r);
    }
}

/// Plans the shape with the turn styles `styles`: one serpentine and, where the shape
/// splits into cells, caps joined by quarter turns; a plan replaces `found.best` when it
/// ranks before it (a count within the tolerance, `miss`, then the largest part left
/// empty, least first, then the fit). `angles` are the shape's monotone row angles and the serpentine's directions.
#[allow(clippy::too_many_arguments)]
fn plan_styles(
    shape: &Shape,
    opts: &PlanOptions,
    styles: &[Style],
    (monotone, directions): (&[f64], &[f64]),
    tiles_est: usize,
    name: &str,
    progress: Progress<'_>,
    found: &mut Found,
    miss: &dyn Fn(&Plan) -> usize,
) {
    // a part left empty is priced with the turns and the fit ([`crate::empty::plan_cost`]):
    // a fill with a few more turns wins, and so does a few tenths of a tile area more
    // empty with half the turns
    let rank = |q: &Plan| (miss(q), rank_key(q, opts.turn_cost));
    let offer = |found: &mut Found, p: Plan| {
        if found.best.as_ref().is_none_or(|b| rank(&p) < rank(b)) {
            found.best = Some(p);
        }
    };
    let mut serp = best_serpentine(
        shape,
        opts,
        styles,
        directions,
        name,
        &mut found.failures,
        progress,
    );
    if let Some(p) = serp.take() {
        let near = crate::empty::near(opts.turns);
        let measured = note_empty(shape, p, near);
        let measured = match measured {
            Err(e) if opts.tile_size.is_none() => {
                serpentine_at_other_widths(shape, opts, styles, directions, name, progress, miss, e)
            }
            // a small part left empty: the widths near its own (issue 26, planaudit13)
            Ok(p) => Ok(crate::near_widths::fewer_empty(
                shape, opts, styles, directions, name, progress, miss, p,
            )),
            m => m,
        };
        match measured {
            Ok(p) => serp = Some(p),
            Err(e) => {
                let (part, p) = *e;
                found.failures.push(format!("one serpentine {part}"));
                let bridges =
                    monotone.is_empty() && p.metrics.outside_share > MAX_OUTSIDE_NON_MONOTONE;
                let r = Box::new(Rejected {
                    plan: p,
                    empty: part,
                });
                if bridges {
                    keep_least_short(&mut found.bridging, r, &found.asked);
                } else {
                    found.reject(r);
                }
            }
        }
    }
    if monotone.is_empty() {
        // one serpentine over a shape that is monotone in no direction (or in separate
        // parts) bridges its gaps: kept only while little of the chain lies outside
        if let Some(p) = serp.take() {
            if p.metrics.outside_share <= MAX_OUTSIDE_NON_MONOTONE {
                serp = Some(p);
            } else {
                found.failures.push(format!(
                    "one serpentine covers {:.0}% of the shape with {:.0}% of the chain outside",
                    100.0 * p.metrics.covered_share,
                    100.0 * p.metrics.outside_share
                ));
            }
        }
    }
    if let Some(p) = serp {
        offer(found, p);
    }
    // caps joined by quarter turns, for shapes that are not one serpentine (and, up to
    // MAX_CELL_TILES tiles, for every shape: a monotone shape keeps the better of the two),
    // where along some axis the cheapest cap decomposition has more than one cell (a shape
    // that one serpentine fills as well needs no caps)
    if !monotone.is_empty() && tiles_est > MAX_CELL_TILES {
        return;
    }
    let by_axis: Vec<Vec<(f64, Vec<CapPlan>, f64)>> = styles
        .iter()
        .map(|&style| cap_axes(shape, style, start_width(shape, opts, style)))
        .collect();
    let splits = by_axis
        .iter()
        .flatten()
        .any(|(_, plans, _)| plans.first().is_some_and(|p| p.cells.len() > 1));
    if !splits {
        return;
    }
    progress("planning by caps", 0, 1);
    let known = known(shape, found);
    let by_caps: Vec<Result<Plan, CellFailure>> = styles
        .par_iter()
        .zip(&by_axis)
        .map(|(&style, axes)| plan_by_caps(shape, opts, style, name, axes, known))
        .collect();
    progress("planning by caps", 1, 1);
    for r in by_caps {
        match r {
            Ok(p) => offer(found, p),
            Err((e, r)) => {
                found.failures.push(format!("by caps: {e}"));
                if let Some(r) = r {
                    found.reject(r);
                }
            }
        }
    }
}

/// The least part left empty (tile areas) by the plans found so far (more slab
/// decompositions are sized only while it is large), and the share of the tile centres
/// inside the shape of the plan found (kept, or rejected for a part left empty; 1 without
/// one), which slab plans need not beat ([`crate::cap_plan`]).
fn known(shape: &Shape, found: &Found) -> (f64, f64) {
    let known_empty = found
        .best
        .iter()
        .map(|b| b.metrics.largest_empty_tiles)
        .chain(found.rejected.iter().map(|r| r.empty.tiles))
        .fold(f64::INFINITY, f64::min);
    let known_inside = found
        .best
        .as_ref()
        .or(found.rejected.as_ref().map(|r| &r.plan))
        .map_or(1.0, |p| centres_inside(shape, p));
    (known_empty, known_inside)
}

/// Where the serpentine sized for the asked count leaves a part larger than
/// [`RETRY_EMPTY_SHARE`] of the count empty (`first`), the serpentines at the widths
/// [`SERPENTINE_RETRIES`] times its own, each with a count within the tolerance, until one
/// leaves less than that share: the one whose part left empty is smallest (in its own tile
/// areas, as issue 26 measures it; none empty first). The size search settles on the rows' fit alone, blind to the parts a serpentine
/// leaves empty, and on a ring with spokes the rows' phase decides which side of the hole
/// the fold check lets them fill (bi-gear-wide-connected at 3000 tiles: 2432 tile areas
/// empty at the width found, 781 at 2% wider).
#[allow(clippy::too_many_arguments)]
fn serpentine_at_other_widths(
    shape: &Shape,
    opts: &PlanOptions,
    styles: &[Style],
    directions: &[f64],
    name: &str,
    progress: Progress<'_>,
    miss: &dyn Fn(&Plan) -> usize,
    first: Box<(EmptyPart, Plan)>,
) -> Result<Plan, Box<(EmptyPart, Plan)>> {
    let target = opts.tiles.unwrap_or(DEFAULT_TILES) as f64;
    let large = |e: &(EmptyPart, Plan)| e.0.tiles > RETRY_EMPTY_SHARE * target;
    // under `auto`, loose serpentines are not tried again: on the corpus none so found
    // ranked first, and they doubled the work (libsi-A at 3000 tiles went past 10 s)
    let loose_under_auto =
        opts.turns == Turns::Auto && styles.iter().all(|s| s.turns == Turns::Loose);
    if loose_under_auto || !large(&first) {
        return Err(first);
    }
    let w = first.1.tile_size;
    let near = crate::empty::near(opts.turns);
    let mut best = first;
    for (f, &style) in SERPENTINE_RETRIES
        .iter()
        .flat_map(|f| styles.iter().map(move |s| (f, s)))
    {
        // the count and the part left empty first, the fold check (the costly part on long
        // chains) only for a plan that would be kept
        let Some((p, sz)) = crate::near_widths::serpentine_at(
            shape,
            opts,
            w * f,
            style,
            directions,
            name,
            progress,
            miss,
        ) else {
            continue;
        };
        let m = note_empty(shape, p, near);
        if m.as_ref().is_err_and(|e| e.0.tiles >= best.0.tiles) {
            continue;
        }
        if !crate::near_widths::folds(&sz, style) {
            continue;
        }
        match m {
            Ok(p) => return Ok(p),
            Err(e) => best = e,
        }
        if !large(&best) {
            break;
        }
    }
    Err(best)
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

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A count within the tolerance is quiet; one outside it is said with both numbers; no
    /// count asked (a tile width) is never warned about.
    #[test]
    fn a_count_outside_the_tolerance_is_warned_about() {
        let opts = PlanOptions::default().with_tiles(300);
        assert_eq!(count_warning(&opts, 300), None);
        assert_eq!(count_warning(&opts, 291), None);
        assert_eq!(count_warning(&opts, 309), None);
        let w = count_warning(&opts, 254).unwrap();
        assert!(
            w.contains("254 tiles") && w.contains("300 asked") && w.contains("15.3% fewer"),
            "{w}"
        );
        assert!(w.contains("tolerance 3.0%"), "{w}");
        let w = count_warning(&opts, 310).unwrap();
        assert!(w.contains("3.3% more"), "{w}");
        let exact = opts.clone().with_tiles_tolerance(0.0);
        assert!(count_warning(&exact, 301).is_some());
        let by_width = PlanOptions {
            tile_size: Some(3.0),
            ..opts
        };
        assert_eq!(count_warning(&by_width, 10), None);
        assert_eq!(count_warning(&PlanOptions::default(), 10), None);
    }
}
