//! What planning by caps ([`crate::cap_plan`]) shares with the rest of the planner: the
//! sweep axes a shape is planned along, and the check every route passes before it becomes
//! a plan (sequential folding, the kinematics, no part left empty).

use std::f64::consts::PI;

use std::sync::Arc;

use crate::assembly::Assembly;
use crate::check::check_folds;
use crate::empty::{excess_empty, note_empty, EMPTY_PRICE};
use crate::error::Rejected;
use crate::frame::Orientation;
use crate::plan::Plan;
use crate::rank::Asked;
use crate::route::Routed;
use crate::rows::Style;
use crate::shape::Shape;

/// What the routes checked so far said when they failed: the last collision, and the route
/// rejected for an empty part that falls least short of the asked chain (with its reason;
/// [`Asked::before`]).
#[derive(Default)]
pub(crate) struct Failed {
    /// The last collision.
    pub collide: String,
    /// The rejected route that falls least short of the asked chain.
    pub rejected: Option<(String, Box<Rejected>)>,
    /// The asked chain, by which rejected routes rank.
    pub asked: Asked,
}

impl Failed {
    /// Nothing failed yet; rejected routes rank by `asked`.
    pub(crate) fn new(asked: Asked) -> Failed {
        Failed {
            asked,
            ..Failed::default()
        }
    }

    /// Adds what `other` says: its collision if any, its rejected route if it falls less
    /// short of the asked chain.
    pub(crate) fn merge(&mut self, other: Failed) {
        if !other.collide.is_empty() {
            self.collide = other.collide;
        }
        if let Some((text, r)) = other.rejected {
            if self
                .asked
                .before(&r, self.rejected.as_ref().map(|(_, b)| &**b))
            {
                self.rejected = Some((text, r));
            }
        }
    }
}

/// Routes (cheapest first, over all axes) checked.
const CHECKED_ROUTES: usize = 10;
/// Plans measured per width (see [`checked_plans`]).
const MEASURED: usize = 3;

/// Why no cell route was returned, with the best one rejected for an empty part.
pub(crate) type CellFailure = (String, Option<Box<Rejected>>);

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

/// The plans of the first [`CHECKED_ROUTES`] of `routes` (at tile width `w`, ranked by
/// `miss`, the tiles by which a count misses the asked one, then by route cost) that fold
/// without collision and leave no part of the shape empty (measured at `near` tile
/// widths), measured: the first [`MEASURED`] of those that rank best by (`miss`, the
/// largest part left empty) in route order (the route cost estimates the fit, the measure on sample
/// points has the last word). The routes are checked in order until [`MEASURED`] plans
/// miss by nothing and leave nothing empty. A plan that `admit` refuses, given its largest
/// part left empty (a slab route with too much of its chain outside the shape for what it
/// fills; asked with 0 before the plan is measured, and not measured when refused then), is
/// passed over like one that collides, so that the plans ranked are those the caller
/// keeps. What the others said is kept in `failed`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn checked_plans(
    shape: &Shape,
    style: Style,
    w: f64,
    name: &str,
    routes: &[(f64, Arc<Routed>)],
    near: f64,
    miss: &dyn Fn(usize) -> usize,
    admit: &dyn Fn(&Plan, f64) -> bool,
    failed: &mut Failed,
) -> Vec<Plan> {
    let Failed {
        collide,
        rejected,
        asked,
    } = failed;
    let mut plans: Vec<(Plan, &Routed, f64)> = Vec::new();
    for (a, r) in routes.iter().take(CHECKED_ROUTES) {
        let good = |p: &Plan| miss(p.tiles) == 0 && p.metrics.largest_empty_tiles == 0.0;
        if plans.iter().filter(|(p, ..)| good(p)).count() >= MEASURED {
            break;
        }
        if let Err(e) = check_folds(&r.word) {
            *collide = e;
            continue;
        }
        let orient = Orientation::along(*a);
        let work = orient.work_shape(shape, w);
        let asm = assembly(&work, orient, r, style, w);
        if !asm.agrees(&r.word, &r.centres) {
            *collide =
                String::from("internal: the route's tile centres disagree with the kinematics");
            continue;
        }
        let plan = asm.to_plan_unmeasured(&r.word, name);
        // refused whatever it leaves empty: not measured
        if !admit(&plan, 0.0) {
            continue;
        }
        let plan = match note_empty(shape, plan, near) {
            Ok(plan) if !admit(&plan, plan.metrics.largest_empty_tiles) => continue,
            Ok(plan) => plan,
            Err(e) => {
                let (part, mut plan) = *e;
                if !admit(&plan, part.tiles) {
                    continue;
                }
                let short = asked.shortfall(plan.tiles, plan.tile_size, part.tiles);
                if rejected
                    .as_ref()
                    .is_none_or(|(_, b)| short < asked.rejected_shortfall(b))
                {
                    asm.measure(&mut plan, &r.word);
                    let text = format!(
                        "the best route ({} cells, {} tiles) {part}",
                        plan.cells, plan.tiles
                    );
                    *rejected = Some((text, Box::new(Rejected { plan, empty: part })));
                }
                continue;
            }
        };
        plans.push((plan, r, *a));
    }
    let Some(top) = plans.iter().map(|(p, ..)| miss(p.tiles)).min() else {
        return Vec::new();
    };
    plans.retain(|(p, ..)| miss(p.tiles) == top);
    // a part left empty is priced with the route's cost (its fit and turns, tile areas) at
    // [`EMPTY_PRICE`] a tile area beyond the allowance, the rule the caller ranks the
    // measured plans by ([`crate::empty::plan_cost`]); route order among equals
    let cost =
        |p: &Plan, r: &Routed| r.cost + EMPTY_PRICE * excess_empty(p.metrics.largest_empty_tiles);
    plans.sort_by(|(p, r, _), (q, s, _)| cost(p, r).total_cmp(&cost(q, s)));
    plans
        .into_iter()
        .take(MEASURED)
        .map(|(mut plan, r, a)| {
            let orient = Orientation::along(a);
            let work = orient.work_shape(shape, w);
            assembly(&work, orient, r, style, w).measure(&mut plan, &r.word);
            plan
        })
        .collect()
}

/// The assembly of route `r` swept along `orient` at tile width `w` (`work`: the shape in
/// its work frame).
fn assembly<'a>(
    work: &'a Shape,
    orient: Orientation,
    r: &Routed,
    style: Style,
    w: f64,
) -> Assembly<'a> {
    Assembly {
        work,
        chain_to_work: r.chain_to_axis,
        work_to_svg: orient.work_to_svg(w),
        row_angle: orient.angle,
        style,
        w,
        u_turns: r.u_turns,
        quarter_turns: r.quarter_turns,
        cells: r.cells,
    }
}
