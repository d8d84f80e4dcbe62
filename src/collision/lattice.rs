//! Exact overlap of tiles in lattice poses (every fold complete or not started).
//!
//! At quarter-turn headings every octagon has the same four face normals (0, 45, 90, 135
//! degrees), so two tiles overlap with positive area exactly when their centre difference is
//! strictly inside `w` along both axes and `sqrt2 w` along both diagonals. With centres held
//! exactly ([`Surd`]) the test is exact: touching is never mistaken for overlap.

use rustc_hash::FxHashMap;

use crate::exact::{ExactPoint, ExactPose, Surd};

use super::Collision;

/// Whether two tiles with centres `a` and `b` overlap with positive area (touching is not
/// overlap).
pub(crate) fn lattice_overlap(a: ExactPoint, b: ExactPoint) -> bool {
    let d = b - a;
    let w = Surd::new(2, 0); // w in half widths
    let diag = Surd::new(0, 4); // sqrt2 w
    d.x.abs() < w && d.y.abs() < w && (d.x + d.y).abs() < diag && (d.x - d.y).abs() < diag
}

/// Whether two centres are so far apart on an axis or a diagonal that the tiles cannot
/// overlap, in `f64`: the margin (`1e-6 w`) lies far above the rounding of centres up to
/// `2e7 w` from the origin (`4e-9 w`), so a pair let through is decided exactly.
fn clearly_apart(a: (f64, f64), b: (f64, f64)) -> bool {
    const AXIS: f64 = 1.0 + 1e-6;
    const DIAGONAL: f64 = std::f64::consts::SQRT_2 + 1e-6;
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    dx.abs() > AXIS || dy.abs() > AXIS || (dx + dy).abs() > DIAGONAL || (dx - dy).abs() > DIAGONAL
}

/// No tile.
const NONE: u32 = u32::MAX;

/// Cells of one tile width, each with the list of tiles whose centre lies in it (linked through
/// `next`, newest first). A flat array over the centres' bounding box when that box is not much
/// larger than the chain (a folded shape), else a hash map of the occupied cells (a chain that
/// runs far along a diagonal).
struct Cells {
    x0: i64,
    y0: i64,
    columns: i64,
    rows: i64,
    flat: Vec<u32>,
    sparse: FxHashMap<(i64, i64), u32>,
    next: Vec<u32>,
}

impl Cells {
    fn new(cells: &[(i64, i64)]) -> Cells {
        let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for &(x, y) in cells {
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        let (columns, rows) = ((x1 - x0 + 1).max(0), (y1 - y0 + 1).max(0));
        let flat_ok = columns
            .checked_mul(rows)
            .is_some_and(|a| a <= 4 * cells.len() as i64 + 4096);
        Cells {
            x0,
            y0,
            columns,
            rows,
            flat: if flat_ok {
                vec![NONE; (columns * rows) as usize]
            } else {
                Vec::new()
            },
            sparse: FxHashMap::default(),
            next: vec![NONE; cells.len()],
        }
    }

    /// The first tile in cell `(x, y)`, or [`NONE`].
    fn head(&self, x: i64, y: i64) -> u32 {
        if self.flat.is_empty() {
            return self.sparse.get(&(x, y)).copied().unwrap_or(NONE);
        }
        let (cx, cy) = (x - self.x0, y - self.y0);
        if cx < 0 || cy < 0 || cx >= self.columns || cy >= self.rows {
            return NONE;
        }
        self.flat[(cy * self.columns + cx) as usize]
    }

    fn insert(&mut self, x: i64, y: i64, j: u32) {
        let slot = if self.flat.is_empty() {
            self.sparse.entry((x, y)).or_insert(NONE)
        } else {
            &mut self.flat[((y - self.y0) * self.columns + (x - self.x0)) as usize]
        };
        self.next[j as usize] = *slot;
        *slot = j;
    }
}

/// The first pair of tiles (by the later tile's index, then the earlier one's) that overlap
/// in the final shape `poses`, exactly. Tiles are found through cells of one width (overlapping
/// centres are less than one width apart on both axes, so they sit in the same or neighbouring
/// cells); the test itself is exact, on the lattice coordinates.
pub(crate) fn final_overlap(poses: &[ExactPose]) -> Option<Collision> {
    let centres: Vec<(f64, f64)> = poses.iter().map(|p| p.centre.to_f64(1.0)).collect();
    let cell: Vec<(i64, i64)> = centres
        .iter()
        .map(|&(x, y)| (x.floor() as i64, y.floor() as i64))
        .collect();
    let mut cells = Cells::new(&cell);
    for (j, p) in poses.iter().enumerate() {
        let (cx, cy) = cell[j];
        let mut hit: Option<usize> = None;
        for gy in cy - 1..=cy + 1 {
            for gx in cx - 1..=cx + 1 {
                let mut i = cells.head(gx, gy);
                while i != NONE {
                    if !clearly_apart(centres[i as usize], centres[j])
                        && lattice_overlap(poses[i as usize].centre, p.centre)
                    {
                        hit = Some(hit.map_or(i as usize, |h| h.min(i as usize)));
                    }
                    i = cells.next[i as usize];
                }
            }
        }
        if let Some(i) = hit {
            return Some(Collision {
                joint: None,
                angle_deg: 90.0,
                time: None,
                tiles: (i, j),
            });
        }
        cells.insert(cx, cy, j as u32);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{kinematics, FoldWord};

    #[test]
    fn ring_touches_and_five_overlap() {
        let ring = kinematics::final_poses(&FoldWord::parse("LLL").unwrap());
        assert_eq!(final_overlap(&ring), None);
        let five = kinematics::final_poses(&FoldWord::parse("LLLL").unwrap());
        let c = final_overlap(&five).unwrap();
        assert_eq!(c.tiles, (0, 4));
        let tight = kinematics::final_poses(&FoldWord::parse("SSLLSS").unwrap());
        assert_eq!(final_overlap(&tight), None);
    }

    /// Every pair, no cells: the reference.
    fn all_pairs(poses: &[ExactPose]) -> Option<(usize, usize)> {
        (0..poses.len()).find_map(|j| {
            (0..j)
                .find(|&i| lattice_overlap(poses[i].centre, poses[j].centre))
                .map(|i| (i, j))
        })
    }

    #[test]
    fn cells_find_the_pair_a_plain_scan_finds() {
        // random words (some folded tight, some running along a diagonal, which takes the
        // sparse cells): the same first pair as the scan of every pair
        let mut next = super::super::xorshift(0x9E37_79B9_7F4A_7C15);
        let mut overlapped = 0;
        for round in 0..300 {
            let n = 2 + (round % 90);
            let folds: Vec<crate::Fold> = (0..n)
                .map(|i| {
                    match (round % 3, next() % 6) {
                        (0, _) => [crate::Fold::L, crate::Fold::R][i % 2], // staircase
                        (_, 0 | 1) => crate::Fold::L,
                        (_, 2) => crate::Fold::R,
                        _ => crate::Fold::S,
                    }
                })
                .collect();
            let poses = kinematics::final_poses(&FoldWord::from_folds(folds));
            let got = final_overlap(&poses).map(|c| c.tiles);
            assert_eq!(got, all_pairs(&poses), "round {round}");
            overlapped += usize::from(got.is_some());
        }
        assert!(overlapped > 30 && overlapped < 270, "{overlapped}");
    }

    #[test]
    fn long_diagonal_takes_sparse_cells() {
        let diagonal: Vec<(i64, i64)> = (0..500).map(|i| (i, i)).collect();
        assert!(Cells::new(&diagonal).flat.is_empty());
        let square: Vec<(i64, i64)> = (0..500).map(|i| (i % 20, i / 20)).collect();
        assert_eq!(Cells::new(&square).flat.len(), 500);
        // the staircase LRLR... runs along a diagonal
        let stairs = FoldWord::from_folds(
            (0..10_000)
                .map(|i| [crate::Fold::L, crate::Fold::R][i % 2])
                .collect(),
        );
        let cells: Vec<(i64, i64)> = kinematics::final_poses(&stairs)
            .iter()
            .map(|p| {
                let (x, y) = p.centre.to_f64(1.0);
                (x.floor() as i64, y.floor() as i64)
            })
            .collect();
        assert!(Cells::new(&cells).flat.is_empty());
    }

    #[test]
    fn neighbours_touch() {
        let straight = kinematics::final_poses(&FoldWord::parse("SS").unwrap());
        assert!(!lattice_overlap(straight[0].centre, straight[1].centre));
        assert!(lattice_overlap(straight[0].centre, straight[0].centre));
    }
}
