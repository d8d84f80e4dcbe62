//! Planning by cells (thesis section 5.5, the key): along each sweep axis the shape is split
//! into monotone cells ([`crate::cells`]), the cells are visited in the orders of the
//! Hamiltonian paths of their graph, and each order is routed ([`crate::route`]); the tile
//! width is searched on the cheapest route ([`crate::sizing`]), the cheapest routes are
//! checked by sequential folding like every plan, and the best fit wins. When no axis gives
//! a route, the error says why, per axis.

use std::f64::consts::PI;

use std::sync::Arc;

use rayon::prelude::*;

use crate::assembly::Assembly;
use crate::cell_search::{route_searches, CellSearch, Reasons, RoutedWidth, CELL_WORK_BUDGET};
use crate::cells::{decompose_merging, Branch, Cells, Merge};
use crate::check::{check_folds, CheckMemo};
use crate::empty::empty_part;
use crate::error::Rejected;
use crate::fit::plan_score;
use crate::frame::{stacking_axis_deg, Orientation};
use crate::options::{PlanOptions, DEFAULT_TILES};
use crate::plan::Plan;
use crate::route::{route_order, Route, Routed};
use crate::rows::Style;
use crate::shape::Shape;
use crate::sizing::{tiles_for, width_for, Attempt, SizeSearch};

/// Cells are split where an end of the sweep interval jumps by more than a tile width. Up
/// to this many such jumps, every way of merging the cells across some of them is routed
/// too (2^jumps decompositions): a key's shaft and bits as one cell, its head another,
/// which a row programme fills with fewer turns than five separate cells.
const MAX_MERGED_JUMPS: usize = 4;
/// Decompositions (merges across jumps times choices at branches, where the sweep meets a
/// hole) routed at most per axis: a ring's two branches have 5 and 3 choices (15), two
/// holes side by side 225; the pinwheels come first (2 for a ring, 4 for two holes).
const MAX_DECOMPOSITIONS: usize = 8;
/// Size steps of the tile width search.
const SIZE_STEPS: usize = 10;
/// The size search stops once the count is within this share of the target (2%: a cell
/// route changes by whole rows in several cells at once).
const CELL_COUNT_TOLERANCE: f64 = 0.02;
/// Factors tried on the tile width when every route checked at the width the steps settle on
/// collides or leaves a part of the shape empty: the joins then fall on the cells at other
/// phases (a dog's leg two tiles wide gets a column or none by where the body's columns
/// fall). Within about 1.5% of the width, so the count stays near the tolerance.
const RETRIES: [f64; 6] = [0.995, 1.005, 0.99, 1.01, 0.985, 1.015];
/// Routes (cheapest first, over all axes) checked and measured.
const CHECKED_ROUTES: usize = 10;
/// Hamiltonian paths tried per axis, and the search steps spent finding them.
const MAX_ORDERS: usize = 12;
const MAX_ORDER_STEPS: usize = 20_000;
/// Axes with more cells than this are not planned by cells.
const MAX_CELLS: usize = 12;
/// Complete routes per axis turned into words and checked.
const ROUTES_KEPT: usize = 4;

/// Why no cell route was returned, with the best one rejected for an empty part.
pub(crate) type CellFailure = (String, Option<Box<Rejected>>);

/// Why an axis gave no route.
type Why = String;

/// The best routes over the cells of `axis_shape` (axis frame, unit tiles), cheapest first,
/// or why there is none, from at most `searches` route searches (the first decompositions,
/// each with an equal share of cell orders, see [`crate::cell_search`]). `describe` names a
/// cell for messages.
fn plan_cells(
    axis_shape: &Shape,
    style: Style,
    memo: &CheckMemo,
    describe: &(dyn Fn(&Shape) -> String + Sync),
    searches: usize,
) -> Result<Vec<Routed>, Why> {
    let split = decompose_merging(axis_shape, 1.0, 1.0, Merge::default());
    let mut merges = merges(&split);
    merges.truncate(searches.max(1));
    let max_orders = (searches / merges.len().max(1)).clamp(1, MAX_ORDERS);
    let per_mask: Vec<Result<Vec<Routed>, Why>> = merges
        .par_iter()
        .map(|(m, b)| {
            let cells = if *m == 0 && b.iter().all(|&c| c == 0) {
                None
            } else {
                Some(decompose_merging(
                    axis_shape,
                    1.0,
                    1.0,
                    Merge {
                        jumps: *m,
                        branches: b,
                    },
                ))
            };
            route_cells(
                cells.as_ref().unwrap_or(&split),
                style,
                memo,
                describe,
                max_orders,
            )
        })
        .collect();
    let mut routed: Vec<Routed> = Vec::new();
    let mut why = None;
    for r in per_mask {
        match r {
            Ok(v) => routed.extend(v),
            Err(e) => {
                why.get_or_insert(e);
            }
        }
    }
    if routed.is_empty() {
        return Err(why.unwrap_or_else(|| "no route".into()));
    }
    routed.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    routed.truncate(ROUTES_KEPT);
    Ok(routed)
}

/// The merges of the cells of `split` to route, at most [`MAX_DECOMPOSITIONS`]: every way
/// of merging across its jumps (up to [`MAX_MERGED_JUMPS`]), each with choices at its
/// branches: first the pinwheels (every split cut along one side or the other of its gap,
/// no join merged: the cells around a hole then each reach the outline at both ends of
/// their rows, which sequential folding needs, since a row pointing across a hole at tiles
/// already laid would sweep into them), then the others, fewest merged branches first.
fn merges(split: &Cells) -> Vec<(u32, Vec<usize>)> {
    let masks: Vec<u32> = if split.jumps <= MAX_MERGED_JUMPS {
        (0..1u32 << split.jumps).collect()
    } else {
        vec![0]
    };
    // branches are merged or cut only around holes: where the graph of the plain cells
    // has a cycle (a sweep meets a hole at a split and a join); a shape without holes keeps
    // its plain branches, as the thesis' key does
    let holes = split.graph.edge_count() + split.components() > split.cells.len();
    let room = if holes {
        (MAX_DECOMPOSITIONS / masks.len()).max(1)
    } else {
        1
    };
    let mut choices: Vec<Vec<usize>> = vec![Vec::new()];
    for b in &split.branches {
        let mut next: Vec<Vec<usize>> = Vec::new();
        for c in &choices {
            for k in 0..b.choices {
                let mut c = c.clone();
                c.push(k);
                next.push(c);
            }
        }
        choices = next;
        if choices.len() > 4 * room {
            choices.sort_by_key(|c| pinwheel_rank(&split.branches, c));
            choices.truncate(4 * room);
        }
    }
    if holes {
        choices.sort_by_key(|c| pinwheel_rank(&split.branches, c));
    } else {
        choices = vec![Vec::new()];
    }
    choices.truncate(room);
    masks
        .iter()
        .flat_map(|&m| choices.iter().map(move |c| (m, c.clone())))
        .collect()
}

/// The rank of branch choices `c` (lower first): 0 for a pinwheel (every split cut, no join
/// merged, as far as `c` goes), else one more than the number of branches merged or cut.
fn pinwheel_rank(branches: &[Branch], c: &[usize]) -> usize {
    let pinwheel = branches
        .iter()
        .zip(c)
        .all(|(b, &k)| if b.cuts { k + 2 >= b.choices } else { k == 0 });
    if pinwheel {
        0
    } else {
        1 + c.iter().filter(|&&k| k > 0).count()
    }
}

/// The best routes through `cells` over at most `max_orders` cell orders, cheapest first, or
/// why there is none.
fn route_cells(
    cells: &Cells,
    style: Style,
    memo: &CheckMemo,
    describe: &(dyn Fn(&Shape) -> String + Sync),
    max_orders: usize,
) -> Result<Vec<Routed>, Why> {
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
    let orders = cells.orders(max_orders, MAX_ORDER_STEPS);
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
        .flat_map_iter(|o| route_order(cells, o, style, memo).into_iter().take(2))
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
/// cheapest routes are checked by sequential folding; the best fit wins. A width whose
/// checked routes all collide or leave a part empty is not the answer; with `retry`, widths
/// a little either side of it are tried too ([`RETRIES`]). The error says, per
/// axis, why no route was found, with the best route that folds but leaves a part empty.
pub(crate) fn plan_by_cells(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    name: &str,
    retry: bool,
    cell_search: &CellSearch,
) -> Result<Plan, CellFailure> {
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let w0 = opts
        .tile_size
        .unwrap_or_else(|| width_for(shape.area(), target, style.pitch));
    let axes = axes(shape);
    // why axes gave no route, at the last width tried
    let mut why: Reasons = Vec::new();
    let tol = ((opts.tiles_tolerance.max(CELL_COUNT_TOLERANCE) * target as f64) as usize).max(1);
    let search = SizeSearch {
        secant_steps: if opts.tile_size.is_some() {
            1
        } else {
            SIZE_STEPS
        },
        nudges: &[],
        tolerance: tol,
        explore: false,
        shrink_when_empty: None,
        // a width given is kept
        retries: if retry && opts.tile_size.is_none() {
            &RETRIES
        } else {
            &[]
        },
    };
    // counts within the tolerance first (routes at one width differ in count), then the
    // best score
    let miss = |p: &Plan| match opts.tile_size {
        Some(_) => 0,
        None => p.tiles.abs_diff(target).saturating_sub(tol),
    };
    let by_rank = |x: &Plan, y: &Plan| {
        miss(x)
            .cmp(&miss(y))
            .then(plan_score(x, opts.turn_cost).total_cmp(&plan_score(y, opts.turn_cost)))
    };
    let mut collide = String::new();
    // the best route rejected for an empty part (the smallest part), with its message
    let mut rejected: Option<(String, Box<Rejected>)> = None;
    let found = search.run_checked(target, w0, |w| {
        // a serpentine's count at this width sets how many route searches it gets
        let searches = route_searches(tiles_for(shape.area(), w, style.pitch), axes.len());
        let Some(routed) =
            cell_search.routes_at(w, || route_axes(shape, &axes, style, w, searches))
        else {
            return Attempt::Nothing;
        };
        why.clone_from(&routed.why);
        let mut routes = routed.routes.clone();
        // routes whose count is within the tolerance first, each group cheapest first
        if opts.tile_size.is_none() {
            routes.sort_by_key(|(_, r)| r.word.tiles().abs_diff(target).saturating_sub(tol));
        }
        let Some(first) = routes.first() else {
            return Attempt::Nothing;
        };
        let n = first.1.word.tiles();
        let plans = checked_plans(shape, style, w, name, &routes, &mut collide, &mut rejected);
        // plans at different widths are compared by their count only: an equal miss keeps
        // the width found first. The first search steers by the count of the cheapest route
        // (as it always did: fewer widths), the retry search by the plan's own count
        match plans.into_iter().min_by(by_rank) {
            Some(p) => Attempt::Plan(if retry { p.tiles } else { n }, 0.0, p),
            None => Attempt::Rejected(n),
        }
    });
    match found {
        Some(found) => Ok(found.plans),
        None if !collide.is_empty() || rejected.is_some() => {
            let (mut text, r) = match rejected {
                Some((text, r)) => (text, Some(r)),
                None => (
                    format!("every cell route collides when folded (first: {collide})"),
                    None,
                ),
            };
            if cell_search.exhausted() {
                text = format!("{text} ({})", budget_note(cell_search));
            }
            Err((text, r))
        }
        None => {
            let mut text: Vec<String> = why
                .iter()
                .map(|(r, axes)| format!("along axes {} deg: {r}", axes.join(", ")))
                .collect();
            if cell_search.exhausted() {
                text.push(budget_note(cell_search));
            }
            Err((text.join("; "), None))
        }
    }
}

/// Says that the search budget stopped the width search (see [`crate::cell_search`]).
fn budget_note(cell_search: &CellSearch) -> String {
    format!(
        "the search budget ({CELL_WORK_BUDGET} units of work per turn style) ran out after {} units, so fewer widths were routed",
        cell_search.spent()
    )
}

/// The plans of the first [`CHECKED_ROUTES`] of `routes` (at tile width `w`) that fold
/// without collision and leave no part of the shape empty. The last collision is kept in
/// `collide`, and the route that leaves the smallest part empty in `rejected`.
fn checked_plans(
    shape: &Shape,
    style: Style,
    w: f64,
    name: &str,
    routes: &[(f64, Arc<Routed>)],
    collide: &mut String,
    rejected: &mut Option<(String, Box<Rejected>)>,
) -> Vec<Plan> {
    let mut plans: Vec<Plan> = Vec::new();
    for (a, r) in routes.iter().take(CHECKED_ROUTES) {
        if let Err(e) = check_folds(&r.word) {
            *collide = e;
            continue;
        }
        let orient = Orientation::along(*a);
        let work = orient.work_shape(shape, w);
        let asm = Assembly {
            work: &work,
            chain_to_work: r.chain_to_axis,
            work_to_svg: orient.work_to_svg(w),
            row_angle: *a,
            style,
            w,
            u_turns: r.u_turns,
            quarter_turns: r.quarter_turns,
            cells: r.cells,
        };
        if !asm.agrees(&r.word, &r.centres) {
            *collide =
                String::from("internal: the route's tile centres disagree with the kinematics");
            continue;
        }
        let plan = asm.to_plan(&r.word, name);
        if let Some(part) = empty_part(shape, &plan) {
            if rejected
                .as_ref()
                .is_none_or(|(_, b)| part.tiles < b.empty.tiles)
            {
                let text = format!(
                    "the best route ({} cells, {} tiles) {part}",
                    plan.cells, plan.tiles
                );
                *rejected = Some((text, Box::new(Rejected { plan, empty: part })));
            }
            continue;
        }
        plans.push(plan);
    }
    plans
}

/// Routes every axis at tile width `w` (in parallel, at most `searches` route searches per
/// axis): the routes with their axis, cheapest first, why the other axes gave none (each
/// reason with the axes, SVG degrees), and the work spent.
fn route_axes(shape: &Shape, axes: &[f64], style: Style, w: f64, searches: usize) -> RoutedWidth {
    // one memo of fold checks for every axis at this width (a check depends on the word)
    let memo = CheckMemo::default();
    let per_axis: Vec<(f64, Result<Vec<Routed>, Why>)> = axes
        .par_iter()
        .map(|&a| {
            let axis_shape = Orientation::along(a).work_shape(shape, w);
            let describe = |cell: &Shape| describe_cell(cell, a, w);
            (
                a,
                plan_cells(&axis_shape, style, &memo, &describe, searches),
            )
        })
        .collect();
    let mut routes: Vec<(f64, Arc<Routed>)> = Vec::new();
    let mut why: Reasons = Vec::new();
    for (a, r) in per_axis {
        match r {
            Ok(v) => routes.extend(v.into_iter().map(|x| (a, Arc::new(x)))),
            Err(e) => {
                let deg = format!("{:.0}", stacking_axis_deg(a).round() % 180.0 + 0.0);
                match why.iter_mut().find(|(r, _)| *r == e) {
                    Some((_, axes)) => axes.push(deg),
                    None => why.push((e, vec![deg])),
                }
            }
        }
    }
    routes.sort_by(|x, y| x.1.cost.total_cmp(&y.1.cost));
    RoutedWidth {
        routes,
        why,
        work: memo.work(),
    }
}

/// A cell (axis frame of row angle `a`, tiles of width `w`) by its bounding box in SVG user
/// units.
fn describe_cell(cell: &Shape, a: f64, w: f64) -> String {
    let b = cell.scaled(w).rotated(a).bbox();
    format!(
        "x {:.0} to {:.0}, y {:.0} to {:.0}",
        b.x0, b.x1, -b.y1, -b.y0
    )
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

    /// The work of routing one width stays about flat as the tiles grow: the route searches
    /// fall as the tiles grow ([`route_searches`]), where before every width routed every
    /// decomposition and order, each search costing in proportion to the tiles (two holes
    /// at 300 tiles: 2e7 units per width and style, 20 widths, minutes). Counted, not timed.
    #[test]
    fn a_widths_work_stays_flat_as_the_tiles_grow() {
        let shape = sample("two-holes.svg");
        let axes = axes(&shape);
        let work = |n: usize| {
            let w = width_for(shape.area(), n, TIGHT.pitch);
            let searches = route_searches(tiles_for(shape.area(), w, TIGHT.pitch), axes.len());
            route_axes(&shape, &axes, TIGHT, w, searches).work
        };
        let (small, large) = (work(600), work(2400));
        // the work of a route search grows with the tiles: 4 times the tiles would be 4
        // times the work without the bound
        assert!(
            large < 2 * small,
            "{small} units at 600 tiles, {large} at 2400"
        );
        assert!(large <= CELL_WORK_BUDGET, "{large}");
    }

    /// The thesis key by cells: head and shaft as separate cells, every route folds.
    #[test]
    fn key_by_cells() {
        let opts = PlanOptions::default().with_tiles(171);
        let p = plan_by_cells(
            &sample("key.svg"),
            &opts,
            TIGHT,
            "key.svg",
            false,
            &CellSearch::default(),
        )
        .unwrap();
        assert!(p.cells >= 2, "{}", p.summary());
        let w = p.fold_word().unwrap();
        assert!(w.first_opposite_pair().is_none());
        assert!(foldchain::collision::check_word(&w, &Default::default()).is_ok());
    }
}
