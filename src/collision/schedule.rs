//! Checking a timed fold schedule: joint angles as functions of time, several joints moving
//! at once (the event engine's output for small `s`).
//!
//! Each joint's signed angle (radians, positive = left) is piecewise linear in time
//! ([`JointTrack`]). Between breakpoints every joint turns at a constant rate, which bounds how
//! fast any point of tile `j` can move relative to tile `i`: by the sum over the moving joints
//! `k` between them of `|rate_k| * ((j - k) + r)` tile widths per second (`r` the
//! circumradius), since a point of tile `j` is at most that far from hinge `k`. Conservative
//! advancement then steps time by the parry2d distance between each close pair over that
//! bound, so no contact can be stepped over; pairs far apart are bounded together by the
//! fastest tile. Pairs with no moving joint between them keep their distance and are skipped.
//!
//! A schedule in which joints fold one at a time, in chain order, each from straight to its
//! full fold, is the thesis' sequential folding: it is handed to the exact sweep check
//! ([`super::check_word`]) and the contact angle is turned back into a time.

use std::f64::consts::FRAC_PI_2;

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::math::Vector;
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy};
use parry2d_f64::query;
use parry2d_f64::shape::ConvexPolygon;

use crate::{kinematics, FoldWord, Octagon, Pose};

use super::{check_word, CheckOptions, Collision};

/// One joint's signed angle against time: piecewise linear through `(times[i], angles[i])`;
/// before the first time the angle is `angles[0]`, after the last it stays at the last.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct JointTrack {
    /// The joint (0 = nearest the reaction initiator).
    pub joint: usize,
    /// Times, non-decreasing, seconds.
    pub times: Vec<f64>,
    /// Signed angles at those times, radians, within `[-pi/2, pi/2]`.
    pub angles: Vec<f64>,
}

impl JointTrack {
    /// The angle at time `t`.
    pub fn angle_at(&self, t: f64) -> f64 {
        let (ts, a) = (&self.times, &self.angles);
        if ts.is_empty() {
            return 0.0;
        }
        if t <= ts[0] {
            return a[0];
        }
        let i = ts.partition_point(|&x| x <= t);
        if i >= ts.len() {
            return a[a.len() - 1];
        }
        let (t0, t1) = (ts[i - 1], ts[i]);
        if t1 <= t0 {
            return a[i];
        }
        a[i - 1] + (a[i] - a[i - 1]) * (t - t0) / (t1 - t0)
    }

    /// The first time at which the track has turned `|angle|` radians from its start
    /// (the tracks of a sequential schedule are monotone), or its end.
    fn time_at_turn(&self, turn: f64) -> f64 {
        let a0 = self.angles.first().copied().unwrap_or(0.0);
        for i in 1..self.times.len() {
            let (p, q) = ((self.angles[i - 1] - a0).abs(), (self.angles[i] - a0).abs());
            if q >= turn {
                if q <= p {
                    return self.times[i - 1];
                }
                return self.times[i - 1]
                    + (self.times[i] - self.times[i - 1]) * (turn - p) / (q - p);
            }
        }
        self.times.last().copied().unwrap_or(0.0)
    }
}

/// The angle tracks of the joints that move; joints without a track stay straight.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FoldSchedule {
    /// One track per moving joint.
    pub tracks: Vec<JointTrack>,
}

/// Why a schedule could not be checked.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ScheduleError {
    /// Two tiles meet.
    #[error("{0}")]
    Collision(Collision),
    /// A track that is not a valid function of time.
    #[error("track of joint {joint}: {reason}")]
    BadTrack {
        /// The track's joint.
        joint: usize,
        /// What is wrong.
        reason: String,
    },
    /// The conservative advancement did not finish within its step budget (two parts that
    /// stay a hair apart while moving fast); the schedule is neither proved clean nor shown
    /// to collide.
    #[error("no verdict after {steps} steps, at t = {time} s: parts keep within a hair's breadth while moving")]
    Undecided {
        /// Steps taken.
        steps: usize,
        /// The time reached.
        time: f64,
    },
}

impl FoldSchedule {
    /// Checks that every track names a joint of `word`, has as many times as angles, finite
    /// non-decreasing times and finite angles within `[-pi/2, pi/2]`, and that no joint has
    /// two tracks.
    pub fn validate(&self, word: &FoldWord) -> Result<(), ScheduleError> {
        let mut seen = vec![false; word.joints()];
        for tr in &self.tracks {
            let bad = |reason: &str| ScheduleError::BadTrack {
                joint: tr.joint,
                reason: reason.to_string(),
            };
            if tr.joint >= word.joints() {
                return Err(bad(&format!("the chain has only {} joints", word.joints())));
            }
            if std::mem::replace(&mut seen[tr.joint], true) {
                return Err(bad("the joint has two tracks"));
            }
            if tr.times.len() != tr.angles.len() || tr.times.is_empty() {
                return Err(bad("expected as many times as angles, at least one"));
            }
            if tr.times.iter().any(|t| !t.is_finite()) || tr.times.windows(2).any(|w| w[1] < w[0]) {
                return Err(bad("times must be finite and non-decreasing"));
            }
            if tr
                .angles
                .iter()
                .any(|a| !a.is_finite() || a.abs() > FRAC_PI_2 * (1.0 + 1e-12))
            {
                return Err(bad("angles must be finite, within [-pi/2, pi/2]"));
            }
        }
        Ok(())
    }

    /// The sequential schedule of the thesis: each fold joint in turn, from straight to its
    /// full fold over `fold_time` seconds, one after another.
    pub fn sequential(word: &FoldWord, fold_time: f64) -> FoldSchedule {
        let mut t = 0.0;
        let mut tracks = Vec::new();
        for (joint, f) in word.folds().iter().enumerate() {
            let target = f.quarter_turns() as f64 * FRAC_PI_2;
            if target != 0.0 {
                tracks.push(JointTrack {
                    joint,
                    times: vec![t, t + fold_time],
                    angles: vec![0.0, target],
                });
                t += fold_time;
            }
        }
        FoldSchedule { tracks }
    }

    fn angles_at(&self, joints: usize, t: f64) -> Vec<f64> {
        let mut a = vec![0.0; joints];
        for tr in &self.tracks {
            a[tr.joint] = tr.angle_at(t);
        }
        a
    }

    /// Whether this is sequential folding in chain order ending in the word's shape.
    fn is_sequential_for(&self, word: &FoldWord) -> bool {
        let mut prev_end = f64::NEG_INFINITY;
        let mut prev_joint: Option<usize> = None;
        let mut tracked = vec![false; word.joints()];
        for tr in &self.tracks {
            let target = word.folds()[tr.joint].quarter_turns() as f64 * FRAC_PI_2;
            let start = tr.angles[0];
            let end = tr.angles[tr.angles.len() - 1];
            if start != 0.0 || (end - target).abs() > 1e-12 {
                return false;
            }
            if target == 0.0 {
                if tr.angles.iter().any(|&a| a != 0.0) {
                    return false;
                }
                continue;
            }
            let monotone = tr.angles.windows(2).all(|w| (w[1] - w[0]) * target >= 0.0);
            let moves_from = tr.times[tr.angles.iter().rposition(|&a| a == 0.0).unwrap_or(0)];
            if !monotone || prev_joint.is_some_and(|p| p > tr.joint) || moves_from < prev_end {
                return false;
            }
            prev_end = tr.times[tr.times.len() - 1];
            prev_joint = Some(tr.joint);
            tracked[tr.joint] = true;
        }
        word.folds()
            .iter()
            .zip(&tracked)
            .all(|(f, &t)| t || f.quarter_turns() == 0)
    }
}

/// Checks a chain folding along `schedule`: every pair of tiles with a moving joint between
/// them, at every moment, by conservative advancement on parry2d distances (or the exact
/// sweep check for a sequential schedule). Returns the first contact with its time.
pub fn check_schedule(
    word: &FoldWord,
    schedule: &FoldSchedule,
    opts: &CheckOptions,
) -> Result<(), ScheduleError> {
    schedule.validate(word)?;
    let mut tracks = schedule.clone();
    tracks.tracks.sort_by_key(|t| t.joint);
    if tracks.is_sequential_for(word) {
        return check_word(word, opts).map_err(|mut c| {
            if let Some(j) = c.joint {
                if let Some(tr) = tracks.tracks.iter().find(|t| t.joint == j) {
                    c.time = Some(tr.time_at_turn(c.angle_deg.to_radians()));
                }
            }
            ScheduleError::Collision(c)
        });
    }
    Advancer::new(word, &tracks, opts.tolerance).run()
}

/// Conservative advancement over a general schedule, at tile width 1.
struct Advancer<'a> {
    joints: usize,
    schedule: &'a FoldSchedule,
    shape: Option<ConvexPolygon>,
    radius: f64,
    breakpoints: Vec<f64>,
}

/// Margin by which tile boxes are grown to find close pairs, in tile widths.
const MARGIN: f64 = 0.25;
/// Distance (tile widths, between inset outlines) at which two tiles count as in contact.
const CONTACT: f64 = 1e-12;
/// Step budget of one check.
const MAX_STEPS: usize = 2_000_000;

impl<'a> Advancer<'a> {
    fn new(word: &FoldWord, schedule: &'a FoldSchedule, tolerance: f64) -> Advancer<'a> {
        let mut breakpoints: Vec<f64> = schedule
            .tracks
            .iter()
            .flat_map(|t| t.times.iter().copied())
            .collect();
        breakpoints.sort_by(f64::total_cmp);
        breakpoints.dedup();
        let o = Octagon::new(1.0);
        Advancer {
            joints: word.joints(),
            schedule,
            shape: o.to_parry(tolerance),
            radius: o.circumradius(),
            breakpoints,
        }
    }

    fn run(&self) -> Result<(), ScheduleError> {
        let Some(shape) = &self.shape else {
            return Ok(());
        };
        let n = self.joints + 1;
        let (Some(&t_start), Some(&t_end)) = (self.breakpoints.first(), self.breakpoints.last())
        else {
            return Ok(());
        };
        let mut t = t_start;
        let mut steps = 0usize;
        let mut seg = 0usize;
        while t < t_end {
            while seg + 1 < self.breakpoints.len() && self.breakpoints[seg + 1] <= t {
                seg += 1;
            }
            let seg_end = self.breakpoints[(seg + 1).min(self.breakpoints.len() - 1)];
            // joint rates over this segment
            let mid = 0.5 * (t + seg_end);
            let dt_probe = (seg_end - t).max(f64::MIN_POSITIVE);
            let a_now = self.schedule.angles_at(self.joints, t);
            let a_end = self.schedule.angles_at(self.joints, seg_end);
            let _ = mid;
            let rates: Vec<f64> = a_now
                .iter()
                .zip(&a_end)
                .map(|(a, b)| ((b - a) / dt_probe).abs())
                .collect();
            if rates.iter().all(|&r| r == 0.0) {
                t = seg_end;
                continue;
            }
            // prefix sums for the pair speed bound: sum_{k in [i, j)} w_k ((j - k) + r)
            let mut sw = vec![0.0; n];
            let mut skw = vec![0.0; n];
            for k in 0..self.joints {
                sw[k + 1] = sw[k] + rates[k];
                skw[k + 1] = skw[k] + rates[k] * k as f64;
            }
            let bound = |i: usize, j: usize| -> f64 {
                let w = sw[j] - sw[i];
                let kw = skw[j] - skw[i];
                j as f64 * w - kw + self.radius * w
            };
            let fastest = (1..n).map(|j| bound(0, j)).fold(0.0, f64::max);
            let poses = kinematics::poses_at_angles(&a_now, 1.0);
            let grow = self.radius + MARGIN;
            let boxes: Vec<Aabb> = poses
                .iter()
                .map(|p| {
                    Aabb::new(
                        Vector::new(p.x - grow, p.y - grow),
                        Vector::new(p.x + grow, p.y + grow),
                    )
                })
                .collect();
            let bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes);
            let mut dt = (seg_end - t).min(if fastest > 0.0 {
                MARGIN / fastest
            } else {
                f64::INFINITY
            });
            for (j, bj) in boxes.iter().enumerate() {
                for i in bvh.intersect_aabb(bj) {
                    let i = i as usize;
                    if i + 2 > j {
                        continue; // each pair once, hinged neighbours skipped
                    }
                    let v = bound(i, j);
                    if v == 0.0 {
                        continue; // no moving joint between them: their distance stays
                    }
                    let d = distance(shape, &poses[i], &poses[j]);
                    if d <= CONTACT {
                        return Err(ScheduleError::Collision(
                            self.collision(i, j, t, &a_now, &rates),
                        ));
                    }
                    dt = dt.min(d / v);
                }
            }
            steps += 1;
            if steps > MAX_STEPS {
                return Err(ScheduleError::Undecided { steps, time: t });
            }
            t += dt.max(1e-15 * (1.0 + t.abs()));
        }
        Ok(())
    }

    fn collision(&self, i: usize, j: usize, t: f64, angles: &[f64], rates: &[f64]) -> Collision {
        let joint = (i..j)
            .filter(|&k| rates[k] > 0.0)
            .max_by(|&a, &b| rates[a].total_cmp(&rates[b]));
        Collision {
            joint,
            angle_deg: joint.map_or(0.0, |k| angles[k].abs().to_degrees()),
            time: Some(t),
            tiles: (i, j),
        }
    }
}

fn distance(shape: &ConvexPolygon, a: &Pose, b: &Pose) -> f64 {
    query::distance(&a.to_parry(), shape, &b.to_parry(), shape).unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn word(s: &str) -> FoldWord {
        FoldWord::parse(s).unwrap()
    }

    /// Every joint folding at once, linearly over one second.
    fn simultaneous(w: &FoldWord) -> FoldSchedule {
        FoldSchedule {
            tracks: w
                .folds()
                .iter()
                .enumerate()
                .filter(|(_, f)| f.quarter_turns() != 0)
                .map(|(joint, f)| JointTrack {
                    joint,
                    times: vec![0.0, 1.0],
                    angles: vec![0.0, f.quarter_turns() as f64 * FRAC_PI_2],
                })
                .collect(),
        }
    }

    #[test]
    fn sequential_schedule_uses_exact_check_and_reports_time() {
        let w = word("LLLL");
        let e = check_schedule(
            &w,
            &FoldSchedule::sequential(&w, 2.0),
            &CheckOptions::default(),
        )
        .unwrap_err();
        let ScheduleError::Collision(c) = e else {
            panic!("{e}")
        };
        assert_eq!(c.joint, Some(2));
        let t = c.time.unwrap();
        assert!(t > 4.0 && t < 6.0, "{t}"); // joint 2 folds from t = 4 s to 6 s
        assert!(check_schedule(
            &word("LLL"),
            &FoldSchedule::sequential(&word("LLL"), 1.0),
            &CheckOptions::default()
        )
        .is_ok());
    }

    #[test]
    fn simultaneous_ring_closes_touching() {
        let w = word("LLL");
        assert!(check_schedule(&w, &simultaneous(&w), &CheckOptions::default()).is_ok());
    }

    #[test]
    fn simultaneous_five_in_a_ring_collides_before_the_end() {
        let w = word("LLLL");
        match check_schedule(&w, &simultaneous(&w), &CheckOptions::default()) {
            Err(ScheduleError::Collision(c)) => {
                assert_eq!(c.tiles, (0, 4));
                let t = c.time.unwrap();
                assert!(t > 0.0 && t < 1.0, "{t}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn general_advancement_agrees_with_exact_sweeps() {
        // the same sequential folding, but with a pause in each track so that it is not
        // recognised as sequential: both methods must agree on every word of 5 and 6 tiles.
        for n in [5usize, 6] {
            let mut letters = vec![crate::Fold::S; n - 1];
            let total = 3usize.pow((n - 1) as u32);
            for code in 0..total {
                let mut c = code;
                for l in letters.iter_mut() {
                    *l = crate::Fold::ALL[c % 3];
                    c /= 3;
                }
                let w = FoldWord::from_folds(letters.clone());
                let exact = check_word(&w, &CheckOptions::default()).is_ok();
                let mut s = FoldSchedule::sequential(&w, 1.0);
                for tr in &mut s.tracks {
                    // overlap each fold slightly with the next: not sequential any more
                    tr.times[1] += 0.02;
                }
                let general = match check_schedule(&w, &s, &CheckOptions::default()) {
                    Ok(()) => true,
                    Err(ScheduleError::Collision(_)) => false,
                    Err(e) => panic!("{w}: {e}"),
                };
                assert_eq!(exact, general, "word {w}");
            }
        }
    }

    #[test]
    fn bad_tracks_are_named() {
        let w = word("SL");
        let s = FoldSchedule {
            tracks: vec![JointTrack {
                joint: 5,
                times: vec![0.0],
                angles: vec![0.0],
            }],
        };
        assert!(check_schedule(&w, &s, &CheckOptions::default())
            .unwrap_err()
            .to_string()
            .contains("joint 5"));
        let s = FoldSchedule {
            tracks: vec![JointTrack {
                joint: 1,
                times: vec![1.0, 0.0],
                angles: vec![0.0, 1.0],
            }],
        };
        assert!(matches!(
            check_schedule(&w, &s, &CheckOptions::default()),
            Err(ScheduleError::BadTrack { .. })
        ));
        let s = FoldSchedule {
            tracks: vec![JointTrack {
                joint: 1,
                times: vec![0.0],
                angles: vec![f64::NAN],
            }],
        };
        assert!(matches!(
            check_schedule(&w, &s, &CheckOptions::default()),
            Err(ScheduleError::BadTrack { .. })
        ));
    }
}
