//! Timed fold schedules: each joint's angle as a function of time, several joints moving at
//! once (the event engine's output for small `s`), checked by [`super::check_schedule`].
//!
//! Each joint's signed angle (radians, positive = left) is piecewise linear in time
//! ([`JointTrack`]). A schedule in which joints fold one at a time, in chain order, each from
//! straight to its full fold, is the thesis' sequential folding
//! ([`FoldSchedule::sequential`]); the check recognises it and uses the exact sweeps.

use std::f64::consts::FRAC_PI_2;

use crate::FoldWord;

use super::Collision;

/// One joint's signed angle against time: piecewise linear through `(times[i], angles[i])`;
/// before the first time the angle is `angles[0]`, after the last it stays at the last.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct JointTrack {
    /// The joint (0 = nearest the reaction initiator).
    pub joint: usize,
    /// Times, non-decreasing, seconds.
    pub times: Vec<f64>,
    /// Signed angles at those times, radians, within `[-pi/2, pi/2]`.
    pub angles: Vec<f64>,
    /// When the joint's fold ended (it closed at its wall), if it did. A joint released
    /// again after that (an inertial fold bouncing, or pulled off by its neighbours) still
    /// moves the tiles, but a contact after its end names another joint between the tiles
    /// that still folds, if one turns ([`super::Collision::joint`]). Default none.
    #[serde(default)]
    pub ended: Option<f64>,
}

/// Steps [`JointTrack::chord_at`] walks from its hint before it searches the track.
const HINT_STEPS: usize = 8;

impl JointTrack {
    /// The track of a fold of `joint` through `(times[i], angles[i])` that ended at `end`
    /// (not finite: it never did).
    pub(crate) fn of_fold(
        joint: usize,
        (times, angles): (Vec<f64>, Vec<f64>),
        end: f64,
    ) -> JointTrack {
        JointTrack {
            joint,
            times,
            angles,
            ended: end.is_finite().then_some(end),
        }
    }

    /// For tests: the track of `joint` through `(times[i], angles[i])`, never ended.
    #[cfg(test)]
    pub(crate) fn open(joint: usize, times: &[f64], angles: &[f64]) -> JointTrack {
        JointTrack {
            joint,
            times: times.to_vec(),
            angles: angles.to_vec(),
            ended: None,
        }
    }

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

    /// [`JointTrack::angle_at`] `t`, and the rate of the chord that runs from `t` on (0
    /// outside the track), the search starting from `hint` (the count of times at or before
    /// the last `t` asked, kept up to date): constant time for a walk forward in time.
    pub(super) fn chord_at(&self, t: f64, hint: &mut usize) -> (f64, f64) {
        let (ts, a) = (&self.times, &self.angles);
        let n = ts.len();
        // a few steps from the hint (a walk forward in time), else a binary search: the
        // count of times at or before `t` either way (the times do not decrease)
        let mut i = (*hint).min(n);
        let mut steps = 0;
        while i < n && ts[i] <= t && steps < HINT_STEPS {
            i += 1;
            steps += 1;
        }
        if (i < n && ts[i] <= t) || (i > 0 && ts[i - 1] > t) {
            i = ts.partition_point(|&x| x <= t);
        }
        *hint = i;
        if n == 0 {
            return (0.0, 0.0);
        }
        let inside = i > 0 && i < n && ts[i] > ts[i - 1];
        let rate = if inside {
            (a[i] - a[i - 1]) / (ts[i] - ts[i - 1])
        } else {
            0.0
        };
        let angle = if t <= ts[0] {
            a[0]
        } else if i >= n {
            a[n - 1]
        } else if !inside {
            a[i]
        } else {
            let (t0, t1) = (ts[i - 1], ts[i]);
            a[i - 1] + (a[i] - a[i - 1]) * (t - t0) / (t1 - t0)
        };
        (angle, rate)
    }

    /// The first time at which the track has turned `|angle|` radians from its start
    /// (the tracks of a sequential schedule are monotone), or its end.
    pub(super) fn time_at_turn(&self, turn: f64) -> f64 {
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
pub(crate) struct FoldSchedule {
    /// One track per moving joint.
    pub tracks: Vec<JointTrack>,
}

/// Why a schedule could not be checked.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub(crate) enum ScheduleError {
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
    #[cfg(test)]
    pub(crate) fn sequential(word: &FoldWord, fold_time: f64) -> FoldSchedule {
        let mut t = 0.0;
        let mut tracks = Vec::new();
        for (joint, f) in word.folds().iter().enumerate() {
            let target = f.quarter_turns() as f64 * FRAC_PI_2;
            if target != 0.0 {
                tracks.push(JointTrack {
                    joint,
                    times: vec![t, t + fold_time],
                    angles: vec![0.0, target],
                    ended: Some(t + fold_time),
                });
                t += fold_time;
            }
        }
        FoldSchedule { tracks }
    }

    /// Every joint's angle at time `t` (joints without a track stay straight).
    #[cfg(test)]
    pub(super) fn angles_at(&self, joints: usize, t: f64) -> Vec<f64> {
        let mut a = vec![0.0; joints];
        for tr in &self.tracks {
            a[tr.joint] = tr.angle_at(t);
        }
        a
    }

    /// Whether this is sequential folding in chain order ending in the word's shape.
    pub(super) fn is_sequential_for(&self, word: &FoldWord) -> bool {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn word(s: &str) -> FoldWord {
        FoldWord::parse(s).unwrap()
    }

    #[test]
    fn tracks_interpolate_and_invert() {
        let tr = JointTrack {
            joint: 0,
            times: vec![1.0, 3.0],
            angles: vec![0.0, FRAC_PI_2],
            ended: None,
        };
        assert_eq!(tr.angle_at(0.0), 0.0);
        assert!((tr.angle_at(2.0) - FRAC_PI_2 / 2.0).abs() < 1e-15);
        assert_eq!(tr.angle_at(9.0), FRAC_PI_2);
        assert!((tr.time_at_turn(FRAC_PI_2 / 4.0) - 1.5).abs() < 1e-15);
    }

    #[test]
    fn chords_from_a_hint_are_those_of_a_search() {
        // a track with a repeated time (a jump) walked forward, back and across its ends
        let tr = JointTrack {
            joint: 0,
            times: vec![1.0, 2.0, 2.0, 3.5, 4.0],
            angles: vec![0.0, 0.4, 0.5, -0.2, 1.0],
            ended: None,
        };
        let rate = |t: f64| {
            let i = tr.times.partition_point(|&x| x <= t);
            if i == 0 || i >= tr.times.len() || tr.times[i] <= tr.times[i - 1] {
                0.0
            } else {
                (tr.angles[i] - tr.angles[i - 1]) / (tr.times[i] - tr.times[i - 1])
            }
        };
        let mut hint = 0;
        for t in [
            0.0, 1.0, 1.5, 2.0, 2.5, 3.5, 3.9, 4.0, 5.0, 1.2, 3.7, 0.5, 2.0,
        ] {
            let (a, r) = tr.chord_at(t, &mut hint);
            assert_eq!(a.to_bits(), tr.angle_at(t).to_bits(), "{t}");
            assert_eq!(r.to_bits(), rate(t).to_bits(), "{t}");
        }
        assert_eq!(rate(1.5), 0.4);
    }

    #[test]
    fn sequential_schedule_is_recognised() {
        let w = word("SLLSR");
        let s = FoldSchedule::sequential(&w, 2.0);
        assert_eq!(s.tracks.len(), 3);
        assert!(s.is_sequential_for(&w));
        let mut overlapping = s.clone();
        overlapping.tracks[0].times[1] += 0.5; // the second fold starts before the first ends
        assert!(!overlapping.is_sequential_for(&w));
        assert!(!s.is_sequential_for(&word("SLLSL")));
    }

    #[test]
    fn bad_tracks_are_named() {
        let w = word("SL");
        let s = FoldSchedule {
            tracks: vec![JointTrack::open(5, &[0.0], &[0.0])],
        };
        assert!(s.validate(&w).unwrap_err().to_string().contains("joint 5"));
        let s = FoldSchedule {
            tracks: vec![JointTrack::open(1, &[1.0, 0.0], &[0.0, 1.0])],
        };
        assert!(matches!(
            s.validate(&w),
            Err(ScheduleError::BadTrack { .. })
        ));
        let s = FoldSchedule {
            tracks: vec![JointTrack::open(1, &[0.0], &[f64::NAN])],
        };
        assert!(matches!(
            s.validate(&w),
            Err(ScheduleError::BadTrack { .. })
        ));
    }
}
