//! Property tests of the core geometry (issue 2): the exact and `f64` kinematics agree within
//! a stated bound, and the folded chain has the geometry of SPEC section 3 exactly.

// Tests may unwrap (CONTRIBUTING.md); the workspace lint is for library code.
#![allow(clippy::unwrap_used)]

mod common;

use std::f64::consts::{FRAC_PI_2, TAU};

use common::{fold, word};
use foldchain::{ExactPoint, ExactPose, Fold, FoldWord, Octagon, Pose, QuarterTurns, Surd};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// Exact against f64 kinematics
// ---------------------------------------------------------------------------------------------

/// Bound on the distance between the `f64`-composed centre ([`kinematics::poses_at_angles`]
/// at the final angles) and the exact centre converted to `f64`, for a chain of `n` joints of
/// width `w` whose centres lie within `extent` of the origin and whose headings stay within
/// `q_max` quarter turns of the start. With `E = f64::EPSILON` (`u = E/2` the unit roundoff):
///
/// - the composed angle is a sum of `fl(pi/2)` terms, each off pi/2 by at most `u pi/2`, and
///   each addition rounds by at most `u |angle| <= u (pi/2) q_max`; so after `n` joints it is
///   off by at most `dtheta = n u (pi/2) (q_max + 2)` (one spare quarter turn for slack);
/// - each joint moves the centre by a vector of length `w`, computed (hinge, `sin_cos`,
///   three products and sums) within `4 E w`, turned by a rotation whose `sin_cos` is off by
///   at most `dtheta + 2 E`, and added to a centre of size at most `extent` with two
///   roundings, `2 E (extent + 2 w)`; per joint at most `w dtheta + E (10 w + 2 extent)`;
/// - the exact centre's conversion to `f64` adds at most `4 E (extent + w)`.
///
/// Summed over the `n` joints, times 2 for norm against components and slack:
/// `2 n (w dtheta + E (10 w + 2 extent)) + 4 E (extent + w)`. The `n * dtheta` term makes
/// the worst case quadratic in `n` when the heading wanders far (random words); a chain whose
/// headings stay in one turn (serpentines) has `q_max <= 2` and a bound linear in `n`.
fn centre_bound(n: usize, w: f64, extent: f64, q_max: f64) -> f64 {
    let e = f64::EPSILON;
    let n = n as f64;
    let dtheta = heading_bound(n as usize, q_max);
    2.0 * n * (w * dtheta + e * (10.0 * w + 2.0 * extent)) + 4.0 * e * (extent + w)
}

/// Bound on the composed angle's error after `n` joints (see [`centre_bound`]), plus the
/// reduction modulo 2 pi: `TAU` is off 2 pi by at most `u 2 pi`, once per turn of the angle.
fn heading_bound(n: usize, q_max: f64) -> f64 {
    let u = 0.5 * f64::EPSILON;
    n as f64 * u * FRAC_PI_2 * (q_max + 2.0) + (q_max / 4.0 + 1.0) * f64::EPSILON * TAU
}

/// The distance between two angles on the circle.
fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

/// Checks exact against f64 poses for `word` at width `w`; returns (max drift, bound).
fn compare_exact_f64(word: &FoldWord, w: f64) -> Result<(f64, f64), TestCaseError> {
    let exact = word.final_poses();
    let float = Pose::chain_at_angles(&word.final_angles(), w);
    prop_assert_eq!(exact.len(), word.tiles());
    prop_assert_eq!(float.len(), word.tiles());
    // headings: the exact quarter-turn count, unwrapped, gives q_max
    let mut q: i64 = 0;
    let mut q_max: i64 = 0;
    for f in word.folds() {
        q += f.quarter_turns() as i64;
        q_max = q_max.max(q.abs());
    }
    let extent = exact
        .iter()
        .map(|p| {
            let (x, y) = p.centre.to_f64(w);
            x.hypot(y)
        })
        .fold(0.0, f64::max);
    let n = word.joints();
    let bound = centre_bound(n, w, extent, q_max as f64);
    let hbound = heading_bound(n, q_max as f64);
    let mut worst: f64 = 0.0;
    for (k, (e, f)) in exact.iter().zip(&float).enumerate() {
        let p = e.to_pose(w);
        let d = (p.x - f.x).hypot(p.y - f.y);
        worst = worst.max(d);
        prop_assert!(
            d <= bound,
            "tile {k} of {}: centre drift {d:e} > bound {bound:e} (w {w}, extent {extent}, q_max {q_max})",
            word.tiles()
        );
        let g = angle_gap(f.angle, p.angle);
        prop_assert!(g <= hbound, "tile {k}: heading drift {g:e} > {hbound:e}");
    }
    Ok((worst, bound))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn exact_and_f64_kinematics_agree(w in word(2000), width in 0.01f64..1000.0) {
        compare_exact_f64(&w, width)?;
        compare_exact_f64(&w, 30.0)?;
    }

    /// Words of a few letters, heavy on folds, where the bound is tightest relative to the
    /// per-joint terms.
    #[test]
    fn exact_and_f64_agree_on_short_words(folds in prop::collection::vec(fold(), 1..12)) {
        compare_exact_f64(&FoldWord::from_folds(folds), 1.0)?;
    }

    /// At any joint angles the hinge of a joint is the same point seen from both of its
    /// tiles: every fold is a rotation about the shared vertex on the fold side.
    #[test]
    fn folds_rotate_about_the_hinge(
        angles in prop::collection::vec(-FRAC_PI_2..=FRAC_PI_2, 1..200),
        w in 0.1f64..100.0,
    ) {
        let poses = Pose::chain_at_angles(&angles, w);
        let o = Octagon::new(w);
        for (k, &a) in angles.iter().enumerate() {
            let (hx, hy) = o.hinge(a >= 0.0);
            let from_k = poses[k].transform_point((hx, hy));
            let from_next = poses[k + 1].transform_point((-hx, hy));
            let size = poses[k].x.hypot(poses[k].y) + w * (1.0 + poses[k].angle.abs());
            let tol = 16.0 * f64::EPSILON * size;
            let d = (from_k.0 - from_next.0).hypot(from_k.1 - from_next.1);
            prop_assert!(d <= tol, "joint {k}: hinge seen {d:e} apart (tol {tol:e})");
            // headings are kept in [-pi, pi): compare the turn modulo a full turn
            let turn = poses[k + 1].angle - poses[k].angle - a;
            let turn = (turn + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI;
            prop_assert!(turn.abs() <= tol, "joint {k}: turned {turn:e} off");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Exact geometric invariants
// ---------------------------------------------------------------------------------------------

/// `|p|^2` exactly, as `(r, c)` with `|p|^2 = (r/2 + c sqrt2) (w/2)^2`: for a coordinate
/// `(a + b/sqrt2) w/2`, `(a + b/sqrt2)^2 = a^2 + b^2/2 + a b sqrt2`.
fn norm2(p: ExactPoint) -> (i128, i128) {
    let sq = |s: Surd| {
        let (a, b) = (s.a as i128, s.b as i128);
        (2 * a * a + b * b, a * b)
    };
    let (rx, cx) = sq(p.x);
    let (ry, cy) = sq(p.y);
    (rx + ry, cx + cy)
}

/// `|p| = w` exactly: `|p|^2 = 4 (w/2)^2`, i.e. `r = 8`, `c = 0`.
const W_SQUARED: (i128, i128) = (8, 0);

fn placed_vertices(p: ExactPose) -> Vec<ExactPoint> {
    Octagon::exact_vertices()
        .iter()
        .map(|&v| p.transform(v))
        .collect()
}

fn mirrored(p: ExactPoint) -> ExactPoint {
    ExactPoint::new(p.x, -p.y)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Neighbouring centres are exactly w apart, straight or folded, and neighbouring tiles
    /// share one whole face; at a fold that face ends at the hinge.
    #[test]
    fn neighbours_are_w_apart_and_share_a_face(w in word(600)) {
        let poses = w.final_poses();
        for (k, &f) in w.folds().iter().enumerate() {
            let (a, b) = (poses[k], poses[k + 1]);
            prop_assert_eq!(norm2(b.centre - a.centre), W_SQUARED, "joint {}", k);
            // heading turns by the fold
            prop_assert_eq!(b.heading, a.heading.turned(f.quarter_turns() as i64));
            // the shared face: exactly two vertices coincide, and they are adjacent
            let va = placed_vertices(a);
            let vb = placed_vertices(b);
            let shared: Vec<usize> = (0..8).filter(|&i| vb.contains(&va[i])).collect();
            prop_assert_eq!(shared.len(), 2, "joint {} shares {:?}", k, shared);
            let (i, j) = (shared[0], shared[1]);
            prop_assert!(j - i == 1 || (i == 0 && j == 7), "not a face: {i} {j}");
            // the hinge in the world: the tile frame's hinge placed by the pose of tile k
            match Octagon::exact_hinge(f).map(|h| a.transform(h)) {
                None => prop_assert_eq!(f, Fold::S),
                Some(h) => {
                    prop_assert!(va.contains(&h) && vb.contains(&h), "hinge not shared");
                    // the hinge is the same point in the next tile's frame (mirrored in x)
                    let local = Octagon::exact_hinge(f).unwrap();
                    let back = ExactPoint::new(-local.x, local.y);
                    prop_assert_eq!(b.transform(back), h);
                }
            }
            // straight: along the heading; folded: the diagonal between the heading and the
            // fold side, (w/sqrt2, +-w/sqrt2) in the tile frame
            let step = b.centre - a.centre;
            let local = step.rotated(QuarterTurns::new(-(a.heading.get() as i64)));
            let expect = match f {
                Fold::S => ExactPoint::new(Surd::new(2, 0), Surd::ZERO),
                Fold::L => ExactPoint::new(Surd::new(0, 2), Surd::new(0, 2)),
                Fold::R => ExactPoint::new(Surd::new(0, 2), Surd::new(0, -2)),
            };
            prop_assert_eq!(local, expect);
        }
    }

    /// The mirrored word gives the mirrored poses, exactly: y -> -y, heading -> -heading.
    #[test]
    fn mirrored_word_mirrors_poses(w in word(2000)) {
        let p = w.final_poses();
        let m = w.mirrored().final_poses();
        prop_assert_eq!(p.len(), m.len());
        for (a, b) in p.iter().zip(&m) {
            prop_assert_eq!(b.centre, mirrored(a.centre));
            prop_assert_eq!(b.heading, QuarterTurns::new(-(a.heading.get() as i64)));
        }
    }

    /// Read from the far end, a chain is the reversed word with left and right swapped, and
    /// its poses are the same shape: a quarter-turn rotation and a translation, exactly.
    #[test]
    fn reversed_chain_is_the_same_shape(w in word(600)) {
        let p = w.final_poses();
        let mut folds: Vec<Fold> = w.folds().iter().rev().map(|f| f.mirrored()).collect();
        folds.shrink_to_fit();
        let r = FoldWord::from_folds(folds).final_poses();
        let last = p[p.len() - 1];
        let back = last.heading.turned(2); // the far end's tile, facing the other way
        let undo = QuarterTurns::new(-(back.get() as i64));
        for (j, rp) in r.iter().enumerate() {
            let orig = p[p.len() - 1 - j];
            prop_assert_eq!(rp.centre, (orig.centre - last.centre).rotated(undo), "tile {}", j);
            prop_assert_eq!(rp.heading, orig.heading.turned(2).turned(-(back.get() as i64)));
        }
    }
}

/// The SPEC section 3 consequences, exactly: a tight U-turn puts the return row sqrt2 w away
/// and a loose one with one straight tile between (1 + sqrt2) w, for any row length.
#[test]
fn u_turn_pitches_for_any_row_length() {
    for row in 1..40 {
        let straight = "S".repeat(row);
        let tight = FoldWord::parse(&format!("{straight}LL{straight}")).unwrap();
        let p = tight.final_poses();
        // tile `row` ends the first row, tile `row + 2` starts the return row
        let d = p[row + 2].centre - p[row].centre;
        assert_eq!(d, ExactPoint::new(Surd::ZERO, Surd::new(0, 4)), "row {row}");
        let loose = FoldWord::parse(&format!("{straight}LSL{straight}")).unwrap();
        let p = loose.final_poses();
        let d = p[row + 3].centre - p[row].centre;
        assert_eq!(d, ExactPoint::new(Surd::ZERO, Surd::new(2, 4)), "row {row}");
        // the return rows run back exactly over the first
        let n = p.len();
        assert_eq!(p[n - 1].heading.get(), 2);
        assert_eq!(p[n - 1].centre.x, p[0].centre.x);
    }
}
