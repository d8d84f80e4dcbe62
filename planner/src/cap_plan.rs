//! Planning by caps: along each axis the shape is peeled into caps ([`crate::caps`]), whose
//! order and stacking directions fold in sequence by construction; each decomposition is
//! laid out exactly by the cell router ([`crate::route`]), the tile width is searched so that
//! the chain holds about the asked number of tiles ([`crate::sizing`]), and the cheapest
//! routes are checked by sequential folding and for empty parts like every plan.

use std::sync::Arc;

use rayon::prelude::*;

use crate::caps::{cap_plans, CapPlan};
use crate::cell_plan::{axes, checked_plans, CellFailure, Failed};
use crate::check::CheckMemo;
use crate::empty::{empty_cost, rank_key, MIN_EMPTY_TILES};
use crate::frame::Orientation;
use crate::options::{PlanOptions, DEFAULT_TILES};
use crate::plan::Plan;
use crate::rank::Asked;
use crate::route::{route_sequence, LegMemo, Need, Routed};
use crate::rows::Style;
use crate::shape::Shape;
use crate::sizing::{width_for, Attempt, SizeSearch};
use crate::slabs::slab_plans;

/// Cap decompositions routed per axis (the cheapest).
const DECOMPOSITIONS: usize = 2;
/// Sweep axes routed (the cheapest, see [`cap_axes`]; the decompositions' prices change
/// little with the width, so the width search routes these only).
const AXES_ROUTED: usize = 2;
/// Slab decompositions ([`crate::slabs`]) sized, the cheapest over all axes.
const SLAB_GROUPS: usize = 2;
/// Slab decompositions sized at most: the next cheapest after [`SLAB_GROUPS`], one at a
/// time while every plan found so far leaves a part empty larger than [`MORE_SLABS_EMPTY`].
/// A slab's price is its rows' misfit alone, blind to whether the route can enter it where
/// its rows begin: a gear's cheapest slabs (its left part, and the rest round the hole) are
/// entered halfway up and leave half the gear empty, its fifth (cut across the hole) goes
/// round the hole.
const MORE_SLAB_GROUPS: usize = 6;
/// The share of the asked count (in tile areas) that a part left empty must exceed, in every
/// plan found so far, for more slab decompositions than [`SLAB_GROUPS`] to be sized: a
/// part that large is a whole arm of the shape left out, worth a few more width searches
/// (each about as much work as one of the first); a smaller one is not.
const MORE_SLABS_EMPTY: f64 = 0.05;
/// A slab plan is kept only while at least this share of its tile centres lies inside the
/// shape: a slab's rows may bridge a gap (a key's teeth), and the U-turns of rows across a
/// round slab may fall outside it; issue 26 asks that a plan keep 97% of its tile centres on
/// the drawn area, and a slab plan that does not is not offered against the others. Unless
/// the plan found before the caps (the serpentine, kept or rejected for a part left empty)
/// keeps fewer: then a slab plan that keeps as many is offered too, down to
/// [`LEAST_SLAB_INSIDE`] (a gear's serpentine bridges its hole with 5.6% of its chain
/// outside at 1000 tiles, while every route of its first four slab groups, 91-97% of their
/// centres inside, was dropped, and the groups given up: 349 tile areas left empty).
const MIN_SLAB_INSIDE: f64 = 0.97;
/// The share of its tile centres inside the shape below which no slab plan is kept.
const LEAST_SLAB_INSIDE: f64 = 0.90;
/// Routes kept per decomposition.
const ROUTES_PER_DECOMPOSITION: usize = 2;
/// Size steps of the tile width search.
const SIZE_STEPS: usize = 10;
/// Tiles routed per slab group's width search (the widths it solves times the asked count):
/// a slab group is an alternative to the caps, routed whole at every width it tries (the
/// cell router's fold checks grow with the chain), so its search is bounded by counted
/// work: the full search (16 widths) up to 300 tiles, 4 widths at 1000, 2 at 3000.
const SLAB_SEARCH_TILES: usize = 4800;
/// Widths a slab group's search solves at least.
const SLAB_MIN_WIDTHS: usize = 2;
/// Widths a slab group solves at most when it is searched on past its first width only
/// because it leaves less empty than the plans before it (it would be given up as
/// [`SLAB_HOPELESS_EMPTY`] otherwise): the budget at 1000 tiles ([`SLAB_SEARCH_TILES`]),
/// so that at 100 and 300 tiles such a group does not search all 16 widths (narrowb-at at
/// 100 tiles: 0.42 -> 2.40 s of CPU with them).
const RESCUED_WIDTHS: usize = 4;
/// A slab group whose routes at its first width all collide, or all leave a part empty
/// larger than this share of the asked count (in tile areas), is given up: other phases of
/// its rows do not fill a whole slab its order cannot reach (a U's arm swept from the
/// wrong end leaves a third of the shape empty at every width).
const SLAB_HOPELESS_EMPTY: f64 = 0.1;
/// Slab decompositions sized for an axis that the first [`SLAB_GROUPS`] do not sweep (the
/// cheapest on it, see [`other_axis`]), after all the others, where every plan found leaves
/// a part empty larger than issue 26's bound, and offered only where its plan leaves less
/// empty than every one of them: at most one more width search.
const OTHER_AXIS_GROUPS: usize = 1;
/// The groups of join-priced slab decompositions sized ([`crate::slabs::slab_plans`]).
const JOINED_GROUPS: usize = 2;
/// Factors tried on the tile width when every route at the width the steps settle on
/// collides or leaves a part empty: the joins then fall on the cells at other phases.
const RETRIES: [f64; 6] = [0.995, 1.005, 0.99, 1.01, 0.985, 1.015];

/// The routes at tile width `w` of every axis with its cap decompositions (found at width
/// `w0`), cheapest first, with their axis; with `spread`, routed with more exits per cell
/// ([`route_sequence`]). `memo` keeps the prefix fold checks and the legs found for the next
/// call.
fn routes_at(
    shape: &Shape,
    axes: &[(f64, Vec<CapPlan>, f64)],
    style: Style,
    w: f64,
    memo: (&CheckMemo, &LegMemo),
    spread: bool,
) -> Vec<(f64, Arc<Routed>)> {
    let mut routes: Vec<(f64, Arc<Routed>)> = axes
        .par_iter()
        .flat_map_iter(|(a, plans, w0)| {
            let a = *a;
            let axis_shape = Orientation::along(a).work_shape(shape, w);
            // the decompositions found at width w0, in tile units of this width
            let k = w0 / w;
            let plans = plans.clone().into_iter().map(move |mut p| {
                for c in &mut p.cells {
                    c.rect = kurbo::Rect::new(
                        c.rect.x0 * k,
                        c.rect.y0 * k,
                        c.rect.x1 * k,
                        c.rect.y1 * k,
                    );
                }
                p
            });
            plans
                .into_iter()
                .flat_map(move |p| {
                    // a decomposition grown over lobes ([`crate::lobes`]): its rows are laid
                    // to reach them, its programmes price the lanes no row reaches
                    let style = if p.cells.iter().any(|c| c.spans) {
                        style.with_lanes()
                    } else {
                        style
                    };
                    let cells: Vec<Shape> =
                        p.cells.iter().map(|c| axis_shape.clipped(c.rect)).collect();
                    let seq: Vec<(&Shape, Need, bool)> = cells
                        .iter()
                        .zip(&p.cells)
                        .map(|(s, c)| (s, Some((c.n.vec(), c.either_sign)), c.spans))
                        .collect();
                    route_sequence(&seq, style, memo, spread)
                        .into_iter()
                        .take(ROUTES_PER_DECOMPOSITION)
                        .filter_map(|r| r.to_routed(style))
                        .map(|r| (a, Arc::new(r)))
                        .collect::<Vec<_>>()
                })
                .collect::<Vec<_>>()
        })
        .collect();
    routes.sort_by(|x, y| x.1.cost.total_cmp(&y.1.cost));
    routes
}

/// The cap decompositions of every sweep axis of `shape` at tile width `w` (the cheapest
/// [`DECOMPOSITIONS`] of each), axes with a decomposition only, cheapest first: `(axis,
/// decompositions, w)`. Computed once per turn style: the top level asks whether the shape
/// splits into cells at all, and [`plan_by_caps`] routes the cheapest [`AXES_ROUTED`].
pub(crate) fn cap_axes(shape: &Shape, style: Style, w: f64) -> Vec<(f64, Vec<CapPlan>, f64)> {
    let mut priced: Vec<(f64, f64, Vec<CapPlan>)> = axes(shape)
        .par_iter()
        .map(|&a| {
            let axis_shape = Orientation::along(a).work_shape(shape, w);
            let mut plans: Vec<CapPlan> = cap_plans(&axis_shape, style.pitch)
                .into_iter()
                .take(DECOMPOSITIONS)
                .collect();
            // and slabs, each swept along its own length (not necessarily caps: the
            // route's fold check decides), in both orders along the axis
            plans.extend(slab_plans(&axis_shape, style));
            // axes rank by their caps (the slabs are sized on their own)
            let cost = plans
                .iter()
                .filter(|p| !p.slabs)
                .map(|p| p.cost)
                .fold(f64::INFINITY, f64::min);
            (cost, a, plans)
        })
        .collect();
    priced.sort_by(|x, y| x.0.total_cmp(&y.0));
    priced
        .into_iter()
        .filter(|p| !p.2.is_empty())
        .map(|p| (p.1, p.2, w))
        .collect()
}

/// The tile width a turn style's cap search starts from: the asked width, or the width at
/// which the asked count of tiles fills the shape.
pub(crate) fn start_width(shape: &Shape, opts: &PlanOptions, style: Style) -> f64 {
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    opts.tile_size
        .unwrap_or_else(|| width_for(shape.area(), target, style.pitch))
}

/// Plans `shape` by caps with one turn style (see the module documentation), or says why
/// no route was found, with the best route rejected for an empty part. `all_axes` is
/// [`cap_axes`] at [`start_width`]; `known_empty` is the least part left empty (tile areas)
/// by the plans found before (one serpentine, kept or rejected; 0 when one fills the shape),
/// which decides whether more slab decompositions are sized ([`MORE_SLABS_EMPTY`]), and
/// `known_inside` the share of that plan's tile centres inside the shape (1 without one),
/// which the slab plans are held to ([`MIN_SLAB_INSIDE`]).
pub(crate) fn plan_by_caps(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    name: &str,
    all_axes: &[(f64, Vec<CapPlan>, f64)],
    (known_empty, known_inside): (f64, f64),
) -> Result<Plan, CellFailure> {
    let min_inside = MIN_SLAB_INSIDE.min(known_inside.max(LEAST_SLAB_INSIDE));
    let (groups, slots) = group_slots(all_axes);
    let Slots {
        first_slab,
        joined_at,
        other_at,
        grown_at,
        pieces_at,
    } = slots;
    let mut made: Vec<(f64, Vec<CapPlan>, f64)>;
    let asked = Asked::new(opts, shape.area(), opts.tiles.unwrap_or(DEFAULT_TILES));
    let mut failed = Failed::new(asked);
    let mut best: Option<Plan> = None;
    let large = MORE_SLABS_EMPTY * opts.tiles.unwrap_or(DEFAULT_TILES) as f64;
    for (i, axes) in groups.iter().enumerate() {
        let least = || {
            best.iter()
                .map(|b| b.metrics.largest_empty_tiles)
                .chain(failed.rejected.iter().map(|r| r.1.empty.tiles))
                .fold(known_empty, f64::min)
        };
        let extra = |j: usize| {
            joined_at.contains(&j) || other_at == Some(j) || grown_at == Some(j) || j == pieces_at
        };
        let axes = if i == pieces_at {
            if least() <= large {
                continue;
            }
            made = crate::pieces::piece_group(shape, all_axes, style).unwrap_or_default();
            &made
        } else {
            axes
        };
        if axes.is_empty() {
            continue;
        }
        if extra(i) {
            // sized where every plan so far leaves a part empty (issue 26's measure)
            if least() <= MIN_EMPTY_TILES {
                continue;
            }
        } else if i >= first_slab + SLAB_GROUPS + (0..i).filter(|&j| extra(j)).count()
            && least() <= large
        {
            // (least() only falls: the later slab groups are passed over too)
            continue;
        }
        let slabs = axes
            .iter()
            .any(|(_, plans, _)| plans.iter().any(|q| q.slabs));
        let mut here = Failed::new(asked);
        let before = least();
        // its routes rejected for an empty part rank by how far they fall short of the
        // asked chain, the count's miss and the part left empty in one price ([`Asked`]);
        // a slab group is given up at its first width only if it leaves more empty than
        // every plan so far too, and its plans under the inside bar are weighed against
        // that least part ([`SlabBar`])
        let bar = SlabBar {
            slabs,
            joined: joined_at.contains(&i),
            before,
            min_inside,
            budgeted: slabs || grown_at == Some(i),
            pieces: i == pieces_at,
        };
        let found = size_group(shape, opts, style, name, axes, bar, &mut here);
        let found = offered(shape, opts, found, &mut here, (extra(i), slabs, before));
        failed.merge(here);
        if let Some(p) = found {
            if best.as_ref().is_none_or(|b| rank(opts, &p, b).is_lt()) {
                best = Some(p);
            }
        }
    }
    // a plan off the count yields to a rejected one nearer it that falls less short of
    // the asked chain ([`Asked::prefers_rejected`])
    let best = best.filter(|b| {
        !failed
            .rejected
            .as_ref()
            .is_some_and(|(_, r)| asked.prefers_rejected(r, b))
    });
    match best {
        Some(p) => Ok(p),
        None => match failed.rejected {
            Some((text, r)) => Err((text, Some(r))),
            None if !failed.collide.is_empty() => Err((
                format!(
                    "every cap route collides when folded (first: {})",
                    failed.collide
                ),
                None,
            )),
            None => Err(("no cap decomposition".into(), None)),
        },
    }
}

/// A group of decompositions sized together: `(axis, decompositions, width)` per axis.
type Group = Vec<(f64, Vec<CapPlan>, f64)>;

/// Where [`plan_by_caps`]'s groups of decompositions added for the part left empty sit.
struct Slots {
    /// The first slab group's index (after the caps' group, if any).
    first_slab: usize,
    /// The join-priced slab groups.
    joined_at: std::ops::Range<usize>,
    /// The other axis' group.
    other_at: Option<usize>,
    /// The caps grown over their lobes.
    grown_at: Option<usize>,
    /// The slabs cut into their pieces ([`crate::pieces`]): an empty slot, filled when
    /// it is reached and sized.
    pieces_at: usize,
}

/// The groups [`plan_by_caps`] sizes in turn, from `all_axes`, and where the added ones sit.
fn group_slots(all_axes: &[(f64, Vec<CapPlan>, f64)]) -> (Vec<Group>, Slots) {
    let (caps, slabs) = caps_and_slabs(all_axes);
    // the caps with a row cell grown over the lobes beside it ([`crate::lobes`]), sized
    // last like the other added groups
    let grown = crate::lobes::grown_group(&caps);
    // the decompositions chosen with their joins priced: the cheapest of them (over the
    // axes) sized in a slot of its own, after the first slab groups
    let (mut joined, mut slabs): (Vec<_>, Vec<_>) = slabs.into_iter().partition(|g| g.1[0].joined);
    joined.sort_by(|x, y| x.1[0].cost.total_cmp(&y.1[0].cost));
    slabs.sort_by(|x, y| x.1[0].cost.total_cmp(&y.1[0].cost));
    // the cheapest decomposition of an axis that none of the first groups sweeps, taken
    // out to be sized in a slot of its own after all the others ([`OTHER_AXIS_GROUPS`]);
    // the others truncated as without it
    let other = other_axis(&mut slabs);
    let mut groups: Vec<Vec<(f64, Vec<CapPlan>, f64)>> = Vec::new();
    let first_slab = usize::from(!caps.is_empty());
    if !caps.is_empty() {
        groups.push(caps);
    }
    let first = slabs.len().min(SLAB_GROUPS);
    let rest = slabs.split_off(first);
    groups.extend(slabs.into_iter().map(|g| vec![g]));
    // the cheapest and the next (the cheapest's laid in the order their joins were priced
    // for, sized only where they leave less empty, see [`crate::slabs`])
    // and the cheapest on an axis neither of those sweeps, sized after them like them
    let taken = JOINED_GROUPS + usize::from(other_joined(&mut joined));
    let joined_at = groups.len()..groups.len() + joined.len().min(taken);
    groups.extend(joined.into_iter().take(taken).map(|g| vec![g]));
    groups.extend(rest.into_iter().map(|g| vec![g]));
    // the other axis' last: offered only where it leaves less empty than every plan found
    let other_at = other.map(|g| {
        groups.push(vec![g]);
        groups.len() - 1
    });
    let grown_at = grown.map(|g| {
        groups.push(g);
        groups.len() - 1
    });
    // the slabs cut into their pieces ([`crate::pieces`]), made and sized last, only where
    // every plan so far leaves a large part empty
    groups.push(Vec::new());
    let pieces_at = groups.len() - 1;
    (
        groups,
        Slots {
            first_slab,
            joined_at,
            other_at,
            grown_at,
            pieces_at,
        },
    )
}

/// What a group's width search `found` is offered as, after the rules of
/// [`plan_by_caps`]: for a group sized for the part left empty (`extra`), only a plan that
/// leaves less than `before` (the least so far) with a count within the tolerance, and its
/// rejected route (in `here`) only with such a count; for a slab group, a plan under
/// [`MIN_SLAB_INSIDE`] only where it leaves less than `before`.
fn offered(
    shape: &Shape,
    opts: &PlanOptions,
    mut found: Option<Plan>,
    here: &mut Failed,
    (extra, slabs, before): (bool, bool, f64),
) -> Option<Plan> {
    if extra {
        // sized for the part left empty: its plan is offered only where it leaves less
        // and with a count within the tolerance, as its rejected routes below: one off
        // the count would stop the later slab groups being sized (fa-gear at 1000 tiles:
        // 1043 tiles leaving 7.7 tile areas empty in place of 971 leaving 8.4)
        found = found.filter(|p| p.metrics.largest_empty_tiles < before && miss(opts, p) == 0);
        // the added decomposition's route rejected for an empty part is kept only with
        // a count within the tolerance: rejected routes rank by their empty part alone,
        // and one that leaves less empty with a quarter of the chain missing is no
        // better plan
        here.rejected = here
            .rejected
            .take()
            .filter(|(_, r)| miss(opts, &r.plan) == 0);
    }
    // a slab plan let in under the 97% bar ([`MIN_SLAB_INSIDE`]) is offered only where
    // it leaves less empty than every plan so far, which is what it is let in for
    if slabs {
        found = found.filter(|p| {
            p.metrics.largest_empty_tiles < before || centres_inside(shape, p) >= MIN_SLAB_INSIDE
        });
    }
    found
}

/// The cap decompositions of the cheapest [`AXES_ROUTED`] axes that have any, and every slab
/// decomposition (both its orders) of every axis, as [`plan_by_caps`] sizes them.
#[allow(clippy::type_complexity)]
fn caps_and_slabs(
    all_axes: &[(f64, Vec<CapPlan>, f64)],
) -> (Vec<(f64, Vec<CapPlan>, f64)>, Vec<(f64, Vec<CapPlan>, f64)>) {
    // the caps of the cheapest axes, sized together as before; then every one of the
    // cheapest slab decompositions (both its orders) sized on its own, so that one that
    // holds the asked count at another width than the caps is not passed over
    let caps: Vec<(f64, Vec<CapPlan>, f64)> = all_axes
        .iter()
        .filter(|(_, plans, _)| plans.iter().any(|p| !p.slabs))
        .take(AXES_ROUTED)
        .map(|(a, plans, w)| (*a, plans.iter().filter(|p| !p.slabs).cloned().collect(), *w))
        .collect();
    let slabs: Vec<(f64, Vec<CapPlan>, f64)> = all_axes
        .iter()
        .flat_map(|(a, plans, w)| {
            let slab: Vec<&CapPlan> = plans.iter().filter(|p| p.slabs).collect();
            // slab_plans returns each decomposition in both orders, one after the other
            slab.chunks(2)
                .map(|pair| (*a, pair.iter().map(|&p| p.clone()).collect(), *w))
                .collect::<Vec<_>>()
        })
        .collect();
    (caps, slabs)
}

/// Takes out of `slabs` (cheapest first) the cheapest decomposition swept along an axis
/// that none of the first [`SLAB_GROUPS`] is swept along, when it is not among them, and
/// keeps of the rest those of the first [`MORE_SLAB_GROUPS`] (one fewer when it was among
/// them: the later groups stay those sized without it, so taking it out lets in no group
/// that was not sized before, a cat's eighth at 100 tiles leaving 12.6 tile areas empty
/// where a serpentine leaves 10.5). The decompositions' prices are their rows' misfit,
/// blind to the empty parts, and a shape whose best plan is on the axis second by that
/// price would never be planned that way (a key: its head in columns and its shaft and
/// teeth in rows comes third, after two on the other axis). One group more at most
/// ([`OTHER_AXIS_GROUPS`]).
fn other_axis(slabs: &mut Vec<(f64, Vec<CapPlan>, f64)>) -> Option<(f64, Vec<CapPlan>, f64)> {
    let first = slabs.len().min(SLAB_GROUPS);
    let at = (first..slabs.len())
        .find(|&j| !slabs[..first].iter().any(|g| same_axis(g.0, slabs[j].0)))
        .filter(|_| OTHER_AXIS_GROUPS > 0);
    let other = at.map(|j| slabs.remove(j));
    slabs.truncate(MORE_SLAB_GROUPS - usize::from(at.is_some_and(|j| j < MORE_SLAB_GROUPS)));
    other
}

/// Moves to just after the first [`JOINED_GROUPS`] of `joined` (cheapest first) the first
/// of the others swept along an axis none of them is swept along, and says whether there
/// is one: the join-priced decompositions of an axis with no decomposition priced alone
/// rank last whatever they cost ([`crate::slabs`]), and a key's (its shaft and both teeth
/// in rows, then its head in columns, one quarter turn) came after two on the other axis.
/// At most [`OTHER_AXIS_GROUPS`].
fn other_joined(joined: &mut Vec<(f64, Vec<CapPlan>, f64)>) -> bool {
    let first = joined.len().min(JOINED_GROUPS);
    let at = (first..joined.len())
        .find(|&j| !joined[..first].iter().any(|g| same_axis(g.0, joined[j].0)))
        .filter(|_| OTHER_AXIS_GROUPS > 0);
    if let Some(j) = at {
        let g = joined.remove(j);
        joined.insert(first, g);
    }
    at.is_some()
}

/// True when the sweep axes `a` and `b` (radians) are the same line.
fn same_axis(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(std::f64::consts::PI);
    d.min(std::f64::consts::PI - d) < 1e-6
}

/// The share of the plan's tile centres that lie inside the shape.
pub(crate) fn centres_inside(shape: &Shape, p: &Plan) -> f64 {
    let inside = p
        .poses
        .iter()
        .filter(|q| shape.contains(kurbo::Point::new(q.x, -q.y)))
        .count();
    inside as f64 / p.poses.len().max(1) as f64
}

/// Plans ranked: a count within the tolerance first, then the outside tier and the cost of
/// fit, turns and part left empty ([`rank_key`]).
fn rank(opts: &PlanOptions, x: &Plan, y: &Plan) -> std::cmp::Ordering {
    miss(opts, x)
        .cmp(&miss(opts, y))
        .then(rank_key(x, opts.turn_cost).cmp(&rank_key(y, opts.turn_cost)))
}

/// The tiles by which a plan's count misses the asked count beyond the tolerance (0 when a
/// tile width was asked).
fn miss(opts: &PlanOptions, p: &Plan) -> usize {
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let tol = (opts.tiles_tolerance * target as f64) as usize;
    match opts.tile_size {
        Some(_) => 0,
        None => p.tiles.abs_diff(target).saturating_sub(tol),
    }
}

/// What a group's width search holds its slab plans to ([`size_group`]).
#[derive(Clone, Copy)]
struct SlabBar {
    /// The group is of slab decompositions (a group of caps is held to nothing here).
    slabs: bool,
    /// The group is a join-priced decomposition sized for the part left empty.
    joined: bool,
    /// The least part left empty (tile areas) by the plans found before the group.
    before: f64,
    /// The share of tile centres inside the shape a slab plan keeps without more ado
    /// ([`MIN_SLAB_INSIDE`]).
    min_inside: f64,
    /// The group's width search is held to the slab groups' budget
    /// ([`SLAB_SEARCH_TILES`]): a group of slabs, or of caps grown over their lobes.
    budgeted: bool,
    /// The group is of slabs cut into their pieces ([`crate::pieces`]): given up at its
    /// first width like a grown group ([`SlabBar::grown_hopeless`]), and its cells routed
    /// once (not again with more exits per cell: its decompositions are many, up to 24,
    /// of up to 16 cells; routed again too, the gear at 3000 tiles leaves 435 tile areas
    /// empty where it leaves 510, at twice the group's CPU).
    pieces: bool,
}

impl SlabBar {
    /// The widths the group's search may solve: [`SLAB_SEARCH_TILES`] over the asked count
    /// `target` (at least [`SLAB_MIN_WIDTHS`]) for a budgeted group, else no bound.
    fn budget(&self, target: usize) -> usize {
        if self.slabs || self.budgeted {
            (SLAB_SEARCH_TILES / target.max(1)).max(SLAB_MIN_WIDTHS)
        } else {
            usize::MAX
        }
    }

    /// True if a group of caps grown over their lobes ([`crate::lobes`]) is given up at its
    /// first width: none of its `plans` there, nor its route rejected for leaving
    /// `least_empty`, leaves less empty than the plans before it (it is offered only where
    /// it does, see [`offered`]).
    fn grown_hopeless(&self, plans: &[Plan], least_empty: Option<f64>) -> bool {
        let least = plans
            .iter()
            .map(|p| p.metrics.largest_empty_tiles)
            .chain(least_empty)
            .fold(f64::INFINITY, f64::min);
        self.budgeted && (!self.slabs || self.pieces) && least >= self.before
    }

    /// Whether a plan of the group whose largest part left empty is `empty` (its own tile
    /// areas) is kept. A slab plan with fewer than `min_inside` of its tile centres inside
    /// the shape (at least [`LEAST_SLAB_INSIDE`]) is kept where the plans before leave a
    /// whole stroke empty (a part over [`SLAB_HOPELESS_EMPTY`] of the asked count `target`)
    /// and it leaves far less: its part left empty and the tiles it lays outside beyond
    /// the bar, both at the asked count, are less than the least part left before. The
    /// bar is the serpentine's share (97% at most), and a slab plan that keeps fewer
    /// centres inside was dropped unmeasured: narrowb-at's slabs at 1000 tiles (89-94%
    /// inside where its serpentine keeps 94.9%), the gear's at 3000 (92-96% against
    /// 96.6%), where the serpentines leave 370 and 1352 tile areas empty. A clipped
    /// logo's plans, which leave less than a tenth of the count, stay at 97% (issue 26's
    /// bar for it; at 100 tiles a two-slab plan with 93 of 98 centres inside fills it,
    /// where the plan kept leaves 9.7 tile areas).
    fn keeps(&self, shape: &Shape, p: &Plan, empty: f64, target: usize) -> bool {
        // a grown group's rows bridge the gaps between its lobes as slabs' rows do (the
        // clipped logo at 100 tiles: 83 of 103 tile centres inside): held to the same bar
        if !self.budgeted {
            return true;
        }
        let inside = centres_inside(shape, p);
        if inside >= self.min_inside {
            return true;
        }
        // tile areas scale with the count: those of this plan's width at the asked count
        let at_count = target as f64 / p.tiles.max(1) as f64;
        let outside = (self.min_inside - inside) * target as f64;
        inside >= LEAST_SLAB_INSIDE
            && self.before.is_finite()
            && self.before > SLAB_HOPELESS_EMPTY * target as f64
            && empty * at_count + outside < self.before
    }
}

/// [`size_group`]'s width search: secant steps from the first width and the retries, unless
/// the tile width is given; `tol` tiles off the count are within it.
fn group_search(opts: &PlanOptions, tol: usize) -> SizeSearch {
    SizeSearch {
        secant_steps: if opts.tile_size.is_some() {
            1
        } else {
            SIZE_STEPS
        },
        nudges: &[],
        tolerance: tol,
        explore: false,
        shrink_when_empty: None,
        retries: if opts.tile_size.is_none() {
            &RETRIES
        } else {
            &[]
        },
        // a plan that leaves a part empty (its cost: the tile areas) keeps the retries going
        settle_cost: 0.0,
    }
}

/// The tile width search over the decompositions `axes` (see [`plan_by_caps`]): the best plan
/// found, what the others said in `failed`. A group of slabs (`bar`) searches within a
/// budget of [`SLAB_SEARCH_TILES`] and is given up at its first width if hopeless (see
/// [`SLAB_HOPELESS_EMPTY`]; not while it leaves less empty than the plans before it), and
/// keeps only slab plans that [`SlabBar::keeps`].
fn size_group(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    name: &str,
    axes: &[(f64, Vec<CapPlan>, f64)],
    bar: SlabBar,
    failed: &mut Failed,
) -> Option<Plan> {
    let slabs = bar.slabs;
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let w0 = start_width(shape, opts, style);
    let tol = (opts.tiles_tolerance * target as f64) as usize;
    let search = group_search(opts, tol);
    let by_rank = |x: &Plan, y: &Plan| rank(opts, x, y);
    let budget = bar.budget(target);
    let mut at_start = true;
    let miss = |n: usize| match opts.tile_size {
        Some(_) => 0,
        None => n.abs_diff(target).saturating_sub(tol),
    };
    // widths solved, and whether the group is searched on only because it leaves less
    // empty than the plans before (then at most [`RESCUED_WIDTHS`] widths)
    let (mut solved, mut rescued) = (0, false);
    let found = search.run_budgeted(target, w0, budget, |w| {
        if rescued && solved >= RESCUED_WIDTHS {
            return Attempt::Nothing;
        }
        solved += 1;
        let (memo, legs) = (CheckMemo::default(), LegMemo::default());
        let routed = |spread: bool| {
            let mut routes = routes_at(shape, axes, style, w, (&memo, &legs), spread);
            if opts.tile_size.is_none() {
                routes.sort_by_key(|(_, r)| miss(r.word.tiles()));
            }
            routes
        };
        let routes = routed(false);
        let Some(first) = routes.first() else {
            return Attempt::Nothing;
        };
        let n = first.1.word.tiles();
        let mut here = Failed::new(failed.asked);
        let check = |routes: &[(f64, Arc<Routed>)], here: &mut Failed| {
            checked_plans(
                shape,
                style,
                w,
                name,
                routes,
                crate::empty::near(opts.turns),
                &miss,
                // a slab plan with much of its chain outside the shape is not kept: passed
                // over where the routes are ranked, so that the width search ranks only
                // plans it keeps
                &|p, empty| bar.keeps(shape, p, empty, target),
                here,
            )
        };
        let mut plans = check(&routes, &mut here);
        // where no plan fills the shape, the routes with more exits per cell (each cell's
        // last row left beside the next cell, at the phase that may fill it) are checked
        // too: added to the cheapest routes, never in their place, and routed only where
        // those leave a part empty (the work doubles there at most)
        let fills = |p: &Plan| miss(p.tiles) == 0 && p.metrics.largest_empty_tiles == 0.0;
        if !bar.pieces && !plans.iter().any(fills) {
            let mut more = routed(true);
            more.retain(|(a, r)| !routes.iter().any(|(b, q)| a == b && q.word == r.word));
            plans.extend(check(&more, &mut here));
        }
        let least_empty = here.rejected.as_ref().map(|r| r.1.empty.tiles);
        // hopeless: leaves more than a tenth of the count empty, and more than the plans
        // before (a joined group's, or any group's where a plan was found before)
        let hopeless_above = |above: f64| {
            least_empty.is_none_or(|e| e > (SLAB_HOPELESS_EMPTY * target as f64).max(above))
        };
        let first_width = std::mem::take(&mut at_start);
        if slabs && first_width && plans.is_empty() {
            let before = if bar.joined || bar.before.is_finite() {
                bar.before
            } else {
                0.0
            };
            if hopeless_above(before) {
                failed.merge(here);
                return Attempt::Nothing;
            }
            // searched on for that alone: a few widths more ([`RESCUED_WIDTHS`])
            rescued = hopeless_above(if bar.joined { bar.before } else { 0.0 });
        }
        if (!slabs || bar.pieces) && first_width && bar.grown_hopeless(&plans, least_empty) {
            failed.merge(here);
            return Attempt::Nothing;
        }
        // what a group searched on for the part left empty finds, and a plan kept under
        // the inside bar, leave the group only with a count within the tolerance (as an
        // added group's, see [`offered`]): gear and narrowb-at at 100 tiles came back with
        // 95 and 94 tiles
        let within = |p: &Plan| {
            miss(p.tiles) == 0
                || (!rescued && (!slabs || centres_inside(shape, p) >= bar.min_inside))
        };
        here.rejected = here.rejected.take().filter(|(_, r)| within(&r.plan));
        plans.retain(within);
        failed.merge(here);
        // a count within the tolerance first, then fit, turns and part left empty priced
        // together; the search's cost is the part left empty ([`empty_cost`]), so that among
        // widths whose plans all leave one, the least empty wins, and the retries go on
        // while the best leaves one
        match plans.into_iter().min_by(by_rank) {
            Some(p) => {
                let empty = empty_cost(&p);
                Attempt::Plan(p.tiles, empty, p)
            }
            None => Attempt::Rejected(n),
        }
    });
    found.map(|f| f.plans)
}
