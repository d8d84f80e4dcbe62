//! A simulation as one call: the event engine's timeline of a chain, its fold schedule
//! checked for self-intersection, and the summary of both ([`simulate`], or its two steps:
//! [`crate::engine::run`] then [`Timeline::checked_summary`]); a reference run's recorded
//! fold schedule checked the same way ([`ReferenceRun::checked_summary`]).

use crate::collision::{
    check_schedule, closest_approach, CheckOptions, Collision, FoldSchedule, JointTrack,
    ScheduleError,
};
use crate::engine::{fold_schedule, run, EngineError, EngineOptions, Timeline};
use crate::reference::{joint_angle_samples, ReferenceError, ReferenceRun};
use crate::timeline::{
    Clearance, CollisionReport, FoldRecord, RunResult, Summary, TileDesigns, Track,
};
use crate::{Chain, Fold, FoldWord};

impl Timeline {
    /// The fold word of what actually folds: each joint's fold if it turned, else S.
    pub fn folded_word(&self) -> FoldWord {
        folded_word(self)
    }

    /// [`simulate`]'s second step: this timeline checked for collisions, and its summary
    /// with the verdict (`result` is `undecided` when the check could not decide within its
    /// work budget). For callers that do other work with the timeline while the check runs
    /// (`fold-run` draws the run's files on a second thread).
    ///
    /// ```
    /// use foldchain::collision::CheckOptions;
    /// use foldchain::engine::{run, EngineOptions};
    /// use foldchain::timeline::{RunResult, TileDesigns};
    /// use foldchain::Chain;
    ///
    /// let tl = run(&Chain::parse("SLLS").unwrap(), &TileDesigns::default(), &EngineOptions::default()).unwrap();
    /// let summary = tl.checked_summary(&CheckOptions::default()).unwrap();
    /// assert_eq!(summary.result, RunResult::Completed);
    /// ```
    pub fn checked_summary(&self, check: &CheckOptions) -> Result<Summary, EngineError> {
        check_engine_run(self, check)
    }
}

impl ReferenceRun {
    /// This run's fold schedule checked for collisions with the engine's checker: each
    /// fold's track through the run's recorded states and wall contacts, linear between them
    /// (only exactly collinear points dropped; a run that recorded none has its final angles
    /// only), with its fold's end, the word of the joints that turned. Its summary, overruled
    /// (`collided`, `first_collision`) or `undecided` as [`simulate`]'s.
    ///
    /// ```
    /// use foldchain::collision::CheckOptions;
    /// use foldchain::reference::{run_reference, ReferenceOptions};
    /// use foldchain::timeline::{RunResult, TileDesigns};
    /// use foldchain::Chain;
    ///
    /// let chain = Chain::parse("SLS").unwrap();
    /// let run = run_reference(&chain, &TileDesigns::default(), &ReferenceOptions::default()).unwrap();
    /// let summary = run.checked_summary(&CheckOptions::default()).unwrap();
    /// assert_eq!(summary.result, RunResult::Completed);
    /// ```
    pub fn checked_summary(&self, check: &CheckOptions) -> Result<Summary, ReferenceError> {
        check_reference(self, check)
    }
}

/// The fold word of what actually folds: each joint's fold if it turned, else S.
pub(crate) fn folded_word(tl: &Timeline) -> FoldWord {
    word_of_folds(tl.tiles(), &tl.folds)
}

fn word_of_folds(tiles: usize, records: &[FoldRecord]) -> FoldWord {
    let mut folds = vec![Fold::S; tiles.saturating_sub(1)];
    for f in records {
        folds[f.joint] = f.fold;
    }
    FoldWord::from_folds(folds)
}

/// [`ReferenceRun::checked_summary`].
fn check_reference(run: &ReferenceRun, check: &CheckOptions) -> Result<Summary, ReferenceError> {
    let mut summary = run.to_summary();
    if run.tiles() < 2 {
        return Ok(summary);
    }
    let word = word_of_folds(run.tiles(), &run.folds);
    let w = run.model.geometry.w;
    if run.folds.is_empty() {
        summary.clearance = clearance(&word, &FoldSchedule::default(), check, w);
        return Ok(summary);
    }
    let tracks = run
        .folds
        .iter()
        .map(|f| {
            let tr = Track::from_samples(&joint_angle_samples(run, f.joint), 0.0);
            let points = tr.points.iter().map(|&(dt, a)| (tr.start + dt, a)).unzip();
            JointTrack::of_fold(f.joint, points, f.end)
        })
        .collect();
    let schedule = FoldSchedule { tracks };
    let (verdict, clearance) = rayon::join(
        || schedule_verdict(&word, &schedule, check, w),
        || clearance(&word, &schedule, check, w),
    );
    let (collision, undecided) = verdict.map_err(ReferenceError::Schedule)?;
    summary = overrule(summary, collision, undecided);
    summary.clearance = clearance;
    Ok(summary)
}

/// The precision of a run's clearance, mm: a twentieth of the 10 um overlap tolerance, and a
/// tenth of the 5 um within which the two simulations' clearances are held to agree.
pub(crate) const CLEARANCE_PRECISION_MM: f64 = 5e-4;

/// How close two tiles that are not neighbours come along `schedule` (tiles `w` mm wide),
/// when it can be measured ([`crate::collision`]'s clearance).
fn clearance(
    word: &FoldWord,
    schedule: &FoldSchedule,
    check: &CheckOptions,
    w: f64,
) -> Option<Clearance> {
    if check.final_only || !check.clearance {
        return None;
    }
    let c = closest_approach(word.tiles(), schedule, CLEARANCE_PRECISION_MM / w)?;
    let mm = c.distance * w;
    Some(Clearance {
        mm,
        tiles: c.tiles,
        time: c.time,
        joint: c.joint,
        graze: mm < 0.0 && -mm <= check.overlap_mm,
        overlap_tolerance_mm: check.overlap_mm,
        precision_mm: CLEARANCE_PRECISION_MM,
    })
}

/// The timed check of `schedule` with the run's touching tolerance (tiles `w` mm wide,
/// [`CheckOptions::overlap_mm`]): the first collision, or why it could not decide; what is
/// wrong with a malformed schedule (a bug of the run that made it) as the error.
fn schedule_verdict(
    word: &FoldWord,
    schedule: &FoldSchedule,
    check: &CheckOptions,
    w: f64,
) -> Result<(Option<Collision>, Option<String>), String> {
    let opts = check.with_tolerance(check.run_tolerance(w));
    match check_schedule(word, schedule, &opts) {
        Ok(()) => Ok((None, None)),
        Err(ScheduleError::Collision(c)) => Ok((Some(c), None)),
        Err(e @ ScheduleError::Undecided { .. }) => {
            Ok((None, Some(format!("collision check undecided: {e}"))))
        }
        Err(e) => Err(e.to_string()),
    }
}

/// A run's summary with the collision check's verdict.
fn overrule(
    mut summary: Summary,
    collision: Option<Collision>,
    undecided: Option<String>,
) -> Summary {
    if let Some(c) = collision {
        summary = summary.overruled(RunResult::Collided, c.to_string());
        summary.first_collision = Some(CollisionReport {
            time: c.time,
            joint: c.joint,
            tiles: c.tiles,
        });
    }
    if let Some(msg) = undecided {
        summary.completed = false;
        summary.result = RunResult::Undecided;
        summary.reason = Some(msg);
    }
    summary
}

/// Runs the engine and checks its fold schedule for collisions: the timeline and its summary
/// (`result` is `undecided` when the check could not decide within its work budget).
///
/// ```
/// use foldchain::collision::CheckOptions;
/// use foldchain::engine::EngineOptions;
/// use foldchain::timeline::{RunResult, TileDesigns};
/// use foldchain::{simulate, Chain};
///
/// let chain = Chain::parse("SLLS").unwrap();
/// let (timeline, summary) = simulate(&chain, &TileDesigns::default(), &EngineOptions::default(), &CheckOptions::default()).unwrap();
/// assert_eq!(timeline.folds.len(), 2);
/// assert_eq!(summary.result, RunResult::Completed);
/// ```
pub fn simulate(
    chain: &Chain,
    designs: &TileDesigns,
    engine: &EngineOptions,
    check: &CheckOptions,
) -> Result<(Timeline, Summary), EngineError> {
    let tl = run(chain, designs, engine)?;
    let summary = check_engine_run(&tl, check)?;
    Ok((tl, summary))
}

/// [`Timeline::checked_summary`].
fn check_engine_run(tl: &Timeline, check: &CheckOptions) -> Result<Summary, EngineError> {
    let (collision, undecided, clearance) = check_timeline(tl, check)?;
    let mut summary = tl.summary();
    summary.clearance = clearance;
    if let Some(why) = solve_stopped(tl) {
        summary = summary.undecided(why);
    }
    Ok(overrule(summary, collision, undecided))
}

/// Why a local solve of the engine ran out of its work budget (its step limit, or no event
/// for 1e4 of its time scales), if one did, with the balance it could not decide and its
/// margin: the run is `undecided`, as a reference run that runs out of its budget
/// ([`ReferenceRun::to_summary`]), not `stalled`, which says the physics came to rest with a
/// magnet short of its trigger (the reference's [`crate::timeline::Outcome::Stalled`]).
fn solve_stopped(tl: &Timeline) -> Option<String> {
    tl.solved
        .as_ref()?
        .chain
        .units
        .iter()
        .find_map(|u| u.0.solution.stopped.clone())
}

/// The collision check of the engine's run: its verdict and its clearance.
type Checked = (Option<Collision>, Option<String>, Option<Clearance>);

fn check_timeline(tl: &Timeline, check: &CheckOptions) -> Result<Checked, EngineError> {
    if tl.tiles() < 2 {
        return Ok((None, None, None));
    }
    let (word, schedule, w) = (folded_word(tl), fold_schedule(tl), tl.geometry.w);
    // the verdict and the clearance side by side (on two cores where there are two)
    let (verdict, clearance) = rayon::join(
        || schedule_verdict(&word, &schedule, check, w),
        || clearance(&word, &schedule, check, w),
    );
    let (collision, undecided) = verdict.map_err(EngineError::Schedule)?;
    Ok((collision, undecided, clearance))
}
