//! A run's files: step frames, `final.svg`, `transition.svg`, `energy.svg`, the animated
//! viewer `index.html`, `timeline.json` and `summary.json`, written into an output directory
//! from either the event engine's timeline or the reference integrator's recorded states
//! ([`RunSource`]); and the page that plays both side by side ([`write_compare_page`]).
//!
//! Frames are drawn and written one at a time, so memory does not grow with their number.
//! Every file is written atomically into the directory, which is shared with whatever else a
//! user keeps there ([`OutputDir`]): only the files named here are replaced, and step frames
//! of an earlier run with more frames are removed (they carry this tool's names).
//! `summary.json` is written last: when it is present and new, so is everything else.
//!
//! What does not depend on the collision check's verdict (the transition diagram, the energy
//! plot, the viewer's tracks) can be made first, in memory
//! ([`prepare_run_files`]): [`check_and_write_run_files`] makes it while the check runs on a
//! second thread. The text of `index.html` and `timeline.json` is made on a second thread
//! while the frames are drawn ([`write_prepared_run_files`]).

use std::path::Path;

use foldchain::collision::CheckOptions;
use foldchain::engine::{Summary, Timeline};
use foldchain::timeline::{ChainState, RunSource};
use foldchain_render::viewer::{viewer_html, viewer_html_of, RunData, RunView};
use foldchain_render::{energy_svg, frame_svg, transition_svg, FrameOptions, FrameView};
use kurbo::Point;

use crate::output::{OutputDir, WriteError};

/// The most step frames a run writes: each is a full SVG of the chain (a few kB to a few MB),
/// so more than this is almost certainly a mistake.
pub const MAX_FRAMES: usize = 100_000;

/// How a run's files are drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct RunFilesOptions {
    /// The run's name (titles).
    pub name: String,
    /// Number of step frames; `None` for [`default_frames`].
    pub frames: Option<usize>,
    /// Tiles shown in the transition diagram (inclusive); `None` for the first six.
    pub transition_tiles: Option<(usize, usize)>,
    /// The target outline the chain was planned for, drawn by the viewer: rings in the
    /// chain's own frame (tile 0 at the origin heading +x, y up) in tile widths; empty when
    /// there is none.
    pub target: Vec<Vec<(f64, f64)>>,
    /// How step frames are framed.
    pub frames_view: FramesView,
    /// The text of `margins.json` ([`crate::margins_file`]); `None`: not written (and an
    /// earlier run's removed).
    pub margins_json: Option<String>,
}

/// How step frames (and `final.svg`) are framed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FramesView {
    /// Each frame on the chain as it stands; when its tiles would be drawn less than
    /// [`MIN_TILE_PIXELS`] wide (a long chain seen whole is a hairline), on the part that
    /// moves instead: [`FOCUS_CONTEXT`] tiles either side of the moving and turning ones,
    /// the rest clipped.
    #[default]
    Auto,
    /// Every frame in one view: the box holding the chain in all of them.
    Fixed,
}

/// Tiles narrower than this in a frame of the whole chain send [`FramesView::Auto`] to the
/// part that moves.
pub const MIN_TILE_PIXELS: f64 = 8.0;

/// Tiles shown either side of the part that moves, in [`FramesView::Auto`].
pub const FOCUS_CONTEXT: usize = 24;

/// The most tiles a run's `index.html` is written for: the page carries about 28 bytes per
/// tile (28 MB at a million tiles), more than a browser opens comfortably beyond this.
pub const MAX_VIEWER_TILES: usize = 200_000;

/// The viewer's view of a run: its title, outcome, first collision and target outline.
pub fn run_view<'a>(
    source: &'a dyn RunSource,
    summary: &Summary,
    opts: &RunFilesOptions,
    label: &str,
) -> RunView<'a> {
    let mut view = outcome_free_view(source, opts)
        .with_label(label)
        .with_note(final_note(summary));
    if let Some(c) = summary.first_collision {
        view = view.with_collision(c.time, c.tiles);
    }
    view
}

/// The viewer's view of a run before its outcome is known: its title and target outline.
fn outcome_free_view<'a>(source: &'a dyn RunSource, opts: &RunFilesOptions) -> RunView<'a> {
    let w = source.geometry().w;
    RunView::new(source, opts.name.clone()).with_target(
        opts.target
            .iter()
            .map(|ring| ring.iter().map(|&(x, y)| (x * w, y * w)).collect())
            .collect(),
    )
}

/// Writes `index.html` into `dir` (created if needed): the page playing `views` side by
/// side on one clock, titled `title`. Returns `false` (and writes nothing) for runs longer
/// than [`MAX_VIEWER_TILES`].
pub fn write_compare_page(
    dir: &Path,
    title: &str,
    views: &[RunView<'_>],
) -> Result<bool, WriteError> {
    if views.iter().any(|v| v.tiles() > MAX_VIEWER_TILES) {
        return Ok(false);
    }
    let mut out = OutputDir::create(dir)?;
    out.write("index.html", viewer_html(title, views).as_bytes())?;
    Ok(true)
}

/// The default number of step frames: 40 for short chains, fewer for long ones (a frame of
/// a long chain is drawn lean, but each still holds every tile).
pub fn default_frames(tiles: usize) -> usize {
    match tiles {
        0..=50 => 40,
        51..=ChainState::DETAIL_TILES => 24,
        401..=20_000 => 12,
        _ => 6,
    }
}

/// Is `name` one of the files [`write_run_files`] writes (a step frame by its own pattern)?
pub fn is_run_file(name: &str) -> bool {
    const FIXED: [&str; 7] = [
        "final.svg",
        "margins.json",
        "transition.svg",
        "energy.svg",
        "timeline.json",
        "summary.json",
        "index.html",
    ];
    FIXED.contains(&name) || is_step_frame(name)
}

/// Is the entry at `path`, in a run's output directory, one `fold-run` owns (replaced by
/// the next run into that directory): a file under one of [`is_run_file`]'s names that the
/// directory's record lists ([`crate::record`]), a temporary name of one (a killed run's
/// torn file), or `engine/` or `reference/` of `--compare` holding nothing but such files.
/// Everything else is a user's, and stays.
pub fn owns_run_entry(path: &Path) -> bool {
    let Some(name) = path.file_name().map(|n| n.to_string_lossy().into_owned()) else {
        return false;
    };
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    // the record itself, and a file being written when a run was killed: `.NAME.tmpPID`
    if meta.is_file()
        && (name == crate::record::RECORD || crate::output::is_temp_of(&name, &is_run_file))
    {
        return true;
    }
    if meta.is_file() {
        return is_run_file(&name) && crate::record::wrote(path);
    }
    if meta.is_dir() && (name == "engine" || name == "reference") {
        return crate::record::wrote(path)
            && std::fs::read_dir(path).is_ok_and(|entries| {
                entries.flatten().all(|e| {
                    let n = e.file_name().to_string_lossy().into_owned();
                    e.file_type().is_ok_and(|t| t.is_file())
                        && (is_run_file(&n)
                            || n == crate::record::RECORD
                            || crate::output::is_temp_of(&n, &is_run_file))
                })
            });
    }
    false
}

/// The first file of `dir` that a run would replace under one of [`is_run_file`]'s names but
/// no tool wrote (the record does not list it). `None` for a new directory or one only runs
/// wrote. (`engine/` and `reference/` of `--compare` that a run did not write are kept as a
/// user's: the run is then refused when it puts its own in place, before anything is
/// replaced.)
pub fn first_foreign_run_entry(dir: &Path) -> Option<std::path::PathBuf> {
    crate::record::first_foreign(dir, "", &is_run_file)
}

/// `step-NNNN.svg` (four or more digits), as [`write_run_files`] names its frames.
fn is_step_frame(name: &str) -> bool {
    name.strip_prefix("step-")
        .and_then(|r| r.strip_suffix(".svg"))
        .is_some_and(|d| d.len() >= 4 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// Writes the run's files into `dir` (created if needed; nothing there but this tool's own
/// files is touched). `collision` marks the two tiles from its time on (`None` time: the
/// final frame only). `progress(stage, done, total)` is called as the work goes on.
/// Returns the names written, in order.
pub fn write_run_files(
    source: &(dyn RunSource + Sync),
    summary: &Summary,
    dir: &Path,
    opts: &RunFilesOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<Vec<String>, WriteError> {
    let prepared = prepare_run_files(source, opts, progress);
    write_prepared_run_files(prepared, source, summary, dir, opts, progress)
}

/// What a run's files hold that does not depend on the collision check's verdict: the
/// transition diagram, the energy plot and the viewer's data (tracks, paths, box: the bulk of
/// `index.html`). Made by [`prepare_run_files`], written by [`write_prepared_run_files`].
/// (`timeline.json` is not held: it is quick to make and large, 27 MB at 100,000 tiles.)
pub struct PreparedFiles {
    transition_svg: String,
    energy_svg: String,
    viewer: Option<RunData>,
}

/// The parts of the run's files that do not depend on its outcome, made in memory (nothing
/// is written): so that they can be made while the collision check runs.
pub fn prepare_run_files(
    source: &dyn RunSource,
    opts: &RunFilesOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> PreparedFiles {
    let tiles = source.tiles();
    let (a, b) = opts
        .transition_tiles
        .unwrap_or((0, 5.min(tiles.saturating_sub(1))));
    let title = format!(
        "{}: transition diagram, tiles {a} to {}",
        opts.name,
        b.min(tiles.saturating_sub(1))
    );
    let transition_svg = transition_svg(source.geometry(), &source.transition(a, b), &title);
    progress("energy", 0, 1);
    let samples = if tiles <= 10_000 { 400 } else { 100 };
    let title = format!("{}: total dipole energy", opts.name);
    let energy_svg = energy_svg(source.folds(), &source.energy(samples), &title);
    progress("energy", 1, 1);
    let viewer = (tiles <= MAX_VIEWER_TILES).then(|| {
        progress("viewer", 0, 1);
        let data = RunData::from_view(&outcome_free_view(source, opts));
        progress("viewer", 1, 1);
        data
    });
    PreparedFiles {
        transition_svg,
        energy_svg,
        viewer,
    }
}

/// Checks the engine's timeline `tl` for collisions
/// ([`foldchain::engine::Timeline::checked_summary`]) on a second thread while this one makes
/// the parts of its files that do not depend on the verdict ([`prepare_run_files`]), then
/// writes the files into `dir` ([`write_prepared_run_files`]): the summary and files of [`foldchain::simulate`] then
/// [`write_run_files`], with the drawing done in the check's time on a second core.
pub fn check_and_write_run_files(
    tl: &Timeline,
    check: &CheckOptions,
    dir: &Path,
    opts: &RunFilesOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> anyhow::Result<Summary> {
    let (summary, prepared) = std::thread::scope(|scope| {
        let checking = scope.spawn(|| tl.checked_summary(check));
        let prepared = prepare_run_files(tl, opts, progress);
        progress("collision check", 0, 1);
        let summary = checking
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        progress("collision check", 1, 1);
        (summary, prepared)
    });
    let summary = summary?;
    write_prepared_run_files(prepared, tl, &summary, dir, opts, progress)?;
    Ok(summary)
}

/// Writes the run's files into `dir` as [`write_run_files`] does, the parts that do not
/// depend on the outcome taken from `prepared` (made by [`prepare_run_files`] for the same
/// `source` and `opts`). The text of `index.html` and `timeline.json` is made on a second
/// thread while the frames are drawn; the files are written in the same order.
pub fn write_prepared_run_files(
    prepared: PreparedFiles,
    source: &(dyn RunSource + Sync),
    summary: &Summary,
    dir: &Path,
    opts: &RunFilesOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<Vec<String>, WriteError> {
    let mut out = OutputDir::create(dir)?;
    let PreparedFiles {
        transition_svg,
        energy_svg,
        viewer,
    } = prepared;
    let (page, timeline_json) = std::thread::scope(|scope| {
        let texts = scope.spawn(move || {
            let page = viewer.map(|data| {
                let data = data.with_outcome_of(&run_view(source, summary, opts, ""));
                viewer_html_of(&opts.name, &[data])
            });
            (page, source.timeline_json())
        });
        let drawn = write_frames(source, summary, &mut out, opts, progress);
        let texts = texts
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        drawn.map(|()| texts)
    })?;
    out.write("transition.svg", transition_svg.as_bytes())?;
    out.write("energy.svg", energy_svg.as_bytes())?;
    if let Some(page) = page {
        out.write("index.html", page.as_bytes())?;
    }
    out.write("timeline.json", timeline_json.as_bytes())?;
    if let Some(m) = &opts.margins_json {
        out.write("margins.json", m.as_bytes())?;
    }
    // a page of an earlier, shorter run of this chain would show the wrong run
    out.remove_stale(
        &|n| is_step_frame(n) || n == "index.html" || n == "margins.json",
        &is_run_file,
    )?;
    out.write_json("summary.json", summary)?;
    Ok(out.written().to_vec())
}

/// Writes the step frames and `final.svg` into `out`.
fn write_frames(
    source: &dyn RunSource,
    summary: &Summary,
    out: &mut OutputDir,
    opts: &RunFilesOptions,
    progress: &mut dyn FnMut(&str, usize, usize),
) -> Result<(), WriteError> {
    let collision = summary.first_collision.map(|c| (c.time, c.tiles));
    let w = source.geometry().w;
    let frames = opts
        .frames
        .unwrap_or_else(|| default_frames(source.tiles()))
        .clamp(1, MAX_FRAMES);
    let duration = source.end_time();
    let times = frame_times(duration, frames, collision.and_then(|(ct, _)| ct));
    let frames = times.len();
    let fixed = match opts.frames_view {
        FramesView::Auto => None,
        FramesView::Fixed => times
            .iter()
            .map(|&t| source.state_at(t))
            .chain(std::iter::once(source.final_state()))
            .map(|s| FrameView::around(s.poses.iter().copied(), w))
            .reduce(FrameView::union),
    };
    for (i, &t) in times.iter().enumerate() {
        progress("frames", i, frames);
        let hit = collision.and_then(|(ct, tiles)| ct.is_some_and(|ct| t >= ct).then_some(tiles));
        let mut state = source.state_at(t);
        let (view, note) = frame_view(source, &mut state, fixed, hit);
        let fo = FrameOptions {
            title: opts.name.clone(),
            collision: hit,
            note,
            target: Vec::new(),
        };
        let svg = frame_svg(source.geometry(), &state, &view, &fo);
        out.write(&format!("step-{i:04}.svg"), svg.as_bytes())?;
    }
    progress("frames", frames, frames);
    // the final frame shows the chain in the target's frame, over the outline it was planned
    // to fill
    let target: Vec<Vec<Point>> = opts
        .target
        .iter()
        .map(|ring| {
            ring.iter()
                .map(|&(x, y)| Point::new(x * w, y * w))
                .collect()
        })
        .collect();
    let fo = FrameOptions {
        title: opts.name.clone(),
        collision: collision.map(|(_, tiles)| tiles),
        note: Some(final_note(summary)),
        target,
    };
    let mut final_state = source.final_state();
    let (mut final_view, _) = frame_view(source, &mut final_state, fixed, fo.collision);
    if let Some(around) = FrameView::around_outline(&fo.target, w) {
        final_view = final_view.union(around);
    }
    let svg = frame_svg(source.geometry(), &final_state, &final_view, &fo);
    out.write("final.svg", svg.as_bytes())?;
    Ok(())
}

/// `frames` evenly spaced times from 0 to `duration` (just `duration` for one frame), and the
/// moment of a collision as a frame of its own.
fn frame_times(duration: f64, frames: usize, collision: Option<f64>) -> Vec<f64> {
    let mut times: Vec<f64> = (0..frames)
        .map(|i| {
            if frames == 1 {
                duration
            } else {
                duration * i as f64 / (frames - 1) as f64
            }
        })
        .collect();
    if let Some(ct) = collision.filter(|ct| (0.0..=duration).contains(ct)) {
        if !times.contains(&ct) {
            let at = times.partition_point(|&t| t < ct);
            times.insert(at, ct);
        }
    }
    times
}

/// The view of a frame of `state` (see [`FramesView`]; `fixed` is the fixed view, if any),
/// and a note saying when it shows only the part that moves. A long chain's state has no
/// magnets: those of the tiles in a view of few tiles are placed from the run's tracks.
fn frame_view(
    source: &dyn RunSource,
    state: &mut ChainState,
    fixed: Option<FrameView>,
    collision: Option<(usize, usize)>,
) -> (FrameView, Option<String>) {
    let w = source.geometry().w;
    let (view, note) = match fixed {
        Some(v) => (v, None),
        None => {
            let whole = FrameView::around(state.poses.iter().copied(), w);
            match FrameView::focus(state, w, FOCUS_CONTEXT, collision) {
                Some((v, (a, b))) if whole.tile_pixels(w) < MIN_TILE_PIXELS => {
                    let note = format!(
                        "the part that moves: tiles {a} to {b} of {} (--frames-view fixed shows the whole run)",
                        state.tiles()
                    );
                    (v, Some(note))
                }
                _ => (whole, None),
            }
        }
    };
    if state.magnets.is_empty() {
        let shown: Vec<usize> = (0..state.tiles())
            .filter(|&i| view.shows(&state.poses[i], w))
            .collect();
        if shown.len() <= ChainState::DETAIL_TILES {
            let g = source.geometry();
            state.magnets = vec![(f64::NAN, f64::NAN); g.magnets()];
            for k in shown.into_iter().flat_map(|i| [2 * i, 2 * i + 1]) {
                let u = source.magnet_travel(k).value_at(state.time);
                state.magnets[k] = state.poses[k / 2].transform_point(g.path(k).point_at(u));
            }
        }
    }
    (view, note)
}

/// The final frame's note: the result and its reason, at most 150 characters.
fn final_note(summary: &Summary) -> String {
    let note = match &summary.reason {
        Some(r) => format!("{}: {r}", summary.result),
        None => summary.result.to_string(),
    };
    if note.chars().count() > 150 {
        format!("{}...", note.chars().take(147).collect::<String>())
    } else {
        note
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn step_frames_are_recognised_by_their_pattern_only() {
        assert!(is_step_frame("step-0000.svg") && is_step_frame("step-12345.svg"));
        for n in [
            "step-7.svg",
            "step-00a0.svg",
            "step-0000.svg.bak",
            "xstep-0000.svg",
        ] {
            assert!(!is_step_frame(n), "{n}");
        }
        assert!(is_run_file("summary.json") && !is_run_file("notes.txt"));
    }

    #[test]
    fn checking_beside_the_drawing_writes_the_files_of_simulate_then_write() {
        use foldchain::engine::{EngineOptions, TileDesigns};
        use foldchain::{simulate, Chain};
        // a clean serpentine and one that collides (its frames marked from the contact on)
        for word in ["S*8 LL S*8 RR S*8", "LLLLLLLL S*6"] {
            let chain = Chain::parse(word).unwrap();
            let (designs, engine) = (TileDesigns::default(), EngineOptions::default());
            let check = CheckOptions::default();
            let opts = RunFilesOptions {
                name: word.into(),
                frames: Some(5),
                transition_tiles: None,
                target: Vec::new(),
                frames_view: FramesView::Auto,
                margins_json: None,
            };
            let base =
                std::env::temp_dir().join(format!("foldchain-runfiles-{}", std::process::id()));
            let (one, two) = (base.join("one"), base.join("two"));
            let (tl, summary) = simulate(&chain, &designs, &engine, &check).unwrap();
            let names = write_run_files(&tl, &summary, &one, &opts, &mut |_, _, _| {}).unwrap();
            let tl = foldchain::engine::run(&chain, &designs, &engine).unwrap();
            let checked =
                check_and_write_run_files(&tl, &check, &two, &opts, &mut |_, _, _| {}).unwrap();
            assert_eq!(checked, summary, "{word}");
            assert_eq!(summary.first_collision.is_some(), word.starts_with('L'));
            assert!(names.contains(&"index.html".to_string()) && names.len() > 8);
            for name in &names {
                let (a, b) = (std::fs::read(one.join(name)), std::fs::read(two.join(name)));
                assert_eq!(a.unwrap(), b.unwrap(), "{word}: {name}");
            }
            let _ = std::fs::remove_dir_all(&base);
        }
    }

    #[test]
    fn a_collision_gets_a_frame_at_its_moment() {
        assert_eq!(frame_times(4.0, 3, None), vec![0.0, 2.0, 4.0]);
        assert_eq!(frame_times(4.0, 3, Some(2.5)), vec![0.0, 2.0, 2.5, 4.0]);
        assert_eq!(frame_times(4.0, 3, Some(2.0)), vec![0.0, 2.0, 4.0]);
        assert_eq!(frame_times(4.0, 1, Some(1.0)), vec![1.0, 4.0]);
    }
}
