//! Monotone cells: the sweep (boustrophedon) decomposition of a shape into cells that every
//! horizontal line meets in one interval, the graph of which cells touch (petgraph), and the
//! orders in which one chain can visit them all (Hamiltonian paths of that graph).
//!
//! The sweep runs up the y axis of the frame it is given. Between two consecutive vertex
//! heights every horizontal line meets the shape in the same number of intervals (the
//! outlines do not cross), so the shape splits into slab pieces; a piece continues the cell
//! below it when the two touch one to one and neither end jumps by more than the given
//! step (a jump is an edge along the sweep line, where the key's shaft meets its head).

use kurbo::Point;
use petgraph::graph::{NodeIndex, UnGraph};

use crate::shape::{Ring, Shape};

/// One monotone cell.
#[derive(Clone, Debug)]
pub(crate) struct Cell {
    /// The cell as a shape (one ring: its left side upwards, its right side downwards).
    pub shape: Shape,
    /// Its area.
    #[allow(dead_code)] // kept for messages and tests
    pub area: f64,
}

/// The cells of a shape and the graph of which cells touch.
pub(crate) struct Cells {
    pub cells: Vec<Cell>,
    pub graph: UnGraph<usize, ()>,
    /// The number of jumps that split a cell (see [`decompose_merging`]).
    pub jumps: usize,
    /// The branches, in sweep order (see [`Merge`]).
    pub branches: Vec<Branch>,
}

/// A branch of the sweep: where a piece splits into several above it or several join.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Branch {
    /// The number of choices (see [`Merge::branches`]).
    pub choices: usize,
    /// True for a split in two, whose last two choices cut the cell below.
    pub cuts: bool,
}

/// Which cells a decomposition merges across its jumps and branches.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Merge<'a> {
    /// The jumps (numbered in sweep order, bit `i` for jump `i`) across which the cells are
    /// merged: where one piece continues one other but an end jumps by more than the step
    /// (a key's shaft with its bits).
    pub jumps: u32,
    /// A choice per branch, in sweep order: where a piece splits into several above it (the
    /// bottom of a hole) or several join into one (its top), 0 starts new cells, `c` goes on
    /// with the `c`-th of them (1-based). A ring's band below its hole with its left side is
    /// one L-shaped cell, monotone like the cells it joins; its band above with the right
    /// side another, and one chain fills the two, rows in one and columns in the other.
    /// Missing choices are 0.
    pub branches: &'a [usize],
}

/// A piece of one slab: the interval at the bottom and at the top of the slab.
#[derive(Clone, Copy, Debug)]
struct Piece {
    lo: (f64, f64),
    hi: (f64, f64),
    y0: f64,
    y1: f64,
}

/// The cell decomposition of a shape in the axis frame at unit tiles: ends jumping by more
/// than a tile start a new cell; cells under one tile are dropped.
pub(crate) fn cells_of(axis_shape: &Shape) -> Cells {
    decompose(axis_shape, 1.0, 1.0)
}

/// Decomposes `shape` along y into monotone cells. Ends that jump by more than `jump` start a
/// new cell; cells smaller than `min_area` are dropped (with their edges).
pub(crate) fn decompose(shape: &Shape, jump: f64, min_area: f64) -> Cells {
    decompose_merging(shape, jump, min_area, Merge::default())
}

/// [`decompose`], but the cells either side of the jumps and branches that `merge` chooses
/// are merged (see [`Merge`]). Every cell stays monotone: one piece in every slab it spans.
pub(crate) fn decompose_merging(
    shape: &Shape,
    jump: f64,
    min_area: f64,
    merge: Merge<'_>,
) -> Cells {
    let size = shape.size();
    let mut ys = shape.vertex_heights();
    ys.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * size);
    // slabs[i]: the pieces between ys[i] and ys[i + 1]
    let mut slabs: Vec<Vec<Piece>> = Vec::new();
    for w in ys.windows(2) {
        let (y0, y1) = (w[0], w[1]);
        let h = y1 - y0;
        if h <= 1e-9 * size {
            continue;
        }
        let eps = 1e-6 * h;
        let mid = shape.intervals_at(0.5 * (y0 + y1));
        let lo = shape.intervals_at(y0 + eps);
        let hi = shape.intervals_at(y1 - eps);
        let pieces = if lo.len() == mid.len() && hi.len() == mid.len() {
            lo.iter()
                .zip(&hi)
                .map(|(&l, &u)| Piece {
                    lo: l,
                    hi: u,
                    y0,
                    y1,
                })
                .collect()
        } else {
            mid.iter()
                .map(|&m| Piece {
                    lo: m,
                    hi: m,
                    y0,
                    y1,
                })
                .collect()
        };
        slabs.push(pieces);
    }
    // cell of every piece, and touching pairs of pieces of consecutive slabs
    let mut cell_of: Vec<Vec<usize>> = Vec::with_capacity(slabs.len());
    let mut members: Vec<Vec<Piece>> = Vec::new();
    let mut touches: Vec<(usize, usize)> = Vec::new();
    let mut jumps = 0usize;
    let mut branches: Vec<Branch> = Vec::new();
    for (i, slab) in slabs.iter().enumerate() {
        let touching = i > 0
            && slabs[i - 1]
                .first()
                .zip(slab.first())
                .is_some_and(|(q, p)| (q.y1 - p.y0).abs() <= 1e-9 * size);
        let meets = |q: &Piece, p: &Piece| q.hi.0 < p.lo.1 && p.lo.0 < q.hi.1;
        // below[m]: the pieces of the slab below that piece m touches
        let below: Vec<Vec<usize>> = slab
            .iter()
            .map(|p| match touching {
                true => (0..slabs[i - 1].len())
                    .filter(|&j| meets(&slabs[i - 1][j], p))
                    .collect(),
                false => Vec::new(),
            })
            .collect();
        let ups = |j: usize| -> Vec<usize> {
            (0..slab.len()).filter(|&m| below[m].contains(&j)).collect()
        };
        // cont[m]: the cell that piece m continues
        let mut cont: Vec<Option<usize>> = vec![None; slab.len()];
        let mut taken = vec![false; if i > 0 { slabs[i - 1].len() } else { 0 }];
        for (m, p) in slab.iter().enumerate() {
            if below[m].len() != 1 || ups(below[m][0]).len() != 1 {
                continue;
            }
            let j = below[m][0];
            let q = slabs[i - 1][j];
            let small = (q.hi.0 - p.lo.0).abs() <= jump && (q.hi.1 - p.lo.1).abs() <= jump;
            if !small {
                jumps += 1;
            }
            if small || (jumps <= 32 && merge.jumps & (1 << (jumps - 1)) != 0) {
                cont[m] = Some(cell_of[i - 1][j]);
                taken[j] = true;
            }
        }
        // branches: a piece below that splits into several (a hole's bottom) may go on in
        // one of them, or, split in two, be cut along either side of the gap between them
        // (its cell with it), each part going on in one; a piece that joins several (a
        // hole's top) may go on from one
        for j in 0..taken.len() {
            let up = ups(j);
            if up.len() < 2 {
                continue;
            }
            let c = merge.branches.get(branches.len()).copied().unwrap_or(0);
            let cuts = up.len() == 2;
            branches.push(Branch {
                choices: up.len() + 1 + if cuts { 2 } else { 0 },
                cuts,
            });
            let x = cell_of[i - 1][j];
            if (1..=up.len()).contains(&c) {
                let m = up[c - 1];
                if cont[m].is_none() && !taken[j] {
                    cont[m] = Some(x);
                    taken[j] = true;
                }
            } else if c > up.len() && !taken[j] && up.iter().all(|&m| cont[m].is_none()) {
                let (a, b) = (slab[up[0]], slab[up[1]]);
                let at = if c == up.len() + 1 { b.lo.0 } else { a.lo.1 };
                if let Some(y) = cut_cell(&mut members, x, at, jump) {
                    touches.push((x.min(y), x.max(y)));
                    // the cell's earlier neighbours may touch either part
                    let near: Vec<(usize, usize)> = touches
                        .iter()
                        .filter(|t| (t.0 == x || t.1 == x) && t.0 != y && t.1 != y)
                        .map(|&(u, v)| {
                            if u == x {
                                (v.min(y), v.max(y))
                            } else {
                                (u.min(y), u.max(y))
                            }
                        })
                        .collect();
                    touches.extend(near);
                    cont[up[0]] = Some(x);
                    cont[up[1]] = Some(y);
                    taken[j] = true;
                }
            }
        }
        for m in 0..slab.len() {
            if below[m].len() < 2 {
                continue;
            }
            let c = merge.branches.get(branches.len()).copied().unwrap_or(0);
            branches.push(Branch {
                choices: below[m].len() + 1,
                cuts: false,
            });
            if let Some(&j) = c.checked_sub(1).and_then(|c| below[m].get(c)) {
                if cont[m].is_none() && !taken[j] {
                    cont[m] = Some(cell_of[i - 1][j]);
                    taken[j] = true;
                }
            }
        }
        let mut ids = Vec::with_capacity(slab.len());
        for (m, p) in slab.iter().enumerate() {
            let id = match cont[m] {
                Some(id) => id,
                None => {
                    members.push(Vec::new());
                    members.len() - 1
                }
            };
            for &j in &below[m] {
                let other = cell_of[i - 1][j];
                if other != id {
                    touches.push((other.min(id), other.max(id)));
                }
            }
            members[id].push(*p);
            ids.push(id);
        }
        cell_of.push(ids);
    }
    // rings, areas; drop tiny cells
    let mut keep: Vec<Option<usize>> = vec![None; members.len()];
    let mut cells = Vec::new();
    for (id, ps) in members.iter().enumerate() {
        let area: f64 = ps
            .iter()
            .map(|p| 0.5 * ((p.lo.1 - p.lo.0) + (p.hi.1 - p.hi.0)) * (p.y1 - p.y0))
            .sum();
        if area < min_area {
            continue;
        }
        let mut pts: Vec<Point> = Vec::with_capacity(4 * ps.len());
        for p in ps {
            pts.push(Point::new(p.lo.0, p.y0));
            pts.push(Point::new(p.hi.0, p.y1));
        }
        for p in ps.iter().rev() {
            pts.push(Point::new(p.hi.1, p.y1));
            pts.push(Point::new(p.lo.1, p.y0));
        }
        pts.dedup();
        keep[id] = Some(cells.len());
        cells.push(Cell {
            shape: Shape::from_rings(vec![Ring { points: pts }]),
            area,
        });
    }
    let mut graph: UnGraph<usize, ()> = UnGraph::with_capacity(cells.len(), touches.len());
    for i in 0..cells.len() {
        graph.add_node(i);
    }
    touches.sort_unstable();
    touches.dedup();
    for (a, b) in touches {
        if let (Some(a), Some(b)) = (keep[a], keep[b]) {
            graph.add_edge(NodeIndex::new(a), NodeIndex::new(b), ());
        }
    }
    Cells {
        cells,
        graph,
        jumps,
        branches,
    }
}

/// Cuts every piece of cell `x` along the sweep line at `at` (each part at least `margin`
/// wide at both ends of every piece): `x` keeps the parts below `at`, a new cell, returned,
/// takes those above. None, and nothing cut, if some piece does not reach across `at`.
fn cut_cell(members: &mut Vec<Vec<Piece>>, x: usize, at: f64, margin: f64) -> Option<usize> {
    let ps = members.get(x)?;
    let across = |iv: (f64, f64)| iv.0 + margin <= at && at + margin <= iv.1;
    if ps.is_empty() || !ps.iter().all(|p| across(p.lo) && across(p.hi)) {
        return None;
    }
    let (low, high): (Vec<Piece>, Vec<Piece>) = ps
        .iter()
        .map(|p| {
            (
                Piece {
                    lo: (p.lo.0, at),
                    hi: (p.hi.0, at),
                    ..*p
                },
                Piece {
                    lo: (at, p.lo.1),
                    hi: (at, p.hi.1),
                    ..*p
                },
            )
        })
        .unzip();
    members[x] = low;
    members.push(high);
    Some(members.len() - 1)
}

impl Cells {
    /// Hamiltonian paths of the cell graph (each cell once, consecutive cells touching), by
    /// depth-first search from every cell; at most `max_paths`, and the search gives up after
    /// `max_steps` extensions (the problem is NP-complete; cell graphs are small).
    pub(crate) fn orders(&self, max_paths: usize, max_steps: usize) -> Vec<Vec<usize>> {
        let n = self.cells.len();
        let mut out = Vec::new();
        let mut steps = 0usize;
        let mut path = Vec::with_capacity(n);
        let mut used = vec![false; n];
        for s in 0..n {
            path.push(s);
            used[s] = true;
            self.extend(
                &mut path, &mut used, &mut out, max_paths, &mut steps, max_steps,
            );
            used[s] = false;
            path.pop();
        }
        out
    }

    fn extend(
        &self,
        path: &mut Vec<usize>,
        used: &mut [bool],
        out: &mut Vec<Vec<usize>>,
        max_paths: usize,
        steps: &mut usize,
        max_steps: usize,
    ) {
        if out.len() >= max_paths || *steps >= max_steps {
            return;
        }
        *steps += 1;
        if path.len() == used.len() {
            out.push(path.clone());
            return;
        }
        let last = NodeIndex::new(path[path.len() - 1]);
        let mut next: Vec<usize> = self.graph.neighbors(last).map(|v| v.index()).collect();
        next.sort_unstable();
        for v in next {
            if !used[v] {
                used[v] = true;
                path.push(v);
                self.extend(path, used, out, max_paths, steps, max_steps);
                path.pop();
                used[v] = false;
            }
        }
    }

    /// The number of separate groups of touching cells.
    pub(crate) fn components(&self) -> usize {
        petgraph::algo::connected_components(&self.graph)
    }

    /// The largest number of cells one cell touches, and that cell.
    pub(crate) fn max_degree(&self) -> (usize, usize) {
        self.graph
            .node_indices()
            .map(|v| (self.graph.neighbors(v).count(), v.index()))
            .max()
            .unwrap_or((0, 0))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn poly(points: &[(f64, f64)]) -> Ring {
        Ring {
            points: points.iter().map(|&p| Point::from(p)).collect(),
        }
    }

    #[test]
    fn square_with_a_hole_is_four_cells_in_a_cycle() {
        let outer = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        // a hole wound the other way
        let hole = poly(&[(4.0, 3.0), (4.0, 7.0), (6.0, 7.0), (6.0, 3.0)]);
        let c = decompose(&Shape::from_rings(vec![outer, hole]), 0.5, 0.0);
        assert_eq!(c.cells.len(), 4);
        assert_eq!(c.graph.edge_count(), 4);
        let total: f64 = c.cells.iter().map(|c| c.area).sum();
        assert!((total - 92.0).abs() < 1e-6, "{total}");
        // a 4-cycle has 8 Hamiltonian paths (4 starts x 2 ways)
        assert_eq!(c.orders(100, 10_000).len(), 8);
        assert_eq!(c.components(), 1);
    }

    /// Around a hole: the split below it can go on in one side (an L-shaped cell) or cut
    /// the cell below along a side of the hole (a pinwheel of three cells, each reaching
    /// the outline at both ends of its rows); the area is kept and every cell is monotone.
    #[test]
    fn a_hole_merges_or_cuts_into_monotone_cells() {
        let outer = poly(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]);
        let hole = poly(&[(4.0, 3.0), (4.0, 7.0), (6.0, 7.0), (6.0, 3.0)]);
        let s = Shape::from_rings(vec![outer, hole]);
        let plain = decompose(&s, 0.5, 0.0);
        // the split below the hole (2 sides: none, either, two cuts), the join above it
        let choices: Vec<usize> = plain.branches.iter().map(|b| b.choices).collect();
        assert_eq!(choices, vec![5, 3]);
        let area = |c: &Cells| c.cells.iter().map(|c| c.area).sum::<f64>();
        let merged = decompose_merging(
            &s,
            0.5,
            0.0,
            Merge {
                jumps: 0,
                branches: &[1, 2],
            },
        );
        assert_eq!(merged.cells.len(), 2);
        assert!((area(&merged) - 92.0).abs() < 1e-6);
        // cut along the hole's left side: below-left with the left side, below-right with
        // the right side, the top alone
        let cut = decompose_merging(
            &s,
            0.5,
            0.0,
            Merge {
                jumps: 0,
                branches: &[4, 0],
            },
        );
        assert_eq!(cut.cells.len(), 3, "{:?}", cut.cells);
        assert!((area(&cut) - 92.0).abs() < 1e-6);
        assert_eq!(cut.graph.edge_count(), 3);
        for c in &cut.cells {
            assert!(c.shape.max_pieces() <= 1, "{:?}", c.shape.bbox());
            assert!((c.shape.area() - c.area).abs() < 1e-6);
        }
        let b = cut.cells.iter().map(|c| c.shape.bbox()).collect::<Vec<_>>();
        assert!(
            b.iter().any(|r| r.x0 == 0.0 && r.x1 == 4.0 && r.y1 == 7.0),
            "{b:?}"
        );
    }

    #[test]
    fn a_jump_splits_a_cell_and_tiny_cells_drop() {
        // an L: a wide foot and a narrow post; the sweep meets one interval everywhere
        let l = poly(&[
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 2.0),
            (2.0, 2.0),
            (2.0, 10.0),
            (0.0, 10.0),
        ]);
        let s = Shape::from_rings(vec![l]);
        assert_eq!(decompose(&s, 100.0, 0.0).cells.len(), 1);
        let c = decompose(&s, 1.0, 0.0);
        assert_eq!(c.cells.len(), 2);
        assert_eq!(c.orders(10, 1000).len(), 2);
        assert_eq!(decompose(&s, 1.0, 17.0).cells.len(), 1);
    }

    /// Two squares one above the other with a gap: the slab between is empty.
    #[test]
    fn separate_parts_are_separate_components() {
        let a = poly(&[(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]);
        let b = poly(&[(0.0, 6.0), (4.0, 6.0), (4.0, 9.0), (0.0, 9.0)]);
        let c = decompose(&Shape::from_rings(vec![a, b]), 1.0, 0.0);
        assert_eq!(c.cells.len(), 2);
        assert_eq!(c.components(), 2);
        assert!(c.orders(10, 100).is_empty());
    }
}
