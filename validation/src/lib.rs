//! The simulations measured, above both: against each other and against the thesis.
//!
//! - [`scenes`]: the scenes `fold-validate` runs; [`experiments`]: the thesis' experiments
//!   (7.3, 7.3.2) with what was observed.
//! - [`validate`]: error against run time (`fold-validate`): for each scene a reference run
//!   at a tight tolerance, then the event engine and each integrator along a ladder of
//!   tolerances, each with its error and wall time; the table, the JSON rows and the
//!   work-precision plot.
//!
//! How the runs' events are compared: [`compare_events`].
//!
//! **The event engine's rows.** `event` is the engine: local solves of the reference's
//! model, one joint at a time (issue 12; overdamped only: with inertial dynamics the row is
//! left out). The kinematic baseline follows: `event-force` with the force rule for
//! starting magnets ([`StartRule::Force`]) at the reference's cutoff and the closed-form
//! speed law, whose best-fit time factor the scene report gives; `event-dist` with the
//! thesis' distance rule (nearest neighbours).

mod compare;
pub mod experiments;
mod results;
pub mod scenes;
pub mod stiff;
mod work_precision_plot;

use std::time::Instant;

use crate::scenes::{all_scenes, Scene};
use foldchain::engine::{run, EngineError, EngineOptions, StartRule, Timeline};
use foldchain::model::ModelOptions;
use foldchain::reference::Method;
use foldchain::reference::{run_reference, ReferenceError, ReferenceOptions, ReferenceRun};
use foldchain::Pose;

pub use compare::{compare_events, compare_events_within, EventComparison};
pub use results::{Row, SceneReport, Validation};

/// Options of a validation. Defaults: every scene, reference tolerance 1e-10 (Dormand-Prince),
/// Dormand-Prince at 1e-3 to 1e-8, ROS2 at 1e-2 to 1e-5.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidateOptions {
    /// Scenes to run (names, exact), or all when empty.
    pub scenes: Vec<String>,
    /// Tolerance of the reference run.
    pub reference_tolerance: f64,
    /// Tolerances for Dormand-Prince.
    pub dopri5: Vec<f64>,
    /// Tolerances for ROS2.
    pub ros2: Vec<f64>,
    /// The model of every reference run, and the pair law of the engine's force rule
    /// (default [`ModelOptions::default`]).
    pub model: ModelOptions,
}

impl Default for ValidateOptions {
    fn default() -> ValidateOptions {
        ValidateOptions {
            scenes: Vec::new(),
            reference_tolerance: 1e-10,
            dopri5: vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
            ros2: vec![1e-2, 1e-3, 1e-4, 1e-5],
            model: ModelOptions::default(),
        }
    }
}

impl ValidateOptions {
    /// Only these scenes.
    pub fn with_scenes(mut self, scenes: Vec<String>) -> ValidateOptions {
        self.scenes = scenes;
        self
    }
}

/// Why a validation could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ValidateError {
    /// An unknown scene name.
    #[error("unknown scene '{name}': expected one of {known}")]
    UnknownScene {
        /// The name given.
        name: String,
        /// The names known.
        known: String,
    },
    /// The engine failed.
    #[error("scene '{scene}': {source}")]
    Engine {
        /// The scene.
        scene: String,
        /// Why.
        source: Box<EngineError>,
    },
    /// The reference failed.
    #[error("scene '{scene}': {source}")]
    Reference {
        /// The scene.
        scene: String,
        /// Why.
        source: Box<ReferenceError>,
    },
}

/// Final tile centres and magnet positions (mm) of an engine run.
fn engine_final(tl: &Timeline) -> Vec<(f64, f64)> {
    let t = tl.duration();
    let angles = tl.joint_angles_at(t);
    let poses = Pose::chain_at_angles(&angles, tl.geometry.w);
    let mut out: Vec<(f64, f64)> = poses.iter().map(|p| (p.x, p.y)).collect();
    for k in 0..tl.geometry.magnets() {
        out.push(poses[k / 2].transform_point(tl.local_position(k, t)));
    }
    out
}

/// Final tile centres and magnet positions (mm) of a reference run.
fn reference_final(r: &ReferenceRun) -> Vec<(f64, f64)> {
    let poses = r.model.poses(&r.final_state);
    let mut out: Vec<(f64, f64)> = poses.iter().map(|p| (p.x, p.y)).collect();
    out.extend(r.final_positions());
    out
}

fn pose_error(a: &[(f64, f64)], b: &[(f64, f64)], w: f64) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt() / w)
        .fold(0.0, f64::max)
}

/// Runs the validation. `progress(scene, method, tolerance)` is called before each run.
pub fn validate(
    opts: &ValidateOptions,
    progress: &mut dyn FnMut(&str, &str, Option<f64>),
) -> Result<Validation, ValidateError> {
    let mut rows = Vec::new();
    let mut scenes = Vec::new();
    for sc in &chosen_scenes(&opts.scenes)? {
        scenes.push(validate_scene(sc, opts, progress, &mut rows)?);
    }
    Ok(Validation { rows, scenes })
}

/// The scenes named (all of them for none), in their order; an unknown name is refused.
fn chosen_scenes(names: &[String]) -> Result<Vec<Scene>, ValidateError> {
    let all = all_scenes();
    let known = all.iter().map(|s| s.name).collect::<Vec<_>>().join(", ");
    if let Some(name) = names
        .iter()
        .find(|n| !all.iter().any(|s| s.name == n.as_str()))
    {
        return Err(ValidateError::UnknownScene {
            name: name.clone(),
            known,
        });
    }
    Ok(all
        .into_iter()
        .filter(|s| names.is_empty() || names.iter().any(|n| n == s.name))
        .collect())
}

fn reference_error(sc: &Scene, source: ReferenceError) -> ValidateError {
    ValidateError::Reference {
        scene: sc.name.to_string(),
        source: Box::new(source),
    }
}

/// What the engine's rows say of a scene for its report: the engine's outcome and duration,
/// and the kinematic baseline's best-fit time factor and scaled error.
struct EngineFacts {
    outcome: String,
    duration: f64,
    scaled: (f64, f64),
}

/// One scene: its reference run at the tight tolerance, then the engine's rows and each
/// integrator's ladder measured against it (into `rows`); its report.
fn validate_scene(
    sc: &Scene,
    opts: &ValidateOptions,
    progress: &mut dyn FnMut(&str, &str, Option<f64>),
    rows: &mut Vec<Row>,
) -> Result<SceneReport, ValidateError> {
    progress(sc.name, "reference", Some(opts.reference_tolerance));
    let t0 = Instant::now();
    let reference = run_reference(
        &sc.chain,
        &sc.designs,
        &ReferenceOptions::default()
            .with_tolerance(opts.reference_tolerance)
            .with_model(opts.model),
    )
    .map_err(|e| reference_error(sc, e))?;
    let reference_wall = t0.elapsed().as_secs_f64();
    let rest = vec![0.0; reference.model.len()];
    let cutoff_error = reference
        .model
        .cutoff_error(&rest)
        .max(reference.model.cutoff_error(&reference.final_state));
    let engine = engine_rows(sc, opts, &reference, progress, rows)?;
    let report = SceneReport {
        scene: sc.name.to_string(),
        tiles: sc.chain.len(),
        reference_outcome: reference.result().name().into(),
        reference_reason: reference.to_summary().reason,
        engine_outcome: engine.outcome,
        reference_duration_s: reference.duration(),
        engine_duration_s: engine.duration,
        reference_wall_s: reference_wall,
        baseline_time_factor: engine.scaled.0,
        baseline_error_time_scaled: engine.scaled.1,
        cutoff_error,
    };
    ladder_rows(sc, opts, &reference, progress, rows)?;
    Ok(report)
}

/// The event engine's rows of a scene (`event`, `event-force`, `event-dist`) against its
/// reference run.
fn engine_rows(
    sc: &Scene,
    opts: &ValidateOptions,
    reference: &ReferenceRun,
    progress: &mut dyn FnMut(&str, &str, Option<f64>),
    rows: &mut Vec<Row>,
) -> Result<EngineFacts, ValidateError> {
    let (duration, w) = (reference.duration(), reference.model.geometry.w);
    let ref_final = reference_final(reference);
    let force = StartRule::Force {
        cutoff: reference.model.options().cutoff,
    };
    let mut facts = EngineFacts {
        outcome: String::new(),
        duration: 0.0,
        scaled: (1.0, 0.0),
    };
    for (method, rule) in [
        ("event", None),
        ("event-force", Some(force)),
        ("event-dist", Some(StartRule::Distance)),
    ] {
        progress(sc.name, method, None);
        let t0 = Instant::now();
        let eo = match rule {
            None => EngineOptions::default().with_model(opts.model),
            Some(rule) => EngineOptions::default()
                .with_start_rule(rule)
                .with_force_law(opts.model.force_law),
        };
        let tl = run(&sc.chain, &sc.designs, &eo).map_err(|source| ValidateError::Engine {
            scene: sc.name.to_string(),
            source: Box::new(source),
        })?;
        let wall = t0.elapsed().as_secs_f64();
        let c = compare_events(&reference.events, &tl.events, duration);
        if rule.is_none() {
            facts.outcome = tl.outcome.name().into();
            facts.duration = tl.duration();
        }
        if rule == Some(force) {
            facts.scaled = (c.time_factor, c.error_time_scaled);
        }
        rows.push(Row {
            scene: sc.name.to_string(),
            method: method.into(),
            tolerance: None,
            error_time: c.error_time,
            error_pose: pose_error(&ref_final, &engine_final(&tl), w),
            wall_s: wall,
            steps: tl.events.len() as u64,
            rejected: 0,
            rhs: 0,
            missing: c.missing,
            inversions: c.inversions,
            interleavings: c.interleavings,
            outcome: tl.outcome.name().into(),
        });
    }
    Ok(facts)
}

/// Each integrator's rows of a scene along its ladder of tolerances, against its reference
/// run.
fn ladder_rows(
    sc: &Scene,
    opts: &ValidateOptions,
    reference: &ReferenceRun,
    progress: &mut dyn FnMut(&str, &str, Option<f64>),
    rows: &mut Vec<Row>,
) -> Result<(), ValidateError> {
    let (duration, w) = (reference.duration(), reference.model.geometry.w);
    let ref_final = reference_final(reference);
    for (method, ladder) in [(Method::Dopri5, &opts.dopri5), (Method::Ros2, &opts.ros2)] {
        for &tol in ladder {
            progress(sc.name, method.name(), Some(tol));
            let t0 = Instant::now();
            let r = run_reference(
                &sc.chain,
                &sc.designs,
                &ReferenceOptions::default()
                    .with_method(method)
                    .with_tolerance(tol)
                    .with_model(opts.model),
            )
            .map_err(|e| reference_error(sc, e))?;
            let wall = t0.elapsed().as_secs_f64();
            let c = compare_events(&reference.events, &r.events, duration);
            rows.push(Row {
                scene: sc.name.to_string(),
                method: method.name().into(),
                tolerance: Some(tol),
                error_time: c.error_time,
                error_pose: pose_error(&ref_final, &reference_final(&r), w),
                wall_s: wall,
                steps: r.stats.accepted,
                rejected: r.stats.rejected,
                rhs: r.stats.rhs,
                missing: c.missing,
                inversions: c.inversions,
                interleavings: c.interleavings,
                outcome: r.result().name().into(),
            });
        }
    }
    Ok(())
}
