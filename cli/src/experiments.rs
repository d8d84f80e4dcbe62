//! `fold-validate --experiments`: the thesis' experiments (section 7.3) in the reference with
//! both pair laws and both dynamics, their table (or JSON), and the energy pictures of the
//! three-tile scenes like the thesis' figures 7.7 and 7.8 at the default physics (inertial,
//! point dipoles).

use std::fmt::Write;
use std::path::{Path, PathBuf};

use foldchain::model::{Dynamics, ModelOptions};
use foldchain::physics::ForceLaw;
use foldchain::Design;
use foldchain_render::pair_energy_svg;
use foldchain_validation::experiments::{run_experiments, ExperimentResult};

use crate::output::OutputDir;

/// What the experiments gave: the results, the table or JSON to print, the files written.
pub struct ExperimentsReport {
    /// One result per experiment and model.
    pub results: Vec<ExperimentResult>,
    /// The table (or the JSON with `json`).
    pub text: String,
    /// The pictures written.
    pub files: Vec<PathBuf>,
}

impl ExperimentsReport {
    /// Whether every model agrees with every observation.
    pub fn all_agree(&self) -> bool {
        self.results.iter().all(|r| r.agrees)
    }
}

/// Runs the experiments in the four models and writes `experiment-NAME.svg` into `out`.
pub fn experiments(out: &Path, json: bool) -> anyhow::Result<ExperimentsReport> {
    let d = Design::thesis();
    let inertial = Dynamics::Inertial;
    let mut models = Vec::new();
    for dynamics in [inertial, Dynamics::Overdamped] {
        for law in [ForceLaw::PointDipole, ForceLaw::cylinder(&d)] {
            models.push(
                ModelOptions::default()
                    .with_force_law(law)
                    .with_dynamics(dynamics),
            );
        }
    }
    let runs = run_experiments(&models, 600)?;
    let mut dir = OutputDir::create(out)?;
    let drawn: Vec<_> = runs
        .iter()
        .filter(|(r, _)| {
            r.force_law == "dipole" && r.dynamics == "inertial" && r.name.starts_with("7.3 ")
        })
        .map(|(r, run)| {
            let stem = r.name.replace(['.', ' '], "-").to_lowercase();
            (r, run, format!("experiment-{stem}.svg"))
        })
        .collect();
    dir.claim(drawn.iter().map(|(_, _, file)| file.as_str()))?;
    for (r, run, file) in drawn {
        let title = format!(
            "{}: {} ({}, {}), {}",
            r.name, r.chain, r.dynamics, r.force_law, r.outcome
        );
        let svg = pair_energy_svg(&run.pair_energies(), &title);
        dir.write(&file, svg.as_bytes())?;
    }
    let files = dir.written().iter().map(|f| out.join(f)).collect();
    let results: Vec<ExperimentResult> = runs.into_iter().map(|(r, _)| r).collect();
    let text = if json {
        format!("{}\n", serde_json::to_string_pretty(&results)?)
    } else {
        table(&results)
    };
    Ok(ExperimentsReport {
        results,
        text,
        files,
    })
}

fn table(results: &[ExperimentResult]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<16} {:<10} {:<9} {:<11} {:>10} {:<8} {:<10} agrees",
        "experiment", "dynamics", "law", "model", "duration", "folds", "observed"
    );
    for r in results {
        let _ = writeln!(
            s,
            "{:<16} {:<10} {:<9} {:<11} {:>8.4} s {:<8} {:<10} {}",
            r.name,
            r.dynamics,
            r.force_law,
            r.outcome,
            r.duration_s,
            format!("{:?}", r.folds),
            format!("{:?}", r.observed_folds),
            if r.agrees { "yes" } else { "NO" }
        );
    }
    let mut seen = Vec::new();
    for r in results {
        if !seen.contains(&r.name) {
            let _ = writeln!(s, "{}: observed {}", r.name, r.observed);
            seen.push(r.name.clone());
        }
    }
    s
}
