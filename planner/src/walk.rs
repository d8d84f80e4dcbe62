//! Single-file walks along thin strokes: where a shape's strokes are one to two tiles wide
//! (a thin letter O or a ring at 100 tiles, an @'s arcs) no two rows fit across them, so
//! rows and cells leave most of the shape empty or shrink the tiles until a corner of it
//! holds the count. A walk lays the chain one tile at a time along the stroke: each joint
//! straight or folded (a quarter turn, the next centre `w/sqrt2` ahead and aside), chosen
//! by a short look-ahead for the tiles that reach most of the shape no tile reaches yet,
//! every tile centre inside the shape, and the chain kept foldable in sequence as it grows
//! ([`PrefixCheck`]). It stops at the asked count or where no step folds cleanly (a lap
//! round a hole, about three quarters of a turn: docs/planner.md, "Why not laps around a
//! hole"). Walks are tried at a few tile widths, start points and headings; the caller
//! ranks them with the other planners' plans by the same rules.
//!
//! The work is bounded by the shape's size: at most [`MAX_WALK_TILES`] tiles a walk, a
//! fixed number of walks, each step a look-ahead of `3^LOOK` nodes over a raster of the
//! shape at [`STEP`] tile widths.

use foldchain::collision::PrefixCheck;
use foldchain::{Fold, FoldWord};
use kurbo::{Affine, Point, Vec2};
use rayon::prelude::*;

use crate::assembly::Assembly;
use crate::empty::{largest_empty_part, DeepLine, OrdF64};
use crate::frame::Orientation;
use crate::plan::Plan;
use crate::rank::Asked;
use crate::rows::TIGHT;
use crate::shape::Shape;

/// Walks are tried only for counts up to this: beyond it a stroke is several tiles wide
/// and rows fill it.
pub(crate) const MAX_WALK_TILES: usize = 1000;

/// The raster's cell side, tile widths.
const STEP: f64 = 0.25;

/// Steps of the look-ahead (`3^LOOK` continuations a step).
const LOOK: usize = 4;

/// The tile widths tried, as factors of the width at which a single file of the asked count
/// would cover the shape's area (each tile reaching a band about `2 NEAR` wide).
const WIDTH_FACTORS: [f64; 6] = [0.7, 0.8, 0.9, 1.0, 1.12, 1.25];

/// Lattice turns tried (radians): the walk's headings are these plus quarter turns.
const ANGLES: [f64; 2] = [0.0, std::f64::consts::FRAC_PI_4];

/// Start points tried: the deepest raster cells nearest each of these directions' extremes.
const START_DIRECTIONS: usize = 4;

/// The best walk plan of about `target` tiles over `shape` (physical frame): a count within
/// the tolerance first, then the least shortfall of the asked chain (`asked`: its count's
/// miss and the part it leaves empty). `None` when no walk lays a tile.
pub(crate) fn best_walk(shape: &Shape, target: usize, asked: &Asked, name: &str) -> Option<Plan> {
    if !(2..=MAX_WALK_TILES).contains(&target) {
        return None;
    }
    // a single file reaches a band about 2 * NEAR wide: tiles of width w cover about
    // 1.9 w^2 of the shape each
    let w0 = (shape.area() / (1.9 * target as f64)).sqrt();
    if !w0.is_finite() || w0 <= 0.0 {
        return None;
    }
    let jobs: Vec<(f64, f64)> = WIDTH_FACTORS
        .iter()
        .flat_map(|&f| ANGLES.iter().map(move |&a| (w0 * f, a)))
        .collect();
    let plans: Vec<((usize, OrdF64), Plan)> = jobs
        .par_iter()
        .filter_map(|&(w, a)| {
            let orient = Orientation::along(a);
            let work = orient.work_shape(shape, w);
            let raster = Raster::new(&work)?;
            let mut best: Option<((usize, OrdF64), Vec<Fold>, Affine)> = None;
            for start in raster.starts() {
                for h in 0..4 {
                    let phi = h as f64 * std::f64::consts::FRAC_PI_2;
                    let to_work = Affine::translate(start.to_vec2()) * Affine::rotate(phi);
                    let folds = walk(&raster, &work, to_work, target);
                    let centres = centres(&folds, to_work);
                    let empty = largest_empty_part(&work, &centres, crate::empty::NEAR)
                        .map_or(0.0, |e| e.0);
                    // the count within the tolerance first, then the shortfall
                    let short = (
                        asked.miss(folds.len() + 1),
                        OrdF64(asked.shortfall(folds.len() + 1, w, empty)),
                    );
                    if best.as_ref().is_none_or(|b| short < b.0) {
                        best = Some((short, folds, to_work));
                    }
                }
            }
            let (short, folds, to_work) = best?;
            let word = FoldWord::from_folds(folds);
            word.check_no_opposite_folds().ok()?;
            let asm = Assembly {
                work: &work,
                chain_to_work: to_work,
                work_to_svg: orient.work_to_svg(w),
                row_angle: a,
                style: TIGHT,
                w,
                u_turns: u_turns(word.folds()),
                quarter_turns: quarter_turns(word.folds()),
                cells: 1,
            };
            Some((short, asm.to_plan(&word, name)))
        })
        .collect();
    plans
        .into_iter()
        .min_by(|a, b| a.0.cmp(&b.0))
        .map(|(_, p)| p)
}

/// The U-turns of a walk, as [`crate::pockets`] finds them (`LL`, `RR`, `LSL`, `RSR`).
fn u_turns(folds: &[Fold]) -> usize {
    crate::pockets::u_turns(folds).len()
}

/// Folds not part of a U-turn.
fn quarter_turns(folds: &[Fold]) -> usize {
    let folded = folds.iter().filter(|&&f| f != Fold::S).count();
    let in_u: usize = crate::pockets::u_turns(folds)
        .iter()
        .map(|&(j, g)| folds[j..j + g].iter().filter(|&&f| f != Fold::S).count())
        .sum();
    folded - in_u
}

/// The tile centres of a chain of `folds` (chain frame: tile 0 at the origin heading +x,
/// unit tiles) mapped by `to_work`.
fn centres(folds: &[Fold], to_work: Affine) -> Vec<Point> {
    let mut pose = Pose::default();
    let mut out = Vec::with_capacity(folds.len() + 1);
    out.push(to_work * pose.at);
    for &f in folds {
        pose = pose.next(f);
        out.push(to_work * pose.at);
    }
    out
}

/// A tile's centre and heading (quarter turns from +x) in the chain frame.
#[derive(Clone, Copy, Default)]
struct Pose {
    at: Point,
    heading: i32,
}

impl Pose {
    /// The next tile's pose across a joint folded `f` (foldchain's kinematics: a straight
    /// joint puts the next centre 1 ahead, a fold at `(1/sqrt2, +-1/sqrt2)`).
    fn next(self, f: Fold) -> Pose {
        let dir = |h: i32| match h.rem_euclid(4) {
            0 => Vec2::new(1.0, 0.0),
            1 => Vec2::new(0.0, 1.0),
            2 => Vec2::new(-1.0, 0.0),
            _ => Vec2::new(0.0, -1.0),
        };
        let s = std::f64::consts::FRAC_1_SQRT_2;
        match f {
            Fold::S => Pose {
                at: self.at + dir(self.heading),
                heading: self.heading,
            },
            Fold::L => Pose {
                at: self.at + (dir(self.heading) + dir(self.heading + 1)) * s,
                heading: self.heading + 1,
            },
            Fold::R => Pose {
                at: self.at + (dir(self.heading) + dir(self.heading - 1)) * s,
                heading: self.heading - 1,
            },
        }
    }
}

/// The shape in the work frame on a grid of [`STEP`]: which cells lie inside, and which of
/// those at least [`crate::empty::EDGE`] inside the outline (the cells the empty-part
/// measure counts).
struct Raster {
    x0: f64,
    y0: f64,
    nx: usize,
    ny: usize,
    deep: Vec<bool>,
}

/// At most this many raster cells (a shape of some 7,000 tile areas at [`STEP`]).
const MAX_CELLS: usize = 120_000;

impl Raster {
    fn new(work: &Shape) -> Option<Raster> {
        let b = work.bbox();
        let nx = (b.width() / STEP).ceil() as usize + 1;
        let ny = (b.height() / STEP).ceil() as usize + 1;
        if nx.checked_mul(ny)? > MAX_CELLS {
            return None;
        }
        let mut deep = vec![false; nx * ny];
        for i in 0..ny {
            let y = b.y0 + (i as f64 + 0.5) * STEP;
            let line = DeepLine::new(work, y);
            for j in 0..nx {
                deep[i * nx + j] = line.deep(b.x0 + (j as f64 + 0.5) * STEP);
            }
        }
        Some(Raster {
            x0: b.x0,
            y0: b.y0,
            nx,
            ny,
            deep,
        })
    }

    /// The deep cells within [`crate::empty::NEAR`] of `c`, appended to `out`.
    fn reached(&self, c: Point, out: &mut Vec<u32>) {
        let r = crate::empty::NEAR;
        let i0 = (((c.y - r - self.y0) / STEP).floor().max(0.0)) as usize;
        let i1 = ((((c.y + r - self.y0) / STEP).ceil()).max(0.0) as usize).min(self.ny);
        let j0 = (((c.x - r - self.x0) / STEP).floor().max(0.0)) as usize;
        let j1 = ((((c.x + r - self.x0) / STEP).ceil()).max(0.0) as usize).min(self.nx);
        for i in i0..i1 {
            let y = self.y0 + (i as f64 + 0.5) * STEP;
            for j in j0..j1 {
                let x = self.x0 + (j as f64 + 0.5) * STEP;
                let k = i * self.nx + j;
                if self.deep[k] && (x - c.x).powi(2) + (y - c.y).powi(2) <= r * r {
                    out.push(k as u32);
                }
            }
        }
    }

    /// Start points: the deep cells furthest along each of [`START_DIRECTIONS`] directions.
    fn starts(&self) -> Vec<Point> {
        let mut out: Vec<Point> = Vec::new();
        for d in 0..START_DIRECTIONS {
            let a = std::f64::consts::TAU * d as f64 / START_DIRECTIONS as f64 + 0.3;
            let u = Vec2::new(a.cos(), a.sin());
            let best = (0..self.deep.len())
                .filter(|&k| self.deep[k])
                .map(|k| self.point(k))
                .max_by(|p, q| p.to_vec2().dot(u).total_cmp(&q.to_vec2().dot(u)));
            if let Some(p) = best {
                if out.iter().all(|q| q.distance(p) > 1.0) {
                    out.push(p);
                }
            }
        }
        out
    }

    fn point(&self, k: usize) -> Point {
        Point::new(
            self.x0 + ((k % self.nx) as f64 + 0.5) * STEP,
            self.y0 + ((k / self.nx) as f64 + 0.5) * STEP,
        )
    }
}

/// The walk from the tile at `to_work`'s origin: its folds (one fewer than its tiles), at
/// most `target - 1`.
fn walk(raster: &Raster, work: &Shape, to_work: Affine, target: usize) -> Vec<Fold> {
    let mut covered = vec![false; raster.deep.len()];
    let mut placed = Placed::default();
    let mut pose = Pose::default();
    let first = to_work * pose.at;
    if !work.contains(first) {
        return Vec::new();
    }
    let mut buf = Vec::new();
    raster.reached(first, &mut buf);
    for &k in &buf {
        covered[k as usize] = true;
    }
    placed.push(first);
    let mut check = PrefixCheck::new();
    let mut folds: Vec<Fold> = Vec::new();
    let ctx = Look {
        raster,
        work,
        to_work,
    };
    while folds.len() + 1 < target {
        let last = folds.last().copied();
        let mut options: Vec<(usize, Fold)> = allowed(last)
            .filter_map(|f| {
                let (mut fresh, mut ahead) = (Vec::new(), Vec::new());
                ctx.gain(&covered, &placed, &mut ahead, pose, f, LOOK, &mut fresh)
                    .map(|g| (g, f))
            })
            .collect();
        // most reached first; straight before folds among equals
        options.sort_by_key(|o| std::cmp::Reverse(o.0));
        if options.first().is_none_or(|o| o.0 == 0) {
            break;
        }
        let mut taken = None;
        for &(g, f) in &options {
            if g == 0 {
                break;
            }
            let mut c = check.clone();
            c.push(&[f]);
            if c.folds_cleanly() {
                taken = Some((f, c));
                break;
            }
        }
        let Some((f, c)) = taken else {
            break;
        };
        check = c;
        pose = pose.next(f);
        let at = to_work * pose.at;
        buf.clear();
        raster.reached(at, &mut buf);
        for &k in &buf {
            covered[k as usize] = true;
        }
        placed.push(at);
        folds.push(f);
    }
    folds
}

/// Centres nearer than this (tile widths) are taken as overlapping by the look-ahead:
/// neighbours along the chain lie exactly 1 apart.
const CLOSE: f64 = 0.999;

/// The folds allowed after a joint folded `last`: no tile folds both ways (an L joint
/// followed by an R one, or the reverse, would need an LR tile, which the model has not).
fn allowed(last: Option<Fold>) -> impl Iterator<Item = Fold> {
    [Fold::S, Fold::L, Fold::R].into_iter().filter(move |&f| {
        !matches!(
            (last, f),
            (Some(Fold::L), Fold::R) | (Some(Fold::R), Fold::L)
        )
    })
}

/// The tile centres laid, bucketed by unit cell.
#[derive(Default)]
struct Placed {
    cells: std::collections::HashMap<(i64, i64), Vec<Point>>,
}

impl Placed {
    fn push(&mut self, p: Point) {
        let c = (p.x.floor() as i64, p.y.floor() as i64);
        self.cells.entry(c).or_default().push(p);
    }

    /// Whether a centre laid lies nearer than [`CLOSE`] to `p`.
    fn near(&self, p: Point) -> bool {
        let (cx, cy) = (p.x.floor() as i64, p.y.floor() as i64);
        (cx - 1..=cx + 1).any(|x| {
            (cy - 1..=cy + 1).any(|y| {
                self.cells
                    .get(&(x, y))
                    .is_some_and(|v| v.iter().any(|q| q.distance(p) < CLOSE))
            })
        })
    }
}

/// What a look-ahead reads.
struct Look<'a> {
    raster: &'a Raster,
    work: &'a Shape,
    to_work: Affine,
}

impl Look<'_> {
    /// The most deep cells not yet covered that the tile across a joint folded `f` from
    /// `pose` and the best `depth - 1` tiles after it reach (`fresh`: cells the steps before
    /// in this look-ahead reached); `None` when that tile is not allowed (its centre outside
    /// the shape, or nearer than a tile width to a tile laid).
    #[allow(clippy::too_many_arguments)]
    fn gain(
        &self,
        covered: &[bool],
        placed: &Placed,
        ahead: &mut Vec<Point>,
        pose: Pose,
        f: Fold,
        depth: usize,
        fresh: &mut Vec<u32>,
    ) -> Option<usize> {
        let next = pose.next(f);
        let at = self.to_work * next.at;
        if !self.work.contains(at) {
            return None;
        }
        // no nearer than a tile width to a tile laid or looked ahead to (the exact overlap
        // test is the fold check's, when a step is taken)
        if placed.near(at) || ahead.iter().any(|p| p.distance(at) < CLOSE) {
            return None;
        }
        let mark = fresh.len();
        let mut cells = Vec::new();
        self.raster.reached(at, &mut cells);
        let mut g = 0;
        for k in cells {
            if !covered[k as usize] && !fresh[..mark].contains(&k) {
                fresh.push(k);
                g += 1;
            }
        }
        if depth > 1 {
            ahead.push(at);
            let more = allowed(Some(f))
                .filter_map(|f2| self.gain(covered, placed, ahead, next, f2, depth - 1, fresh))
                .max()
                .unwrap_or(0);
            ahead.pop();
            g += more;
        }
        fresh.truncate(mark);
        Some(g)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    fn word(s: &str) -> Vec<Fold> {
        FoldWord::parse(s).unwrap().folds().to_vec()
    }

    /// A U-turn is two folds the same way in a row, or with one straight joint between
    /// ([`crate::pockets`]' rule, not part of a longer run); other folds are quarter turns.
    #[test]
    fn turns_are_counted_as_the_plans_count_them() {
        assert_eq!(
            (u_turns(&word("SLSLS")), quarter_turns(&word("SLSLS"))),
            (1, 0)
        );
        assert_eq!(
            (u_turns(&word("SLLS")), quarter_turns(&word("SLLS"))),
            (1, 0)
        );
        assert_eq!(
            (u_turns(&word("SLSRS")), quarter_turns(&word("SLSRS"))),
            (0, 2)
        );
        assert_eq!(
            (u_turns(&word("LLLS")), quarter_turns(&word("LLLS"))),
            (0, 3)
        );
    }

    /// No tile folds both ways: after an L joint no R, after an R no L.
    #[test]
    fn a_fold_is_never_followed_by_the_opposite_fold() {
        assert!(!allowed(Some(Fold::L)).any(|f| f == Fold::R));
        assert!(!allowed(Some(Fold::R)).any(|f| f == Fold::L));
        assert_eq!(allowed(None).count(), 3);
    }

    /// The walk's poses are foldchain's kinematics.
    #[test]
    fn poses_follow_the_exact_kinematics() {
        let folds = word("SSLSLLSRSS");
        let mine = centres(&folds, Affine::IDENTITY);
        let exact = FoldWord::from_folds(folds).final_poses();
        for (p, e) in mine.iter().zip(&exact) {
            let (x, y) = e.centre.to_f64(1.0);
            assert!((p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12);
        }
    }

    /// A band one and a half tiles wide round a square hole (a thin square ring of side 40,
    /// physical frame, tile width about 1): the walk lays a lap of about the count with every
    /// centre on the band, a word without LR tiles that folds in sequence.
    #[test]
    fn a_thin_square_ring_is_walked_round_its_hole() {
        let outer = Ring::rect(0.0, 0.0, 40.0, 40.0);
        let mut inner = Ring::rect(1.5, 1.5, 38.5, 38.5);
        inner.points.reverse();
        let shape = Shape::from_rings(vec![outer, inner]);
        let target = 100;
        let asked = Asked::new(
            &crate::PlanOptions::default().with_tiles(target),
            shape.area(),
            target,
        );
        let p = best_walk(&shape, target, &asked, "ring").unwrap();
        assert!(p.tiles >= 90, "{} tiles", p.tiles);
        let word = p.fold_word().unwrap();
        assert!(word.first_opposite_pair().is_none());
        assert!(crate::check::check_folds(&word).is_ok());
        let inside = p
            .poses
            .iter()
            .filter(|q| shape.contains(Point::new(q.x, -q.y)))
            .count();
        assert_eq!(inside, p.tiles, "centres off the band");
    }
}
