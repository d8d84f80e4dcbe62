//! One fold of a run: a joint of an LL or RR pair turning from straight to 90 degrees.

use crate::Fold;

/// One fold: when it starts and ends, and how far its pair had come when it started.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FoldRecord {
    /// The joint.
    pub joint: usize,
    /// The direction.
    pub fold: Fold,
    /// Start, s (both magnets of the pair are moving).
    pub start: f64,
    /// End, s (the joint is closed; NaN for a fold that never closed).
    pub end: f64,
    /// The pair's progress when the fold starts: the mean fraction of their paths the two
    /// magnets had travelled.
    pub p0: f64,
}
