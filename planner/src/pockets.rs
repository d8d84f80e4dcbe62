//! Pockets at row ends: the repair of the commonest small part a plan leaves empty (issue
//! 26; BENCHMARKS, "Where the small empty parts sit"). A U-turn joins two rows at the same
//! column, so a pair whose outer row meets a slanted or curved edge stops there, and the
//! inner row's lane beyond the turn stays empty: a wedge about a tile wide between the turn
//! and the edge (the letters' bowls, a country's slanted border).
//!
//! The repair pushes such a U-turn outward by `d` columns: `d` straight joints inserted
//! before the turn and `d` after it lengthen both rows at that end and move the turn, and
//! nothing else of the chain moves (the row after the turn runs back `d` tiles farther, to
//! the column it ended at before). It is tried on every part left empty over the allowance,
//! for every U-turn whose extension reaches into one, as far as the new tiles' centres lie
//! on the shape (the outer row's up to half a tile off it), touch no other tile and land in
//! a part or next to it; the pushed plan is kept only when its largest
//! empty part is smaller, it ranks before the plan it came from by the planner's own price
//! ([`crate::empty::rank_key`]: fit, turns, parts left empty), its count stays within the
//! asked tolerance, at most [`MAX_OFF_SHARE`] of its tile centres lie off the shape (unless
//! more did before) and it folds without collision; or, where the largest part is of a kind
//! no push reaches (a lobe, a seam between cells), when that part stays and the plan is
//! cheaper with every part priced ([`all_parts_cost`]). Rounds repeat while they help.

use foldchain::{Fold, FoldWord};
use kurbo::{Affine, Point, Rect};

use crate::assembly::Assembly;
use crate::check::check_folds;
use crate::empty::{
    empty_part, empty_parts, excess_empty, near, plan_cost, rank_key, DeepLine, EmptyPart,
    EMPTY_PRICE,
};
use crate::frame::Orientation;
use crate::options::{PlanOptions, Turns, DEFAULT_TILES};
use crate::plan::Plan;
use crate::rows::{LOOSE, TIGHT};
use crate::shape::Shape;

/// The most columns a U-turn is pushed by.
const MAX_PUSH: usize = 8;
/// The most rounds of pushes (each on the largest part left then).
const MAX_ROUNDS: usize = 4;
/// A new tile's centre may lie this far (tile widths) off the shape, towards the row beside
/// it.
const OUTER: f64 = 0.5;
/// The share of tile centres that may lie off the shape after a push (unless more did
/// before): issue 26's bar for a plan that follows the drawn shape (97% of the centres on
/// the drawn area).
const MAX_OFF_SHARE: f64 = 0.03;
/// Tile centres closer than this (tile widths) overlap.
const TOUCH: f64 = 1.0 - 1e-6;

/// The warning [`crate::empty::note_empty`] words a part left empty with begins so.
const EMPTY_WARNING: &str = "the plan leaves a part of the shape empty";

/// `plan` with U-turns pushed into the parts it leaves empty where that helps (see the
/// module's documentation); `plan` itself where nothing does.
pub(crate) fn fill_row_ends(shape: &Shape, plan: Plan, opts: &PlanOptions) -> Plan {
    let mut best = plan;
    for _ in 0..MAX_ROUNDS {
        if best.metrics.largest_empty_tiles <= 0.0 {
            break;
        }
        match pushed(shape, &best, opts) {
            Some(p) => best = p,
            None => break,
        }
    }
    best
}

/// One round: the plan with the U-turns next to its largest empty part pushed into it, if
/// that plan is kept (see the module's documentation).
fn pushed(shape: &Shape, plan: &Plan, opts: &PlanOptions) -> Option<Plan> {
    let reach = near(opts.turns);
    let parts = empty_parts(shape, plan, reach);
    if parts.is_empty() {
        return None;
    }
    let w = plan.tile_size;
    let work = shape.scaled(1.0 / w);
    let to_work = Affine::new([1.0 / w, 0.0, 0.0, -1.0 / w, 0.0, 0.0]);
    let word = plan.fold_word().ok()?;
    let folds = word.folds();
    let centres: Vec<Point> = plan
        .poses
        .iter()
        .map(|p| to_work * Point::new(p.x, p.y))
        .collect();
    let grid = Grid::new(&centres);
    let boxes: Vec<Rect> = parts
        .iter()
        .map(|p| to_work.transform_rect_bbox(p.bbox).inflate(1.0, 1.0))
        .collect();
    let ctx = Pocket {
        work: &work,
        centres: &centres,
        grid: &grid,
        boxes: &boxes,
        reach,
    };
    let mut pushes: Vec<(usize, usize, usize)> = u_turns(folds)
        .into_iter()
        .filter_map(|(j, g)| ctx.push(j, g).map(|d| (j, g, d)))
        .collect();
    if pushes.is_empty() {
        return None;
    }
    // the count within the asked tolerance: the longest pushes first
    if opts.tile_size.is_none() {
        let asked = opts.tiles.unwrap_or(DEFAULT_TILES);
        let most = asked + (opts.tiles_tolerance * asked as f64) as usize;
        pushes.sort_by_key(|&(j, _, d)| (std::cmp::Reverse(d), j));
        let mut room = most.saturating_sub(plan.tiles);
        pushes.retain(|&(_, _, d)| {
            let keep = 2 * d <= room;
            if keep {
                room -= 2 * d;
            }
            keep
        });
        pushes.sort_unstable();
    }
    if pushes.is_empty() {
        return None;
    }
    let new_word = FoldWord::from_folds(with_pushes(folds, &pushes));
    let candidate = remeasured(shape, plan, &new_word, reach)?;
    let off = |p: &Plan| {
        let n = p.poses.iter();
        let off = n
            .filter(|q| !work.contains(to_work * Point::new(q.x, q.y)))
            .count();
        off as f64 / p.poses.len().max(1) as f64
    };
    if off(&candidate) > off(plan).max(MAX_OFF_SHARE) {
        return None;
    }
    let (old_key, new_key) = (
        rank_key(plan, opts.turn_cost),
        rank_key(&candidate, opts.turn_cost),
    );
    let (old_largest, new_largest) = (
        plan.metrics.largest_empty_tiles,
        candidate.metrics.largest_empty_tiles,
    );
    // the largest part smaller at a lower price, or (where the largest part is of another
    // kind, which no push reaches) no larger and the plan cheaper with every part priced
    let kept = (new_largest < old_largest && new_key < old_key)
        || (new_key.0 <= old_key.0
            && new_largest <= old_largest
            && all_parts_cost(shape, &candidate, opts, reach)
                < all_parts_cost(shape, plan, opts, reach));
    if !kept || check_folds(&new_word).is_err() {
        return None;
    }
    Some(candidate)
}

/// [`plan_cost`] with every part left empty priced, not only the largest: the
/// [`EMPTY_PRICE`] of the tile areas beyond the allowance of the others added.
fn all_parts_cost(shape: &Shape, plan: &Plan, opts: &PlanOptions, reach: f64) -> f64 {
    let excess: Vec<f64> = empty_parts(shape, plan, reach)
        .iter()
        .map(|e| excess_empty(e.tiles))
        .collect();
    let others = excess.iter().sum::<f64>() - excess.iter().copied().fold(0.0, f64::max);
    let area_tiles = plan.metrics.shape_area / (plan.tile_size * plan.tile_size);
    plan_cost(plan, opts.turn_cost) + EMPTY_PRICE * others / area_tiles.max(1e-9)
}

/// The U-turns of a fold word: `(j, g)` for the `g` joints from joint `j` that turn the
/// chain back (two like folds, `LL` or `RR`, or two with a straight joint between, `LSL`,
/// `RSR`), not part of a longer run of like folds. Tile `j` is the last of the row before
/// the turn, tile `j + g` the first of the row after it.
pub(crate) fn u_turns(folds: &[Fold]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut j = 0;
    while j + 1 < folds.len() {
        let f = folds[j];
        let before_like = j > 0 && folds[j - 1] == f;
        let g = if f == Fold::S || before_like {
            0
        } else if folds[j + 1] == f {
            2
        } else if folds[j + 1] == Fold::S && folds.get(j + 2) == Some(&f) {
            3
        } else {
            0
        };
        if g > 0 && folds.get(j + g) != Some(&f) {
            out.push((j, g));
            j += g;
        } else {
            j += 1;
        }
    }
    out
}

/// `folds` with `d` straight joints inserted before and after each U-turn `(j, g, d)`
/// (sorted by `j`).
fn with_pushes(folds: &[Fold], pushes: &[(usize, usize, usize)]) -> Vec<Fold> {
    let extra: usize = pushes.iter().map(|&(_, _, d)| 2 * d).sum();
    let mut out = Vec::with_capacity(folds.len() + extra);
    let mut at = 0;
    for &(j, g, d) in pushes {
        out.extend_from_slice(&folds[at..j]);
        out.extend(std::iter::repeat_n(Fold::S, d));
        out.extend_from_slice(&folds[j..j + g]);
        out.extend(std::iter::repeat_n(Fold::S, d));
        at = j + g;
    }
    out.extend_from_slice(&folds[at..]);
    out
}

/// The plan of `word`, which is `plan`'s word with U-turns pushed: the same frames, counts
/// and scale, its fit and its largest empty part measured anew (the warning that words it
/// replaced).
fn remeasured(shape: &Shape, plan: &Plan, word: &FoldWord, reach: f64) -> Option<Plan> {
    let w = plan.tile_size;
    // the tiles' lattice turned as the plan's (the fit measures octagons aligned with the
    // work frame's axes): the first tile's heading, seen in the physical frame (y up)
    let heading = plan.poses.first().map_or(0.0, |p| p.heading_deg);
    let orient = Orientation::along(-heading.to_radians());
    let work_to_svg = orient.work_to_svg(w);
    let work = orient.work_shape(shape, w);
    let chain_to_work = work_to_svg.inverse() * Affine::new(plan.chain_to_svg);
    let style = if plan.turns == Turns::Loose {
        LOOSE
    } else {
        TIGHT
    };
    let mut p = Assembly {
        work: &work,
        chain_to_work,
        work_to_svg,
        row_angle: 0.0,
        style,
        w,
        u_turns: plan.u_turns,
        quarter_turns: plan.quarter_turns,
        cells: plan.cells,
    }
    .to_plan(word, &plan.source);
    p.axis_deg = plan.axis_deg;
    p.set_scale(plan.mm_per_unit);
    p.warnings = plan
        .warnings
        .iter()
        .filter(|s| !s.starts_with(EMPTY_WARNING))
        .cloned()
        .collect();
    let part: Option<EmptyPart> = empty_part(shape, &p, reach);
    p.metrics.largest_empty_tiles = part.map_or(0.0, |e| e.tiles);
    if let Some(e) = part {
        p.warnings.insert(0, format!("the plan {e}"));
    }
    Some(p)
}

/// What a push is judged against: the shape and the plan's tile centres (work frame, unit
/// tiles), the boxes of the parts left empty (grown by a tile) and the empty measure's reach.
struct Pocket<'a> {
    work: &'a Shape,
    centres: &'a [Point],
    grid: &'a Grid,
    boxes: &'a [Rect],
    reach: f64,
}

impl Pocket<'_> {
    /// The columns by which the U-turn of `g` joints from joint `j` may be pushed, if any:
    /// the most `d` such that at every column up to it both new tiles touch no other tile and
    /// have their centres on the shape (a plan's tiles are where the drawing is), and at least
    /// one of them lands in the part left empty (in its box, at least half a tile inside the
    /// outline and beyond the reach of every other tile).
    fn push(&self, j: usize, g: usize) -> Option<usize> {
        let (p, q) = (*self.centres.get(j)?, *self.centres.get(j + g)?);
        let next = *self.centres.get(j + 1)?;
        // the row direction at tile j: towards the first turn tile, less the turn's sideways part
        let side = q - p;
        let across = if side.hypot() > 0.0 {
            side / side.hypot()
        } else {
            return None;
        };
        let along0 = next - p;
        let along = along0 - across * along0.dot(across);
        if along.hypot() < 1e-9 {
            return None;
        }
        let u = along / along.hypot();
        // not a turn near the part
        let m = MAX_PUSH as f64;
        if !self.boxes.iter().any(|b| b.inflate(m, m).contains(p)) {
            return None;
        }
        let skip = |i: usize| i > j && i < j + g;
        let mut best = 0;
        for t in 1..=MAX_PUSH {
            let (a, b) = (p + u * t as f64, q + u * t as f64);
            let on_shape = |x: Point, inward: kurbo::Vec2| {
                self.work.contains(x) || self.work.contains(x + inward * OUTER)
            };
            let fits = self.free(a, &skip)
                && self.free(b, &skip)
                && on_shape(a, across)
                && on_shape(b, -across);
            if !fits {
                break;
            }
            let useful = |x: Point| {
                self.boxes.iter().any(|b| b.contains(x))
                    && self.grid.nearest_beyond(self.centres, x, self.reach, &skip)
                    && DeepLine::new(self.work, x.y).deep(x.x)
            };
            if useful(a) || useful(b) {
                best = t;
            } else if best > 0 {
                break;
            }
        }
        // the turn tiles moved with the turn touch nothing either
        let moved_free = (j + 1..j + g).all(|i| {
            self.centres
                .get(i)
                .is_some_and(|&c| self.free(c + u * best as f64, &skip))
        });
        (best > 0 && moved_free).then_some(best)
    }

    /// True if a tile centred at `x` touches no tile but those `skip` names.
    fn free(&self, x: Point, skip: &dyn Fn(usize) -> bool) -> bool {
        self.grid.nearest_beyond(self.centres, x, TOUCH, skip)
    }
}

/// Tile centres bucketed by unit cells, for the nearest-centre tests.
struct Grid {
    cells: std::collections::HashMap<(i64, i64), Vec<usize>>,
}

impl Grid {
    fn new(centres: &[Point]) -> Grid {
        let mut cells: std::collections::HashMap<(i64, i64), Vec<usize>> =
            std::collections::HashMap::new();
        for (i, c) in centres.iter().enumerate() {
            cells.entry(Grid::key(*c)).or_default().push(i);
        }
        Grid { cells }
    }

    fn key(p: Point) -> (i64, i64) {
        (p.x.floor() as i64, p.y.floor() as i64)
    }

    /// True if every centre but those `skip` names lies at least `r` (at most 1) from `x`.
    fn nearest_beyond(
        &self,
        centres: &[Point],
        x: Point,
        r: f64,
        skip: &dyn Fn(usize) -> bool,
    ) -> bool {
        let (kx, ky) = Grid::key(x);
        for dx in -1..=1 {
            for dy in -1..=1 {
                let Some(list) = self.cells.get(&(kx + dx, ky + dy)) else {
                    continue;
                };
                if list
                    .iter()
                    .any(|&i| !skip(i) && (centres[i] - x).hypot() < r)
                {
                    return false;
                }
            }
        }
        true
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::empty::NEAR;
    use crate::shape::Ring;

    /// A serpentine of ten rows (unit tiles, lanes `sqrt2` apart from y = 0.7) in a band
    /// whose right edge slants (x = 80 - 4 y), each U-turn pair cut at the column its outer
    /// row reaches: the plan, and the shape (physical frame, w = 1).
    fn slanted_band() -> (Plan, Shape) {
        let edge = |y: f64| 80.0 - 4.0 * y;
        let lane = |k: usize| 0.7 + k as f64 * std::f64::consts::SQRT_2;
        let top = lane(9) + 0.7;
        let shape = Shape::from_rings(vec![Ring {
            points: vec![
                Point::new(0.0, 0.0),
                Point::new(edge(0.0), 0.0),
                Point::new(edge(top), top),
                Point::new(0.0, top),
            ],
        }]);
        // each pair's last column: its upper row's tile wholly inside
        let end = |k: usize| (edge(lane(k) + 0.5) - 0.5 - 0.5).floor() as usize;
        let pairs: Vec<String> = (0..5)
            .map(|i| {
                let e = end(2 * i + 1);
                format!("S*{e} LL S*{e}")
            })
            .collect();
        let word = FoldWord::parse(&pairs.join(" RR ")).unwrap();
        let orient = Orientation::along(0.0);
        let work = orient.work_shape(&shape, 1.0);
        let mut plan = Assembly {
            work: &work,
            chain_to_work: Affine::translate((0.5, 0.7)),
            work_to_svg: orient.work_to_svg(1.0),
            row_angle: 0.0,
            style: TIGHT,
            w: 1.0,
            u_turns: 9,
            quarter_turns: 0,
            cells: 1,
        }
        .to_plan(&word, "band");
        plan.metrics.largest_empty_tiles = empty_part(&shape, &plan, NEAR).map_or(0.0, |e| e.tiles);
        (plan, shape)
    }

    /// The band's lower lane of each pair runs on past the pair's U-turn, empty; pushing
    /// the turns fills them (the largest part left shrinks), adds two tiles a column, and
    /// leaves the last row where it was.
    #[test]
    fn a_u_turn_is_pushed_into_the_lane_its_pair_leaves() {
        let (plan, shape) = slanted_band();
        assert!(plan.metrics.largest_empty_tiles > 2.0, "{}", plan.summary());
        let opts = PlanOptions::default().with_tiles(plan.tiles);
        let opts = opts.with_tiles_tolerance(0.2);
        let pushed = fill_row_ends(&shape, plan.clone(), &opts);
        assert!(
            pushed.metrics.largest_empty_tiles < plan.metrics.largest_empty_tiles,
            "{} -> {}",
            plan.summary(),
            pushed.summary()
        );
        let added = pushed.tiles - plan.tiles;
        assert!(added > 0 && added % 2 == 0, "{added}");
        // the last row ends where it did
        let tail = |p: &Plan| p.poses[p.poses.len() - 5..].to_vec();
        assert_eq!(tail(&plan), tail(&pushed));
        assert!(check_folds(&pushed.fold_word().unwrap()).is_ok());
        assert_eq!(pushed.u_turns, plan.u_turns);
    }

    /// No push beyond the asked count's tolerance: at a tolerance of zero the plan stays.
    #[test]
    fn no_push_beyond_the_tolerance() {
        let (plan, shape) = slanted_band();
        let opts = PlanOptions::default()
            .with_tiles(plan.tiles)
            .with_tiles_tolerance(0.0);
        assert_eq!(fill_row_ends(&shape, plan.clone(), &opts), plan);
    }

    /// The U-turns of a word: tight and loose, not the joints of a longer spiral.
    #[test]
    fn u_turns_are_found_in_a_word() {
        let w = |s: &str| {
            FoldWord::parse(s)
                .map(|w| w.folds().to_vec())
                .unwrap_or_default()
        };
        assert_eq!(u_turns(&w("SSLLSSRRSS")), vec![(2, 2), (6, 2)]);
        assert_eq!(u_turns(&w("SLSLSS")), vec![(1, 3)]);
        assert_eq!(u_turns(&w("SLLLS")), Vec::<(usize, usize)>::new());
        assert_eq!(u_turns(&w("SLSS")), Vec::<(usize, usize)>::new());
    }

    /// Pushing a U-turn inserts straight joints on both sides, and the tiles after the row
    /// that follows it stay where they were.
    #[test]
    fn a_pushed_u_turn_moves_nothing_after_its_rows() {
        let old = FoldWord::parse("S*3 LL S*3 RR S*3").unwrap_or_default();
        let pushes = [(3, 2, 2)];
        let new = FoldWord::from_folds(with_pushes(old.folds(), &pushes));
        assert_eq!(new.tiles(), old.tiles() + 4);
        let (a, b) = (old.final_poses(), new.final_poses());
        // the last row (after the second U-turn) is the same in both
        for k in 1..=4 {
            assert_eq!(a[a.len() - k], b[b.len() - k]);
        }
        // the first row is two tiles longer
        assert_eq!(b[5].heading, b[0].heading);
    }
}
