//! Where a run stands: when each magnet started and how it moves, and the folds so far; so
//! how far every magnet has travelled and every joint has turned at any time. The run reads
//! it while it is being made (the force start rule weighs the magnets where they are), and
//! its result ([`crate::engine::Timeline`]) reads it afterwards.

use crate::engine::fold_law::fold_angle_from;
use crate::engine::local::{solved_fold_angle, Solved};
use crate::engine::speed::{Motion, MotionTable};
use crate::timeline::FoldRecord;

/// A view of a run's starts, motions and folds.
#[derive(Clone, Copy)]
pub(crate) struct RunState<'a> {
    /// Each magnet's start, s (NaN: not started).
    pub(crate) start: &'a [f64],
    /// Each magnet's motion.
    pub(crate) motions: &'a MotionTable,
    /// The folds, in the order they start.
    pub(crate) folds: &'a [FoldRecord],
    /// Index into `folds` of each joint's fold (`u32::MAX`: none).
    pub(crate) fold_of_joint: &'a [u32],
    /// The local solves' tracks, when the run made them.
    pub(crate) solved: Option<&'a Solved>,
}

impl<'a> RunState<'a> {
    /// When magnet `k` starts, or `None` if it has not.
    pub(crate) fn start_of(&self, k: usize) -> Option<f64> {
        let t = self.start[k];
        (!t.is_nan()).then_some(t)
    }

    /// Magnet `k`'s motion law.
    pub(crate) fn motion(&self, k: usize) -> &'a Motion {
        self.motions.of(k)
    }

    /// When magnet `k` arrives, or `None` if it has not started.
    pub(crate) fn arrival_of(&self, k: usize) -> Option<f64> {
        if let Some(s) = self.solved {
            let t = s.arrival[k];
            return (!t.is_nan() && self.start_of(k).is_some()).then_some(t);
        }
        self.start_of(k).map(|s| s + self.motion(k).duration())
    }

    /// The arc length magnet `k` has travelled at time `t`, mm.
    pub(crate) fn travel_at(&self, k: usize, t: f64) -> f64 {
        if let Some(s) = self.solved {
            return s.fraction(k, t) * self.motion(k).length;
        }
        match self.start_of(k) {
            Some(s) if t > s => self.motion(k).distance_at(t - s),
            _ => 0.0,
        }
    }

    /// The fold of joint `j`, if it folds.
    pub(crate) fn fold_at(&self, j: usize) -> Option<&'a FoldRecord> {
        self.fold_of_joint
            .get(j)
            .and_then(|&i| self.folds.get(i as usize))
    }

    /// The signed angle (radians, positive = left) of `fold` at time `t`.
    pub(crate) fn fold_angle(&self, fold: &FoldRecord, t: f64) -> f64 {
        if let Some(s) = self.solved {
            return solved_fold_angle(s, fold, t);
        }
        let (a, b) = (2 * fold.joint + 1, 2 * fold.joint + 2);
        let frac = |k: usize| self.travel_at(k, t) / self.motion(k).length;
        if t <= fold.start || t >= fold.end {
            return fold_angle_from(fold, t, 0.0, 0.0);
        }
        fold_angle_from(fold, t, frac(a), frac(b))
    }

    /// Joint `j`'s signed angle at time `t` (0 for a joint that does not fold).
    pub(crate) fn joint_angle(&self, j: usize, t: f64) -> f64 {
        self.fold_at(j).map_or(0.0, |f| self.fold_angle(f, t))
    }
}
