//! Slab decompositions (issue 26, "each part swept along its own length"; the boustrophedon
//! cells of Bähnemann et al. 2019, each with its own sweep direction as in Fields2Cover):
//! the shape is cut across one axis at its critical lines, where a line across the axis
//! meets the shape in a different number of runs or where a run's end jumps by more than a
//! tile (a key's head meets its shaft, a tooth hangs below the shaft), and every set of those
//! cuts is a decomposition into slabs, taken in order along the axis.
//!
//! Unlike a cap ([`crate::caps`]), a slab need not be monotone across its rows: each slab is
//! priced by the exact row programme ([`crate::rows::solve_rows`]) in both sweep directions
//! (rows along x, rows along y), so its rows may bridge a short gap where that fits better
//! than leaving a part empty (a key's two teeth below its shaft, in one row under the shaft's
//! row), and a slab takes the direction in which it is cheaper: along its own length. A
//! decomposition costs the sum of its slabs' misfits plus a price per join; the work is
//! bounded: at most [`MAX_CUTS`] cuts (2^6 sets), each slab solved once. The cheapest
//! decompositions are laid out by the cell router ([`crate::route`]) in both orders along the
//! axis, each slab's stacking side, start and exit chosen there, and every route is checked
//! by sequential folding like any other.

use std::collections::HashMap;

use kurbo::Affine;

use crate::caps::{CapCell, CapPlan, Dir, PBox, Raster, Search};
use crate::rows::{tile_area, Phased, Style};
use crate::shape::Shape;

/// A slab of a decomposition: its tight box, the cut before it (its first line along the
/// axis), and its price in each direction whose rows fit ([`slab_price`]).
type Slab = (PBox, usize, Vec<(f64, Dir)>);

/// The most cuts considered per axis (the largest jumps): 2^6 decompositions at most.
const MAX_CUTS: usize = 6;
/// Decompositions returned per shape (each in both orders along its axis).
const KEEP: usize = 2;
/// The price of a join between slabs, in tile areas (a quarter turn is priced like a U-turn
/// by the route; this is its share in ranking decompositions).
const JOIN_PRICE: f64 = 1.0;

/// The cheapest slab decompositions of `axis_shape` (axis frame, unit tiles) into at least
/// two slabs for rows of `style`, cheapest first by their slabs' misfits alone, each in both
/// orders along its axis: at most `2 KEEP`; then the two decompositions (each in its own
/// laying order) not among those whose slabs' misfits and joins ([`entry_price`]) cost
/// least, with each slab's direction chosen with its joins and allowed only where it may
/// follow the slabs laid before ([`directions`]), marked `joined`. The joined price also
/// sees cuts across the middle of each hole, so a ring may be laid as two halves, the second
/// swept along the cut. Empty when the shape is not one piece or has no cut.
pub(crate) fn slab_plans(axis_shape: &Shape, style: Style) -> Vec<CapPlan> {
    let r = Raster::new(axis_shape);
    let s = Search::new(&r, style.pitch);
    let Some(b) = s.whole() else {
        return Vec::new();
    };
    let mut priced: HashMap<PBox, Vec<(f64, Dir)>> = HashMap::new();
    let mut found: Vec<CapPlan> = Vec::new();
    // the same decompositions, priced with what their joins leave empty
    let mut joined: Vec<CapPlan> = Vec::new();
    // the cheapest of them at the cuts where the runs change, each slab's direction chosen
    // with its joins alone (not by the order of laying)
    let mut first: Option<CapPlan> = None;
    for across_x in [true, false] {
        let (lo, hi) = if across_x { (b.x0, b.x1) } else { (b.y0, b.y1) };
        let cuts = critical_cuts(&s, b, across_x, false);
        // the joined price also sees cuts across the holes' middles
        let middles = critical_cuts(&s, b, across_x, true);
        let sets: Vec<(&[usize], bool)> = if middles == cuts {
            vec![(&cuts, true)]
        } else {
            vec![(&cuts, true), (&middles, false)]
        };
        for (cuts, old) in sets {
            for mask in 1u32..(1u32 << cuts.len()) {
                let mut edges = vec![lo];
                edges.extend(
                    cuts.iter()
                        .enumerate()
                        .filter(|(i, _)| mask >> i & 1 == 1)
                        .map(|(_, &c)| c),
                );
                edges.push(hi);
                let mut price = |t: PBox| {
                    priced
                        .entry(t)
                        .or_insert_with(|| slab_price(axis_shape, &s, t, style))
                        .clone()
                };
                let Some(slabs) = cut_slabs(&s, b, across_x, &edges, &mut price) else {
                    continue;
                };
                if slabs.len() < 2 {
                    continue;
                }
                let joins = JOIN_PRICE * (edges.len() - 2) as f64;
                let make = |cost: f64, dirs: Vec<Dir>| CapPlan {
                    cells: slabs
                        .iter()
                        .zip(dirs)
                        .map(|((t, _, _), n)| CapCell {
                            rect: s.rect(*t),
                            n,
                            either_sign: true,
                            spans: false,
                        })
                        .collect(),
                    cost,
                    slabs: true,
                    joined: false,
                };
                // each slab alone in its cheaper direction (the first price; only for the
                // cuts where the runs change), and the directions chosen with the joins in
                // both laying orders
                if old {
                    let alone: Vec<(f64, Dir)> = slabs
                        .iter()
                        .map(|(_, _, p)| {
                            p.iter().copied().fold((f64::INFINITY, Dir::PosY), |a, b| {
                                if b.0 < a.0 {
                                    b
                                } else {
                                    a
                                }
                            })
                        })
                        .collect();
                    found.push(make(
                        joins + alone.iter().map(|a| a.0).sum::<f64>(),
                        alone.iter().map(|a| a.1).collect(),
                    ));
                }
                for reverse in [false, true] {
                    if let Some((cost, dirs)) = directions(&s, across_x, &slabs, (reverse, true)) {
                        let mut p = make(cost + joins, dirs);
                        if reverse {
                            p.cells.reverse();
                        }
                        joined.push(p);
                    }
                }
                if old {
                    if let Some((cost, dirs)) = directions(&s, across_x, &slabs, (false, false)) {
                        let p = make(cost + joins, dirs);
                        if first.as_ref().is_none_or(|f| p.cost < f.cost) {
                            first = Some(p);
                        }
                    }
                }
            }
        }
    }
    assemble(found, joined, first)
}

/// The slabs of `b` between consecutive `edges` (pixel columns if `across_x`, else rows):
/// each slab's tight box, the cut before it and its `price` in each direction; None when a
/// slab is not one piece or has no direction whose rows fit.
fn cut_slabs(
    s: &Search<'_>,
    b: PBox,
    across_x: bool,
    edges: &[usize],
    price: &mut dyn FnMut(PBox) -> Vec<(f64, Dir)>,
) -> Option<Vec<Slab>> {
    let mut slabs: Vec<Slab> = Vec::new();
    for e in edges.windows(2) {
        let slab = if across_x {
            PBox {
                x0: e[0],
                x1: e[1],
                ..b
            }
        } else {
            PBox {
                y0: e[0],
                y1: e[1],
                ..b
            }
        };
        let t = s.tight(slab).filter(|&t| s.components(t) == 1)?;
        let p = price(t);
        if p.is_empty() {
            return None;
        }
        slabs.push((t, e[0], p));
    }
    Some(slabs)
}

/// The cheapest [`KEEP`] of the decompositions priced alone (`found`), each in both orders,
/// then `first` (the cheapest by the joined price at the cuts where the runs change) in both
/// orders where it is not one of those, and the two cheapest of `joined` (each in the laying
/// order it was priced for) that are none of these, all marked `joined`, `first`'s pair
/// sized first and the other two in a slot of their own after it (see [`slab_plans`]).
fn assemble(
    mut found: Vec<CapPlan>,
    mut joined: Vec<CapPlan>,
    first: Option<CapPlan>,
) -> Vec<CapPlan> {
    found.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    found.truncate(KEEP);
    joined.sort_by(|a, b| a.cost.total_cmp(&b.cost));
    let same = |a: &CapPlan, b: &CapPlan| {
        a.cells.len() == b.cells.len()
            && a.cells
                .iter()
                .zip(&b.cells)
                .all(|(x, y)| x.rect == y.rect && x.n == y.n)
    };
    // the cheapest with each slab's direction chosen with its joins alone, added (never in
    // place of one of the others) when it differs from them, in both orders
    let alone = first.filter(|j| !found.iter().any(|f| same(f, j)));
    let mut out: Vec<CapPlan> = found
        .into_iter()
        .flat_map(|p| {
            let mut rev = p.clone();
            rev.cells.reverse();
            [p, rev]
        })
        .collect();
    let mut group: Vec<CapPlan> = Vec::new();
    if let Some(j) = alone {
        let mut rev = j.clone();
        rev.cells.reverse();
        group.extend([j, rev]);
    }
    // then the two cheapest laid in the order the joins were priced for that are none of
    // those; the group ranks by the first, after every group that has one (infinite cost)
    let group_cost = group.first().map_or(f64::INFINITY, |j| j.cost);
    let mut extra = 0;
    for j in joined {
        if extra == 2 {
            break;
        }
        if out.iter().chain(&group).any(|f| same(f, &j)) {
            continue;
        }
        group.push(j);
        extra += 1;
    }
    for p in &mut group {
        p.joined = true;
        p.cost = group_cost;
    }
    out.extend(group);
    out
}

/// The lines (pixel columns if `across_x`, else pixel rows) of `b` at which a slab may be
/// cut: where the runs of a line differ in number from the line before or an end moves by
/// more than a tile; at most [`MAX_CUTS`], the largest changes, at least a tile from the
/// box's sides and from each other, in order.
pub(crate) fn critical_cuts(s: &Search<'_>, b: PBox, across_x: bool, middles: bool) -> Vec<usize> {
    let tile = s.raster().per_tile();
    let min = tile.ceil() as usize;
    let (lo, hi, alo, ahi) = if across_x {
        (b.x0, b.x1, b.y0, b.y1)
    } else {
        (b.y0, b.y1, b.x0, b.x1)
    };
    // (line, size of the change)
    let mut changes: Vec<(usize, f64)> = Vec::new();
    let mut prev = s.runs(!across_x, lo, alo, ahi);
    // the line where the runs last grew in number (a hole or a notch opens)
    let mut opened: Option<usize> = None;
    for k in lo + 1..hi {
        let runs = s.runs(!across_x, k, alo, ahi);
        if runs.len() > prev.len() {
            opened = Some(k);
        } else if runs.len() < prev.len() {
            if let Some(o) = opened.take().filter(|_| middles) {
                // a hole's middle: the halves beside it may be laid one after the other,
                // the second swept along the cut ([`may_follow`])
                let mid = (o + k) / 2;
                if mid >= lo + min && mid + min <= hi {
                    changes.push((mid, f64::MAX));
                }
            }
        }
        let change = if runs.len() != prev.len() {
            f64::INFINITY
        } else {
            runs.iter()
                .zip(&prev)
                .map(|(a, p)| (a.0.abs_diff(p.0)).max(a.1.abs_diff(p.1)) as f64)
                .fold(0.0, f64::max)
        };
        if change > tile && k >= lo + min && k + min <= hi {
            changes.push((k, change));
        }
        prev = runs;
    }
    // the largest changes first, each at least a tile from those kept
    changes.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    let mut out: Vec<usize> = Vec::new();
    for (k, _) in changes {
        if out.len() >= MAX_CUTS {
            break;
        }
        if out.iter().all(|&o| o.abs_diff(k) >= min) {
            out.push(k);
        }
    }
    out.sort_unstable();
    out
}

/// The part a route must leave empty to pass from slab `a` to the next slab `b` across the
/// cut at line `cut` (a pixel column if `across_x`, else a pixel row), in tile areas, each
/// slab with the stacking direction of its rows. A slab whose rows run across the cut is
/// entered (or left) by its first (or last) row, which lies at one of its sides along the
/// cut: where the slabs meet only farther than a tile from those sides, the rows between
/// the crossing and the nearer side are skipped (a gear's slab round its hole entered
/// halfway up). A slab whose rows run along the cut is entered at any point of its first
/// row. The crossing is chosen where the two slabs' skipped parts are least; slabs that do
/// not meet at the cut are not priced here (the route's fold check decides).
fn entry_price(s: &Search<'_>, across_x: bool, cut: usize, a: (PBox, Dir), b: (PBox, Dir)) -> f64 {
    let tile = s.raster().per_tile();
    // the slab's sides along the cut, its depth along the axis (tiles), and whether its rows
    // run across the cut (stacked along the cut)
    let sides = |t: PBox, n: Dir| {
        let across = matches!(n, Dir::PosY | Dir::NegY) == across_x;
        if across_x {
            ((t.y0, t.y1), (t.x1 - t.x0) as f64 / tile, across)
        } else {
            ((t.x0, t.x1), (t.y1 - t.y0) as f64 / tile, across)
        }
    };
    let (sa, da, xa) = sides(a.0, a.1);
    let (sb, db, xb) = sides(b.0, b.1);
    if !xa && !xb {
        return 0.0;
    }
    let (lo, hi) = (sa.0.min(sb.0), sa.1.max(sb.1));
    let before = s.runs(!across_x, cut.saturating_sub(1), lo, hi);
    let after = s.runs(!across_x, cut, lo, hi);
    let skipped = |e: usize, (s0, s1): (usize, usize), depth: f64| {
        let d = e.abs_diff(s0).min(e.abs_diff(s1)) as f64 / tile;
        (d - 1.0).max(0.0) * depth
    };
    let price = |e: usize| {
        let mut p = 0.0;
        if xa {
            p += skipped(e, sa, da);
        }
        if xb {
            p += skipped(e, sb, db);
        }
        p
    };
    let mut best: Option<f64> = None;
    for &(a0, a1) in &before {
        for &(b0, b1) in &after {
            let (r0, r1) = (a0.max(b0), a1.min(b1));
            if r0 >= r1 {
                continue;
            }
            let last = r1 - 1;
            let candidates = [r0, last, sa.0, sa.1, sb.0, sb.1];
            for e in candidates {
                let p = price(e.clamp(r0, last));
                if best.is_none_or(|q| p < q) {
                    best = Some(p);
                }
            }
        }
    }
    best.unwrap_or(0.0)
}

/// The misfit of the slab `t` swept in each direction whose rows fit, with that direction
/// (the stacking direction of its rows): the row programme's least cost over the lattice
/// phases, plus the area the rows of `style` would cover were they perfect (so that a slab
/// filled as well as rows can fill costs about its turns), in tile areas.
pub(crate) fn slab_price(
    axis_shape: &Shape,
    s: &Search<'_>,
    t: PBox,
    style: Style,
) -> Vec<(f64, Dir)> {
    let cell = axis_shape.clipped(s.rect(t));
    let ideal = cell.area() * tile_area() / style.pitch;
    let mut out: Vec<(f64, Dir)> = Vec::new();
    for (n, work) in [
        (Dir::PosY, cell.clone()),
        // rows along y: the cell with x and y swapped
        (
            Dir::PosX,
            cell.transformed(Affine::new([0.0, 1.0, 1.0, 0.0, 0.0, 0.0])),
        ),
    ] {
        let cost = Phased::new(&work, style)
            .solve(style)
            .filter_map(|(_, sol)| sol.best_end(|_| true).map(|e| e.0))
            .fold(f64::INFINITY, f64::min);
        if cost.is_finite() {
            out.push((cost + ideal, n));
        }
    }
    out
}

/// Whether slab `t` swept with rows stacked along `n` may follow the slabs `earlier` under
/// sequential folding: the unfolded tail runs straight on from the tile being laid, as long
/// as the chain still to lay, so rows that run across the cuts (towards the slabs beside
/// this one) may not be laid once a slab across their lines is laid (it lies beside the
/// slab, or across a hole: a ring's second half swept in columns heads into its first
/// half). Rows along the cuts never meet another slab of the decomposition.
fn may_follow(across_x: bool, t: PBox, n: Dir, earlier: &[PBox], tile: f64) -> bool {
    let across = matches!(n, Dir::PosY | Dir::NegY) == across_x;
    if !across {
        return true;
    }
    // the slab's extent along its rows' lines' spacing (rows along x: its y range)
    let span = |b: PBox| if across_x { (b.y0, b.y1) } else { (b.x0, b.x1) };
    let (a0, a1) = span(t);
    earlier.iter().all(|&e| {
        let (e0, e1) = span(e);
        (a1.min(e1) as f64 - a0.max(e0) as f64) < tile
    })
}

/// The sweep direction of each slab of a decomposition (`(tight box, cut before it, price
/// in each direction)`, in order along the axis), laid in that order or (`reverse`) the
/// other, that makes the least sum of the slabs' misfits and the parts their joins leave
/// empty ([`entry_price`]), each slab's rows allowed (if `follow`) only where they may
/// follow the slabs laid before ([`may_follow`]), and that sum: exact, by dynamic programming over the slabs
/// (two directions each). None if a slab has no allowed direction.
fn directions(
    s: &Search<'_>,
    across_x: bool,
    slabs: &[Slab],
    (reverse, follow): (bool, bool),
) -> Option<(f64, Vec<Dir>)> {
    let tile = s.raster().per_tile();
    let order: Vec<usize> = if reverse {
        (0..slabs.len()).rev().collect()
    } else {
        (0..slabs.len()).collect()
    };
    // per slab in laying order, per direction: (cost so far, previous slab's direction)
    let mut table: Vec<Vec<(f64, usize)>> = Vec::with_capacity(slabs.len());
    for (i, &k) in order.iter().enumerate() {
        let (t, _, prices) = &slabs[k];
        let earlier: Vec<PBox> = order[..i].iter().map(|&e| slabs[e].0).collect();
        let row: Vec<(f64, usize)> = prices
            .iter()
            .map(|&(c, n)| {
                if follow && !may_follow(across_x, *t, n, &earlier, tile) {
                    return (f64::INFINITY, 0);
                }
                if i == 0 {
                    return (c, 0);
                }
                let prev = order[i - 1];
                let (pt, _, pp) = &slabs[prev];
                // the cut between the two: the start of the later one along the axis
                let (lower, upper) = if prev < k { (prev, k) } else { (k, prev) };
                let cut = slabs[upper].1;
                table[i - 1]
                    .iter()
                    .zip(pp)
                    .enumerate()
                    .map(|(j, (&(sofar, _), &(_, m)))| {
                        let (a, b) = if lower == prev {
                            ((*pt, m), (*t, n))
                        } else {
                            ((*t, n), (*pt, m))
                        };
                        (sofar + c + entry_price(s, across_x, cut, a, b), j)
                    })
                    .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
            })
            .collect();
        table.push(row);
    }
    let last = table.last()?;
    let (mut d, &(cost, _)) = last
        .iter()
        .enumerate()
        .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0))?;
    if !cost.is_finite() {
        return None;
    }
    let mut dirs = vec![Dir::PosY; slabs.len()];
    for i in (0..order.len()).rev() {
        dirs[order[i]] = slabs[order[i]].2[d].1;
        d = table[i][d].1;
    }
    Some((cost, dirs))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
pub(crate) mod tests {
    use super::*;
    use crate::rows::TIGHT;
    use crate::shape::Ring;
    use kurbo::Point;

    /// A shape of one ring through `points`.
    pub(crate) fn poly(points: &[(f64, f64)]) -> Shape {
        Shape::from_rings(vec![Ring {
            points: points.iter().map(|&p| Point::from(p)).collect(),
        }])
    }

    /// A key in tile widths (head 12 x 14.3, shaft 20 x 2.9 with two teeth below it): the
    /// cheapest slabs cut the head off the shaft, and the shaft's slab, teeth included, is
    /// swept in rows along its length (one serpentine of columns across it would need 14
    /// U-turns); each decomposition comes in both orders.
    #[test]
    fn a_key_is_cut_at_its_head_and_its_shaft_swept_along() {
        let key = poly(&[
            (0.0, 0.0),
            (12.0, 0.0),
            (12.0, 5.7),
            (24.4, 5.7),
            (24.4, 2.9),
            (26.6, 2.9),
            (26.6, 5.7),
            (29.2, 5.7),
            (29.2, 2.0),
            (32.1, 2.0),
            (32.1, 8.6),
            (12.0, 8.6),
            (12.0, 14.3),
            (0.0, 14.3),
        ]);
        let plans = slab_plans(&key, TIGHT.priced(1.0));
        let best = &plans[0];
        assert!(best.slabs && best.cells.len() >= 2, "{best:?}");
        let head = &best.cells[0];
        assert!(
            head.rect.x0 < 0.5 && (head.rect.x1 - 12.0).abs() < 0.5,
            "{best:?}"
        );
        let shaft = &best.cells[1];
        assert!((shaft.rect.x0 - 12.0).abs() < 0.5, "{best:?}");
        assert_eq!(shaft.n, Dir::PosY, "the shaft in rows along x: {best:?}");
        assert!(
            shaft.rect.x1 > 26.6,
            "the shaft's slab reaches past both teeth: {best:?}"
        );
        assert!(shaft.rect.y0 < 3.5, "and holds them: {best:?}");
        // the same decomposition in the other order next
        let rev: Vec<_> = plans[1].cells.iter().rev().map(|c| c.rect).collect();
        let fwd: Vec<_> = best.cells.iter().map(|c| c.rect).collect();
        assert_eq!(rev, fwd);
    }

    /// A convex shape has no cut.
    #[test]
    fn a_square_has_no_slabs() {
        let s = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        assert!(slab_plans(&s, TIGHT).is_empty());
    }
}
