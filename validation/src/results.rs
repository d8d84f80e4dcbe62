//! The validation's results: one row per run (the work-precision table), one report per
//! scene, as JSON and as a plain-text table.

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
    /// The factor that best maps the kinematic baseline's (force rule, `event-force`) event
    /// times onto the reference's, and the time error left after it (see
    /// [`super::EventComparison`]). Reported for the baseline only: the engine (`event`)
    /// has no fitted factor.
    pub baseline_time_factor: f64,
    /// The kinematic baseline's time error after that factor.
    pub baseline_error_time_scaled: f64,
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
                "{}: {} tiles; reference {} in {:.4} s ({:.2} s wall), engine {} in {:.4} s; the kinematic baseline's (event-force) times x{:.3} best fit the reference's, leaving err_time {:.3e}; cutoff error {:.2e} of the bonded rest force\n",
                sc.scene,
                sc.tiles,
                sc.reference_outcome,
                sc.reference_duration_s,
                sc.reference_wall_s,
                sc.engine_outcome,
                sc.engine_duration_s,
                sc.baseline_time_factor,
                sc.baseline_error_time_scaled,
                sc.cutoff_error
            ));
            if let Some(r) = &sc.reference_reason {
                s.push_str(&format!("  reference: {r}\n"));
            }
        }
        s
    }
}
