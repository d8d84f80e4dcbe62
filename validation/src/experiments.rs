//! The thesis' experiments (section 7.3) as scenes with their observed outcome, run in the
//! reference model ([`run_experiments`]); `fold-validate --experiments` prints the table and
//! exits 1 when the model disagrees with an observation.
//!
//! - 7.3: the four three-tile configurations, "each test was carried out 5 times with a 100%
//!   success rate": two linear propagations (fold word SS), linear then a 90 degree turn (SL),
//!   a turn then linear (LS), two turns making 180 degrees (LL). Observed: complete, the joints
//!   of the L letters folded.
//! - 7.3.2: a straight path paired with a curved one still propagates linearly: the tile
//!   sequence SL-SR-SL "would produce the same outcome as" SS-SS-SS. Observed: complete, no
//!   fold.
//!
//! The thesis' other statement of 7.3.2, that a left and a right curve (SR-LS) inhibit
//! propagation, is Table 7.1's geometry (the event engine and the reference both find it),
//! not an observation with a count, and is left out here.
//!
//! [`foldchain::reference::ReferenceRun::pair_energies`] gives the energy curves of thesis figures 7.7 and 7.8
//! of the runs: each pair of adjacent magnets (the RI with magnet 0, then magnet `k` with
//! `k + 1`) and the total (the sum over every pair) against time.

use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::{
    run_reference, Recording, ReferenceError, ReferenceOptions, ReferenceRun,
};
use foldchain::timeline::TileDesigns;
use foldchain::{Chain, ChainError, FoldWord};

/// One experiment of the thesis with what was observed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Experiment {
    /// Its name, e.g. `7.3 SL`.
    pub name: &'static str,
    /// The chain: a fold word (`word:SL`) or a tile list (`SL SR SL`).
    pub chain: &'static str,
    /// What the thesis says happened, in its words.
    pub observed: &'static str,
    /// The joints observed folded.
    pub folds: &'static [usize],
}

/// The experiments, in the thesis' order.
pub const EXPERIMENTS: [Experiment; 5] = [
    Experiment {
        name: "7.3 SS",
        chain: "word:SS",
        observed: "two linear propagations: complete, 5 of 5",
        folds: &[],
    },
    Experiment {
        name: "7.3 SL",
        chain: "word:SL",
        observed: "linear then a 90 degree turn: complete, 5 of 5 (figures 7.6 a-f, 7.7)",
        folds: &[1],
    },
    Experiment {
        name: "7.3 LS",
        chain: "word:LS",
        observed: "a 90 degree turn then linear: complete, 5 of 5",
        folds: &[0],
    },
    Experiment {
        name: "7.3 LL",
        chain: "word:LL",
        observed: "two turns making 180 degrees: complete, 5 of 5 (figures 7.6 g-l, 7.8)",
        folds: &[0, 1],
    },
    Experiment {
        name: "7.3.2 SL-SR-SL",
        chain: "SL SR SL",
        observed: "a straight path paired with a curved one propagates linearly, as SS-SS-SS",
        folds: &[],
    },
];

impl Experiment {
    /// The experiment's chain.
    pub fn to_chain(&self) -> Result<Chain, ChainError> {
        match self.chain.strip_prefix("word:") {
            Some(w) => Ok(FoldWord::parse(w)?.to_chain()),
            None => Chain::parse(self.chain),
        }
    }
}

/// Why the experiments could not be run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExperimentError {
    /// An experiment's chain does not parse.
    #[error("experiment chain: {0}")]
    Chain(#[from] ChainError),
    /// A reference run refused its input.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
}

/// An experiment run in one model.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ExperimentResult {
    /// The experiment's name.
    pub name: String,
    /// The chain as given.
    pub chain: String,
    /// What was observed.
    pub observed: String,
    /// The joints observed folded.
    pub observed_folds: Vec<usize>,
    /// The pair law (`dipole` or `cylinder`).
    pub force_law: String,
    /// The dynamics (`inertial` or `overdamped`).
    pub dynamics: String,
    /// The model's outcome (`completed`, `stalled`, `inhibited`, `stopped`).
    pub outcome: String,
    /// The joints the model folded.
    pub folds: Vec<usize>,
    /// When the model's last event happened, s.
    pub duration_s: f64,
    /// Whether the model agrees: completed with the observed folds.
    pub agrees: bool,
}

/// Runs every experiment in each model of `models` (the thesis design, tolerance 1e-8),
/// keeping `max_states` states of each run for pictures (0: none). Returns each result with
/// its run.
pub fn run_experiments(
    models: &[ModelOptions],
    max_states: usize,
) -> Result<Vec<(ExperimentResult, ReferenceRun)>, ExperimentError> {
    let mut out = Vec::new();
    for e in EXPERIMENTS {
        for model in models {
            let record = if max_states > 0 {
                Recording::Grid { max_states }
            } else {
                Recording::Off
            };
            let opts = ReferenceOptions::default()
                .with_model(*model)
                .with_record(record);
            let run = run_reference(&e.to_chain()?, &TileDesigns::default(), &opts)?;
            let folds = run.folded_joints();
            let outcome = run.result().name().to_string();
            let agrees = outcome == "completed" && folds == e.folds;
            out.push((
                ExperimentResult {
                    name: e.name.into(),
                    chain: e.chain.into(),
                    observed: e.observed.into(),
                    observed_folds: e.folds.to_vec(),
                    force_law: model.force_law.name().into(),
                    dynamics: dynamics_name(model.dynamics).into(),
                    outcome,
                    folds,
                    duration_s: run.duration(),
                    agrees,
                },
                run,
            ));
        }
    }
    Ok(out)
}

fn dynamics_name(d: Dynamics) -> &'static str {
    d.name()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::physics::ForceLaw;

    #[test]
    fn chains_parse_and_energy_falls() {
        for e in EXPERIMENTS {
            assert_eq!(e.to_chain().unwrap().len(), 3, "{}", e.name);
        }
        let model = ModelOptions::default()
            .with_force_law(ForceLaw::PointDipole)
            .with_dynamics(Dynamics::Inertial);
        let runs = run_experiments(&[model], 200).unwrap();
        assert_eq!(runs.len(), EXPERIMENTS.len());
        for (r, run) in &runs {
            assert!(r.agrees, "{r:?}");
            let pe = run.pair_energies();
            assert_eq!(pe.pairs.len(), 6);
            assert!(pe.times.len() > 10);
            // the chain ends lower than it starts: the assembly releases energy
            let (first, last) = (pe.total[0], *pe.total.last().unwrap());
            assert!(last < first, "{}: {first} {last}", r.name);
            assert!(!pe.phases.is_empty());
        }
    }
}
