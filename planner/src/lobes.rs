//! Lobes beside a cell taken by the cell's own rows (issue 26; BENCHMARKS, "Where the small
//! empty parts sit", kind N): a cap decomposition ([`crate::caps`]) gives every lobe that
//! hangs off a row cell's side a cell of its own (a key's teeth below its shaft, a cat's
//! ears above its head), each joined by quarter turns, and a lobe too small for a
//! serpentine of its own is left empty or costs turns. Here the cell's box is grown to take
//! the lobes on one side of it: the grown cell is one serpentine whose rows run on into the
//! lobes (rows added beyond the cell's side, shorter, or bridging a short gap between two
//! lobes, as the row programme prices them), and the lobes' cells leave the decomposition.
//! Whether the grown cell can be laid where the cell was is the route's to decide (its fold
//! check), and whether the plan is better is the rank's.
//!
//! A lobe of cell `C` (rows across `C.n`) is another cell whose box lies wholly beside one
//! side of `C`'s box along `n` (touching it) and within `C`'s extent along the rows; the
//! grown box must not reach into a cell that stays.

use kurbo::Rect;

use crate::caps::{CapCell, CapPlan, Dir};

/// How far (tile widths) boxes may miss touching, or reach past an extent, and still count.
const SLACK: f64 = 0.25;
/// The most grown decompositions made from one decomposition.
const MAX_VARIANTS: usize = 2;

/// The extent of `r` along the rows of a cell stacked along `n` (`along`) and along `n`
/// (`across`): `((along0, along1), (across0, across1))`.
fn extents(r: Rect, rows_along_x: bool) -> ((f64, f64), (f64, f64)) {
    if rows_along_x {
        ((r.x0, r.x1), (r.y0, r.y1))
    } else {
        ((r.y0, r.y1), (r.x0, r.x1))
    }
}

/// The stacking direction across rows along x (`rows_along_x`) or along y, towards the
/// higher coordinate if `up`: a grown cell laid first starts at its lobes (its rows stacked
/// away from them), a later one ends there (stacked towards them).
fn toward(rows_along_x: bool, up: bool) -> Dir {
    match (rows_along_x, up) {
        (true, true) => Dir::PosY,
        (true, false) => Dir::NegY,
        (false, true) => Dir::PosX,
        (false, false) => Dir::NegX,
    }
}

/// True if the open boxes `a` and `b` overlap by more than [`SLACK`] in both directions.
fn overlap(a: Rect, b: Rect) -> bool {
    a.x0.max(b.x0) + SLACK < a.x1.min(b.x1) && a.y0.max(b.y0) + SLACK < a.y1.min(b.y1)
}

/// The decompositions of `plan` with one row cell's box grown over the lobes on one side
/// of it (see the module's documentation), at most [`MAX_VARIANTS`], the cells that take
/// the most lobes first; each keeps `plan`'s price and kind.
pub(crate) fn grown(plan: &CapPlan) -> Vec<CapPlan> {
    let cells = &plan.cells;
    let mut out: Vec<(usize, CapPlan)> = Vec::new();
    for (c, cell) in cells.iter().enumerate() {
        let rows_x = matches!(cell.n, Dir::PosY | Dir::NegY);
        let ((a0, a1), (b0, b1)) = extents(cell.rect, rows_x);
        for below in [true, false] {
            let lobes: Vec<usize> = cells
                .iter()
                .enumerate()
                .filter(|&(i, l)| {
                    let ((la0, la1), (lb0, lb1)) = extents(l.rect, rows_x);
                    let within = la0 >= a0 - SLACK && la1 <= a1 + SLACK;
                    let beside = if below {
                        (lb1 - b0).abs() <= SLACK
                    } else {
                        (lb0 - b1).abs() <= SLACK
                    };
                    i != c && within && beside
                })
                .map(|(i, _)| i)
                .collect();
            if lobes.is_empty() {
                continue;
            }
            let rect = lobes.iter().fold(cell.rect, |r, &i| r.union(cells[i].rect));
            // the grown box reaches into no cell that stays
            let clear = cells
                .iter()
                .enumerate()
                .all(|(i, o)| i == c || lobes.contains(&i) || !overlap(rect, o.rect));
            if !clear {
                continue;
            }
            let first = cells
                .iter()
                .enumerate()
                .filter(|(i, _)| !lobes.contains(i))
                .map(|(i, _)| i)
                .next()
                == Some(c);
            let kept: Vec<CapCell> = cells
                .iter()
                .enumerate()
                .filter(|(i, _)| !lobes.contains(i))
                .map(|(i, o)| {
                    if i == c {
                        CapCell {
                            rect,
                            n: toward(rows_x, below == first),
                            either_sign: false,
                            spans: true,
                        }
                    } else {
                        o.clone()
                    }
                })
                .collect();
            out.push((
                lobes.len(),
                CapPlan {
                    cells: kept,
                    ..plan.clone()
                },
            ));
        }
    }
    out.sort_by_key(|(n, _)| std::cmp::Reverse(*n));
    out.truncate(MAX_VARIANTS);
    out.into_iter().map(|(_, p)| p).collect()
}

/// The grown decompositions ([`grown`]) of every decomposition of the cap groups `caps`
/// (`(axis, decompositions, width)`), as one group of the same axes; None when there are
/// none.
#[allow(clippy::type_complexity)]
pub(crate) fn grown_group(
    caps: &[(f64, Vec<CapPlan>, f64)],
) -> Option<Vec<(f64, Vec<CapPlan>, f64)>> {
    let group: Vec<(f64, Vec<CapPlan>, f64)> = caps
        .iter()
        .map(|(a, plans, w)| (*a, plans.iter().flat_map(grown).collect::<Vec<_>>(), *w))
        .filter(|g| !g.1.is_empty())
        .collect();
    (!group.is_empty()).then_some(group)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn plan(cells: Vec<CapCell>) -> CapPlan {
        CapPlan {
            cells,
            cost: 5.0,
            slabs: false,
            joined: false,
        }
    }

    fn cell(x0: f64, y0: f64, x1: f64, y1: f64, n: Dir) -> CapCell {
        CapCell {
            rect: Rect::new(x0, y0, x1, y1),
            n,
            either_sign: false,
            spans: false,
        }
    }

    /// A key's cells (a shaft in rows, two teeth below it in columns, the head in columns
    /// beside it): the shaft's box grows over both teeth and not over the head; the teeth
    /// leave the decomposition, the grown cell spans.
    #[test]
    fn a_shaft_grows_over_its_teeth_not_its_head() {
        let plan = plan(vec![
            cell(0.0, 0.0, 10.0, 14.0, Dir::PosX),
            cell(10.0, 5.0, 30.0, 8.0, Dir::PosY),
            cell(20.0, 8.0, 22.0, 11.0, Dir::PosX),
            cell(26.0, 8.0, 30.0, 12.0, Dir::PosX),
        ]);
        let grown = grown(&plan);
        assert_eq!(grown.len(), 1, "{:?}", grown.len());
        for g in &grown {
            assert_eq!(g.cells.len(), 2);
            let shaft = g.cells.iter().find(|c| c.spans).unwrap();
            assert_eq!(shaft.rect, Rect::new(10.0, 5.0, 30.0, 12.0));
            assert!(g.cells.iter().any(|c| c.rect == plan.cells[0].rect));
            assert_eq!(g.cost, plan.cost);
        }
    }

    /// A lobe that would make the grown box reach into a cell that stays is not taken.
    #[test]
    fn no_growth_into_a_cell_that_stays() {
        let plan = plan(vec![
            cell(10.0, 5.0, 30.0, 8.0, Dir::PosY),
            cell(12.0, 8.0, 14.0, 11.0, Dir::PosX),
            cell(26.0, 8.0, 30.0, 12.0, Dir::PosX),
            // below the shaft between the two lobes, not touching it: the box grown over
            // the lobes would reach into it
            cell(16.0, 9.0, 24.0, 20.0, Dir::PosX),
        ]);
        assert!(grown(&plan).is_empty());
    }
}
