//! What `fold-run` does, given checked options ([`RunRequest`]): run the event engine, the
//! reference or both, check the fold schedule for collisions, write the run's files into a
//! staging directory swapped into place at the end ([`crate::run_dir`]), and say what the
//! user should know ([`RunReport`]: each run's summary, the smallest margin, notes such as
//! why `fold-check` and this run disagree). The binary parses, calls [`run`] and prints.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context};
use foldchain::collision::{check_chain, CheckOptions, Verdict};
use foldchain::engine::{EngineMethod, EngineOptions, StartRule, Summary, TileDesigns};
use foldchain::model::ModelOptions;
use foldchain::physics::ForceLaw;
use foldchain::reference::{
    run_free_body, run_reference, FreeBodyOptions, Recording, ReferenceOptions, ReferenceRun,
};
use foldchain::timeline::{FoldRecord, RunSource, SpeedLaw};
use foldchain::{simulate, AutoEngine, Chain};

use crate::margins_file::MarginsJob;
use crate::numbers::thousands;
use crate::progress::Progress;
use crate::run_dir::StagedDir;
use crate::run_files::{
    check_and_write_run_files, first_foreign_run_entry, owns_run_entry, run_view,
    write_compare_page, write_run_files, RunFilesOptions, MAX_VIEWER_TILES,
};

/// The most tiles `--reference` and `--compare` take: the reference's cost grows with tiles
/// times steps, and the validation scenes go up to 107 tiles.
pub const MAX_REFERENCE_TILES: usize = 2_000;

/// The most tiles `--reference --model free-body` takes: a step costs what moves, but every
/// step keeps one entry per unknown (BENCHMARKS.md, "Free-body reference").
pub const MAX_FREE_BODY_TILES: usize = 100_000;

/// Which reference `--reference` and `--compare` run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ReferenceModel {
    /// Magnets on their paths and folding joints' angles, upstream of a fold held still.
    JointAngle,
    /// Every tile a rigid body floating free.
    FreeBody,
    /// Magnets on their paths and folding joints' angles, the joints turning at once
    /// integrated together (the free body's equations with the chain's momentum held at
    /// zero; `ReferenceOptions::coupled`).
    Coupled,
}

impl ReferenceModel {
    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ReferenceModel::JointAngle => "joint-angle",
            ReferenceModel::FreeBody => "free-body",
            ReferenceModel::Coupled => "coupled",
        }
    }

    /// The most tiles it takes.
    pub fn max_tiles(self) -> usize {
        match self {
            ReferenceModel::JointAngle | ReferenceModel::Coupled => MAX_REFERENCE_TILES,
            ReferenceModel::FreeBody => MAX_FREE_BODY_TILES,
        }
    }
}

/// What `fold-run` runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunMode {
    /// The event engine.
    Engine,
    /// The force-integrated reference (`--reference`).
    Reference,
    /// Both, side by side (`--compare`).
    Compare,
}

/// How the event engine is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EngineRequest {
    /// [`foldchain::AutoEngine::of`] decides: local solves up to a number of distinct joint
    /// neighbourhoods, the kinematic baseline beyond.
    Auto,
    /// The local solves.
    Local,
    /// The kinematic baseline with this speed law and start rule.
    Kinematic {
        /// The speed law.
        speed: SpeedLaw,
        /// The start rule.
        start: StartRule,
    },
}

/// A run, checked: everything [`run`] needs.
#[derive(Clone, Debug)]
pub struct RunRequest {
    /// The chain.
    pub chain: Chain,
    /// Its name (titles, the default output directory).
    pub name: String,
    /// The tiles' designs.
    pub designs: TileDesigns,
    /// Engine, reference or both.
    pub mode: RunMode,
    /// The reference's model (`--reference`, `--compare`).
    pub reference_model: ReferenceModel,
    /// How the engine is chosen.
    pub engine: EngineRequest,
    /// The physics of the local solves and of the reference.
    pub model: ModelOptions,
    /// The pair law (kinematic force rule, margins, energy plot).
    pub force_law: ForceLaw,
    /// The local solves' threads (0: the machine's cores).
    pub threads: usize,
    /// The deepest overlap that counts as touching, mm ([`CheckOptions::overlap_mm`]).
    pub overlap_mm: f64,
    /// How the files are drawn (its `margins_json` is filled in by [`run`]).
    pub files: RunFilesOptions,
    /// The output directory.
    pub out_dir: PathBuf,
}

/// One run's outcome: what it was, its summary, where its files went.
#[derive(Clone, Debug)]
pub struct RunResult {
    /// `engine` or `reference` when both ran (`--compare`), else empty.
    pub label: &'static str,
    /// The run's name as printed.
    pub name: String,
    /// The summary.
    pub summary: Summary,
    /// Where its files are.
    pub dir: PathBuf,
}

/// What [`run`] reports.
#[derive(Clone, Debug)]
pub struct RunReport {
    /// The runs: one, or the engine's and the reference's.
    pub runs: Vec<RunResult>,
    /// The output directory.
    pub out_dir: PathBuf,
    /// The smallest margin of the chain, in words, when it was worked out.
    pub weakest_margin: Option<String>,
    /// What the user should know, one line each (printed after `fold-run: note: `).
    pub notes: Vec<String>,
}

impl RunReport {
    /// 0 when every run completed, 1 otherwise.
    pub fn exit_code(&self) -> u8 {
        if self.runs.iter().all(|r| r.summary.completed) {
            0
        } else {
            1
        }
    }
}

/// Runs `req`: see the module documentation. A second run into the same directory is
/// refused before any work; an error (a full disk) leaves the directory as it was.
pub fn run(req: &RunRequest, progress: &Progress) -> anyhow::Result<RunReport> {
    let most = req.reference_model.max_tiles();
    if req.mode != RunMode::Engine && req.chain.len() > most {
        bail!(
            "--reference/--compare: {} tiles; the {} reference takes at most {} (use the event engine for longer chains)",
            thousands(req.chain.len() as u64),
            req.reference_model.name(),
            thousands(most as u64)
        );
    }
    if let Some(file) = first_foreign_run_entry(&req.out_dir) {
        bail!(
            "--out {}: {}",
            file.display(),
            crate::record::not_ours(&req.out_dir)
        );
    }
    let staged = StagedDir::open(&req.out_dir, owns_run_entry)?;
    let sdir = staged.path().to_path_buf();
    let unwritten = || {
        format!(
            "cannot write the run into {} (left as it was)",
            req.out_dir.display()
        )
    };
    let mut notes = Vec::new();
    let engine = engine_options(req, &mut notes);
    let margins = MarginsJob::start(&req.chain, &req.designs, req.force_law);
    let check = CheckOptions::default().with_overlap_mm(req.overlap_mm);
    let mut files = req.files.clone();
    let mut on_files = |stage: &str, done: usize, total: usize| {
        let unit = if stage == "frames" { "frames" } else { "" };
        progress.update_in(stage, unit, done as u64, total as u64);
    };
    let mut runs = Vec::new();
    let weakest_margin;
    match req.mode {
        RunMode::Engine => {
            progress.stage(&format!(
                "event engine ({} tiles)",
                thousands(req.chain.len() as u64)
            ));
            let tl = foldchain::engine::run(&req.chain, &req.designs, &engine)?;
            let m = margins.finish();
            files.margins_json = m.as_ref().map(|(_, text)| text.clone());
            weakest_margin = m.and_then(|(m, _)| m.weakest().map(|w| w.to_string()));
            progress.stage("collision check");
            let summary = check_and_write_run_files(&tl, &check, &sdir, &files, &mut on_files)
                .with_context(unwritten)?;
            notes.extend(verdict_note(&req.chain, &summary, tl.folds()));
            runs.push(result("", &req.name, summary, &req.out_dir));
        }
        RunMode::Reference => {
            progress.stage(&format!(
                "reference ({} tiles)",
                thousands(req.chain.len() as u64)
            ));
            let run = reference(req)?;
            progress.stage("collision check");
            let summary = run.checked_summary(&check)?;
            let m = margins.finish();
            files.margins_json = m.as_ref().map(|(_, text)| text.clone());
            weakest_margin = m.and_then(|(m, _)| m.weakest().map(|w| w.to_string()));
            write_run_files(&run, &summary, &sdir, &files, &mut on_files)
                .with_context(unwritten)?;
            notes.extend(verdict_note(&req.chain, &summary, run.folds()));
            runs.push(result("", &files.name, summary, &req.out_dir));
        }
        RunMode::Compare => {
            progress.stage("reference");
            let run = reference(req)?;
            let rs = run.checked_summary(&check)?;
            progress.stage("event engine");
            let (tl, es) = simulate(&req.chain, &req.designs, &engine, &check)?;
            let m = margins.finish();
            files.margins_json = m.as_ref().map(|(_, text)| text.clone());
            weakest_margin = m.and_then(|(m, _)| m.weakest().map(|w| w.to_string()));
            let rfiles = RunFilesOptions {
                name: format!("{} (reference)", req.name),
                ..files.clone()
            };
            (|| -> anyhow::Result<()> {
                write_run_files(&tl, &es, &sdir.join("engine"), &files, &mut on_files)?;
                write_run_files(&run, &rs, &sdir.join("reference"), &rfiles, &mut on_files)?;
                let views = [
                    run_view(&tl, &es, &files, "engine"),
                    run_view(&run, &rs, &rfiles, "reference"),
                ];
                let title = format!("{}: event engine and reference", req.name);
                write_compare_page(&sdir, &title, &views)?;
                Ok(())
            })()
            .with_context(unwritten)?;
            runs.push(result("engine", &req.name, es, &req.out_dir.join("engine")));
            runs.push(result(
                "reference",
                &rfiles.name,
                rs,
                &req.out_dir.join("reference"),
            ));
        }
    }
    staged.commit()?;
    for r in &runs {
        notes.extend(file_notes(&r.summary));
    }
    Ok(RunReport {
        runs,
        out_dir: req.out_dir.clone(),
        weakest_margin,
        notes,
    })
}

fn result(label: &'static str, name: &str, summary: Summary, dir: &Path) -> RunResult {
    RunResult {
        label,
        name: name.to_string(),
        summary,
        dir: dir.to_path_buf(),
    }
}

/// The engine's options: the local solves or the kinematic baseline, `--engine auto` decided
/// by [`AutoEngine::of`] (said in `notes` when it chose the baseline).
fn engine_options(req: &RunRequest, notes: &mut Vec<String>) -> EngineOptions {
    let method = match req.engine {
        EngineRequest::Kinematic { .. } => EngineMethod::Kinematic,
        EngineRequest::Local => EngineMethod::Local,
        EngineRequest::Auto => {
            let auto = AutoEngine::of(&req.chain, &req.designs);
            if auto.method == EngineMethod::Kinematic {
                notes.push(format!(
                    "{} tiles with {} distinct joint neighbourhoods: the kinematic engine (the local solves take a few ms for each; --engine local to use them anyway)",
                    thousands(req.chain.len() as u64),
                    thousands(auto.neighbourhoods as u64)
                ));
            }
            auto.method
        }
    };
    match (method, req.engine) {
        (EngineMethod::Local, _) => EngineOptions::default()
            .with_model(req.model)
            .with_threads(req.threads),
        (_, EngineRequest::Kinematic { speed, start }) => EngineOptions::default()
            .with_speed(speed)
            .with_force_law(req.force_law)
            .with_start_rule(start),
        _ => EngineOptions::default()
            .with_speed(SpeedLaw::Overdamped {
                drag: req.designs.global_design().channel_drag(false),
            })
            .with_force_law(req.force_law),
    }
}

/// The force-integrated reference of `req`'s chain.
fn reference(req: &RunRequest) -> anyhow::Result<ReferenceRun> {
    let ro = ReferenceOptions::default()
        .with_record(Recording::within_budget(req.chain.len()))
        .with_model(req.model);
    Ok(match req.reference_model {
        ReferenceModel::JointAngle => run_reference(&req.chain, &req.designs, &ro)?,
        ReferenceModel::Coupled => run_reference(&req.chain, &req.designs, &ro.with_coupled(true))?,
        ReferenceModel::FreeBody => {
            run_free_body(
                &req.chain,
                &req.designs,
                &FreeBodyOptions::default().with_reference(ro),
            )?
            .run
        }
    })
}

/// When `fold-check` (folding one joint at a time, sequentially) and this run (the physical
/// timeline, folds overlapping in time) disagree about a collision, one line saying both and
/// why.
pub fn verdict_note(chain: &Chain, summary: &Summary, folds: &[FoldRecord]) -> Option<String> {
    if summary.inhibited_at.is_some() {
        return None;
    }
    let sequential = check_chain(chain, &CheckOptions::default());
    let overlap = most_folds_at_once(folds);
    match (&sequential, &summary.first_collision) {
        (Verdict::Collides(c), None) if summary.completed => Some(format!(
            "fold-check, which folds one joint at a time, finds a collision ({c}); this run folds as the magnets drive it, up to {overlap} joints turning at once, and its tiles never meet: see docs/verifying.md"
        )),
        (Verdict::Valid, Some(c)) => Some(format!(
            "fold-check, which folds one joint at a time, finds no collision; in this run up to {overlap} joints turn at once and tiles {} and {} meet{}: see docs/verifying.md",
            c.tiles.0,
            c.tiles.1,
            c.time.map(|t| format!(" at t = {t:.4} s")).unwrap_or_default()
        )),
        _ => None,
    }
}

/// The most folds in progress at one moment.
fn most_folds_at_once(folds: &[FoldRecord]) -> usize {
    let mut edges: Vec<(f64, i32)> = folds
        .iter()
        .flat_map(|f| [(f.start, 1), (f.end, -1)])
        .collect();
    // a fold ending at the instant another starts does not overlap it
    edges.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let (mut now, mut most) = (0i32, 0i32);
    for (_, step) in edges {
        now += step;
        most = most.max(now);
    }
    most.max(0) as usize
}

/// Notes on a run's files: no viewer for a long chain, a simulated time far from a physical
/// chain's.
fn file_notes(s: &Summary) -> Vec<String> {
    let mut notes = Vec::new();
    if s.tiles > MAX_VIEWER_TILES {
        notes.push(format!(
            "no index.html: the viewer takes at most {} tiles ({} here)",
            thousands(MAX_VIEWER_TILES as u64),
            thousands(s.tiles as u64)
        ));
    }
    let d = s.duration_s;
    if s.tiles > 1 && d.is_finite() && !(1e-4..=1e8).contains(&d) {
        notes.push(format!(
            "warning: the run takes {d:.3e} s of simulated time, far from the seconds to minutes a physical chain takes: check the design's parameters (remanence, drag, sizes)"
        ));
    }
    notes
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::Fold;

    fn fold(start: f64, end: f64) -> FoldRecord {
        FoldRecord {
            joint: 0,
            fold: Fold::L,
            start,
            end,
            p0: 0.0,
        }
    }

    #[test]
    fn overlapping_folds_are_counted() {
        assert_eq!(most_folds_at_once(&[]), 0);
        let f = [
            fold(0.0, 1.0),
            fold(1.0, 2.0),
            fold(1.5, 3.0),
            fold(1.6, 1.7),
        ];
        assert_eq!(most_folds_at_once(&f), 3);
    }
}
