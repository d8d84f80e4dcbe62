//! The result of a reference run ([`ReferenceRun`]): its events, folds and outcome in the
//! event engine's vocabulary ([`crate::timeline`]), the final and recorded states, and the
//! work it took; its summary and `timeline.json` in the engine's forms.

use std::f64::consts::FRAC_PI_2;

use crate::model::Dynamics;
use crate::model::Model;
use crate::ode::{Method, StepStats};
use crate::reference::options::ReferenceOptions;
use crate::timeline::{
    Event, FoldRecord, Outcome, RunFacts, RunResult, SpeedLaw, Summary, TimelineJson, EVENT_INDEX,
};

/// The result of a reference run.
#[derive(Debug)]
pub struct ReferenceRun {
    /// The model (geometry and unknowns).
    pub model: Model,
    /// The options used.
    pub options: ReferenceOptions,
    /// Every event, in time order (the engine's kinds and indices).
    pub events: Vec<Event>,
    /// The folds, in the order they start (`end` is NaN for a fold that never closed).
    pub folds: Vec<FoldRecord>,
    /// How propagation ended.
    pub outcome: Outcome,
    /// Why integration stopped early (its work budget, step-size underflow), if it did.
    pub stopped: Option<String>,
    /// Whether it stopped on its work budget ([`ReferenceOptions::step_budget`], or no event
    /// for 1e4 of its time scales) before the physics decided: the result is then
    /// `undecided`, `stopped` saying the balance and its margin.
    pub undecided: bool,
    /// The state at the end.
    pub final_state: Vec<f64>,
    /// Recorded `(time s, state)` pairs in time order, the last one the final state
    /// ([`ReferenceOptions::record`]; empty when off).
    pub states: Vec<(f64, Vec<f64>)>,
    /// Every moment a free unknown met one of its walls while states were recorded (a
    /// bounce, an arrival, a fold closing): `(time s, state index, the wall 0 or 1)`, in
    /// time order (empty when not recording). An even grid of states straddles such a
    /// corner and cuts it (a fold's bounce by up to its speed times the grid spacing): the
    /// tracks drawn from the states ([`crate::timeline::RunSource`]) keep these points too.
    pub walls: Vec<(f64, usize, f64)>,
    /// When the chain came to rest (or integration stopped), s.
    pub end_time: f64,
    /// The most magnets moving at once, and when first.
    pub max_moving: (usize, f64),
    /// Work counters.
    pub stats: StepStats,
    /// Which reference made the run, as `summary.json`'s parameters name it
    /// ("joint-angle reference" or "free-body reference").
    pub made_by: &'static str,
}

/// The law a reference timeline's times are in, as its JSON names it.
#[derive(serde::Serialize)]
struct ReferenceLaw {
    reference: ReferenceSettings,
}

#[derive(serde::Serialize)]
struct ReferenceSettings {
    method: Method,
    tolerance: f64,
    drag: f64,
}

impl ReferenceRun {
    /// The energy of each pair of neighbouring magnets against time, from the recorded states
    /// (or the final state alone): what the thesis' experiments plot.
    pub fn pair_energies(&self) -> crate::timeline::PairEnergies {
        crate::reference::pair_energies(self)
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.model.geometry.tiles()
    }

    /// When the last event happens, s.
    pub fn duration(&self) -> f64 {
        self.events.last().map_or(0.0, |e| e.time)
    }

    /// The joints that folded (closed), in the order they started.
    pub fn folded_joints(&self) -> Vec<usize> {
        self.folds
            .iter()
            .filter(|f| !f.end.is_nan())
            .map(|f| f.joint)
            .collect()
    }

    /// The final signed joint angles, radians.
    pub fn final_angles(&self) -> Vec<f64> {
        self.model.joint_angles(&self.final_state)
    }

    /// The final world positions of the magnets, mm.
    pub fn final_positions(&self) -> Vec<(f64, f64)> {
        self.model.positions(&self.final_state)
    }

    /// The outcome's result, or [`RunResult::Undecided`] when integration ran out of its
    /// work budget, [`RunResult::Stopped`] when it stopped early otherwise.
    pub fn result(&self) -> RunResult {
        if self.stopped.is_some() && self.undecided {
            RunResult::Undecided
        } else if self.stopped.is_some() {
            RunResult::Stopped
        } else {
            RunResult::from(&self.outcome)
        }
    }

    /// The summary, with the same fields as the event engine's `summary.json` (no collision
    /// check: `first_collision` is null; `speed_law` is the dynamics with its drag).
    pub fn to_summary(&self) -> Summary {
        let summary = Summary::new(RunFacts {
            tiles: self.tiles(),
            outcome: &self.outcome,
            decided_by: "reference dynamics",
            duration_s: self.duration(),
            events: self.events.len(),
            folds: self.folded_joints(),
            max_moving_magnets: self.max_moving.0,
            speed_law: match self.model.options().dynamics {
                Dynamics::Inertial => SpeedLaw::Inertial {
                    drag: self.model.drag,
                },
                _ => SpeedLaw::Overdamped {
                    drag: self.model.drag,
                },
            },
        });
        let mut summary = summary.with_parameters(self.model.parameters(self.made_by));
        // the joints' angles against time are known only from recorded states
        if !self.states.is_empty() {
            summary = summary.with_free_motion(self.model.free_motion(self));
        }
        match &self.stopped {
            Some(why) if self.undecided => summary.undecided(why.clone()),
            Some(why) => summary.overruled(RunResult::Stopped, why.clone()),
            None => summary,
        }
    }

    /// `timeline.json` in the event engine's format, the law named `reference`.
    pub fn timeline_json(&self) -> String {
        TimelineJson {
            tiles: self.tiles(),
            speed_law: ReferenceLaw {
                reference: ReferenceSettings {
                    method: self.options.method,
                    tolerance: self.options.tolerance,
                    drag: self.model.drag,
                },
            },
            events_total: None,
            truncated: None,
            index: EVENT_INDEX,
            events: &self.events,
        }
        .to_json()
    }

    /// The fraction of each fold made at the end (1 = closed by the walls).
    pub fn fold_fractions(&self) -> Vec<(usize, f64)> {
        (0..self.tiles().saturating_sub(1))
            .filter_map(|j| self.model.joint_var(j).map(|v| (j, self.final_state[v])))
            .collect()
    }

    /// The final angle of joint `j` in degrees.
    pub fn final_angle_degrees(&self, j: usize) -> f64 {
        self.final_angles()
            .get(j)
            .map_or(0.0, |a| a / FRAC_PI_2 * 90.0)
    }
}
