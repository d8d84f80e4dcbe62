//! The reference's run as a [`RunSource`]: its recorded states answer what the pictures
//! and the viewer ask (the chain at a time, the transition diagram, the energy curve), and
//! each magnet's travel and joint's angle are its recorded values thinned within the
//! tracks' tolerances.

use std::f64::consts::FRAC_PI_2;

use crate::reference::pictures::{
    reference_energy, reference_final_state, reference_state_near, reference_transition,
};
use crate::reference::ReferenceRun;
use crate::timeline::{
    ChainState, EnergySample, FoldRecord, Geometry, RunSource, Track, TransitionData,
    ANGLE_TOLERANCE, TRAVEL_TOLERANCE,
};

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
        Track::from_samples(
            &recorded_samples(self, v, |x| x.clamp(0.0, 1.0) * len),
            TRAVEL_TOLERANCE,
        )
    }
    fn joint_angle(&self, j: usize) -> Track {
        match self.model.joint_var(j) {
            None => Track::constant(0.0),
            Some(_) => Track::from_samples(&joint_angle_samples(self, j), ANGLE_TOLERANCE),
        }
    }
}

/// Joint `j`'s signed angle (radians, positive = left) at every recorded state and wall
/// contact, unthinned ([`recorded_samples`]); empty for a joint that never turns. What the
/// collision check of a reference run reads ([`ReferenceRun::checked_summary`](crate::reference::ReferenceRun::checked_summary)).
pub(crate) fn joint_angle_samples(run: &ReferenceRun, j: usize) -> Vec<(f64, f64)> {
    match run.model.joint_var(j) {
        None => Vec::new(),
        Some(v) => {
            let sign = run.model.joint_sign(j);
            recorded_samples(run, v, |x| sign * x.clamp(0.0, 1.0) * FRAC_PI_2)
        }
    }
}

/// Unknown `v` of the reference's recorded states (the final state alone when none were
/// recorded) as `value` gives it, with the moments it met a wall
/// ([`ReferenceRun::walls`]: a bounce's peak or an arrival's corner, which the grid of
/// states straddles), in time order.
fn recorded_samples(run: &ReferenceRun, v: usize, value: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    if run.states.is_empty() {
        return vec![(run.end_time, value(run.final_state[v]))];
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
    samples
}
