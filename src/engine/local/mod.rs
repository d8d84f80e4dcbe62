//! The physical event engine: the chain's motion solved causally from the RI end, one joint
//! at a time, with the reference's physics (issue 12).
//!
//! Unit `j` is joint `j`'s pair of magnets (`2j + 1`, `2j + 2`) and, when the joint folds,
//! its angle ([`window`]). Only those unknowns are integrated ([`solve`]), each driven by
//! the pair forces of the magnets within the cutoff (the drives of
//! [`crate::physics`], the rates and the modes of [`crate::model::Model`], so the
//! dynamics and the pair law follow the reference's [`crate::model::ModelOptions`]):
//! the magnets upstream move on the tracks already solved, those downstream are at rest in
//! the first sweep and on their previous tracks in the later ones ([`sweeps`]). Starts,
//! arrivals and folds are the modes' switches, located on each step's dense output
//! ([`trajectory`]). The cost is a few hundred right-hand sides of a handful of pairs per
//! magnet; units that repeat an earlier one shifted in time cost a hash look-up.
//!
//! At `s = 0` every interior magnet sits exactly balanced and is driven off its rest point
//! by a rounding-sized force; its start is reported when it has moved
//! [`crate::timeline::S0_START_FRACTION`] of its path, as the reference reports it.

mod cache;
mod cluster;
mod relaxation;
mod solve;
mod sweep;
mod swing;
#[cfg(test)]
mod test_support;
mod trajectory;
mod unit_forces;

use std::f64::consts::FRAC_PI_2;

pub(crate) use relaxation::ChainSolution;

use crate::model::{Mode, Model, RestState};
use crate::timeline::{joint_of_magnet, start_fraction, Event, EventKind, FoldRecord, Outcome};
use crate::Fold;

/// Default tolerance of the local solves (fraction of a path or fold): 1e-8.
pub(crate) const DEFAULT_LOCAL_TOLERANCE: f64 = 1e-8;

/// What the engine takes from a chain solution.
pub(crate) struct Solved {
    pub(crate) chain: ChainSolution,
    /// Each magnet's reported start (NaN: never).
    pub(crate) start: Vec<f64>,
    /// Each magnet's arrival, or its last motion if it never arrived (NaN: never moved).
    pub(crate) arrival: Vec<f64>,
}

impl std::fmt::Debug for Solved {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Solved")
            .field("sweeps", &self.chain.sweeps)
            .field("solves", &self.chain.solves)
            .field("solves_per_sweep", &self.chain.solves_per_sweep)
            .finish()
    }
}

impl Solved {
    /// Magnet `k`'s fraction of path travelled at `t`.
    pub(crate) fn fraction(&self, k: usize, t: f64) -> f64 {
        self.chain
            .shapes
            .value(self.chain.magnets[k], t)
            .clamp(0.0, 1.0)
    }

    /// The times within `(from, to)` around which joint `j`'s fold turns back: both nodes of
    /// every piece of its solved track whose rate changes sign (a bounce at a wall, or a
    /// peak short of it), in order. The fold schedule's knots: a chord across such a turn
    /// can cut its peak whatever its midpoint says.
    pub(crate) fn turning_times(&self, j: usize, from: f64, to: f64) -> Vec<f64> {
        let track = self.chain.joints[j];
        if self.chain.shapes.first_move(track).is_none() {
            return Vec::new();
        }
        let shape = self.chain.shapes.get(track.shape);
        let mut out = Vec::new();
        for i in 1..shape.t.len() {
            if shape.dy[i - 1] * shape.dy[i] < 0.0 {
                for t in [shape.t[i - 1], shape.t[i]] {
                    let t = t + track.offset;
                    if t > from && t < to && out.last().is_none_or(|&l| l < t) {
                        out.push(t);
                    }
                }
            }
        }
        out
    }

    /// Joint `j`'s fraction of fold made at `t`.
    pub(crate) fn fold_fraction(&self, j: usize, t: f64) -> f64 {
        self.chain
            .shapes
            .value(self.chain.joints[j], t)
            .clamp(0.0, 1.0)
    }
}

/// Everything a run takes from the local solves.
pub(crate) struct LocalRun {
    pub(crate) solved: Solved,
    pub(crate) events: Vec<Event>,
    pub(crate) folds: Vec<FoldRecord>,
    pub(crate) fold_of_joint: Vec<u32>,
    pub(crate) outcome: Outcome,
    pub(crate) max_moving: (usize, f64),
}

/// Solves `model`'s chain (starts reported at [`start_fraction`]), the sweeps on `threads`
/// threads ([`EngineOptions::threads`](crate::engine::EngineOptions::threads)), each solve
/// at most `max_steps` steps.
pub(crate) fn run_local(model: &Model, tol: f64, threads: usize, max_steps: usize) -> LocalRun {
    let inertial = solve::InertialModel::new(model);
    let coupled = model
        .coupled_folds
        .then(|| cluster::Coupled::new(model))
        .flatten();
    let opts = solve::SolveOptions {
        tol,
        start_fraction: start_fraction(&model.geometry),
        max_steps,
        inertial: inertial.as_ref(),
        // a coupled joint's drive reads its velocity: RODAS4's Jacobian holds the drives
        // fixed, and a unit at rest may be released by a fold anywhere
        rosenbrock: coupled.is_none(),
        rest_skip: coupled.is_none(),
        coupled: coupled.as_ref(),
        horizon: f64::INFINITY,
    };
    let chain = relaxation::solve_chain(model, opts, threads);
    let g = &model.geometry;
    let n = g.magnets();
    let joints = g.tiles().saturating_sub(1);
    let mut events = chain.events();
    let mut start = vec![f64::NAN; n];
    let mut arrival = vec![f64::NAN; n];
    let mut folds = Vec::new();
    let mut fold_of_joint = vec![u32::MAX; joints];
    let (mut moving, mut max_moving) = (0usize, (0usize, 0.0));
    for e in &events {
        let i = e.index as usize;
        match e.kind {
            EventKind::MagnetStarts => {
                start[i] = e.time;
                moving += 1;
                if moving > max_moving.0 {
                    max_moving = (moving, e.time);
                }
            }
            EventKind::MagnetArrives => {
                arrival[i] = e.time;
                moving = moving.saturating_sub(1);
            }
            EventKind::FoldStarts => {
                let p0 = chain.units[i + 1].0.solution.p0;
                fold_of_joint[i] = folds.len() as u32;
                folds.push(FoldRecord {
                    joint: i,
                    fold: if model.joint_sign(i) > 0.0 {
                        Fold::L
                    } else {
                        Fold::R
                    },
                    start: e.time,
                    end: f64::NAN,
                    p0,
                });
            }
            EventKind::FoldEnds => {
                if let Some(f) = folds.get_mut(fold_of_joint[i] as usize) {
                    f.end = e.time;
                }
            }
            _ => {}
        }
    }
    for (a, &track) in arrival.iter_mut().zip(&chain.magnets) {
        if a.is_nan() {
            if let Some(t) = chain.shapes.last_move(track) {
                *a = t;
            }
        }
    }
    for f in &mut folds {
        if f.end.is_nan() {
            f.end = chain
                .shapes
                .last_move(chain.joints[f.joint])
                .unwrap_or(f.start);
        }
    }
    let time = events.last().map_or(0.0, |e| e.time);
    let outcome = outcome(model, &chain, time);
    events.extend(outcome.stop_event(time));
    LocalRun {
        solved: Solved {
            chain,
            start,
            arrival,
        },
        events,
        folds,
        fold_of_joint,
        outcome,
        max_moving,
    }
}

/// Unit and position of magnet `k` in it.
fn magnet_slot(k: usize) -> (usize, usize) {
    if k == 0 {
        (0, 0)
    } else if k % 2 == 1 {
        (k.div_ceil(2), 0)
    } else {
        (k / 2, 1)
    }
}

/// How the run ended, from each unit's final modes (the reference's verdict,
/// [`RestState::ending`]).
fn outcome(model: &Model, chain: &ChainSolution, time: f64) -> Outcome {
    let magnet_mode = |k: usize| {
        let (u, i) = magnet_slot(k);
        chain.units[u].0.solution.modes.get(i).copied()
    };
    let joint_mode = |j: usize| chain.units[j + 1].0.solution.modes.get(2).copied();
    RestState::ending(model, magnet_mode, joint_mode, time, |stall| {
        let j = stall.joint;
        let reason = match stall.unarrived.filter(|&k| joint_of_magnet(k) == j) {
            Some(k) => {
                let (u, i) = magnet_slot(k);
                let sol = &chain.units[u].0.solution;
                let drive = sol.drive.get(i).copied().unwrap_or(0.0);
                let len = model.path_length(k);
                match sol.modes.get(i) {
                    Some(Mode::AtStart) => format!(
                        "magnet {k} never started: the force along its path stays {drive:.3e} N (towards its rest point) once every magnet before it has stopped (local solve)"
                    ),
                    _ => format!(
                        "magnet {k} came to rest {:.4} mm along its {len:.4} mm path, the forces along it balanced ({drive:.3e} N): it cannot reach the point that starts the next magnet (local solve)",
                        sol.y.get(i).copied().unwrap_or(0.0) * len
                    ),
                }
            }
            None => match stall.open {
                Some(jj) => {
                    let sol = &chain.units[jj + 1].0.solution;
                    format!(
                        "joint {jj} stopped at {:.2} degrees, its torque balanced ({:.3e} N m) before the walls close it (local solve)",
                        sol.y.get(2).copied().unwrap_or(0.0) * 90.0,
                        sol.drive.get(2).copied().unwrap_or(0.0)
                    )
                }
                None => format!("propagation stopped at joint {j} (local solve)"),
            },
        };
        // a solve that ran out of its work budget decided nothing: its reason alone (the run is
        // `undecided`, `crate::simulation::check_engine_run`), not a rest it never came to
        chain
            .units
            .iter()
            .find_map(|u| u.0.solution.stopped.clone())
            .unwrap_or(reason)
    })
}

/// The signed angle of `fold` at `t` from its joint's solved track.
pub(crate) fn solved_fold_angle(solved: &Solved, fold: &FoldRecord, t: f64) -> f64 {
    let target = fold.fold.quarter_turns() as f64 * FRAC_PI_2;
    if t <= fold.start {
        return 0.0;
    }
    if t >= fold.end {
        // a fold that closed (its joint's final mode is at the end) ends exactly closed,
        // whatever the rounding of the track's offset or a shape shared within
        // SHAPE_TOLERANCE; one that stopped short ends where its track ends
        let closed = solved
            .chain
            .units
            .get(fold.joint + 1)
            .and_then(|u| u.0.solution.modes.get(2))
            == Some(&Mode::AtEnd);
        return if closed {
            target
        } else {
            target * solved.fold_fraction(fold.joint, fold.end)
        };
    }
    target * solved.fold_fraction(fold.joint, t)
}
