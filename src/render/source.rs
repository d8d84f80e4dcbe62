//! A run as the pictures see it: the event engine's timeline and the reference integrator's
//! recorded states answer the same questions (the chain at a time, the transition diagram's
//! data, the energy curve, the folds, the timeline's JSON), so every picture and the viewer
//! are drawn once for both.

use crate::engine::{energy_curve, EnergySample, FoldRecord, Geometry, Timeline};
use crate::reference::{
    reference_energy, reference_final_state, reference_state_near, reference_transition,
    ReferenceRun,
};
use crate::render::{ChainState, TransitionData};

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
}

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
}
