//! Forward kinematics of the tile chain: exact final poses and poses at any fold angles.
//!
//! Tile 0 sits at the origin heading +x. A straight joint puts the next centre `w` ahead; a
//! fold turns everything after the joint by 90 degrees about the hinge, which puts the next
//! centre at `(w/sqrt2, +-w/sqrt2)` in the old frame. [`final_poses`] does this exactly
//! (see [`crate::exact`]); [`poses_at_angles`] composes `f64` transforms for arbitrary signed
//! joint angles (positive = left), and the two agree at the final angles.

use std::f64::consts::FRAC_PI_2;

use crate::exact::{ExactPoint, ExactPose, Surd};
use crate::pose::wrap_angle;
use crate::{Fold, FoldWord, Octagon, Pose};

/// The offset from one tile centre to the next in the first tile's frame, exactly.
pub(crate) fn exact_step(fold: Fold) -> ExactPoint {
    match fold {
        Fold::S => ExactPoint::new(Surd::new(2, 0), Surd::ZERO),
        Fold::L => ExactPoint::new(Surd::new(0, 2), Surd::new(0, 2)),
        Fold::R => ExactPoint::new(Surd::new(0, 2), Surd::new(0, -2)),
    }
}

/// The exact final pose of every tile of a designed chain, all folds made.
pub(crate) fn final_poses(word: &FoldWord) -> Vec<ExactPose> {
    let mut poses = Vec::with_capacity(word.tiles());
    let mut pose = ExactPose::default();
    poses.push(pose);
    for &fold in word.folds() {
        pose = next_exact_pose(pose, fold);
        poses.push(pose);
    }
    poses
}

/// The pose of the tile after a joint with fold `fold`, exactly.
pub(crate) fn next_exact_pose(pose: ExactPose, fold: Fold) -> ExactPose {
    ExactPose {
        centre: pose.transform(exact_step(fold)),
        heading: pose.heading.turned(fold.quarter_turns() as i64),
    }
}

/// The world position of the hinge of joint `joint` (between tiles `joint` and `joint + 1`),
/// exactly, given the pose of tile `joint`. `None` for a straight joint.
pub(crate) fn exact_hinge(pose: ExactPose, fold: Fold) -> Option<ExactPoint> {
    Octagon::exact_hinge(fold).map(|h| pose.transform(h))
}

/// The final signed angle of each joint: +pi/2 for L, -pi/2 for R, 0 for S.
pub(crate) fn final_angles(word: &FoldWord) -> Vec<f64> {
    word.folds()
        .iter()
        .map(|f| f.quarter_turns() as f64 * FRAC_PI_2)
        .collect()
}

/// The pose of the next tile relative to a tile whose joint is turned by `angle` radians
/// (positive = left), for tiles of width `w`: a rotation about the hinge on the turning side.
pub(crate) fn joint_transform(angle: f64, w: f64) -> Pose {
    let o = Octagon::new(w);
    let left = angle >= 0.0;
    let (hx, hy) = o.hinge(left);
    // The next centre sits at (w/2, -hy) from the hinge when straight; turn that by `angle`.
    let (s, c) = angle.sin_cos();
    let (dx, dy) = (0.5 * w, -hy);
    Pose::new(hx + c * dx - s * dy, hy + s * dx + c * dy, angle)
}

/// The pose of every tile for joint angles `angles` (one per joint, radians, positive = left,
/// each within `[-pi/2, pi/2]`), composing `f64` transforms from tile 0 at the origin.
pub(crate) fn poses_at_angles(angles: &[f64], w: f64) -> Vec<Pose> {
    let mut poses = Vec::with_capacity(angles.len() + 1);
    for_each_pose_at_angles(angles, w, |p| poses.push(p));
    poses
}

/// The poses of [`poses_at_angles`] handed to `each` in tile order, without storing them:
/// the same numbers bit for bit (`Pose::then` of [`joint_transform`]s), but a joint's
/// transform and a heading's sine and cosine are computed again only when the angle changes,
/// which along a straight run it does not.
pub(crate) fn for_each_pose_at_angles(angles: &[f64], w: f64, mut each: impl FnMut(Pose)) {
    each(Pose::IDENTITY);
    compose_poses(Pose::IDENTITY, angles, w, each);
}

/// The poses of the tiles after one at `pose`, whose joints turn by `angles`, handed to
/// `each` in order: from tile 0's pose, [`for_each_pose_at_angles`] less tile 0; from a
/// later tile's pose, the same numbers as from tile 0.
pub(crate) fn compose_poses(mut pose: Pose, angles: &[f64], w: f64, mut each: impl FnMut(Pose)) {
    // the last joint angle and its transform, the last heading and its sine and cosine
    let mut joint: Option<(u64, Pose)> = None;
    let mut heading: Option<(u64, f64, f64)> = None;
    for &a in angles {
        let step = match joint {
            Some((bits, t)) if bits == a.to_bits() => t,
            _ => {
                let t = joint_transform(a, w);
                joint = Some((a.to_bits(), t));
                t
            }
        };
        let (s, c) = match heading {
            Some((bits, s, c)) if bits == pose.angle.to_bits() => (s, c),
            _ => {
                let (s, c) = pose.angle.sin_cos();
                heading = Some((pose.angle.to_bits(), s, c));
                (s, c)
            }
        };
        // Pose::then with the sine and cosine above (Pose::transform_point's arithmetic)
        pose = Pose::new(
            pose.x + c * step.x - s * step.y,
            pose.y + s * step.x + c * step.y,
            wrap_angle(pose.angle + step.angle),
        );
        each(pose);
    }
}

impl FoldWord {
    /// The exact final pose of every tile, all folds made: tile 0 at the origin heading +x; a
    /// straight joint puts the next centre `w` ahead, a fold the next centre at
    /// `(w/sqrt2, +-w/sqrt2)` in the tile's frame, exactly ([`ExactPose`]).
    ///
    /// ```
    /// use foldchain::FoldWord;
    ///
    /// // a tight U-turn: the return row runs sqrt2 * w from the first, exactly
    /// let poses = FoldWord::parse("SSLLSS").unwrap().final_poses();
    /// let w = 30.0;
    /// let pitch = poses[4].centre.y.to_f64(w) - poses[2].centre.y.to_f64(w);
    /// assert!((pitch - 2f64.sqrt() * w).abs() < 1e-12);
    /// ```
    pub fn final_poses(&self) -> Vec<ExactPose> {
        final_poses(self)
    }

    /// The final signed angle of each joint, radians: +pi/2 for L, -pi/2 for R, 0 for S (the
    /// angles [`Pose::chain_at_angles`] takes).
    pub fn final_angles(&self) -> Vec<f64> {
        final_angles(self)
    }
}

impl Pose {
    /// The pose of every tile of a chain of tiles of width `w` whose joints turn by `angles`
    /// (one per joint, radians, positive = left, each within `[-pi/2, pi/2]`), composing
    /// `f64` transforms from tile 0 at the origin heading +x. At a word's
    /// [`FoldWord::final_angles`](crate::FoldWord::final_angles) they agree with its exact
    /// [`FoldWord::final_poses`](crate::FoldWord::final_poses).
    ///
    /// ```
    /// use foldchain::{FoldWord, Pose};
    ///
    /// let word = FoldWord::parse("SLLS").unwrap();
    /// let poses = Pose::chain_at_angles(&word.final_angles(), 30.0);
    /// let exact = word.final_poses();
    /// assert_eq!(poses.len(), 5);
    /// assert!((poses[4].y - exact[4].centre.y.to_f64(30.0)).abs() < 1e-9);
    /// ```
    pub fn chain_at_angles(angles: &[f64], w: f64) -> Vec<Pose> {
        poses_at_angles(angles, w)
    }

    /// The poses of [`Pose::chain_at_angles`] handed to `each` in tile order, without storing
    /// them (the same numbers bit for bit; a joint's transform and a heading's sine and cosine
    /// are computed again only when the angle changes).
    pub fn for_each_at_angles(angles: &[f64], w: f64, each: impl FnMut(Pose)) {
        for_each_pose_at_angles(angles, w, each)
    }

    /// The poses of the tiles after one at this pose, whose joints turn by `angles`, handed to
    /// `each` in order: from tile 0's pose, [`Pose::for_each_at_angles`] less tile 0; from a
    /// later tile's pose, the same numbers as from tile 0.
    pub fn compose_at_angles(self, angles: &[f64], w: f64, each: impl FnMut(Pose)) {
        compose_poses(self, angles, w, each)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::SQRT_2;

    fn word(s: &str) -> FoldWord {
        FoldWord::parse(s).unwrap()
    }

    fn centre(p: &ExactPose, w: f64) -> (f64, f64) {
        p.centre.to_f64(w)
    }

    #[test]
    fn one_fold_offsets_by_w_over_sqrt2() {
        let w = 30.0;
        let p = final_poses(&word("L"));
        let (x, y) = centre(&p[1], w);
        assert!((x - w / SQRT_2).abs() < 1e-12 && (y - w / SQRT_2).abs() < 1e-12);
        assert_eq!(p[1].heading.get(), 1);
    }

    #[test]
    fn tight_u_turn_pitch_is_sqrt2_w() {
        // S S L L S S: tiles 3 and 4 fold a tight U-turn; the return row is sqrt2 w away.
        let w = 30.0;
        let p = final_poses(&word("SSLLSS"));
        let (x2, y2) = centre(&p[2], w);
        let (x4, y4) = centre(&p[4], w);
        assert!((x4 - x2).abs() < 1e-12);
        assert!((y4 - y2 - SQRT_2 * w).abs() < 1e-12, "pitch {}", y4 - y2);
        assert_eq!(p[4].heading.get(), 2);
        // exactly: the y difference is 2/sqrt2 * ... i.e. b = 4 half widths over sqrt2
        assert_eq!((p[4].centre.y - p[2].centre.y), Surd::new(0, 4));
        // and the f64 kinematics at the final angles say the same
        let f = poses_at_angles(&final_angles(&word("SSLLSS")), w);
        assert!((f[4].y - f[2].y - SQRT_2 * w).abs() < 1e-9);
    }

    #[test]
    fn loose_u_turn_pitch_is_1_plus_sqrt2_w() {
        let w = 30.0;
        let p = final_poses(&word("SSLSLSS"));
        let (_, y2) = centre(&p[2], w);
        let (_, y5) = centre(&p[5], w);
        assert!(
            (y5 - y2 - (1.0 + SQRT_2) * w).abs() < 1e-12,
            "pitch {}",
            y5 - y2
        );
        assert_eq!(p[5].centre.y - p[2].centre.y, Surd::new(2, 4));
        let f = poses_at_angles(&final_angles(&word("SSLSLSS")), w);
        assert!((f[5].y - f[2].y - (1.0 + SQRT_2) * w).abs() < 1e-9);
    }

    #[test]
    fn lll_ring_closes_touching_the_first_tile() {
        let w = 1.0;
        let p = final_poses(&word("LLL"));
        // the last tile's centre is exactly w from the first, along a diagonal: the two
        // octagons share a diagonal face.
        let d = p[3].centre - p[0].centre;
        assert_eq!(d, ExactPoint::new(Surd::new(0, -2), Surd::new(0, 2)));
        assert_eq!(p[3].heading.get(), 3);
        // the shared face: two vertices of tile 3 coincide exactly with two of tile 0.
        let v0: Vec<ExactPoint> = Octagon::exact_vertices()
            .iter()
            .map(|&v| p[0].transform(v))
            .collect();
        let v3: Vec<ExactPoint> = Octagon::exact_vertices()
            .iter()
            .map(|&v| p[3].transform(v))
            .collect();
        let shared = v3.iter().filter(|v| v0.contains(v)).count();
        assert_eq!(shared, 2);
        let (x, y) = d.to_f64(w);
        assert!(((x * x + y * y).sqrt() - w).abs() < 1e-15);
    }

    #[test]
    fn poses_are_the_composed_transforms_bit_for_bit() {
        // straight runs, folds part way, signed zeros, full turns past pi
        let mut angles = Vec::new();
        for i in 0..400 {
            angles.push(match i % 7 {
                0..=2 => 0.0,
                3 => -0.0,
                4 => 0.3 * (i as f64).sin(),
                5 => FRAC_PI_2,
                _ => -FRAC_PI_2 * 0.999,
            });
        }
        let w = 30.0;
        let fast = poses_at_angles(&angles, w);
        let mut pose = Pose::IDENTITY;
        let mut slow = vec![pose];
        for &a in &angles {
            pose = pose.then(&joint_transform(a, w));
            slow.push(pose);
        }
        assert_eq!(fast.len(), slow.len());
        for (i, (f, s)) in fast.iter().zip(&slow).enumerate() {
            let bits = |p: &Pose| (p.x.to_bits(), p.y.to_bits(), p.angle.to_bits());
            assert_eq!(bits(f), bits(s), "tile {i}");
        }
    }

    #[test]
    fn joint_transform_is_continuous_at_zero() {
        let l = joint_transform(0.0, 2.0);
        let r = joint_transform(-0.0, 2.0);
        let tiny = joint_transform(-1e-300, 2.0);
        assert!((l.x - 2.0).abs() < 1e-15 && l.y.abs() < 1e-15);
        assert!((r.x - 2.0).abs() < 1e-15);
        assert!((tiny.x - 2.0).abs() < 1e-15 && tiny.y.abs() < 1e-15);
    }
}
