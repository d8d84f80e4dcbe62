//! `fold-run` as a library call: run the event engine on a chain, check the fold schedule for
//! self-intersection, and write the pictures and JSON into one output directory
//! ([`fold_run`]); or run the force-integrated reference and write the same files from its
//! states ([`fold_run_reference`]).
//!
//! Everything is written into a temporary directory beside the target, which is renamed into
//! place only when every file is complete: a failed run leaves no half-written output (an
//! older run's directory of the same name is replaced only then).

mod plan_file;
mod reference;

use std::fmt::Write as _;
use std::path::{Path as FsPath, PathBuf};

use crate::atomic::{write_atomic, WriteError};
use crate::collision::{check_schedule, CheckOptions, Collision, ScheduleError};
use crate::engine::{
    energy_curve, fold_schedule, run, EngineError, EngineOptions, Summary, TileDesigns, Timeline,
};
use crate::reference::ReferenceError;
use crate::render::{
    energy_svg, frame_svg, transition_svg, ChainState, FrameOptions, FrameView, TransitionData,
    DETAIL_TILES,
};
use crate::{Chain, Fold, FoldWord};

pub use plan_file::{read_plan_file, PlanFileError};
pub use reference::{
    fold_run_reference, reference_energy, reference_state, reference_transition, state_budget,
    state_energy, ReferenceRunReport, STATE_BUDGET_BYTES,
};

/// Options of a run. Defaults: thesis design, overdamped speed law, `out/run`, frames chosen
/// by chain length ([`default_frames`]), transition diagram of the first six tiles.
#[derive(Clone, Debug, PartialEq)]
pub struct FoldRunOptions {
    /// The run's name (titles).
    pub name: String,
    /// The tile designs.
    pub designs: TileDesigns,
    /// The engine options.
    pub engine: EngineOptions,
    /// The output directory.
    pub out_dir: PathBuf,
    /// Number of step frames; `None` for [`default_frames`].
    pub frames: Option<usize>,
    /// Tiles shown in the transition diagram (inclusive); `None` for the first six.
    pub transition_tiles: Option<(usize, usize)>,
    /// The collision check's options.
    pub check: CheckOptions,
}

impl Default for FoldRunOptions {
    fn default() -> FoldRunOptions {
        FoldRunOptions {
            name: "run".into(),
            designs: TileDesigns::default(),
            engine: EngineOptions::default(),
            out_dir: PathBuf::from("out/run"),
            frames: None,
            transition_tiles: None,
            check: CheckOptions::default(),
        }
    }
}

/// The default number of step frames: 40 for short chains, fewer for long ones (a frame of
/// a long chain is drawn lean, but each still holds every tile).
pub fn default_frames(tiles: usize) -> usize {
    match tiles {
        0..=50 => 40,
        51..=DETAIL_TILES => 24,
        401..=20_000 => 12,
        _ => 6,
    }
}

/// Why a run could not be made (all bad input or an unwritable output: exit 2).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FoldRunError {
    /// The engine refused the input.
    #[error(transparent)]
    Engine(#[from] EngineError),
    /// An output file or directory could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// The fold schedule was malformed (an engine bug, reported rather than hidden).
    #[error("fold schedule: {0}")]
    Schedule(ScheduleError),
    /// The reference integrator refused the input.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
}

/// What a run produced.
#[derive(Debug)]
pub struct FoldRunReport {
    /// The summary (also in `summary.json`).
    pub summary: Summary,
    /// The output directory.
    pub out_dir: PathBuf,
    /// The files written, relative to it.
    pub files: Vec<String>,
    /// The timeline.
    pub timeline: Timeline,
}

/// The fold word of what actually folds: each joint's fold if it turned, else S.
pub fn folded_word(tl: &Timeline) -> FoldWord {
    let mut folds = vec![Fold::S; tl.tiles().saturating_sub(1)];
    for f in &tl.folds {
        folds[f.joint] = f.fold;
    }
    FoldWord::from_folds(folds)
}

/// Runs the engine and the collision check only (no files).
pub fn simulate(
    chain: &Chain,
    designs: &TileDesigns,
    engine: &EngineOptions,
    check: &CheckOptions,
) -> Result<(Timeline, Summary), FoldRunError> {
    let tl = run(chain, designs, engine)?;
    let (collision, undecided) = check_timeline(&tl, check)?;
    let mut summary = Summary::new(&tl, collision.as_ref());
    if let Some(msg) = undecided {
        summary.completed = false;
        summary.result = "undecided";
        summary.reason = Some(msg);
    }
    Ok((tl, summary))
}

fn check_timeline(
    tl: &Timeline,
    check: &CheckOptions,
) -> Result<(Option<Collision>, Option<String>), FoldRunError> {
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
        Err(e) => Err(FoldRunError::Schedule(e)),
    }
}

/// Runs the engine, checks the folding and writes every output into `opts.out_dir`.
/// `progress(stage, done, total)` is called as the work goes on.
pub fn fold_run(
    chain: &Chain,
    opts: &FoldRunOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<FoldRunReport, FoldRunError> {
    progress("engine", 0, 1);
    let (tl, summary) = simulate(chain, &opts.designs, &opts.engine, &opts.check)?;
    progress("engine", 1, 1);
    let collision_tiles = summary.first_collision.map(|c| c.tiles);
    let duration = tl.duration();
    let frames = opts
        .frames
        .unwrap_or_else(|| default_frames(tl.tiles()))
        .max(1);
    let times = frame_times(duration, frames);
    let w = tl.geometry.w;
    // Each step is framed on the chain as it stands at that moment: one view holding every
    // sweep would show a long straight tail and leave the folded part a speck.
    let collision_time = summary.first_collision.and_then(|c| c.time);
    let mut files: Vec<(String, String)> = Vec::new();
    for (i, &t) in times.iter().enumerate() {
        progress("frames", i, frames);
        let hit = collision_time.is_some_and(|ct| t >= ct);
        let fo = FrameOptions {
            title: opts.name.clone(),
            collision: if hit { collision_tiles } else { None },
            note: None,
        };
        let state = ChainState::from_timeline(&tl, t);
        let view = FrameView::around(state.poses.iter().copied(), w);
        files.push((
            format!("step-{i:04}.svg"),
            frame_svg(&tl.geometry, &state, &view, &fo),
        ));
    }
    progress("frames", frames, frames);
    let fo = FrameOptions {
        title: opts.name.clone(),
        collision: collision_tiles,
        note: Some(final_note(&summary)),
    };
    {
        let final_state = ChainState::from_timeline(&tl, duration);
        let final_view = FrameView::around(final_state.poses.iter().copied(), w);
        files.push((
            "final.svg".into(),
            frame_svg(&tl.geometry, &final_state, &final_view, &fo),
        ));
    }
    let (a, b) = opts.transition_tiles.unwrap_or((0, 5.min(tl.tiles() - 1)));
    let transition = TransitionData::from_timeline(&tl, a, b);
    files.push((
        "transition.svg".into(),
        transition_svg(
            &tl.geometry,
            &transition,
            &transition_title(&opts.name, a, b, tl.tiles()),
        ),
    ));
    progress("energy", 0, 1);
    let curve = energy_curve(&tl, energy_samples(tl.tiles()));
    files.push((
        "energy.svg".into(),
        energy_svg(
            &tl.folds,
            &curve,
            &format!("{}: total dipole energy", opts.name),
        ),
    ));
    progress("energy", 1, 1);
    files.push(("timeline.json".into(), timeline_json(&tl)));
    let mut summary_json = summary.to_json();
    summary_json.push('\n');
    files.push(("summary.json".into(), summary_json));
    write_dir(&opts.out_dir, &files, progress)?;
    Ok(FoldRunReport {
        summary,
        out_dir: opts.out_dir.clone(),
        files: files.into_iter().map(|(n, _)| n).collect(),
        timeline: tl,
    })
}

/// `frames` evenly spaced times from 0 to `duration` (just `duration` for one frame).
fn frame_times(duration: f64, frames: usize) -> Vec<f64> {
    (0..frames)
        .map(|i| {
            if frames == 1 {
                duration
            } else {
                duration * i as f64 / (frames - 1) as f64
            }
        })
        .collect()
}

/// Points of the energy curve: 400, or 100 beyond 10,000 tiles.
fn energy_samples(tiles: usize) -> usize {
    if tiles <= 10_000 {
        400
    } else {
        100
    }
}

/// The final frame's note: the result and its reason, at most 150 characters.
fn final_note(summary: &Summary) -> String {
    let note = format!(
        "{}{}",
        summary.result,
        summary
            .reason
            .as_ref()
            .map(|r| format!(": {r}"))
            .unwrap_or_default()
    );
    abbreviate(&note, 150)
}

fn transition_title(name: &str, a: usize, b: usize, tiles: usize) -> String {
    format!(
        "{name}: transition diagram, tiles {a} to {}",
        b.min(tiles - 1)
    )
}

fn abbreviate(s: &str, max: usize) -> String {
    if s.chars().count() > max {
        format!("{}...", s.chars().take(max - 3).collect::<String>())
    } else {
        s.to_string()
    }
}

/// The most events written to `timeline.json` (about 70 MB): a longer run writes the first
/// ones and says so (`"truncated": true`, `"events_total"`); `summary.json` always counts all.
pub const MAX_TIMELINE_EVENTS: usize = 2_000_000;

/// All events as JSON: `{"tiles": n, "speed_law": ..., "events": [[t, "kind", index], ...]}`
/// (index: the magnet, or the joint for fold, inhibited and stalled events), at most
/// [`MAX_TIMELINE_EVENTS`] of them.
pub fn timeline_json(tl: &Timeline) -> String {
    let shown = tl.events.len().min(MAX_TIMELINE_EVENTS);
    let mut s = String::with_capacity(40 * shown + 200);
    let _ = writeln!(
        s,
        "{{\"tiles\":{},\"speed_law\":{},\"events_total\":{},\"truncated\":{},\"index\":\"magnet k is magnet k mod 2 of tile k/2; joint events index the joint\",\"events\":[",
        tl.tiles(),
        serde_json::to_string(&tl.speed).unwrap_or_else(|_| "null".into()),
        tl.events.len(),
        shown < tl.events.len()
    );
    for (i, e) in tl.events.iter().take(shown).enumerate() {
        if i > 0 {
            s.push_str(",\n");
        }
        s.push_str(&e.to_json());
    }
    s.push_str("\n]}\n");
    s
}

fn write_dir(
    dir: &FsPath,
    files: &[(String, String)],
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<(), WriteError> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into());
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    crate::atomic::create_dir_all(&parent)?;
    let pid = std::process::id();
    let tmp = parent.join(format!(".{name}.tmp{pid}"));
    let old = parent.join(format!(".{name}.old{pid}"));
    let werr = |path: &FsPath, source: std::io::Error| WriteError {
        path: path.to_path_buf(),
        source,
    };
    let _ = std::fs::remove_dir_all(&tmp);
    let result = (|| {
        std::fs::create_dir(&tmp).map_err(|e| werr(&tmp, e))?;
        for (i, (file, body)) in files.iter().enumerate() {
            progress("writing", i, files.len());
            write_atomic(&tmp.join(file), body.as_bytes())?;
        }
        if dir.is_dir() {
            std::fs::rename(dir, &old).map_err(|e| werr(dir, e))?;
        } else if dir.exists() {
            return Err(werr(
                dir,
                std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    "exists and is not a directory",
                ),
            ));
        }
        if let Err(e) = std::fs::rename(&tmp, dir) {
            let _ = std::fs::rename(&old, dir);
            return Err(werr(dir, e));
        }
        let _ = std::fs::remove_dir_all(&old);
        progress("writing", files.len(), files.len());
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    result
}
