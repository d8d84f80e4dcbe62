//! Error against run time (`fold-validate`): for each scene a reference run at a tight
//! tolerance, then the event engine and each integrator along a ladder of tolerances, each
//! with its error and wall time; the table, the JSON rows and the work-precision plot.
//!
//! **Errors.** Events are matched by kind and index (magnet starts and arrivals, fold starts
//! and ends). `error_time` is the largest difference of a matched event's time from the
//! reference's, over the reference's duration. `error_pose` is the largest distance between
//! the final positions of any tile centre or magnet, in tile widths. Events one run has and
//! the other has not are counted (`missing`), and the order of the matched events is compared
//! pair by pair, ties excepted: `inversions` counts pairs of events of the same kind (two
//! starts, two arrivals, two fold starts or two fold ends) that the two runs put in opposite
//! order, the order in which the chain propagates; `interleavings` counts pairs of
//! different kinds (a start against an arrival, say) in opposite order, which depends on
//! how fast each magnet moves and so measures the speed law, not the propagation.
//!
//! **The event engine's rows.** `event` is the engine with the force rule for starting
//! magnets ([`StartRule::Force`]) at the reference's cutoff, so both decide every start
//! from the same pair forces; `event-dist` is the engine's default, the thesis' distance
//! rule (nearest neighbours), shown for comparison.

use std::time::Instant;

use crate::engine::{run, EngineError, EngineOptions, EventKind, Outcome, StartRule, Timeline};
use crate::kinematics::poses_at_angles;
use crate::reference::events::{run_reference, ReferenceError, ReferenceOptions, ReferenceRun};
use crate::reference::integrators::Method;
use crate::reference::scenes::{all_scenes, Scene};

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
}

impl Default for ValidateOptions {
    fn default() -> ValidateOptions {
        ValidateOptions {
            scenes: Vec::new(),
            reference_tolerance: 1e-10,
            dopri5: vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8],
            ros2: vec![1e-2, 1e-3, 1e-4, 1e-5],
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

/// One row of the work-precision table.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Row {
    /// The scene.
    pub scene: String,
    /// `event`, `dopri5` or `ros2`.
    pub method: String,
    /// The tolerance (null for the event engine).
    pub tolerance: Option<f64>,
    /// Largest event-time difference over the reference's duration.
    pub error_time: f64,
    /// Largest final-position difference, tile widths.
    pub error_pose: f64,
    /// Wall time, s.
    pub wall_s: f64,
    /// Accepted steps (events for the event engine).
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Right-hand-side evaluations.
    pub rhs: u64,
    /// Events one run has and the other has not.
    pub missing: usize,
    /// Matched pairs of events of the same kind in opposite order.
    pub inversions: usize,
    /// Matched pairs of events of different kinds in opposite order.
    pub interleavings: usize,
    /// The outcome (`completed`, `inhibited`, `stalled`, `stopped`).
    pub outcome: String,
}

/// What one scene showed.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SceneReport {
    /// The scene.
    pub scene: String,
    /// Tiles.
    pub tiles: usize,
    /// The reference's outcome.
    pub reference_outcome: String,
    /// The reference's reason, if it did not complete.
    pub reference_reason: Option<String>,
    /// The engine's outcome.
    pub engine_outcome: String,
    /// Reference duration, s.
    pub reference_duration_s: f64,
    /// Engine duration, s.
    pub engine_duration_s: f64,
    /// Reference wall time, s.
    pub reference_wall_s: f64,
    /// The factor that best maps the engine's (force rule) event times onto the
    /// reference's, and the time error left after it (see [`EventComparison`]).
    pub engine_time_factor: f64,
    /// The engine's time error after that factor.
    pub engine_error_time_scaled: f64,
    /// Largest drive change the cutoff makes at rest and at the end, over the bonded rest
    /// force.
    pub cutoff_error: f64,
}

/// The validation's results.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Validation {
    /// Every row.
    pub rows: Vec<Row>,
    /// Every scene.
    pub scenes: Vec<SceneReport>,
}

fn outcome_name(o: &Outcome) -> &'static str {
    match o {
        Outcome::Completed => "completed",
        Outcome::Inhibited { .. } => "inhibited",
        Outcome::Stalled { .. } => "stalled",
    }
}

/// Timed events of a run keyed by (kind, index), in time order.
type Keyed = Vec<((EventKind, u32), f64)>;

fn keyed(events: &[crate::engine::Event]) -> Keyed {
    events
        .iter()
        .filter(|e| {
            matches!(
                e.kind,
                EventKind::MagnetStarts
                    | EventKind::MagnetArrives
                    | EventKind::FoldStarts
                    | EventKind::FoldEnds
            )
        })
        .map(|e| ((e.kind, e.index), e.time))
        .collect()
}

/// How one run's events compare with the reference's (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EventComparison {
    /// Largest difference of a matched event's time, over the reference's duration.
    pub error_time: f64,
    /// Events one run has and the other has not.
    pub missing: usize,
    /// Matched pairs of the same kind in opposite order.
    pub inversions: usize,
    /// Matched pairs of different kinds in opposite order.
    pub interleavings: usize,
    /// The single factor that best maps the run's event times onto the reference's (least
    /// squares through the origin; 1 when nothing matched).
    pub time_factor: f64,
    /// `error_time` after scaling the run's times by `time_factor`: what is left once the
    /// time scale is right.
    pub error_time_scaled: f64,
}

/// Compares `run`'s events with `reference`'s, whose run lasted `duration` s.
pub fn compare_events(
    reference: &[crate::engine::Event],
    run: &[crate::engine::Event],
    duration: f64,
) -> EventComparison {
    let a = keyed(reference);
    let b = keyed(run);
    let map: std::collections::HashMap<(EventKind, u32), f64> = b.iter().copied().collect();
    let mut pairs = Vec::new();
    for (k, t) in &a {
        if let Some(u) = map.get(k) {
            pairs.push((k.0, *t, *u));
        }
    }
    let missing = a.len() + b.len() - 2 * pairs.len();
    let span = duration.max(f64::MIN_POSITIVE);
    let error_time = pairs.iter().map(|p| (p.1 - p.2).abs()).fold(0.0, f64::max) / span;
    let (num, den) = pairs
        .iter()
        .fold((0.0, 0.0), |(n, d), p| (n + p.1 * p.2, d + p.2 * p.2));
    let time_factor = if den > 0.0 { num / den } else { 1.0 };
    let error_time_scaled = pairs
        .iter()
        .map(|p| (p.1 - time_factor * p.2).abs())
        .fold(0.0, f64::max)
        / span;
    // tied within 1e-9 of the duration in either run: not out of order
    let tie = 1e-9 * duration;
    let (mut inversions, mut interleavings) = (0, 0);
    for i in 0..pairs.len() {
        for j in i + 1..pairs.len() {
            let da = pairs[j].1 - pairs[i].1;
            let db = pairs[j].2 - pairs[i].2;
            if da.abs() > tie && db.abs() > tie && (da > 0.0) != (db > 0.0) {
                if pairs[i].0 == pairs[j].0 {
                    inversions += 1;
                } else {
                    interleavings += 1;
                }
            }
        }
    }
    EventComparison {
        error_time,
        missing,
        inversions,
        interleavings,
        time_factor,
        error_time_scaled,
    }
}

/// Final tile centres and magnet positions (mm) of an engine run.
fn engine_final(tl: &Timeline) -> Vec<(f64, f64)> {
    let t = tl.duration();
    let angles = crate::engine::joint_angles_at(tl, t);
    let poses = poses_at_angles(&angles, tl.geometry.w);
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

fn result_name(r: &ReferenceRun) -> String {
    if r.stopped.is_some() {
        "stopped".into()
    } else {
        outcome_name(&r.outcome).into()
    }
}

/// Runs the validation. `progress(scene, method, tolerance)` is called before each run.
pub fn validate(
    opts: &ValidateOptions,
    progress: &mut dyn FnMut(&str, &str, Option<f64>),
) -> Result<Validation, ValidateError> {
    let all = all_scenes();
    let known = all.iter().map(|s| s.name).collect::<Vec<_>>().join(", ");
    for name in &opts.scenes {
        if !all.iter().any(|s| s.name == name) {
            return Err(ValidateError::UnknownScene {
                name: name.clone(),
                known,
            });
        }
    }
    let chosen: Vec<Scene> = all
        .into_iter()
        .filter(|s| opts.scenes.is_empty() || opts.scenes.iter().any(|n| n == s.name))
        .collect();
    let mut rows = Vec::new();
    let mut scenes = Vec::new();
    for sc in &chosen {
        let name = sc.name.to_string();
        let ref_err = |source| ValidateError::Reference {
            scene: name.clone(),
            source: Box::new(source),
        };
        progress(sc.name, "reference", Some(opts.reference_tolerance));
        let t0 = Instant::now();
        let reference = run_reference(
            &sc.chain,
            &sc.designs,
            &ReferenceOptions::default().with_tolerance(opts.reference_tolerance),
        )
        .map_err(ref_err)?;
        let reference_wall = t0.elapsed().as_secs_f64();
        let duration = reference.duration();
        let w = reference.model.geometry.w;
        let ref_final = reference_final(&reference);
        let mut rest = vec![0.0; reference.model.len()];
        let cutoff_error = reference
            .model
            .cutoff_error(&rest)
            .max(reference.model.cutoff_error(&reference.final_state));
        rest.clear();

        let force = StartRule::Force {
            cutoff: reference.model.options().cutoff,
        };
        let mut engine_outcome = String::new();
        let mut engine_duration = 0.0;
        let mut engine_scaled = (1.0, 0.0);
        for (method, rule) in [("event", force), ("event-dist", StartRule::Distance)] {
            progress(sc.name, method, None);
            let t0 = Instant::now();
            let tl = run(
                &sc.chain,
                &sc.designs,
                &EngineOptions::default().with_start_rule(rule),
            )
            .map_err(|source| ValidateError::Engine {
                scene: name.clone(),
                source: Box::new(source),
            })?;
            let wall = t0.elapsed().as_secs_f64();
            let c = compare_events(&reference.events, &tl.events, duration);
            if rule == force {
                engine_outcome = outcome_name(&tl.outcome).into();
                engine_duration = tl.duration();
                engine_scaled = (c.time_factor, c.error_time_scaled);
            }
            rows.push(Row {
                scene: name.clone(),
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
                outcome: outcome_name(&tl.outcome).into(),
            });
        }
        scenes.push(SceneReport {
            scene: name.clone(),
            tiles: sc.chain.len(),
            reference_outcome: result_name(&reference),
            reference_reason: reference.to_summary().reason,
            engine_outcome,
            reference_duration_s: duration,
            engine_duration_s: engine_duration,
            reference_wall_s: reference_wall,
            engine_time_factor: engine_scaled.0,
            engine_error_time_scaled: engine_scaled.1,
            cutoff_error,
        });
        for (method, ladder) in [(Method::Dopri5, &opts.dopri5), (Method::Ros2, &opts.ros2)] {
            for &tol in ladder {
                progress(sc.name, method.name(), Some(tol));
                let t0 = Instant::now();
                let r = run_reference(
                    &sc.chain,
                    &sc.designs,
                    &ReferenceOptions::default()
                        .with_method(method)
                        .with_tolerance(tol),
                )
                .map_err(ref_err)?;
                let wall = t0.elapsed().as_secs_f64();
                let c = compare_events(&reference.events, &r.events, duration);
                rows.push(Row {
                    scene: name.clone(),
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
                    outcome: result_name(&r),
                });
            }
        }
    }
    Ok(Validation { rows, scenes })
}

impl Validation {
    /// `{"rows": [...], "scenes": [...]}`.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// The table, plain text.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        s.push_str(&format!(
            "{:<16} {:<10} {:>6} {:>10} {:>10} {:>9} {:>8} {:>8} {:>4} {:>4} {:>5}  {}\n",
            "scene",
            "method",
            "tol",
            "err_time",
            "err_pose",
            "wall_s",
            "steps",
            "rejected",
            "miss",
            "inv",
            "intl",
            "outcome"
        ));
        for r in &self.rows {
            let tol = r.tolerance.map_or("-".to_string(), |t| format!("{t:.0e}"));
            s.push_str(&format!(
                "{:<16} {:<10} {:>6} {:>10.3e} {:>10.3e} {:>9.4} {:>8} {:>8} {:>4} {:>4} {:>5}  {}\n",
                r.scene,
                r.method,
                tol,
                r.error_time,
                r.error_pose,
                r.wall_s,
                r.steps,
                r.rejected,
                r.missing,
                r.inversions,
                r.interleavings,
                r.outcome
            ));
        }
        s.push('\n');
        for sc in &self.scenes {
            s.push_str(&format!(
                "{}: {} tiles; reference {} in {:.4} s ({:.2} s wall), engine {} in {:.4} s; engine times x{:.3} best fit the reference's, leaving err_time {:.3e}; cutoff error {:.2e} of the bonded rest force\n",
                sc.scene,
                sc.tiles,
                sc.reference_outcome,
                sc.reference_duration_s,
                sc.reference_wall_s,
                sc.engine_outcome,
                sc.engine_duration_s,
                sc.engine_time_factor,
                sc.engine_error_time_scaled,
                sc.cutoff_error
            ));
            if let Some(r) = &sc.reference_reason {
                s.push_str(&format!("  reference: {r}\n"));
            }
        }
        s
    }

    /// The work-precision plot: one panel per scene, event-time error against wall time,
    /// both axes logarithmic.
    pub fn to_svg(&self) -> String {
        let cols = 3usize;
        let n = self.scenes.len().max(1);
        let rows = n.div_ceil(cols);
        let (pw, ph) = (320.0, 250.0);
        let (ml, mt, mr, mb) = (58.0, 30.0, 12.0, 40.0);
        let width = cols as f64 * pw;
        let height = rows as f64 * ph + 40.0;
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
        );
        s.push_str(&format!(
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">event-time error (over the duration) against wall time; blue: dopri5, red: ros2 (tolerance ladder), diamonds: event engine (filled: force rule, open: distance rule)</text>\n",
            width / 2.0,
            height - 12.0
        ));
        let floor = 1e-12;
        for (i, sc) in self.scenes.iter().enumerate() {
            let ox = (i % cols) as f64 * pw;
            let oy = (i / cols) as f64 * ph;
            let rs: Vec<&Row> = self.rows.iter().filter(|r| r.scene == sc.scene).collect();
            let lx = |v: f64| v.max(1e-6).log10();
            let ly = |v: f64| v.max(floor).log10();
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for r in &rs {
                x0 = x0.min(lx(r.wall_s));
                x1 = x1.max(lx(r.wall_s));
                y0 = y0.min(ly(r.error_time));
                y1 = y1.max(ly(r.error_time));
            }
            let (x0, x1) = (x0.floor(), x1.ceil().max(x0.floor() + 1.0));
            let (y0, y1) = (y0.floor(), y1.ceil().max(y0.floor() + 1.0));
            let (iw, ih) = (pw - ml - mr, ph - mt - mb);
            let px = |v: f64| ox + ml + (lx(v) - x0) / (x1 - x0) * iw;
            let py = |v: f64| oy + mt + (1.0 - (ly(v) - y0) / (y1 - y0)) * ih;
            s.push_str(&format!(
                "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\" font-weight=\"bold\">{} (ref: {})</text>\n",
                ox + ml + iw / 2.0,
                oy + 18.0,
                sc.scene,
                sc.reference_outcome
            ));
            s.push_str(&format!(
                "<rect x=\"{}\" y=\"{}\" width=\"{iw}\" height=\"{ih}\" fill=\"none\" stroke=\"#444\"/>\n",
                ox + ml,
                oy + mt
            ));
            let mut d = x0;
            while d <= x1 + 1e-9 {
                let x = ox + ml + (d - x0) / (x1 - x0) * iw;
                s.push_str(&format!(
                    "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{}</text>\n",
                    oy + mt,
                    oy + mt + ih,
                    oy + mt + ih + 14.0,
                    d as i64
                ));
                d += 1.0;
            }
            let step = ((y1 - y0) / 6.0).ceil().max(1.0);
            let mut d = y0;
            while d <= y1 + 1e-9 {
                let y = oy + mt + (1.0 - (d - y0) / (y1 - y0)) * ih;
                s.push_str(&format!(
                    "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{}</text>\n",
                    ox + ml,
                    ox + ml + iw,
                    ox + ml - 4.0,
                    y + 4.0,
                    d as i64
                ));
                d += step;
            }
            s.push_str(&format!(
                "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">wall time, s</text>\n",
                ox + ml + iw / 2.0,
                oy + mt + ih + 28.0
            ));
            s.push_str(&format!(
                "<text transform=\"translate({},{}) rotate(-90)\" text-anchor=\"middle\">error_time</text>\n",
                ox + 14.0,
                oy + mt + ih / 2.0
            ));
            for (method, colour) in [("dopri5", "#1f5fbf"), ("ros2", "#c0392b")] {
                let pts: Vec<(f64, f64)> = rs
                    .iter()
                    .filter(|r| r.method == method)
                    .map(|r| (px(r.wall_s), py(r.error_time)))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                let path: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.1},{y:.1}")).collect();
                s.push_str(&format!(
                    "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>\n",
                    path.join(" ")
                ));
                for (x, y) in pts {
                    s.push_str(&format!(
                        "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"{colour}\"/>\n"
                    ));
                }
            }
            // the event engine: filled diamond (force rule), open diamond (distance rule)
            for r in rs
                .iter()
                .filter(|r| r.method == "event" || r.method == "event-dist")
            {
                let (x, y) = (px(r.wall_s), py(r.error_time));
                let fill = if r.method == "event" {
                    "fill=\"black\""
                } else {
                    "fill=\"none\" stroke=\"black\""
                };
                s.push_str(&format!(
                    "<path d=\"M{x:.1},{:.1} L{:.1},{y:.1} L{x:.1},{:.1} L{:.1},{y:.1} Z\" {fill}/>\n",
                    y - 6.0,
                    x + 6.0,
                    y + 6.0,
                    x - 6.0
                ));
            }
        }
        s.push_str("</svg>\n");
        s
    }
}
