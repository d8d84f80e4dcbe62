//! The fold angle law, and the fold schedule handed to the collision check.
//!
//! **Fold angle.** A fold is driven by its pair of magnets (tile `j`'s second, tile `j+1`'s
//! first). Its progress is the mean fraction of their paths travelled,
//! `p = (u_a / L_a + u_b / L_b) / 2`; the fold starts when the second magnet starts (at
//! `p = p0`, the first one's fraction at its trigger point, halved) and the joint angle is
//! `theta = theta_final * (p - p0) / (1 - p0)`, reaching 90 degrees when both magnets have
//! arrived. It is monotone and continuous; under the overdamped law it speeds up as the pair
//! closes.
//!
//! **Schedule.** Each fold becomes a piecewise-linear [`JointTrack`], sampled adaptively:
//! an interval is halved until the law at its midpoint lies within [`ANGLE_TOLERANCE`] of the
//! chord, so the track follows the law within that tolerance.

use std::f64::consts::FRAC_PI_2;

use crate::collision::{FoldSchedule, JointTrack};
use crate::engine::run::{FoldRecord, Timeline};

/// How closely a schedule track follows the fold angle law: 1e-3 rad (0.057 degrees). On
/// 30 mm tiles a tile next to the hinge moves by at most 1e-3 * 1.1 w = 0.03 mm within it.
pub const ANGLE_TOLERANCE: f64 = 1e-3;

/// Deepest halving of a schedule interval.
const MAX_DEPTH: u32 = 14;

/// The signed angle (radians, positive = left) of the fold `fold` at time `t`.
pub fn fold_angle(timeline: &Timeline, fold: &FoldRecord, t: f64) -> f64 {
    let target = fold.fold.quarter_turns() as f64 * FRAC_PI_2;
    if t <= fold.start {
        return 0.0;
    }
    if t >= fold.end {
        return target;
    }
    let (a, b) = (2 * fold.joint + 1, 2 * fold.joint + 2);
    let frac = |k: usize| timeline.travel_at(k, t) / timeline.motion(k).length;
    fold_angle_from(fold, t, frac(a), frac(b))
}

/// The fold law at time `t` given the fractions of their paths its two magnets have
/// travelled then (see the module documentation).
pub(crate) fn fold_angle_from(fold: &FoldRecord, t: f64, frac_a: f64, frac_b: f64) -> f64 {
    let target = fold.fold.quarter_turns() as f64 * FRAC_PI_2;
    if t <= fold.start {
        return 0.0;
    }
    if t >= fold.end {
        return target;
    }
    let p = 0.5 * (frac_a + frac_b);
    let x = if fold.p0 < 1.0 {
        ((p - fold.p0) / (1.0 - fold.p0)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    target * x
}

/// Every joint's angle at time `t` (joints that never fold stay at 0).
pub fn joint_angles_at(timeline: &Timeline, t: f64) -> Vec<f64> {
    let mut a = vec![0.0; timeline.tiles().saturating_sub(1)];
    for f in &timeline.folds {
        a[f.joint] = fold_angle(timeline, f, t);
    }
    a
}

/// The fold schedule: one adaptively sampled track per fold.
pub fn fold_schedule(timeline: &Timeline) -> FoldSchedule {
    let tracks = timeline
        .folds
        .iter()
        .map(|f| {
            let mut times = vec![f.start];
            let mut angles = vec![0.0];
            let n0 = 8;
            for i in 0..n0 {
                let t0 = f.start + (f.end - f.start) * i as f64 / n0 as f64;
                let t1 = f.start + (f.end - f.start) * (i + 1) as f64 / n0 as f64;
                refine(timeline, f, t0, t1, 0, &mut times, &mut angles);
            }
            JointTrack {
                joint: f.joint,
                times,
                angles,
            }
        })
        .collect();
    FoldSchedule { tracks }
}

fn refine(
    tl: &Timeline,
    f: &FoldRecord,
    t0: f64,
    t1: f64,
    depth: u32,
    times: &mut Vec<f64>,
    angles: &mut Vec<f64>,
) {
    let (a0, a1) = (fold_angle(tl, f, t0), fold_angle(tl, f, t1));
    let tm = 0.5 * (t0 + t1);
    let am = fold_angle(tl, f, tm);
    if depth < MAX_DEPTH && (am - 0.5 * (a0 + a1)).abs() > ANGLE_TOLERANCE {
        refine(tl, f, t0, tm, depth + 1, times, angles);
        refine(tl, f, tm, t1, depth + 1, times, angles);
    } else {
        times.push(t1);
        angles.push(a1);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::engine::{run, EngineOptions, TileDesigns};
    use crate::{Chain, Design};

    #[test]
    fn tracks_follow_the_law_within_tolerance() {
        let chain = Chain::parse("SLLS").unwrap();
        let tl = run(
            &chain,
            &TileDesigns::global(Design::thesis()),
            &EngineOptions::default(),
        )
        .unwrap();
        let sched = fold_schedule(&tl);
        assert_eq!(sched.tracks.len(), 2);
        for (tr, f) in sched.tracks.iter().zip(&tl.folds) {
            assert_eq!(*tr.angles.last().unwrap(), FRAC_PI_2);
            assert!(tr.angles.windows(2).all(|w| w[1] >= w[0]));
            for i in 0..=1000 {
                let t = f.start + (f.end - f.start) * i as f64 / 1000.0;
                let err = (tr.angle_at(t) - fold_angle(&tl, f, t)).abs();
                assert!(err < 2.0 * ANGLE_TOLERANCE, "{t}: {err}");
            }
        }
    }
}
