//! The event engine's timeline as a [`RunSource`]: the chain at any time, the transition
//! diagram's data, the energy curve, the tracks the viewer plays and `timeline.json`.

use crate::engine::{energy_curve, fold_angle, joint_angles_at, Timeline};
use crate::kinematics::poses_at_angles;
use crate::timeline::{
    ChainState, EnergySample, FoldRecord, Geometry, MagnetTrack, RunSource, TimelineJson, Track,
    TransitionData, ANGLE_TOLERANCE, DETAIL_TILES, EVENT_INDEX, TRAVEL_TOLERANCE,
};

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
        chain_state(self, t)
    }
    fn final_state(&self) -> ChainState {
        chain_state(self, self.duration())
    }
    fn transition(&self, first: usize, last: usize) -> TransitionData {
        transition(self, first, last)
    }
    fn energy(&self, samples: usize) -> Vec<EnergySample> {
        energy_curve(self, samples)
    }
    fn folds(&self) -> &[FoldRecord] {
        &self.folds
    }
    fn timeline_json(&self) -> String {
        timeline_json(self)
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
    fn magnet_travel_key(&self, k: usize) -> Option<([u64; 4], f64)> {
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

/// The engine's chain at time `t`.
fn chain_state(tl: &Timeline, t: f64) -> ChainState {
    let poses = poses_at_angles(&joint_angles_at(tl, t), tl.geometry.w);
    let magnets = if tl.tiles() <= DETAIL_TILES {
        (0..tl.geometry.magnets())
            .map(|k| poses[k / 2].transform_point(tl.local_position(k, t)))
            .collect()
    } else {
        Vec::new()
    };
    let moving = (0..tl.geometry.magnets())
        .map(|k| tl.is_moving(k, t))
        .collect();
    let joints = tl.tiles().saturating_sub(1);
    let folding = (0..joints)
        .map(|j| tl.fold_at(j).is_some_and(|f| t >= f.start && t < f.end))
        .collect();
    let folds = (0..joints).map(|j| tl.fold_at(j).map(|f| f.fold)).collect();
    ChainState {
        time: t,
        poses,
        magnets,
        moving,
        folding,
        folds,
    }
}

/// The engine's transition diagram for tiles `first..=last` (clamped to the chain): each
/// track sampled 48 times while its magnet moves.
fn transition(tl: &Timeline, first: usize, last: usize) -> TransitionData {
    let (first, last) = TransitionData::tile_range(tl.tiles(), first, last);
    let (k0, k1) = (2 * first, 2 * last + 1);
    let end_time = (k0..=k1)
        .filter_map(|k| tl.arrival_of(k))
        .fold(0.0, f64::max);
    let t1 = TransitionData::axis_end(end_time);
    let tracks = (k0..=k1)
        .map(|k| {
            let mut travel = vec![(0.0, 0.0)];
            if let (Some(s0), Some(a)) = (tl.start_of(k), tl.arrival_of(k)) {
                travel.push((s0, 0.0));
                for i in 1..=48 {
                    let t = s0 + (a - s0) * i as f64 / 48.0;
                    travel.push((t, tl.travel_at(k, t)));
                }
            }
            travel.push((t1, tl.travel_at(k, t1)));
            MagnetTrack {
                start: tl.start_of(k),
                travel,
            }
        })
        .collect();
    TransitionData::from_tracks((first, last), t1, tracks, &tl.events, |_, k, t| {
        tl.travel_at(k, t)
    })
}

/// The most events written by [`timeline_json`] (about 70 MB): a longer run writes the first
/// ones and says so (`"truncated": true`, `"events_total"`); the summary always counts all.
pub(crate) const MAX_TIMELINE_EVENTS: usize = 2_000_000;

/// All events as JSON: `{"tiles": n, "speed_law": ..., "events": [[t, "kind", index], ...]}`
/// (index: the magnet, or the joint for fold, inhibited and stalled events), at most
/// 2,000,000 of them (`MAX_TIMELINE_EVENTS`).
pub(crate) fn timeline_json(tl: &Timeline) -> String {
    let shown = tl.events.len().min(MAX_TIMELINE_EVENTS);
    TimelineJson {
        tiles: tl.tiles(),
        speed_law: tl.speed,
        events_total: Some(tl.events.len()),
        truncated: Some(shown < tl.events.len()),
        index: EVENT_INDEX,
        events: &tl.events[..shown],
    }
    .to_json()
}
