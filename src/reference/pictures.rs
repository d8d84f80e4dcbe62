//! The reference run as pictures: the chain's state (tile poses, magnet positions, what is
//! moving) at a recorded time, the energy curve and the transition diagram's data, drawn from
//! the reference's own recorded states, in the shapes the event engine's pictures take
//! (the `foldchain-render` crate reads them through [`crate::timeline::RunSource`]).
//!
//! The reference records its state on an evenly spaced time grid
//! ([`Recording::Grid`], at most [`STATE_BUDGET_BYTES`] of states). A step frame shows the
//! recorded state nearest its time (stamped with that state's own time); the final frame
//! shows the final state at [`ReferenceRun::end_time`], when the chain came to rest or the
//! integration stopped. Tile poses come from the joint angles and magnets from their paths,
//! as the integrator had them ([`crate::model::Model::poses`],
//! [`crate::model::Model::positions`]).

use kurbo::Point;

use crate::physics::{EnergyUnit, Pole};
#[cfg(doc)]
use crate::reference::options::Recording;
use crate::reference::run_result::ReferenceRun;
use crate::timeline::{ChainState, MagnetTrack, PairEnergies, TransitionData, DETAIL_TILES};
use crate::timeline::{EnergySample, EventKind};

/// Memory the recorded states of a reference run may take, bytes: 48 MiB, at most 4,096
/// states (one state is 8 bytes per unknown, at most three unknowns per tile).
pub(crate) const STATE_BUDGET_BYTES: usize = 48 << 20;

/// The states recorded for a chain of `tiles`: [`STATE_BUDGET_BYTES`] worth, from 64 to
/// 4,096 (about 1,000 at 2,000 tiles).
pub(crate) fn state_budget(tiles: usize) -> usize {
    (STATE_BUDGET_BYTES / (24 * tiles.max(1) + 32)).clamp(64, 4096)
}

/// The chain of state `y` at time `time` (magnet positions only for chains drawn in detail,
/// as [`ChainState::magnets`] says). A magnet counts as moving from its start event until its
/// arrival event, as in the event engine, and also whenever it lies strictly inside its path
/// (free, in the integrator's terms: pulled off an end, or balanced mid-path until the run
/// ends); a joint counts as turning likewise from its fold's start to its end, or while
/// strictly between straight and closed. A joint's hinge is drawn when it starts folding at
/// some time in the run.
pub fn reference_state(run: &ReferenceRun, time: f64, y: &[f64]) -> ChainState {
    let m = &run.model;
    let inside = |v: f64| v > 0.0 && v < 1.0;
    let joints = run.tiles().saturating_sub(1);
    let mut folds = vec![None; joints];
    for f in &run.folds {
        if let Some(slot) = folds.get_mut(f.joint) {
            *slot = Some(f.fold);
        }
    }
    let mut moving: Vec<bool> = (0..m.geometry.magnets())
        .map(|k| inside(y[m.magnet_var(k)]))
        .collect();
    let mut folding: Vec<bool> = (0..joints)
        .map(|j| m.joint_var(j).is_some_and(|v| inside(y[v])))
        .collect();
    let mut started = vec![false; moving.len()];
    let mut turning = vec![false; joints];
    for e in run.events.iter().take_while(|e| e.time <= time) {
        let i = e.index as usize;
        let (flag, on) = match e.kind {
            EventKind::MagnetStarts => (started.get_mut(i), true),
            EventKind::MagnetArrives => (started.get_mut(i), false),
            EventKind::FoldStarts => (turning.get_mut(i), true),
            EventKind::FoldEnds => (turning.get_mut(i), false),
            _ => (None, false),
        };
        if let Some(flag) = flag {
            *flag = on;
        }
    }
    moving.iter_mut().zip(&started).for_each(|(m, s)| *m |= s);
    folding.iter_mut().zip(&turning).for_each(|(f, s)| *f |= s);
    ChainState {
        time,
        poses: m.poses(y),
        magnets: if run.tiles() <= DETAIL_TILES {
            m.positions(y)
        } else {
            Vec::new()
        },
        moving,
        folding,
        folds,
    }
}

/// The recorded states, or the final state alone when none were recorded.
fn recorded(run: &ReferenceRun) -> Vec<(f64, &[f64])> {
    if run.states.is_empty() {
        vec![(run.end_time, run.final_state.as_slice())]
    } else {
        run.states.iter().map(|(t, y)| (*t, y.as_slice())).collect()
    }
}

/// Index of the recorded state nearest `t` (`states` is not empty and in time order).
fn nearest(states: &[(f64, &[f64])], t: f64) -> usize {
    let i = states.partition_point(|s| s.0 < t);
    if i == 0 {
        0
    } else if i == states.len() || t - states[i - 1].0 <= states[i].0 - t {
        i - 1
    } else {
        i
    }
}

/// The value at `t` of the polyline `points` (in time order), linear between its points and
/// constant outside them.
fn along(points: &[(f64, f64)], t: f64) -> f64 {
    let i = points.partition_point(|p| p.0 < t);
    match (i.checked_sub(1).and_then(|j| points.get(j)), points.get(i)) {
        (Some(&(ta, ua)), Some(&(tb, ub))) if tb > ta => ua + (ub - ua) * (t - ta) / (tb - ta),
        (_, Some(&(_, u))) | (Some(&(_, u)), None) => u,
        (None, None) => 0.0,
    }
}

/// The total dipole energy (J) of state `y`: the pairs the event engine's curve sums
/// ([`EnergyUnit`]: the RI with tile 0's magnets, the two magnets of each tile and the four
/// pairs across each joint), under the model's pair law at the world positions.
pub fn state_energy(run: &ReferenceRun, y: &[f64]) -> f64 {
    let g = &run.model.geometry;
    let moment = g.design(0).moment();
    let law = run.model.options().force_law;
    let p = run.model.positions(y);
    let ri = g.ri().position;
    let at = |pole: Pole| match pole {
        Pole::Ri => ri,
        Pole::Magnet(k) => Point::from(p[k]),
    };
    EnergyUnit::all(g.tiles())
        .map(|u| u.energy(law, moment, at))
        .sum()
}

/// The energy curve: for each of `samples` evenly spaced times from 0 to
/// [`ReferenceRun::end_time`], the recorded state nearest it (each state once, at its own
/// time), the last point the final state.
pub(crate) fn reference_energy(run: &ReferenceRun, samples: usize) -> Vec<EnergySample> {
    let states = recorded(run);
    let samples = samples.max(2);
    let mut picked: Vec<usize> = (0..samples)
        .map(|i| nearest(&states, run.end_time * i as f64 / (samples - 1) as f64))
        .collect();
    picked.dedup();
    picked
        .into_iter()
        .map(|i| EnergySample {
            time: states[i].0,
            energy_j: state_energy(run, states[i].1),
        })
        .collect()
}

/// The transition diagram's data for tiles `first..=last` (clamped to the chain), from the
/// reference's events (first start and last arrival of each magnet, the trigger ticks) and
/// its recorded states (the travel in between, linear between states: coarse when the
/// shown tiles move for only a few grid steps, as on long chains).
pub fn reference_transition(run: &ReferenceRun, first: usize, last: usize) -> TransitionData {
    let states = recorded(run);
    let (first, last) = TransitionData::tile_range(run.tiles(), first, last);
    let (k0, k1) = (2 * first, 2 * last + 1);
    let is_magnet = |k: usize| (k0..=k1).contains(&k);
    let mut start = vec![None; k1 - k0 + 1];
    let mut arrival = vec![None; k1 - k0 + 1];
    for e in &run.events {
        let k = e.index as usize;
        if !is_magnet(k) {
            continue;
        }
        match e.kind {
            EventKind::MagnetStarts => {
                start[k - k0].get_or_insert(e.time);
            }
            EventKind::MagnetArrives => arrival[k - k0] = Some(e.time),
            _ => {}
        }
    }
    // a magnet that started and never arrived moves (or rests mid-path) to the end
    let window_end = |i: usize| start[i].map(|_| arrival[i].unwrap_or(run.end_time));
    let end_time = (0..start.len()).filter_map(window_end).fold(0.0, f64::max);
    let t1 = TransitionData::axis_end(end_time);
    let tracks: Vec<MagnetTrack> = (k0..=k1)
        .map(|k| {
            let i = k - k0;
            let v = run.model.magnet_var(k);
            let len = run.model.path_length(k);
            let mut travel = vec![(0.0, 0.0)];
            if let (Some(s0), Some(end)) = (start[i], window_end(i)) {
                travel.push((s0, 0.0));
                travel.extend(
                    states
                        .iter()
                        .filter(|(t, _)| *t > s0 && *t < end)
                        .map(|(t, y)| (*t, y[v] * len)),
                );
                // an arrival puts the magnet exactly at its path's end; one that never
                // arrived is where the final state holds it
                let u = match arrival[i] {
                    Some(_) => len,
                    None => run.final_state[v] * len,
                };
                travel.push((end, u));
            }
            // still after its last arrival (or the end of the run), to the axis' end
            let u = travel.last().map_or(0.0, |p| p.1);
            travel.push((t1, u));
            MagnetTrack {
                start: start[i],
                travel,
            }
        })
        .collect();
    TransitionData::from_tracks((first, last), t1, tracks, &run.events, |track, _, t| {
        along(&track.travel, t)
    })
}

/// The recorded state nearest `time`, stamped with that state's own time (the final state
/// when none were recorded).
pub fn reference_state_near(run: &ReferenceRun, time: f64) -> ChainState {
    let states = recorded(run);
    let (t, y) = states[nearest(&states, time)];
    reference_state(run, t, y)
}

/// The final state at [`ReferenceRun::end_time`]; when the run ended because the chain came
/// to rest, nothing is drawn as moving.
pub fn reference_final_state(run: &ReferenceRun) -> ChainState {
    let mut state = reference_state(run, run.end_time, &run.final_state);
    if run.stopped.is_none() {
        state.moving.iter_mut().for_each(|m| *m = false);
        state.folding.iter_mut().for_each(|f| *f = false);
    }
    state
}

/// The energy curves of `run` from its recorded states (or its final state alone).
pub(crate) fn pair_energies(run: &ReferenceRun) -> PairEnergies {
    let states: Vec<(f64, &[f64])> = if run.states.is_empty() {
        vec![(run.end_time, run.final_state.as_slice())]
    } else {
        run.states.iter().map(|(t, y)| (*t, y.as_slice())).collect()
    };
    let g = &run.model.geometry;
    let n = g.magnets();
    let law = run.model.options().force_law;
    let ri = g.ri();
    let moment = |k: usize| g.design(k / 2).moment();
    let mut pairs = vec![Vec::with_capacity(states.len()); n];
    let mut times = Vec::with_capacity(states.len());
    let mut total = Vec::with_capacity(states.len());
    for (t, y) in &states {
        let p: Vec<Point> = run
            .model
            .positions(y)
            .into_iter()
            .map(Point::from)
            .collect();
        times.push(*t);
        total.push(state_energy(run, y));
        for (k, series) in pairs.iter_mut().enumerate() {
            let e = if k == 0 {
                let attract = Pole::Ri.attracts(Pole::Magnet(0));
                law.energy(ri.position, p[0], ri.moment, moment(0), attract)
            } else {
                let attract = Pole::Magnet(k - 1).attracts(Pole::Magnet(k));
                law.energy(p[k - 1], p[k], moment(k - 1), moment(k), attract)
            };
            series.push(e);
        }
    }
    let mut phases: Vec<f64> = run
        .events
        .iter()
        .filter(|e| e.kind.is_motion())
        .map(|e| e.time)
        .collect();
    phases.dedup();
    PairEnergies {
        times,
        pairs,
        total,
        phases,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use crate::reference::{run_reference, Recording, ReferenceOptions};
    use crate::timeline::{Outcome, TileDesigns};
    use crate::Chain;

    #[test]
    fn recorded_states_are_bounded_evenly_spaced_and_end_with_the_final_state() {
        let chain = Chain::parse("SLLS").unwrap();
        let opts = ReferenceOptions::default().with_record(Recording::Grid { max_states: 20 });
        let r = run_reference(&chain, &TileDesigns::default(), &opts).unwrap();
        assert_eq!(r.outcome, Outcome::Completed);
        let n = r.states.len();
        assert!((10..=20).contains(&n), "{n} states");
        assert_eq!(r.states[0].0, 0.0);
        let (t_end, y_end) = r.states.last().unwrap();
        assert_eq!(*t_end, r.end_time);
        assert_eq!(y_end, &r.final_state);
        let dt = r.states[1].0;
        for (i, (t, y)) in r.states[..n - 1].iter().enumerate() {
            assert!((t - i as f64 * dt).abs() <= 1e-9 * t.max(dt), "{i}: {t}");
            assert!(y.iter().all(|v| (0.0..=1.0).contains(v)));
        }
        // off by default: nothing but the final state
        let off = run_reference(
            &chain,
            &TileDesigns::default(),
            &ReferenceOptions::default(),
        )
        .unwrap();
        assert!(off.states.is_empty());
        assert_eq!(off.final_state, r.final_state);
    }
}
