//! The stiff cases of the reference model (issue 6: "the stiff integrator must finish the
//! stiff cases where the explicit one needs far more steps"), and the study that runs each
//! with both integrators and counts their work (`fold-validate --stiff`).
//!
//! **Where the model is stiff.** Two time scales meet in it: a magnet's, its path travelled
//! at the bonded rest force's speed ([`Model::time_scale`]), and a fold's, a quarter turn
//! under the bonded rest torque against its two sides' water drag ([`TimeScales::fold_s`]).
//! With the default drags a fold is the faster (the overdamped model's magnet drag is an
//! assumption far above the water's) and nothing is stiff. Tiles turning slowly in a
//! liquid many decades more viscous than water
//! make the folds far slower than the magnets: the magnets of a folding pair then follow
//! their balances, which the fold moves slowly, relaxing to them at a rate of the order of
//! `1 / time_scale`. That is a stiff system. Dormand-Prince's stability region bounds its
//! step by about `3.3 / |lambda|` whatever the tolerance, so its step count grows in
//! proportion to the fold time (to the viscosity); ROS2 is L-stable and steps at the
//! pace the fold's own accuracy asks, so its count does not grow. On non-stiff cases ROS2,
//! second order, needs more steps than the fifth-order Dormand-Prince: the control cases
//! show that too.
//!
//! **The moment factor.** Forces go as the square of the moment and the dynamics is
//! overdamped, so scaling every moment by `f` divides every time by `f^2` and changes
//! nothing else: step counts and outcomes stay (the integrators and the driver measure
//! steps against the model's own time scales). The cases use `f = 100` only so that their
//! end times read in seconds rather than in months.
//!
//! **Counts, not clocks.** Step and right-hand-side counts are deterministic; wall times are
//! reported for reading but depend on the machine and on whatever else runs on it.
//!
//! ```
//! use foldchain_validation::stiff::{select_cases, run_stiff_study};
//!
//! let cases = select_cases(&["SLLS control".to_string()]).unwrap();
//! let study = run_stiff_study(&cases, &mut |_, _| {}).unwrap();
//! assert_eq!(study.rows.len(), 2); // dopri5, ros2
//! assert!(study.cases[0].stiffness_ratio < 1.0); // default drags: not stiff
//! ```

use std::time::Instant;

use foldchain::model::{Model, ModelOptions};
use foldchain::reference::{run_reference, Method, ReferenceError, ReferenceOptions, ReferenceRun};
use foldchain::timeline::TileDesigns;
use foldchain::{Chain, ChainError, Design};

/// One case of the study: a chain, a design and drags, and the tolerance both integrators
/// run at.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct StiffCase {
    /// Short name (table, JSON, `--case`).
    pub name: &'static str,
    /// The fold word.
    pub word: &'static str,
    /// Every magnet's remanence (so its moment) times this, on the thesis design.
    pub moment_factor: f64,
    /// The water's viscosity is the design's times this, and with it every tile's drag on
    /// the water (the magnet drag in its channel stays the default).
    pub viscosity_factor: f64,
    /// Tolerance of both integrators.
    pub tolerance: f64,
    /// Whether the case is meant to be stiff (false: a non-stiff control).
    pub stiff: bool,
    /// Why it is (or is not) stiff.
    pub why: &'static str,
}

/// The cases, in table order: two non-stiff controls, then three stiff cases by growing
/// water viscosity (so tile drag). `SLLS visc x1e9` is cheap enough for the tests (Dormand-Prince under a
/// second in release); `SLLS visc x1e10` shows the widest gap (Dormand-Prince several
/// seconds).
pub const STIFF_CASES: &[StiffCase] = &[
    StiffCase {
        name: "SLLS control",
        word: "SLLS",
        moment_factor: 100.0,
        viscosity_factor: 1.0,
        tolerance: 1e-3,
        stiff: false,
        why: "default drags: a fold is no slower than the magnets' move, so nothing is stiff and the fifth-order explicit method needs fewer steps than the second-order ROS2",
    },
    StiffCase {
        name: "SLLS control 1e-6",
        word: "SLLS",
        moment_factor: 100.0,
        viscosity_factor: 1.0,
        tolerance: 1e-6,
        stiff: false,
        why: "the same non-stiff case at a tight tolerance, where ROS2's second order costs it most: the explicit method's fifth order wins by far",
    },
    StiffCase {
        name: "LL visc x1e8",
        word: "LL",
        moment_factor: 100.0,
        viscosity_factor: 1e8,
        tolerance: 1e-4,
        stiff: true,
        why: "heavy tiles fold about 1e5 times slower than the magnets move; the magnets of the folding pair follow their slowly moving balances, so the explicit method's steps are held to its stability bound",
    },
    StiffCase {
        name: "SLLS visc x1e9",
        word: "SLLS",
        moment_factor: 100.0,
        viscosity_factor: 1e9,
        tolerance: 1e-3,
        stiff: true,
        why: "heavier tiles, folds about 1e6 times slower than the magnets: the explicit method's steps grow with the fold time, ROS2's do not",
    },
    StiffCase {
        name: "SLLS visc x1e10",
        word: "SLLS",
        moment_factor: 100.0,
        viscosity_factor: 1e10,
        tolerance: 1e-3,
        stiff: true,
        why: "ten times heavier again, folds about 1e7 times slower than the magnets: ten times the explicit method's steps, ROS2's the same",
    },
];

/// Why the study could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StiffError {
    /// A case name that is not in [`STIFF_CASES`].
    #[error("unknown stiff case '{name}': expected one of {known}")]
    UnknownCase {
        /// The name given.
        name: String,
        /// The names known.
        known: String,
    },
    /// A case's fold word does not parse.
    #[error("stiff case '{case}': fold word: {source}")]
    Chain {
        /// The case.
        case: String,
        /// Why.
        source: ChainError,
    },
    /// The model or a reference run refused the case.
    #[error("stiff case '{case}': {source}")]
    Reference {
        /// The case.
        case: String,
        /// Why.
        source: Box<ReferenceError>,
    },
}

/// The model's two time scales on a case (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TimeScales {
    /// A magnet's time scale, s: its path travelled at the bonded rest force's speed.
    pub magnet_s: f64,
    /// A fold's, s: the slowest quarter turn at the bonded rest torque against its two
    /// sides' water drag about the hinge ([`Model::slowest_fold_time`]). An estimate: the torque on a real fold
    /// changes as it turns and its magnets move; on these cases the folds measured
    /// ([`StiffRow::longest_fold_s`]) take between about 0.4 and 2 times this.
    pub fold_s: f64,
}

impl TimeScales {
    /// The fold's time scale over the magnets': far above 1 is stiff.
    pub fn ratio(&self) -> f64 {
        self.fold_s / self.magnet_s
    }
}

impl StiffCase {
    /// The chain.
    pub fn chain(&self) -> Result<Chain, StiffError> {
        Chain::parse(self.word).map_err(|source| StiffError::Chain {
            case: self.name.to_string(),
            source,
        })
    }

    /// The thesis design with the moments scaled by [`StiffCase::moment_factor`] and the
    /// water's viscosity by [`StiffCase::viscosity_factor`].
    pub fn designs(&self) -> TileDesigns {
        let t = Design::thesis();
        TileDesigns::global(Design {
            remanence: t.remanence * self.moment_factor,
            water_viscosity: t.water_viscosity * self.viscosity_factor,
            ..t
        })
    }

    /// The default model (overdamped).
    pub fn model_options(&self) -> ModelOptions {
        ModelOptions::default()
    }

    /// The reference options of a run with `method`.
    pub fn reference_options(&self, method: Method) -> ReferenceOptions {
        ReferenceOptions::default()
            .with_method(method)
            .with_tolerance(self.tolerance)
            .with_model(self.model_options())
    }

    fn reference_error(&self, source: ReferenceError) -> StiffError {
        StiffError::Reference {
            case: self.name.to_string(),
            source: Box::new(source),
        }
    }

    /// The model's time scales on this case.
    pub fn time_scales(&self) -> Result<TimeScales, StiffError> {
        let model = Model::new(&self.chain()?, &self.designs(), &self.model_options())
            .map_err(|e| self.reference_error(e.into()))?;
        Ok(TimeScales {
            magnet_s: model.time_scale,
            fold_s: model.slowest_fold_time(),
        })
    }

    /// One reference run with `method`, and its wall time in seconds.
    pub fn run(&self, method: Method) -> Result<(ReferenceRun, f64), StiffError> {
        let chain = self.chain()?;
        let designs = self.designs();
        let opts = self.reference_options(method);
        let t0 = Instant::now();
        let r = run_reference(&chain, &designs, &opts).map_err(|e| self.reference_error(e))?;
        Ok((r, t0.elapsed().as_secs_f64()))
    }
}

/// The cases named in `names`, in [`STIFF_CASES`] order, or all of them when `names` is
/// empty.
pub fn select_cases(names: &[String]) -> Result<Vec<StiffCase>, StiffError> {
    for name in names {
        if !STIFF_CASES.iter().any(|c| c.name == name) {
            return Err(StiffError::UnknownCase {
                name: name.clone(),
                known: STIFF_CASES
                    .iter()
                    .map(|c| format!("'{}'", c.name))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    Ok(STIFF_CASES
        .iter()
        .filter(|c| names.is_empty() || names.iter().any(|n| n == c.name))
        .copied()
        .collect())
}

/// One run of one case.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StiffRow {
    /// The case.
    pub case: String,
    /// `dopri5` or `ros2`.
    pub method: String,
    /// The tolerance.
    pub tolerance: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Right-hand-side evaluations (Jacobians and event location included).
    pub rhs: u64,
    /// Wall time, s (depends on the machine and its load; the counts do not).
    pub wall_s: f64,
    /// When the chain came to rest (or integration stopped), s.
    pub end_time_s: f64,
    /// The last event, s.
    pub duration_s: f64,
    /// The longest fold that closed, s, if one did.
    pub longest_fold_s: Option<f64>,
    /// `completed`, `inhibited` or `stalled`.
    pub outcome: String,
    /// Why integration stopped early, if it did ([`ReferenceRun::stopped`]).
    pub stopped: Option<String>,
}

impl StiffRow {
    fn new(case: &StiffCase, method: Method, r: &ReferenceRun, wall_s: f64) -> StiffRow {
        StiffRow {
            case: case.name.to_string(),
            method: method.name().to_string(),
            tolerance: case.tolerance,
            steps: r.stats.accepted,
            rejected: r.stats.rejected,
            rhs: r.stats.rhs,
            wall_s,
            end_time_s: r.end_time,
            duration_s: r.duration(),
            longest_fold_s: r
                .folds
                .iter()
                .filter(|f| !f.end.is_nan())
                .map(|f| f.end - f.start)
                .reduce(f64::max),
            outcome: r.outcome.name().to_string(),
            stopped: r.stopped.clone(),
        }
    }
}

/// What one case showed.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CaseReport {
    /// The case.
    #[serde(flatten)]
    pub case: StiffCase,
    /// The model's time scales.
    pub time_scales: TimeScales,
    /// Their ratio, fold over magnet ([`TimeScales::ratio`]).
    pub stiffness_ratio: f64,
    /// Dormand-Prince's accepted steps over ROS2's.
    pub step_ratio: f64,
}

/// The study's results.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StiffStudy {
    /// Every run, two per case (Dormand-Prince, then ROS2).
    pub rows: Vec<StiffRow>,
    /// Every case.
    pub cases: Vec<CaseReport>,
}

/// Runs every case in `cases` with Dormand-Prince and with ROS2. `progress(case, method)`
/// is called before each run.
pub fn run_stiff_study(
    cases: &[StiffCase],
    progress: &mut dyn FnMut(&str, Method),
) -> Result<StiffStudy, StiffError> {
    let mut rows = Vec::new();
    let mut reports = Vec::new();
    for case in cases {
        let time_scales = case.time_scales()?;
        let mut steps = [0u64; 2];
        for (i, method) in [Method::Dopri5, Method::Ros2].into_iter().enumerate() {
            progress(case.name, method);
            let (r, wall) = case.run(method)?;
            steps[i] = r.stats.accepted;
            rows.push(StiffRow::new(case, method, &r, wall));
        }
        reports.push(CaseReport {
            case: *case,
            time_scales,
            stiffness_ratio: time_scales.ratio(),
            step_ratio: steps[0] as f64 / steps[1].max(1) as f64,
        });
    }
    Ok(StiffStudy {
        rows,
        cases: reports,
    })
}

impl StiffStudy {
    /// `{"rows": [...], "cases": [...]}`.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// The table, plain text: one line per run, then one paragraph per case.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        s.push_str(&format!(
            "{:<18} {:<7} {:>6} {:>8} {:>8} {:>9} {:>8} {:>11} {:>11}  {:<9} {}\n",
            "case",
            "method",
            "tol",
            "steps",
            "rejected",
            "rhs",
            "wall_s",
            "end_s",
            "fold_s",
            "outcome",
            "stopped"
        ));
        for r in &self.rows {
            s.push_str(&format!(
                "{:<18} {:<7} {:>6} {:>8} {:>8} {:>9} {:>8.3} {:>11.4e} {:>11}  {:<9} {}\n",
                r.case,
                r.method,
                format!("{:.0e}", r.tolerance),
                r.steps,
                r.rejected,
                r.rhs,
                r.wall_s,
                r.end_time_s,
                r.longest_fold_s
                    .map_or("-".to_string(), |f| format!("{f:.4e}")),
                r.outcome,
                if r.stopped.is_some() { "yes" } else { "-" }
            ));
        }
        s.push_str(
            "\nfold_s: the longest fold that closed. Counts are deterministic; wall times depend on the machine and its load.\n",
        );
        for c in &self.cases {
            s.push_str(&format!(
                "\n{} ({}; {}, moments x{}, water viscosity x{:e}, tolerance {:.0e}): fold time scale {:.3e} s over the magnets' {:.3e} s = {:.2e}; dopri5 took {}x ROS2's accepted steps.\n  {}\n",
                c.case.name,
                if c.case.stiff { "stiff" } else { "control" },
                c.case.word,
                c.case.moment_factor,
                c.case.viscosity_factor,
                c.case.tolerance,
                c.time_scales.fold_s,
                c.time_scales.magnet_s,
                c.stiffness_ratio,
                if c.step_ratio < 1.0 {
                    format!("{:.3}", c.step_ratio)
                } else {
                    format!("{:.1}", c.step_ratio)
                },
                c.case.why
            ));
            for r in self.rows.iter().filter(|r| r.case == c.case.name) {
                if let Some(why) = &r.stopped {
                    s.push_str(&format!("  {} stopped: {why}\n", r.method));
                }
            }
        }
        s
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn cases_are_well_formed_and_the_ratio_tells_stiff_from_control() {
        let mut names: Vec<&str> = STIFF_CASES.iter().map(|c| c.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), STIFF_CASES.len(), "names must be unique");
        for c in STIFF_CASES {
            assert!(c.tolerance > 0.0 && c.tolerance <= 0.1, "{}", c.name);
            let ts = c.time_scales().unwrap();
            // thresholds with decades of room: controls sit near 0.1, stiff cases at 1e5+
            if c.stiff {
                assert!(ts.ratio() > 1e4, "{}: {}", c.name, ts.ratio());
            } else {
                assert!(ts.ratio() < 1.0, "{}: {}", c.name, ts.ratio());
            }
            // the ratio follows the drags alone: a pure time rescale leaves it
            let one = StiffCase {
                moment_factor: 1.0,
                ..*c
            };
            let r1 = one.time_scales().unwrap().ratio();
            assert!((r1 / ts.ratio() - 1.0).abs() < 1e-9, "{}: {r1}", c.name);
        }
    }

    #[test]
    fn unknown_case_is_an_error_naming_the_known_ones() {
        let e = select_cases(&["SLLS rot x1e9".to_string()]).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("'SLLS rot x1e9'"), "{msg}");
        assert!(msg.contains("'SLLS visc x1e10'"), "{msg}");
        assert_eq!(select_cases(&[]).unwrap().len(), STIFF_CASES.len());
    }

    #[test]
    fn control_study_table_and_json() {
        let cases = select_cases(&["SLLS control".to_string()]).unwrap();
        let mut calls = Vec::new();
        let study = run_stiff_study(&cases, &mut |c, m| calls.push((c.to_string(), m))).unwrap();
        assert_eq!(
            calls,
            vec![
                ("SLLS control".to_string(), Method::Dopri5),
                ("SLLS control".to_string(), Method::Ros2)
            ]
        );
        for r in &study.rows {
            assert_eq!(r.outcome, "completed", "{r:?}");
            assert_eq!(r.stopped, None);
            assert!(r.longest_fold_s.is_some());
        }
        // not stiff: the second-order ROS2 needs more steps than the fifth-order method
        assert!(study.rows[1].steps > study.rows[0].steps, "{study:?}");
        assert!(study.cases[0].step_ratio < 1.0);
        let table = study.to_table();
        assert!(table.contains("SLLS control"), "{table}");
        assert!(table.contains("(control; SLLS"), "{table}");
        let json: serde_json::Value = serde_json::from_str(&study.to_json()).unwrap();
        assert_eq!(json["rows"].as_array().unwrap().len(), 2);
        assert_eq!(json["rows"][1]["method"], "ros2");
        assert_eq!(json["cases"][0]["name"], "SLLS control");
        assert_eq!(json["cases"][0]["stiff"], false);
        assert!(json["cases"][0]["time_scales"]["fold_s"].as_f64().unwrap() > 0.0);
    }
}
