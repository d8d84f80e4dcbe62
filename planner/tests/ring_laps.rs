//! Laps around a round hole under the sequential fold check (issue 26, "no part left
//! empty"; docs/planner.md, "Why not laps around a hole"): a chain that follows a ring on
//! the tile lattice (a staircase of rows and columns joined by single folds, L where it
//! turns towards the hole's side, R where it turns back) folds for about three quarters of
//! a turn and no more, and a second lap beside the first cannot be laid at all. Each lap is
//! followed by 300 straight tiles, the rest of a chain that goes on after it.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};

use foldchain::collision::{check_word, CheckOptions, Collision};
use foldchain::FoldWord;

/// A pose on the lattice: centre (tile widths) and heading in quarter turns from +x.
#[derive(Clone, Copy)]
struct Pose {
    x: f64,
    y: f64,
    h: i32,
}

impl Pose {
    /// The pose after a joint folded `f` ('S', 'L' or 'R'), as the kinematics place it: a
    /// straight joint one width ahead, a fold `(1/sqrt2, +-1/sqrt2)` and a quarter turn.
    fn step(self, f: char) -> Pose {
        let (s, c) = (self.h as f64 * FRAC_PI_2).sin_cos();
        let (dx, dy, dh) = match f {
            'L' => (FRAC_1_SQRT_2, FRAC_1_SQRT_2, 1),
            'R' => (FRAC_1_SQRT_2, -FRAC_1_SQRT_2, -1),
            _ => (1.0, 0.0, 0),
        };
        Pose {
            x: self.x + c * dx - s * dy,
            y: self.y + s * dx + c * dy,
            h: (self.h + dh).rem_euclid(4),
        }
    }
}

/// The folds of a lap from `start` around the origin (the hole's centre) at radius `rho`
/// growing by `grow` a turn, `sweep_deg` degrees counterclockwise (clockwise if `cw`):
/// folded towards the hole where the radius has grown past `rho + 1/2` on a heading that
/// grows it, back where it has fallen below `rho - 1/2` on one that shrinks it.
fn lap(start: Pose, rho: f64, grow: f64, sweep_deg: f64, cw: bool) -> (String, Pose) {
    let (mut p, mut word, mut turned) = (start, String::new(), 0.0);
    let mut prev = p.y.atan2(p.x);
    while turned < sweep_deg.to_radians() {
        let r = p.x.hypot(p.y);
        let target = rho + grow * turned / (2.0 * PI);
        let (s, c) = (p.h as f64 * FRAC_PI_2).sin_cos();
        let outward = c * p.x + s * p.y > 0.0;
        let (towards, back) = if cw { ('R', 'L') } else { ('L', 'R') };
        let f = if r > target + 0.5 && outward {
            towards
        } else if r < target - 0.5 && !outward {
            back
        } else {
            'S'
        };
        p = p.step(f);
        word.push(f);
        let a = p.y.atan2(p.x);
        let da = (a - prev + PI).rem_euclid(2.0 * PI) - PI;
        turned += if cw { -da } else { da };
        prev = a;
    }
    (word, p)
}

/// A counterclockwise lap from the bottom of the hole (heading +x at `(0, -rho)`).
fn lap_from_bottom(rho: f64, grow: f64, sweep_deg: f64) -> (String, Pose) {
    lap(
        Pose {
            x: 0.0,
            y: -rho,
            h: 0,
        },
        rho,
        grow,
        sweep_deg,
        false,
    )
}

/// The sequential fold check of `folds` followed by 300 straight joints.
fn check(folds: &str) -> Result<(), Collision> {
    let word = FoldWord::parse(&format!("{folds}S*300")).unwrap();
    check_word(&word, &CheckOptions::default())
}

/// One lap at 31.5 tile widths (a ring of about 28 to 35, ring0.8 at 1000 tiles): three
/// quarters of a turn fold; at 300 degrees a fold in the last quarter (towards the start)
/// swings the tail across the lap's first tiles.
#[test]
fn one_lap_folds_three_quarters_of_a_turn_and_no_more() {
    let (three_quarters, _) = lap_from_bottom(31.5, 0.0, 270.0);
    assert_eq!(three_quarters.len() + 1, 175);
    assert!(check(&three_quarters).is_ok());
    let (more, _) = lap_from_bottom(31.5, 0.0, 300.0);
    let c = check(&more).unwrap_err();
    let joint = c.joint.unwrap();
    assert!(joint < more.len(), "a fold of the lap itself: {c:?}");
    assert!(
        c.tiles.0 < 10,
        "the tail meets the lap's first tiles: {c:?}"
    );
}

/// A spiral (the radius growing or shrinking by 1.6 widths a turn, a row and a bit) stops
/// where one lap stops: it cannot close a turn, inwards or outwards.
#[test]
fn a_spiral_cannot_close_a_turn() {
    for (rho, grow) in [(28.8, 1.6), (34.5, -1.6)] {
        assert!(check(&lap_from_bottom(rho, grow, 270.0).0).is_ok());
        let (turn, _) = lap_from_bottom(rho, grow, 360.0);
        let c = check(&turn).unwrap_err();
        assert!(c.joint.unwrap() < turn.len() && c.tiles.0 < 10, "{c:?}");
    }
}

/// A half lap, a tight U-turn outwards, and a lap back beside it: the second lap's first
/// fold towards the hole swings the tail across the first lap.
#[test]
fn a_second_lap_beside_the_first_cannot_be_laid() {
    let (first, end) = lap_from_bottom(31.5, 0.0, 180.0);
    assert!(check(&first).is_ok());
    let turn = end.step('R').step('R');
    let outer = turn.x.hypot(turn.y);
    let (second, _) = lap(turn, outer, 0.0, 45.0, true);
    let folds = format!("{first}RR{second}");
    let c = check(&folds).unwrap_err();
    let joint = c.joint.unwrap();
    assert!(joint > first.len() + 2 && joint < folds.len(), "{c:?}");
    assert!(c.tiles.0 < first.len(), "the first lap is hit: {c:?}");
}
