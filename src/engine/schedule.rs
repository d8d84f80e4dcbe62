//! The fold schedule handed to the collision check: each fold of a timeline as a
//! piecewise-linear [`JointTrack`], sampled adaptively: an interval is halved until the fold
//! law ([`crate::engine::result::fold_angle`]) at its midpoint lies within [`ANGLE_TOLERANCE`] of the
//! chord, so the track follows the law within that tolerance.

use crate::collision::{FoldSchedule, JointTrack};
use crate::engine::result::{fold_angle, Timeline};
use crate::timeline::FoldRecord;

/// How closely a schedule track follows the fold angle law: 1e-4 rad (0.0057 degrees). On
/// 30 mm tiles a tile next to the hinge moves by at most 1e-4 * 1.1 w = 3.3 um within it.
/// Inertial folds end in bounces at their walls, where tiles that close face to face pass
/// within a few thousandths of `w` of each other: at 1e-3 rad the chords cut each bounce's
/// peak and hid true contacts there (SRLLLRR at s = 0.1 mm: tiles 1 and 6 overlap by
/// 2.7e-3 w in the law while joints 3 and 4 bounce).
pub(crate) const ANGLE_TOLERANCE: f64 = 1e-4;

/// The schedule's tolerance on chains of at most [`FINE_TILES`] tiles: 1e-6 rad. A run's
/// clearance ([`crate::timeline::Clearance`]) is measured on the schedule, and the event
/// engine's and the reference's are held to agree within 5 um: at 1e-4 rad a 9-tile chain's
/// far tile, 240 mm from a hinge, moved 24 um off the law (SRLSLLSR at s = 0.05: the law
/// and the reference within 5e-6 rad of each other, the chords 7e-5 rad off both). The
/// chords grow as the square root: ten times as many as at 1e-4, which on short chains
/// costs the check milliseconds.
pub(crate) const FINE_ANGLE_TOLERANCE: f64 = 1e-6;

/// The longest chain whose schedule follows the law within [`FINE_ANGLE_TOLERANCE`]: 100
/// tiles (longer ones keep [`ANGLE_TOLERANCE`], whose check the long serpentines' figures
/// in BENCHMARKS.md were measured with).
pub(crate) const FINE_TILES: usize = 100;

/// Deepest halving of a schedule interval.
const MAX_DEPTH: u32 = 14;

/// The fold schedule the timed collision check takes ([`crate::collision::check_schedule`]):
/// one adaptively sampled angle track per fold, within [`FINE_ANGLE_TOLERANCE`] of the law
/// up to [`FINE_TILES`] tiles, [`ANGLE_TOLERANCE`] beyond.
pub(crate) fn fold_schedule(timeline: &Timeline) -> FoldSchedule {
    let tol = if timeline.tiles() <= FINE_TILES {
        FINE_ANGLE_TOLERANCE
    } else {
        ANGLE_TOLERANCE
    };
    let tracks = timeline
        .folds
        .iter()
        .map(|f| {
            let mut times = vec![f.start];
            let mut angles = vec![0.0];
            // the law bends where one of its two magnets arrives: a knot there, so that the
            // midpoint test never straddles it
            let progress = timeline.progress();
            let mut knots = vec![f.start];
            for k in [2 * f.joint + 1, 2 * f.joint + 2] {
                if let Some(t) = progress.arrival_of(k) {
                    if t > f.start && t < f.end {
                        knots.push(t);
                    }
                }
            }
            // and where it turns back (bounces at its wall, peaks short of it): a chord
            // across a turn can cut its peak while its midpoint lies on the law
            if let Some(solved) = timeline.solved.as_deref() {
                knots.extend(solved.turning_times(f.joint, f.start, f.end));
            }
            knots.push(f.end);
            knots.sort_by(f64::total_cmp);
            knots.dedup();
            for w in knots.windows(2) {
                for (t0, t1) in subintervals(w[0], w[1], FIRST_SPLIT) {
                    refine(timeline, f, (t0, t1), tol, 0, (&mut times, &mut angles));
                }
            }
            JointTrack {
                joint: f.joint,
                times,
                angles,
                ended: f.end.is_finite().then_some(f.end),
            }
        })
        .collect();
    FoldSchedule { tracks }
}

/// Intervals a knot-to-knot stretch of a track is first cut into: 8.
const FIRST_SPLIT: usize = 8;

/// `[a, b]` cut into `n` equal intervals, the last ending at `b` exactly and none reaching
/// past it: `a + (b - a)` can round one unit above `b`, and a knot one unit below the next
/// (a magnet's arrival computed to the last bit of its fold's end, 100,000-tile inertial
/// serpentine, joint 9191) then put the track's times out of order.
fn subintervals(a: f64, b: f64, n: usize) -> impl Iterator<Item = (f64, f64)> {
    let at = move |i: usize| {
        if i == n {
            b
        } else {
            (a + (b - a) * i as f64 / n as f64).min(b)
        }
    };
    (0..n).map(move |i| (at(i), at(i + 1)))
}

fn refine(
    tl: &Timeline,
    f: &FoldRecord,
    (t0, t1): (f64, f64),
    tol: f64,
    depth: u32,
    out: (&mut Vec<f64>, &mut Vec<f64>),
) {
    let (a0, a1) = (fold_angle(tl, f, t0), fold_angle(tl, f, t1));
    let tm = 0.5 * (t0 + t1);
    let am = fold_angle(tl, f, tm);
    if depth < MAX_DEPTH && (am - 0.5 * (a0 + a1)).abs() > tol {
        refine(tl, f, (t0, tm), tol, depth + 1, (&mut *out.0, &mut *out.1));
        refine(tl, f, (tm, t1), tol, depth + 1, out);
    } else {
        out.0.push(t1);
        out.1.push(a1);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;
    use crate::engine::thesis_timeline;

    /// The 100,000-tile inertial serpentine's joint 9191 (s = 0.1 mm): a magnet arrives one
    /// unit of the last place before the fold ends, and its track's times went back there
    /// ("times must be finite and non-decreasing").
    #[test]
    fn a_knot_a_rounding_before_the_end_keeps_the_times_in_order() {
        let knots = [252.3154602017206, 1343.5895102293132, 1343.5895102293134];
        // the old cut: the first stretch's last time rounded past the next knot
        let (a, b) = (knots[0], knots[1]);
        assert!(a + (b - a) > b);
        let mut times = vec![knots[0]];
        for w in knots.windows(2) {
            for (t0, t1) in subintervals(w[0], w[1], FIRST_SPLIT) {
                assert!(t0 <= t1 && t0 >= w[0] && t1 <= w[1]);
                times.push(t1);
            }
        }
        assert!(times.windows(2).all(|w| w[0] <= w[1]), "{times:?}");
        assert_eq!(times.last(), knots.last());
    }

    #[test]
    fn tracks_follow_the_law_within_tolerance() {
        let tl = thesis_timeline("SLLS");
        let sched = fold_schedule(&tl);
        assert_eq!(sched.tracks.len(), 2);
        for (tr, f) in sched.tracks.iter().zip(&tl.folds) {
            assert_eq!(*tr.angles.last().unwrap(), FRAC_PI_2);
            assert!(tr.angles.windows(2).all(|w| w[1] >= w[0]));
            for i in 0..=1000 {
                let t = f.start + (f.end - f.start) * i as f64 / 1000.0;
                let err = (tr.angle_at(t) - fold_angle(&tl, f, t)).abs();
                assert!(err < 2.0 * FINE_ANGLE_TOLERANCE, "{t}: {err}");
            }
        }
    }
}
