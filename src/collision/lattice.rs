//! Exact overlap of tiles in lattice poses (every fold complete or not started).
//!
//! At quarter-turn headings every octagon has the same four face normals (0, 45, 90, 135
//! degrees), so two tiles overlap with positive area exactly when their centre difference is
//! strictly inside `w` along both axes and `sqrt2 w` along both diagonals. With centres held
//! exactly ([`Surd`]) the test is exact: touching is never mistaken for overlap.

use std::collections::HashMap;

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

/// The first pair of tiles (by the later tile's index, then the earlier one's) that overlap
/// in the final shape `poses`, exactly.
pub fn final_overlap(poses: &[ExactPose]) -> Option<Collision> {
    let cell = |p: &ExactPose| -> (i64, i64) {
        let (x, y) = p.centre.to_f64(1.0);
        (x.floor() as i64, y.floor() as i64)
    };
    let mut grid: HashMap<(i64, i64), Vec<u32>> = HashMap::with_capacity(poses.len());
    for (j, p) in poses.iter().enumerate() {
        let (cx, cy) = cell(p);
        let mut hit: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(cx + dx, cy + dy)) {
                    for &i in list {
                        if lattice_overlap(poses[i as usize].centre, p.centre) {
                            hit = Some(hit.map_or(i as usize, |h| h.min(i as usize)));
                        }
                    }
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
        grid.entry((cx, cy)).or_default().push(j as u32);
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

    #[test]
    fn neighbours_touch() {
        let straight = kinematics::final_poses(&FoldWord::parse("SS").unwrap());
        assert!(!lattice_overlap(straight[0].centre, straight[1].centre));
        assert!(lattice_overlap(straight[0].centre, straight[0].centre));
    }
}
