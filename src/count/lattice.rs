//! Placed tiles as exact lattice points, seen from the tile whose joint folds.
//!
//! Final tile centres are integer combinations of `w` and `w/sqrt2` ([`crate::exact`]) and
//! headings are quarter turns, so the offset of a placed tile from the folding tile, turned
//! into that tile's frame (and mirrored for a right fold), is an exact lattice point: the key
//! of the first-hit memo ([`super::first_hit`]).

use crate::exact::{ExactPoint, ExactPose, QuarterTurns, Surd};
use crate::kinematics::next_exact_pose;
use crate::Fold;

/// The offset of the tile centred at `fixed` from the tile at `at`, in the frame of `at`
/// (centre at the origin, chain along +x), mirrored (y negated) when the fold is to the
/// right, so that every fold is seen as a left fold. (Turned with integer signs rather than a
/// `match` on the heading: this runs in the search's inner loop.)
#[inline]
pub(super) fn canonical_offset(fixed: ExactPoint, at: ExactPose, fold: Fold) -> ExactPoint {
    // cos and sin of the heading: turning back by it maps (x, y) to (c x + s y, c y - s x)
    const COS_SIN: [(i64, i64); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
    let (c, s) = COS_SIN[usize::from(at.heading.get() & 3)];
    let m = if fold == Fold::R { -1 } else { 1 };
    let d = fixed - at.centre;
    let turn =
        |p: Surd, q: Surd, sp: i64, sq: i64| Surd::new(sp * p.a + sq * q.a, sp * p.b + sq * q.b);
    ExactPoint::new(turn(d.x, d.y, c, s), turn(d.y, d.x, m * c, -m * s))
}

/// The pose after each letter from each heading, from [`next_exact_pose`]: a table, so that
/// placing a tile in the search costs a lookup and four additions.
#[derive(Clone, Copy, Debug)]
pub(super) struct Steps {
    /// Per heading and letter (S, L, R): the pose after it from a tile at the origin.
    after: [[ExactPose; 3]; 4],
    /// The same centre offsets in `f32` (tile widths), for screening.
    delta: [[(f32, f32); 3]; 4],
}

impl Steps {
    /// The table.
    pub fn new() -> Steps {
        let mut after = [[ExactPose::default(); 3]; 4];
        let mut delta = [[(0.0, 0.0); 3]; 4];
        for h in 0..4 {
            let from = ExactPose {
                centre: ExactPoint::ORIGIN,
                heading: QuarterTurns::new(h as i64),
            };
            for f in Fold::ALL {
                let to = next_exact_pose(from, f);
                let (x, y) = to.centre.to_f64(1.0);
                after[h][f as usize] = to;
                delta[h][f as usize] = (x as f32, y as f32);
            }
        }
        Steps { after, delta }
    }

    /// The pose of the tile after `pose` across a joint folded `f`.
    #[inline]
    pub fn next(&self, pose: ExactPose, f: Fold) -> ExactPose {
        let step = self.after[usize::from(pose.heading.get() & 3)][f as usize];
        ExactPose {
            centre: pose.centre + step.centre,
            heading: step.heading,
        }
    }

    /// The centre offset of that step in `f32`, from a tile heading `pose.heading` (each
    /// within 3e-8 w of the exact one).
    #[inline]
    pub fn delta(&self, pose: ExactPose, f: Fold) -> (f32, f32) {
        self.delta[usize::from(pose.heading.get() & 3)][f as usize]
    }
}

/// A lattice point packed into one integer (16 bits per coefficient). Exact for coefficients
/// within `i16`: offsets in a chain of `n` tiles have coefficients of at most `4 n` half widths
/// (the search stops at [`super::MAX_COUNT_TILES`] = 40 tiles).
pub(super) fn pack(p: ExactPoint) -> u64 {
    [p.x.a, p.x.b, p.y.a, p.y.b]
        .iter()
        .fold(0u64, |acc, &c| (acc << 16) | u64::from(c as i16 as u16))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::final_poses;
    use crate::FoldWord;

    fn poses(w: &str) -> Vec<ExactPose> {
        final_poses(&FoldWord::parse(w).unwrap())
    }

    #[test]
    fn offsets_are_seen_from_the_folding_tile() {
        let behind = ExactPoint::new(Surd::new(-2, 0), Surd::ZERO);
        // after a straight joint the previous tile is one width behind, whatever the heading
        for w in ["S", "LS", "LLS", "RRRS"] {
            let p = poses(w);
            let n = p.len() - 1;
            for f in [Fold::L, Fold::R] {
                assert_eq!(canonical_offset(p[n - 1].centre, p[n], f), behind, "{w}");
            }
        }
        // after a left fold it sits at (-1/sqrt2, +1/sqrt2); a right fold mirrors that
        let p = poses("SL");
        let l = canonical_offset(p[1].centre, p[2], Fold::L);
        assert_eq!(l, ExactPoint::new(Surd::new(0, -2), Surd::new(0, 2)));
        let r = canonical_offset(p[1].centre, p[2], Fold::R);
        assert_eq!(r, ExactPoint::new(Surd::new(0, -2), Surd::new(0, -2)));
    }

    #[test]
    fn steps_follow_the_kinematics() {
        let steps = Steps::new();
        for w in ["SLLRSSRLLLS", "RRSLSRRRLSS"] {
            let p = poses(w);
            let word = FoldWord::parse(w).unwrap();
            for (j, &f) in word.folds().iter().enumerate() {
                assert_eq!(steps.next(p[j], f), p[j + 1]);
                let (dx, dy) = steps.delta(p[j], f);
                let (x0, y0) = p[j].centre.to_f64(1.0);
                let (x1, y1) = p[j + 1].centre.to_f64(1.0);
                assert!((f64::from(dx) - (x1 - x0)).abs() < 1e-7);
                assert!((f64::from(dy) - (y1 - y0)).abs() < 1e-7);
            }
        }
    }

    #[test]
    fn canonical_offsets_turn_back_every_heading() {
        // a tile ahead-left of the folding tile stays ahead-left whatever the heading
        let ahead = ExactPoint::new(Surd::new(4, 1), Surd::new(2, -1));
        for h in 0..4 {
            let at = ExactPose {
                centre: ExactPoint::new(Surd::new(3, -2), Surd::new(-5, 4)),
                heading: QuarterTurns::new(h),
            };
            let fixed = at.transform(ahead);
            assert_eq!(canonical_offset(fixed, at, Fold::L), ahead);
            let mirrored = ExactPoint::new(ahead.x, -ahead.y);
            assert_eq!(canonical_offset(fixed, at, Fold::R), mirrored);
        }
    }

    #[test]
    fn packing_keeps_points_apart() {
        let pts = [
            ExactPoint::new(Surd::new(1, -1), Surd::new(0, 0)),
            ExactPoint::new(Surd::new(-1, 1), Surd::new(0, 0)),
            ExactPoint::new(Surd::new(0, 0), Surd::new(1, -1)),
            ExactPoint::new(Surd::new(-80, 160), Surd::new(-160, 80)),
        ];
        for (i, a) in pts.iter().enumerate() {
            for (j, b) in pts.iter().enumerate() {
                assert_eq!(pack(*a) == pack(*b), i == j);
            }
        }
    }
}
