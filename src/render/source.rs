//! A run as the pictures see it: the event engine's timeline and the reference integrator's
//! recorded states answer the same questions (the chain at a time, the transition diagram's
//! data, the energy curve, the folds, the timeline's JSON), so every picture and the viewer
//! are drawn once for both.

use std::f64::consts::FRAC_PI_2;

use crate::engine::{energy_curve, fold_angle, EnergySample, FoldRecord, Geometry, Timeline};
use crate::reference::{
    reference_energy, reference_final_state, reference_state_near, reference_transition,
    ReferenceRun,
};
use crate::render::{ChainState, TransitionData};
use crate::viewer::{Track, ANGLE_TOLERANCE, TRAVEL_TOLERANCE};

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
    /// time, within [`TRAVEL_TOLERANCE`]: what the viewer plays.
    fn magnet_travel(&self, k: usize) -> Track;
    /// Joint `j`'s signed angle (radians, positive = left) against time, within
    /// [`ANGLE_TOLERANCE`]: what the viewer turns the tiles by.
    fn joint_angle(&self, j: usize) -> Track;
    /// Which magnets travel alike, so that a caller samples each such track once: a key and
    /// magnet `k`'s [`RunSource::magnet_travel`] start, where magnets of equal keys have the
    /// same travel law from their starts on, over the same duration (their tracks differ by
    /// the rounding of their absolute times only: some 1e-13 s, far below
    /// [`TRAVEL_TOLERANCE`] at any speed a magnet has).
    /// `None` (the default) when the source cannot tell.
    fn magnet_travel_key(&self, k: usize) -> Option<(TrackKey, f64)> {
        let _ = k;
        None
    }
}

/// Names a magnet's travel law ([`RunSource::magnet_travel_key`]); its meaning is the
/// source's own, and only equality counts.
pub type TrackKey = [u64; 4];

impl RunSource for Timeline {
    fn tiles(&self) -> usize {
        Timeline::tiles(self)
    }
    fn end_time(&self) -> f64 {
        self.duration()
    }
    fn geometry(&self) -> &Geometry {
        &self.geometry
    }
    fn state_at(&self, t: f64) -> ChainState {
        ChainState::from_timeline(self, t)
    }
    fn final_state(&self) -> ChainState {
        ChainState::from_timeline(self, self.duration())
    }
    fn transition(&self, first: usize, last: usize) -> TransitionData {
        TransitionData::from_timeline(self, first, last)
    }
    fn energy(&self, samples: usize) -> Vec<EnergySample> {
        energy_curve(self, samples)
    }
    fn folds(&self) -> &[FoldRecord] {
        &self.folds
    }
    fn timeline_json(&self) -> String {
        crate::timeline_json(self)
    }
    fn magnet_travel(&self, k: usize) -> Track {
        match self.start_of(k) {
            None => Track::constant(0.0),
            Some(s) => {
                let a = self.arrival_of(k).unwrap_or(s).max(s);
                Track::sample(s, a - s, TRAVEL_TOLERANCE, |dt| self.travel_at(k, s + dt))
            }
        }
    }
    /// The motion law (its address in the run's table: one per distinct path, partner and
    /// fold), the local solves' shape of the magnet and its start against that shape's origin
    /// (the local solves repeat a few shapes shifted in time), and the track's duration.
    fn magnet_travel_key(&self, k: usize) -> Option<(TrackKey, f64)> {
        let s = self.start_of(k)?;
        let a = self.arrival_of(k).unwrap_or(s).max(s);
        let motion = self.motion(k) as *const _ as usize as u64;
        let (shape, lag) = match self.solved.as_deref() {
            Some(solved) => {
                let tr = solved.chain.magnets[k];
                (u64::from(tr.shape), (s - tr.offset).to_bits())
            }
            None => (u64::MAX, 0),
        };
        Some(([motion, shape, lag, (a - s).to_bits()], s))
    }
    fn joint_angle(&self, j: usize) -> Track {
        match self.fold_at(j) {
            None => Track::constant(0.0),
            Some(f) => Track::sample(f.start, f.end - f.start, ANGLE_TOLERANCE, |dt| {
                fold_angle(self, f, f.start + dt)
            }),
        }
    }
}

impl RunSource for ReferenceRun {
    fn tiles(&self) -> usize {
        ReferenceRun::tiles(self)
    }
    fn end_time(&self) -> f64 {
        self.end_time
    }
    fn geometry(&self) -> &Geometry {
        &self.model.geometry
    }
    fn state_at(&self, t: f64) -> ChainState {
        reference_state_near(self, t)
    }
    fn final_state(&self) -> ChainState {
        reference_final_state(self)
    }
    fn transition(&self, first: usize, last: usize) -> TransitionData {
        reference_transition(self, first, last)
    }
    fn energy(&self, samples: usize) -> Vec<EnergySample> {
        reference_energy(self, samples)
    }
    fn folds(&self) -> &[FoldRecord] {
        &self.folds
    }
    fn timeline_json(&self) -> String {
        ReferenceRun::timeline_json(self)
    }
    fn magnet_travel(&self, k: usize) -> Track {
        let (v, len) = (self.model.magnet_var(k), self.model.path_length(k));
        reference_track(self, v, TRAVEL_TOLERANCE, |x| x.clamp(0.0, 1.0) * len)
    }
    fn joint_angle(&self, j: usize) -> Track {
        match self.model.joint_var(j) {
            None => Track::constant(0.0),
            Some(v) => {
                let sign = self.model.joint_sign(j);
                reference_track(self, v, ANGLE_TOLERANCE, |x| {
                    sign * x.clamp(0.0, 1.0) * FRAC_PI_2
                })
            }
        }
    }
}

/// Unknown `v` of the reference's recorded states (the final state alone when none were
/// recorded) as `value` gives it, with the moments it met a wall
/// ([`ReferenceRun::walls`]: a bounce's peak or an arrival's corner, which the grid of
/// states straddles), thinned within `tolerance`.
fn reference_track(
    run: &ReferenceRun,
    v: usize,
    tolerance: f64,
    value: impl Fn(f64) -> f64,
) -> Track {
    if run.states.is_empty() {
        return Track::from_samples(&[(run.end_time, value(run.final_state[v]))], tolerance);
    }
    let mut walls = run
        .walls
        .iter()
        .filter(|w| w.1 == v)
        .map(|&(t, _, x)| (t, value(x)))
        .peekable();
    let mut samples = Vec::with_capacity(run.states.len());
    for (t, y) in &run.states {
        while let Some(&w) = walls.peek() {
            if w.0 >= *t {
                break;
            }
            // a contact at a time already sampled is that sample
            if samples
                .last()
                .is_none_or(|&(last, _): &(f64, f64)| last < w.0)
            {
                samples.push(w);
            }
            walls.next();
        }
        samples.push((*t, value(y[v])));
    }
    Track::from_samples(&samples, tolerance)
}
