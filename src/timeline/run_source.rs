//! A run as its readers see it: the event engine's timeline and the reference integrator's
//! recorded states answer the same questions (the chain at a time, the transition diagram's
//! data, the energy curve, the folds, the timeline's JSON, each magnet's travel and each
//! joint's angle against time), so every picture and the viewer (the `foldchain-render`
//! crate) are drawn once for both, from this trait alone.

use crate::timeline::{ChainState, EnergySample, FoldRecord, Geometry, Track, TransitionData};

/// What a run's pictures are drawn from.
pub trait RunSource {
    /// Tiles in the chain.
    fn tiles(&self) -> usize;
    /// The time the run ends (s).
    fn end_time(&self) -> f64;
    /// The chain's geometry.
    fn geometry(&self) -> &Geometry;
    /// The chain at time `t` (a step frame).
    fn state_at(&self, t: f64) -> ChainState;
    /// The chain as the run ends.
    fn final_state(&self) -> ChainState;
    /// The transition diagram's data for tiles `first..=last`.
    fn transition(&self, first: usize, last: usize) -> TransitionData;
    /// The total dipole energy at `samples` times.
    fn energy(&self, samples: usize) -> Vec<EnergySample>;
    /// The folds, in order.
    fn folds(&self) -> &[FoldRecord];
    /// `timeline.json`.
    fn timeline_json(&self) -> String;
    /// Magnet `k`'s travel along its path (mm of arc length from its rest point) against
    /// time, within [`Track::TRAVEL_TOLERANCE`]: what the viewer plays.
    fn magnet_travel(&self, k: usize) -> Track;
    /// Joint `j`'s signed angle (radians, positive = left) against time, within
    /// [`Track::ANGLE_TOLERANCE`]: what the viewer turns the tiles by.
    fn joint_angle(&self, j: usize) -> Track;
    /// Which magnets travel alike, so that a caller samples each such track once: a key (its
    /// meaning is the source's own, and only equality counts) and magnet `k`'s
    /// [`RunSource::magnet_travel`] start, where magnets of equal keys have the same travel law
    /// from their starts on, over the same duration (their tracks differ by the rounding of
    /// their absolute times only: some 1e-13 s, far below [`Track::TRAVEL_TOLERANCE`] at any
    /// speed a magnet has).
    /// `None` (the default) when the source cannot tell.
    fn magnet_travel_key(&self, k: usize) -> Option<([u64; 4], f64)> {
        let _ = k;
        None
    }
}
