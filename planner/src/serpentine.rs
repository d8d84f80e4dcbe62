//! One serpentine over the whole shape (thesis section 5.5): rows of straight tiles
//! orthogonal to a direction in which the shape is monotone, joined by U-turns that
//! alternate in direction.
//!
//! For every row direction, start corner (an [`Orientation`]) and lattice phase, the row
//! programme of [`crate::rows`] finds the best row ends in the work frame; the candidates are
//! ranked by cost, the tile width is searched so that the best one holds about the asked
//! number of tiles ([`crate::sizing`]), and the best few are checked by sequential folding.

use std::f64::consts::PI;
use std::sync::{Arc, Mutex};

use foldchain::FoldWord;
use kurbo::Affine;
use rayon::prelude::*;

use crate::assembly::Assembly;
use crate::check::check_folds;
use crate::fit::estimate;
use crate::frame::Orientation;
use crate::options::{PlanOptions, DEFAULT_TILES};
use crate::plan::Plan;
use crate::rows::{Phased, Serpentine, Style};
use crate::shape::Shape;
use crate::sizing::{tiles_for, width_for, SizeSearch};
use crate::Progress;

/// At most this many row directions are compared by full planning.
const MAX_DIRECTIONS: usize = 16;
/// Above this many tiles the direction is chosen on a coarser plan of this many tiles.
const COARSE_TILES: usize = 3000;
/// Plans tried (best first) until one passes the collision check.
const MAX_CHECKED: usize = 8;
/// The size search stops once the tile count is within this share of the target (0.1%:
/// 100 tiles in 100,000; below 1,000 tiles it must be met exactly, or as near as the steps
/// reach).
const COUNT_TOLERANCE: f64 = 1e-3;
/// Secant steps of the size search, then these nudges around the best width: the count
/// jumps by whole rows, so the nearest count may lie between two steps.
const SECANT_STEPS: usize = 12;
/// Up to this many tiles, every nudge is tried even once the count is within the
/// tolerance, for a better fit (a programme at this size takes milliseconds).
const EXPLORE_TILES: usize = 20_000;
/// Orientations (direction and start corner) solved at every width after the first: the
/// best at the first width (the search then moves the width by a few percent; keeping six
/// changed the dog's plan at 150 tiles to one with 8.4% of the chain outside, sixteen keep
/// it at 7.4%).
const KEPT_ORIENTATIONS: usize = 16;
const NUDGES: [f64; 8] = [0.98, 1.02, 0.96, 1.04, 0.99, 1.01, 0.97, 1.03];

/// A solved serpentine over the whole shape, in the work frame of its orientation.
#[derive(Clone, Debug)]
pub(crate) struct Candidate {
    orient: Orientation,
    /// The rank of the candidate (lower is better): its estimated fit error plus the price
    /// of its turns ([`crate::fit::estimate`]).
    cost: f64,
    serp: Serpentine,
}

impl Candidate {
    /// The number of tiles of its chain.
    fn tiles(&self, style: Style) -> usize {
        self.serp.tiles(style)
    }

    /// The fold word: rows of straight joints, U-turns between them.
    pub(crate) fn word(&self, style: Style) -> FoldWord {
        let mut folds = Vec::new();
        // turning from +x towards +y is counter-clockwise in the work frame: an L fold when
        // the work frame keeps the physical handedness
        self.serp
            .folds(style, self.orient.keeps_handedness(), &mut folds);
        FoldWord::from_folds(folds)
    }

    /// The map from the chain frame (w = 1) to the work frame: tile 0 on the first row's
    /// start, heading along that row.
    fn chain_to_work(&self) -> Affine {
        let (k, s) = self.serp.first();
        let d0 = Serpentine::runs(k);
        let sigma = self.orient.sx * self.orient.sy;
        let start = self.serp.centre(k, s);
        Affine::new([d0, 0.0, 0.0, d0 * sigma, start.x, start.y])
    }
}

/// The serpentines of one turn style at the tile width the size search settled on.
pub(crate) struct Sized {
    pub style: Style,
    pub w: f64,
    /// Every serpentine at that width, lowest cost first.
    pub all: Vec<Candidate>,
}

impl Sized {
    /// The best serpentine as a plan, unchecked (for ranking the turn styles).
    pub(crate) fn best_unchecked(&self, shape: &Shape, name: &str) -> Option<Plan> {
        let first = self.all.first()?;
        Some(to_plan(
            shape,
            first,
            self.style,
            self.w,
            &first.word(self.style),
            name,
        ))
    }

    /// The best serpentine that folds without collision, as a plan; `ranked` is
    /// [`Sized::best_unchecked`]'s answer, reused when the best one passes.
    pub(crate) fn best_checked(
        &self,
        shape: &Shape,
        ranked: Plan,
        name: &str,
    ) -> Result<Plan, String> {
        let mut why = String::from("no serpentine found");
        for (i, c) in self.all.iter().enumerate().take(MAX_CHECKED) {
            let word = c.word(self.style);
            match check_folds(&word) {
                Ok(()) if i == 0 => return Ok(ranked),
                Ok(()) => return Ok(to_plan(shape, c, self.style, self.w, &word, name)),
                Err(e) => why = format!("every candidate chain collides when folded (first: {e})"),
            }
        }
        Err(why)
    }
}

/// Row directions to compare: the long-edge directions and the SVG axes where the shape is
/// monotone for them, then an even spread over the monotone directions; every direction
/// (a 15 degree spread) when there is none.
pub(crate) fn pick_directions(shape: &Shape, monotone: &[f64]) -> Vec<f64> {
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
pub(crate) fn size_style(
    shape: &Shape,
    opts: &PlanOptions,
    style: Style,
    directions: &[f64],
    progress: Progress<'_>,
) -> Result<Sized, String> {
    let area = shape.area();
    let coarse_over = |tiles: usize| {
        if tiles > COARSE_TILES {
            let w = width_for(area, COARSE_TILES, style.pitch);
            coarse_orientation(shape, style, directions, w)
        } else {
            directions
                .iter()
                .flat_map(|&angle| Orientation::corners(angle))
                .collect()
        }
    };
    if let Some(w) = opts.tile_size {
        let dirs = coarse_over(tiles_for(area, w, style.pitch));
        let all = solve_all(shape, style, &dirs, w);
        return Ok(Sized { style, w, all });
    }
    let target = opts.tiles.unwrap_or(DEFAULT_TILES);
    let mut dirs = coarse_over(target);
    // small plans may float within the asked tolerance for fit; large ones gain nothing
    // measurable by it and aim at the count
    let explore = target <= EXPLORE_TILES;
    let share = if explore {
        opts.tiles_tolerance.max(COUNT_TOLERANCE)
    } else {
        COUNT_TOLERANCE.min(opts.tiles_tolerance.max(COUNT_TOLERANCE))
    };
    let search = SizeSearch {
        secant_steps: SECANT_STEPS,
        nudges: &NUDGES,
        tolerance: (share * target as f64) as usize,
        explore,
        shrink_when_empty: Some(0.97),
        retries: &[],
        settle_cost: f64::INFINITY,
    };
    let stage = format!("sizing the {} serpentine", style.turns);
    let total = (SECANT_STEPS + NUDGES.len()) as u64;
    let mut step = 0u64;
    // the size is settled on unchecked plans (the check is the costly part on long chains);
    // the caller checks the plans at that size, best first
    let found = search.run(target, width_for(area, target, style.pitch), |w| {
        progress(&stage, step, total);
        step += 1;
        let mut all = solve_all(shape, style, &dirs, w);
        // the orientations rank alike at nearby widths: after the first width, only the
        // best few are solved again
        if dirs.len() > KEPT_ORIENTATIONS {
            let mut kept: Vec<Orientation> = Vec::new();
            for c in &all {
                if kept.len() < KEPT_ORIENTATIONS && !kept.contains(&c.orient) {
                    kept.push(c.orient);
                }
            }
            // in their first order, so that orientations of equal cost rank as before
            dirs.retain(|o| kept.contains(o));
        }
        // candidates whose count is within the tolerance come first, each group best first
        let tol = search.tolerance;
        all.sort_by_key(|c| c.tiles(style).abs_diff(target).saturating_sub(tol));
        let first = all.first()?;
        Some((first.tiles(style), first.cost, all))
    });
    match found {
        Some(f) => Ok(Sized {
            style,
            w: f.w,
            all: f.plans,
        }),
        None => Err(String::from("no serpentine found")),
    }
}

/// The best direction and start corner on a coarse plan, for large plans (the lattice
/// phases are still compared at full size).
fn coarse_orientation(shape: &Shape, style: Style, directions: &[f64], w: f64) -> Vec<Orientation> {
    let all: Vec<Orientation> = directions
        .iter()
        .flat_map(|&angle| Orientation::corners(angle))
        .collect();
    match solve_all(shape, style, &all, w).first() {
        Some(c) => vec![c.orient],
        None => all,
    }
}

/// Solves over more orientations than this are remembered ([`LargeSolve`]).
const REMEMBERED_ORIENTATIONS: usize = KEPT_ORIENTATIONS;
/// Large solves remembered at most (the latest).
const REMEMBERED_SOLVES: usize = 4;

/// A solve over many orientations ([`solve_all`]) with its inputs: the first width of a
/// size search over every orientation and the coarse choice of orientation
/// ([`coarse_orientation`]) solve the same programmes, and the serpentine retried at other
/// widths chooses its orientation on the same coarse plan at every width it tries
/// (libsi-A at 3000 tiles solved 64 orientations at the same width four times). A
/// remembered solve is returned only for equal inputs, so it is what solving again gives.
struct LargeSolve {
    shape: Shape,
    style: Style,
    tasks: Vec<Orientation>,
    w: u64,
    all: Vec<Candidate>,
}

impl LargeSolve {
    /// True if the solve had these inputs.
    fn is(&self, shape: &Shape, style: Style, tasks: &[Orientation], w: f64) -> bool {
        self.w == w.to_bits() && self.style == style && self.tasks == tasks && self.shape == *shape
    }
}

/// The latest large solves, newest last.
static LARGE_SOLVES: Mutex<Vec<Arc<LargeSolve>>> = Mutex::new(Vec::new());

/// Every serpentine over the orientations (directions and corners) and phases at tile
/// width `w`, lowest cost first (solved in parallel; the order is deterministic); a solve
/// over more than [`REMEMBERED_ORIENTATIONS`] is remembered ([`LargeSolve`]).
fn solve_all(shape: &Shape, style: Style, tasks: &[Orientation], w: f64) -> Vec<Candidate> {
    if tasks.len() <= REMEMBERED_ORIENTATIONS {
        return solve_fresh(shape, style, tasks, w);
    }
    let known = LARGE_SOLVES.lock().ok().and_then(|l| {
        l.iter()
            .find(|s| s.is(shape, style, tasks, w))
            .map(Arc::clone)
    });
    if let Some(s) = known {
        return s.all.clone();
    }
    let all = solve_fresh(shape, style, tasks, w);
    if let Ok(mut l) = LARGE_SOLVES.lock() {
        if l.len() >= REMEMBERED_SOLVES {
            l.remove(0);
        }
        l.push(Arc::new(LargeSolve {
            shape: shape.clone(),
            style,
            tasks: tasks.to_vec(),
            w: w.to_bits(),
            all: all.clone(),
        }));
    }
    all
}

/// [`solve_all`] without the memory of large solves.
fn solve_fresh(shape: &Shape, style: Style, tasks: &[Orientation], w: f64) -> Vec<Candidate> {
    let area = shape.area() / (w * w);
    let mut out: Vec<Candidate> = tasks
        .par_iter()
        .flat_map_iter(|&orient| {
            let work = orient.work_shape(shape, w);
            Phased::new(&work, style)
                .solve(style)
                .filter_map(|(lat, sol)| {
                    let (cost, k, e) = sol.best_end(|_| true)?;
                    let serp = sol.serpentine(lat, style.pitch, k, e);
                    let rank = estimate(area, serp.tiles(style), serp.u_turns(), cost, style);
                    Some(Candidate {
                        orient,
                        cost: rank,
                        serp,
                    })
                })
                .collect::<Vec<_>>()
        })
        .collect();
    out.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    out
}

/// Turns a checked serpentine into the plan.
fn to_plan(
    shape: &Shape,
    c: &Candidate,
    style: Style,
    w: f64,
    word: &FoldWord,
    name: &str,
) -> Plan {
    let work = c.orient.work_shape(shape, w);
    Assembly {
        work: &work,
        chain_to_work: c.chain_to_work(),
        work_to_svg: c.orient.work_to_svg(w),
        row_angle: c.orient.angle,
        style,
        w,
        u_turns: c.serp.u_turns(),
        quarter_turns: 0,
        cells: 1,
    }
    .to_plan(word, name)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::rows::{LOOSE, TIGHT};
    use crate::shape::Ring;
    use kurbo::Point;

    #[test]
    fn tile_count_matches_the_word() {
        let disc = Shape::from_rings(vec![Ring {
            points: (0..64)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / 64.0;
                    Point::new(10.0 * a.cos(), 10.0 * a.sin())
                })
                .collect(),
        }]);
        for style in [TIGHT, LOOSE] {
            let orients: Vec<Orientation> = [0.0, 0.7]
                .iter()
                .flat_map(|&a| Orientation::corners(a))
                .collect();
            let all = solve_all(&disc, style, &orients, 1.0);
            assert!(!all.is_empty());
            for c in &all {
                assert_eq!(c.tiles(style), c.word(style).tiles());
                assert_eq!(c.serp.centres(style).len(), c.tiles(style));
            }
            assert!(all.windows(2).all(|p| p[0].cost <= p[1].cost));
        }
    }
}
