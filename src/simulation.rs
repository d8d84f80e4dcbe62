//! A simulation as one call: the event engine's timeline of a chain, its fold schedule
//! checked for self-intersection, and the summary of both ([`simulate`], or its two steps:
//! [`crate::engine::run`] then [`check_engine_run`]); a reference run's recorded fold
//! schedule checked the same way ([`check_reference`]).

use crate::collision::{
    check_schedule, CheckOptions, Collision, FoldSchedule, JointTrack, ScheduleError,
};
use crate::engine::{fold_schedule, run, EngineError, EngineOptions, Timeline};
use crate::reference::{joint_angle_samples, ReferenceRun};
use crate::timeline::{CollisionReport, FoldRecord, RunResult, Summary, TileDesigns, Track};
use crate::{Chain, Fold, FoldWord};

/// Why a simulation could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimulateError {
    /// The engine refused the input.
    #[error(transparent)]
    Engine(#[from] EngineError),
    /// The fold schedule was malformed (an engine bug, reported rather than hidden).
    #[error("fold schedule: {0}")]
    Schedule(ScheduleError),
}

impl Timeline {
    /// The fold word of what actually folds: each joint's fold if it turned, else S.
    pub fn folded_word(&self) -> FoldWord {
        folded_word(self)
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

/// Checks a reference run's fold schedule for collisions with the engine's checker
/// ([`check_schedule`]): each fold's track through the run's recorded states and wall
/// contacts, linear between them (only exactly collinear points dropped; a run that recorded
/// none has its final angles only), with its fold's end, the word of the joints that
/// turned. Its summary, overruled (`collided`, `first_collision`) or `undecided` as
/// [`simulate`]'s.
pub fn check_reference(run: &ReferenceRun, check: &CheckOptions) -> Result<Summary, SimulateError> {
    let mut summary = run.to_summary();
    if run.tiles() < 2 || run.folds.is_empty() {
        return Ok(summary);
    }
    let word = word_of_folds(run.tiles(), &run.folds);
    let tracks = run
        .folds
        .iter()
        .map(|f| {
            let tr = Track::from_samples(&joint_angle_samples(run, f.joint), 0.0);
            let (times, angles) = tr.points.iter().map(|&(dt, a)| (tr.start + dt, a)).unzip();
            JointTrack {
                joint: f.joint,
                times,
                angles,
                ended: f.end.is_finite().then_some(f.end),
            }
        })
        .collect();
    let schedule = FoldSchedule { tracks };
    let (collision, undecided) = match check_schedule(&word, &schedule, check) {
        Ok(()) => (None, None),
        Err(ScheduleError::Collision(c)) => (Some(c), None),
        Err(e @ ScheduleError::Undecided { .. }) => {
            (None, Some(format!("collision check undecided: {e}")))
        }
        Err(e) => return Err(SimulateError::Schedule(e)),
    };
    summary = overrule(summary, collision, undecided);
    Ok(summary)
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
pub fn simulate(
    chain: &Chain,
    designs: &TileDesigns,
    engine: &EngineOptions,
    check: &CheckOptions,
) -> Result<(Timeline, Summary), SimulateError> {
    let tl = run(chain, designs, engine)?;
    let summary = check_engine_run(&tl, check)?;
    Ok((tl, summary))
}

/// [`simulate`]'s second step: the engine's timeline `tl` checked for collisions, and its
/// summary with the verdict. For callers that do other work with the timeline while the
/// check runs (`fold-run` draws the run's files on a second thread).
pub fn check_engine_run(tl: &Timeline, check: &CheckOptions) -> Result<Summary, SimulateError> {
    let (collision, undecided) = check_timeline(tl, check)?;
    let mut summary = tl.summary();
    if let Some(why) = solve_stopped(tl) {
        // a stall's reason already ends with it
        if summary.reason.as_deref().is_some_and(|r| r.contains(&why)) {
            summary.result = RunResult::Stopped;
            summary.completed = false;
        } else {
            summary = summary.overruled(RunResult::Stopped, why);
        }
    }
    Ok(overrule(summary, collision, undecided))
}

/// Why a local solve of the engine gave up (its step limit), if one did: the run is
/// `stopped`, as a reference run whose integration stopped early
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

fn check_timeline(
    tl: &Timeline,
    check: &CheckOptions,
) -> Result<(Option<Collision>, Option<String>), SimulateError> {
    if tl.tiles() < 2 {
        return Ok((None, None));
    }
    let word = folded_word(tl);
    let schedule = fold_schedule(tl);
    match check_schedule(&word, &schedule, check) {
        Ok(()) => Ok((None, None)),
        Err(ScheduleError::Collision(c)) => Ok((Some(c), None)),
        Err(e @ ScheduleError::Undecided { .. }) => {
            Ok((None, Some(format!("collision check undecided: {e}"))))
        }
        Err(e) => Err(SimulateError::Schedule(e)),
    }
}
