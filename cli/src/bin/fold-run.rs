//! `fold-run`: derive when every magnet moves and every joint folds, check the folding for
//! self-intersection, and draw it. Exit 0 when the chain folds completely and cleanly, 1 when
//! it collides, is inhibited or stalls, 2 for bad input.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{anyhow, bail, Context};
use clap::Parser;
use foldchain::collision::CheckOptions;
use foldchain::engine::{EngineOptions, SValue, SpeedLaw, StartRule, Summary, TileDesigns};
use foldchain::margins::Margins;
use foldchain::model::ModelOptions;
use foldchain::physics::{magnet_drag, ForceLaw, FORCE_LAW_NAMES};
use foldchain::reference::Recording;
use foldchain::reference::{run_reference, state_budget, ReferenceOptions, ReferenceRun};
use foldchain::timeline::RunSource;
use foldchain::{check_reference, simulate, Chain};
use foldchain_cli::choices::{
    DynamicsChoice, EngineChoice, FramesViewChoice, SpeedChoice, StartRuleChoice,
};
use foldchain_cli::engine_choice::{distinct_neighbourhoods, LOCAL_ENGINE_MAX_NEIGHBOURHOODS};
use foldchain_cli::inputs::{read_chain, read_plan_file, refuse_overwrite_in, target_outline};
use foldchain_cli::margins_file::MarginsJob;
use foldchain_cli::numbers::{count_in, number_in, thousands};
use foldchain_cli::physics_args::PhysicsArgs;
use foldchain_cli::report::{finish, parse_args};
use foldchain_cli::run_dir::{install_interrupt_cleanup, StagedDir};
use foldchain_cli::run_files::{
    check_and_write_run_files, is_run_file, owns_run_entry, run_view, write_compare_page,
    write_run_files, FramesView, RunFilesOptions, MAX_FRAMES, MAX_VIEWER_TILES,
};
use foldchain_cli::run_name::{inline_name, stem};
use foldchain_cli::{errln, outln};
use foldchain_planner::{plan_svg_file, PlanOptions, Turns};

/// Simulate a self-folding tile chain: event timeline, collision check, SVG frames.
#[derive(Parser, Debug)]
#[command(
    name = "fold-run",
    version,
    about = "Folds a chain of tiles: when every magnet moves and every joint folds (the event engine, or the force-integrated reference with --reference), whether two tiles collide on the way, and the pictures and JSON of the run.",
    after_help = "Examples:
  fold-run SLLS                         a straight tile, a tight U-turn, a straight tile
  fold-run \"S*4 L L S*4 R R S*4\" --json
  fold-run shapes/key.svg --tiles 171   plan the shape, then fold it
  fold-run --plan key-plan.json --design my-design.json
  fold-run LSLLSR --s e/3 --frames 60 --out out/lsllsr
  fold-run SLLS --reference             the force-integrated reference (up to 2,000 tiles)
  fold-run LSLLSR --compare             engine and reference side by side in one page

Writes into --out DIR (default out/NAME/): step-NNNN.svg frames, final.svg, transition.svg,
energy.svg, index.html (the animated viewer: open it in a browser; #t=SECONDS opens it at
that time), timeline.json, margins.json (the margin of every start and fold, chains up to
20,000 tiles) and summary.json (written last). Nothing else in DIR is touched.
Times are simulated seconds. The design JSON is described in README.md (see also
docs/design-example.json).

Exit codes: 0 folded completely and cleanly, 1 collided, inhibited, stalled or undecided,
2 bad input."
)]
struct Args {
    /// The chain: a tile list (`SS SL LS`), a fold word (`SLLS`), a file holding one, or a
    /// target shape `SHAPE.svg` to plan and fold in one go.
    chain: Option<String>,
    /// Read the chain from fold-plan's JSON.
    #[arg(long, value_name = "PLAN.json")]
    plan: Option<PathBuf>,
    /// Tile design JSON (a design object, or {"global": ..., "tiles": [...]}); default: the
    /// thesis design.
    #[arg(long, value_name = "DESIGN.json")]
    design: Option<PathBuf>,
    /// s for every tile: millimetres (0.3, 0.3mm) or a fraction of e (e/3, 0.25e).
    #[arg(long, value_name = "MM")]
    s: Option<String>,
    /// Output directory (default out/<name>/).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Number of step frames (default: 40, fewer for long chains; at most 100000).
    #[arg(long, value_name = "N", value_parser = frames_arg, allow_hyphen_values = true)]
    frames: Option<usize>,
    /// How step frames are framed: auto (each on the chain as it stands, or on the part
    /// that moves when a long chain seen whole would be a hairline) or fixed (every frame in
    /// one view holding the whole run).
    #[arg(long, value_name = "VIEW", value_enum, default_value_t = FramesViewChoice::Auto)]
    frames_view: FramesViewChoice,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
    /// How the engine times its events: local (solves of the reference's physics with
    /// --dynamics, one joint at a time from the RI end: the reference's events within 0.5%
    /// of the run; a few ms for each distinct neighbourhood of a joint, repeated ones cached:
    /// 100,000 straight tiles in about 2 s of CPU, a serpentine's inertial U-turns about 0.05 s each), kinematic (the baseline: a start rule
    /// and a closed-form speed law, --speed and --start-rule; microseconds per tile, its times
    /// 7-9x early and folds that overlap in time), or auto (local up to 2,000 distinct joint
    /// neighbourhoods, as in a 2,000-tile random word, kinematic beyond, said on stderr).
    #[arg(long, value_enum, default_value_t = EngineChoice::Auto)]
    engine: EngineChoice,
    /// The kinematic baseline's speed law: overdamped (seconds) or unit (1 mm/s, the
    /// transition diagram's timeline; implies --engine kinematic).
    #[arg(long, value_enum, default_value_t = SpeedChoice::Overdamped)]
    speed: SpeedChoice,
    /// The kinematic baseline's start rule: distance (the thesis' inequalities, nearest
    /// neighbours) or force (the pair forces of every magnet within 3 in chain index, as the
    /// reference integrator weighs them; about 0.4 us per tile). Default distance; giving it
    /// selects the kinematic engine (refused with --engine local).
    #[arg(long, value_enum)]
    start_rule: Option<StartRuleChoice>,
    /// The pair law of the reference and of the force start rule (and the energy plot):
    /// dipole (point dipoles, thesis 6.11/6.12) or cylinder (the design's magnets as
    /// uniformly magnetised cylinders, tabulated).
    #[arg(long, default_value = "dipole", value_parser = FORCE_LAW_NAMES)]
    force_law: String,
    /// The physics of the event engine's local solves and of the reference (--reference,
    /// --compare), the same for both: inertial (magnets of 0.265 g with a drag of 0.05 N s/m,
    /// tiles with rotational inertia, bouncing at path ends; README, "Physical parameters")
    /// or overdamped (first order, drag --drag: the stiff limit of negligible mass, the one
    /// fold-validate uses by default). The kinematic engine ignores it.
    #[arg(long, value_enum, default_value_t = DynamicsChoice::Inertial)]
    dynamics: DynamicsChoice,
    /// The reference's distance cutoff, mm: pairs nearer than this interact too, however far
    /// apart in chain index (a ring's first and last tiles); default: none, pairs up to 3
    /// apart in chain index only.
    #[arg(long, value_name = "MM", value_parser = cutoff_arg, allow_hyphen_values = true)]
    distance_cutoff: Option<f64>,
    /// The physical parameters (each overrides the design file's).
    #[command(flatten)]
    physics: PhysicsArgs,
    /// Threads of the local solves' sweeps: 1 one sweep after the other, 2 two at once (the
    /// events are the same to the last bit); default: the machine's cores, one thread under
    /// 500 tiles
    #[arg(long, value_name = "N", default_value_t = 0, hide_default_value = true, value_parser = threads_arg)]
    threads: usize,
    /// Tiles shown in the transition diagram, `A..B` (inclusive; default 0..5).
    #[arg(long, value_name = "A..B")]
    transition: Option<String>,
    /// Run the force-integrated reference (Dormand-Prince 5(4), tolerance 1e-8) instead of the
    /// event engine: writes the same files (step frames, final.svg, transition.svg,
    /// energy.svg, index.html, timeline.json, summary.json) drawn from the reference's
    /// recorded states (default out/<name>-reference/), its fold schedule (the recorded
    /// states' joint angles) checked for collisions by the engine's checker, with
    /// first_collision and exit code as the engine's. For chains up to 2,000 tiles.
    #[arg(long, conflicts_with = "compare")]
    reference: bool,
    /// Run both the event engine and the reference on the chain: both runs' files in
    /// DIR/engine and DIR/reference, and DIR/index.html playing them side by side on one
    /// clock (default out/<name>-compare/). For chains up to 2,000 tiles.
    #[arg(long)]
    compare: bool,
    /// SHAPE.svg only: about this many tiles.
    #[arg(long, value_parser = tiles_arg, allow_hyphen_values = true)]
    tiles: Option<usize>,
    /// SHAPE.svg only: tile width in SVG user units.
    #[arg(long, value_parser = tile_size_arg, allow_hyphen_values = true)]
    tile_size: Option<f64>,
    /// SHAPE.svg only: tight, loose or auto.
    #[arg(long)]
    turns: Option<Turns>,
}

fn main() -> ExitCode {
    match parse_args::<Args>("fold-run") {
        Ok(args) => {
            install_interrupt_cleanup();
            finish("fold-run", run(args))
        }
        Err(code) => code,
    }
}

/// The most tiles `fold-run` takes: its memory grows with the chain (BENCHMARKS.md), and a
/// longer chain is refused before any work rather than left to exhaust the machine.
const MAX_RUN_TILES: usize = 2_000_000;

fn frames_arg(s: &str) -> Result<usize, String> {
    count_in(s, 1, MAX_FRAMES as u64, "frames").map(|n| n as usize)
}

fn tiles_arg(s: &str) -> Result<usize, String> {
    count_in(s, 1, MAX_RUN_TILES as u64, "tiles").map(|n| n as usize)
}

fn threads_arg(s: &str) -> Result<usize, String> {
    count_in(s, 0, 256, "threads (0: the machine's cores)").map(|n| n as usize)
}

fn cutoff_arg(s: &str) -> Result<f64, String> {
    number_in(s, 1e-3, 1e4, "mm", "")
}

fn tile_size_arg(s: &str) -> Result<f64, String> {
    number_in(s, 1e-9, 1e9, "SVG user units", "")
}

/// The value of `--s`: a plain number is millimetres (`1e-3` too), otherwise the forms
/// [`SValue::parse`] reads (`0.3mm`, `e/3`, `0.25e`).
fn s_value(text: &str) -> anyhow::Result<SValue> {
    Ok(SValue::parse(text)?)
}

/// Bad input is an `Err` (exit 2); outcomes are exit codes.
fn run(args: Args) -> anyhow::Result<u8> {
    let shape_opts_given = args.tiles.is_some() || args.tile_size.is_some() || args.turns.is_some();
    // the target outline, in tile widths, when the chain was planned from a shape
    let mut target = Vec::new();
    if args.engine == EngineChoice::Local && args.start_rule.is_some() {
        bail!("--start-rule is the kinematic engine's option; the local solves start magnets from the reference's forces (use --engine kinematic, or leave --start-rule out)");
    }
    let (chain, name): (Chain, String) = match (&args.chain, &args.plan) {
        (Some(_), Some(_)) => bail!("give either CHAIN or --plan, not both"),
        (None, None) => bail!(
            "no chain: give CHAIN (a tile list, fold word, file or SHAPE.svg) or --plan PLAN.json"
        ),
        (None, Some(plan_path)) => {
            let (chain, plan) = read_plan_file(plan_path)?;
            // the plan names its shape file; drawn when it is still there
            let shape = Path::new(&plan.source);
            if shape.is_file() {
                target = target_outline(&plan, shape).unwrap_or_default();
            }
            (chain, stem(plan_path))
        }
        (Some(arg), None) if arg.to_ascii_lowercase().ends_with(".svg") => {
            let path = Path::new(arg);
            let mut po = PlanOptions::default();
            if let Some(n) = args.tiles {
                po = po.with_tiles(n);
            }
            if let Some(w) = args.tile_size {
                po = po.with_tile_size(w);
            }
            if let Some(t) = args.turns {
                po = po.with_turns(t);
            }
            let plan = match plan_svg_file(path, &po) {
                Ok(p) => p,
                Err(e) if e.is_bad_input() => return Err(anyhow!(e)),
                Err(e) => {
                    errln!("fold-run: cannot plan {}: {e:#}", path.display());
                    return Ok(1);
                }
            };
            let word = plan
                .fold_word()
                .with_context(|| format!("plan of {}", path.display()))?;
            target = target_outline(&plan, path).unwrap_or_default();
            (word.to_chain(), stem(path))
        }
        (Some(arg), None) => {
            if shape_opts_given {
                bail!("--tiles, --tile-size and --turns apply only to a SHAPE.svg");
            }
            let chain = read_chain(arg)?;
            let name = if Path::new(arg).is_file() {
                stem(Path::new(arg))
            } else {
                inline_name(arg, &chain)
            };
            (chain, name)
        }
    };
    if chain.len() > MAX_RUN_TILES {
        bail!(
            "{name}: {} tiles; fold-run takes at most {} (its memory grows with the chain; fold-check checks longer chains)",
            thousands(chain.len() as u64),
            thousands(MAX_RUN_TILES as u64)
        );
    }
    let mut designs = match &args.design {
        Some(p) => TileDesigns::from_file(p)?,
        None => TileDesigns::default(),
    };
    if let Some(s) = &args.s {
        designs = designs.with_s(s_value(s)?);
        designs.check_ranges("--s")?;
    }
    designs = args.physics.apply(designs);
    designs.check_ranges("command line")?;
    let force_law =
        ForceLaw::named(&args.force_law, &designs.global_design()).ok_or_else(|| {
            anyhow!(
                "--force-law {}: expected one of {FORCE_LAW_NAMES:?}",
                args.force_law
            )
        })?;
    let dynamics = args.dynamics.to_dynamics();
    // the kinematic baseline is overdamped: the magnet drag of the overdamped model
    let drag = magnet_drag(&designs.global_design(), false);
    let speed = match args.speed {
        SpeedChoice::Unit => SpeedLaw::Unit,
        SpeedChoice::Overdamped => SpeedLaw::Overdamped { drag },
    };
    if let Some(n) = args.frames.filter(|&n| n > MAX_FRAMES) {
        bail!("--frames {n}: at most {MAX_FRAMES} step frames (each is a full SVG of the chain)");
    }
    let transition_tiles = match &args.transition {
        None => None,
        Some(t) => {
            let (a, b) = t
                .split_once("..")
                .and_then(|(a, b)| {
                    Some((
                        a.trim().parse::<usize>().ok()?,
                        b.trim().parse::<usize>().ok()?,
                    ))
                })
                .filter(|(a, b)| a <= b)
                .ok_or_else(|| {
                    anyhow!("--transition '{t}': expected A..B with whole numbers A <= B")
                })?;
            Some((a, b))
        }
    };
    let mode = if args.compare {
        Mode::Compare
    } else if args.reference {
        Mode::Reference
    } else {
        Mode::Engine
    };
    // the margins worked out on a second thread while the engine or the reference runs
    let margins = MarginsJob::start(&chain, &designs, force_law);
    let mut files = RunFilesOptions {
        margins_json: None,
        name: match mode {
            Mode::Reference => format!("{name} (reference)"),
            _ => name.clone(),
        },
        frames: args.frames,
        transition_tiles,
        target,
        frames_view: match args.frames_view {
            FramesViewChoice::Fixed => FramesView::Fixed,
            FramesViewChoice::Auto => FramesView::Auto,
        },
    };
    let out_dir = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("out").join(match mode {
            Mode::Engine => name.clone(),
            Mode::Reference => format!("{name}-reference"),
            Mode::Compare => format!("{name}-compare"),
        })
    });
    let mut inputs: Vec<&Path> = Vec::new();
    if let Some(arg) = &args.chain {
        if Path::new(arg).is_file() {
            inputs.push(Path::new(arg));
        }
    }
    inputs.extend(args.plan.as_deref());
    inputs.extend(args.design.as_deref());
    refuse_overwrite_in(&inputs, &out_dir, &is_run_file, "--out")?;
    if mode == Mode::Compare {
        for sub in ["engine", "reference"] {
            refuse_overwrite_in(&inputs, &out_dir.join(sub), &is_run_file, "--out")?;
        }
    }
    // the run goes into a staging directory beside DIR, swapped into place at the end; a
    // second run into DIR is refused now, before any work
    let staged = StagedDir::open(&out_dir, owns_run_entry)?;
    let sdir = staged.path().to_path_buf();
    let unwritten = || {
        format!(
            "cannot write the run into {} (left as it was)",
            out_dir.display()
        )
    };
    let reference = || -> anyhow::Result<ReferenceRun> {
        if chain.len() > MAX_REFERENCE_TILES {
            bail!(
                "--reference/--compare: {} tiles; the reference integrator takes at most {MAX_REFERENCE_TILES} (use the event engine for longer chains)",
                chain.len()
            );
        }
        let ro = ReferenceOptions::default()
            .with_record(Recording::Grid {
                max_states: state_budget(chain.len()),
            })
            .with_model(ModelOptions {
                distance_cutoff: args.distance_cutoff,
                ..ModelOptions::default()
                    .with_force_law(force_law)
                    .with_dynamics(dynamics)
            });
        Ok(run_reference(&chain, &designs, &ro)?)
    };
    let kinematic = match args.engine {
        EngineChoice::Kinematic => true,
        _ if args.start_rule.is_some() => true,
        EngineChoice::Auto
            if speed != SpeedLaw::Unit
                && distinct_neighbourhoods(&chain, &designs) > LOCAL_ENGINE_MAX_NEIGHBOURHOODS =>
        {
            errln!(
                "fold-run: {} tiles with {} distinct joint neighbourhoods: the kinematic engine (the local solves take a few ms for each; --engine local to use them anyway)",
                chain.len(),
                distinct_neighbourhoods(&chain, &designs)
            );
            true
        }
        _ => speed == SpeedLaw::Unit,
    };
    let engine = if kinematic {
        EngineOptions::default()
            .with_speed(speed)
            .with_force_law(force_law)
            .with_start_rule(match args.start_rule {
                Some(StartRuleChoice::Force) => StartRule::Force {
                    cutoff: foldchain::physics::DEFAULT_CUTOFF,
                },
                Some(StartRuleChoice::Distance) | None => StartRule::Distance,
            })
    } else {
        // the local solves follow --dynamics and the design's physical parameters, as the
        // reference does
        EngineOptions::default()
            .with_model(
                ModelOptions::default()
                    .with_force_law(force_law)
                    .with_dynamics(dynamics),
            )
            .with_threads(args.threads)
    };
    let bar = (chain.len() > 2000).then(|| {
        let b = indicatif::ProgressBar::new(1);
        b.set_style(
            indicatif::ProgressStyle::with_template("{msg:>16} [{bar:40}] {pos}/{len}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    });
    let say_margins = |dir: &Path, run_margins: &Option<(Margins, String)>| {
        if let (false, Some((m, _))) = (args.json, run_margins) {
            if let Some(w) = m.weakest() {
                outln!(
                    "  smallest margin {w} ({})",
                    dir.join("margins.json").display()
                );
            }
        }
    };
    let result = match mode {
        Mode::Reference => {
            let run = reference()?;
            let summary = check_reference(&run, &CheckOptions::default())?;
            let margins = margins.finish();
            files.margins_json = margins.as_ref().map(|(_, text)| text.clone());
            write_files(&run, &summary, &sdir, &files, bar.as_ref()).with_context(unwritten)?;
            staged.commit()?;
            print_summary(&files.name, &summary, &out_dir, args.json)?;
            say_margins(&out_dir, &margins);
            Ok(exit_code(&[&summary]))
        }
        Mode::Engine => {
            // the collision check on a second thread while the files are drawn
            let tl = foldchain::engine::run(&chain, &designs, &engine)?;
            let margins = margins.finish();
            files.margins_json = margins.as_ref().map(|(_, text)| text.clone());
            let check = CheckOptions::default();
            let mut progress = bar_progress(bar.as_ref());
            let summary = check_and_write_run_files(&tl, &check, &sdir, &files, &mut progress)
                .with_context(unwritten)?;
            staged.commit()?;
            notes(&summary);
            print_summary(&name, &summary, &out_dir, args.json)?;
            say_margins(&out_dir, &margins);
            Ok(exit_code(&[&summary]))
        }
        Mode::Compare => {
            let run = reference()?;
            let rs = check_reference(&run, &CheckOptions::default())?;
            let (tl, es) = simulate(&chain, &designs, &engine, &CheckOptions::default())?;
            let margins = margins.finish();
            files.margins_json = margins.as_ref().map(|(_, text)| text.clone());
            let rfiles = RunFilesOptions {
                name: format!("{name} (reference)"),
                ..files.clone()
            };
            let (edir, rdir) = (out_dir.join("engine"), out_dir.join("reference"));
            (|| -> anyhow::Result<()> {
                write_files(&tl, &es, &sdir.join("engine"), &files, bar.as_ref())?;
                write_files(&run, &rs, &sdir.join("reference"), &rfiles, bar.as_ref())?;
                Ok(())
            })()
            .with_context(unwritten)?;
            let views = [
                run_view(&tl, &es, &files, "engine"),
                run_view(&run, &rs, &rfiles, "reference"),
            ];
            let title = format!("{name}: event engine and reference");
            write_compare_page(&sdir, &title, &views).with_context(unwritten)?;
            staged.commit()?;
            if args.json {
                let v = serde_json::json!({
                    "engine": with_out_dir(&es, &edir)?,
                    "reference": with_out_dir(&rs, &rdir)?,
                    "out_dir": out_dir.display().to_string(),
                });
                outln!("{}", serde_json::to_string_pretty(&v)?);
            } else {
                print_summary(&name, &es, &edir, false)?;
                print_summary(&rfiles.name, &rs, &rdir, false)?;
                say_margins(&edir, &margins);
                outln!("  side by side: {}", out_dir.join("index.html").display());
            }
            Ok(exit_code(&[&es, &rs]))
        }
    };
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    result
}

/// What `fold-run` runs.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// The event engine.
    Engine,
    /// The force-integrated reference (`--reference`).
    Reference,
    /// Both, side by side (`--compare`).
    Compare,
}

/// The most tiles `--reference` takes: its cost grows with tiles times steps, and the
/// validation scenes go up to 107 tiles.
const MAX_REFERENCE_TILES: usize = 2_000;

/// Writes the run's files, with a progress bar for long runs, and warns of a simulated
/// time far from a physical chain's.
fn write_files(
    source: &(dyn RunSource + Sync),
    s: &Summary,
    out_dir: &Path,
    files: &RunFilesOptions,
    bar: Option<&indicatif::ProgressBar>,
) -> anyhow::Result<()> {
    write_run_files(source, s, out_dir, files, &mut bar_progress(bar))?;
    notes(s);
    Ok(())
}

/// Reports the stages of writing a run's files on the progress bar, if any.
fn bar_progress(bar: Option<&indicatif::ProgressBar>) -> impl FnMut(&str, usize, usize) + '_ {
    move |stage: &str, done: usize, total: usize| {
        if let Some(b) = bar {
            b.set_message(stage.to_string());
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    }
}

/// Notes on a run's files: no viewer for a long chain, a simulated time far from a physical
/// chain's.
fn notes(s: &Summary) {
    if s.tiles > MAX_VIEWER_TILES {
        errln!(
            "fold-run: note: no index.html: the viewer takes at most {MAX_VIEWER_TILES} tiles ({} here)",
            s.tiles
        );
    }
    let d = s.duration_s;
    if s.tiles > 1 && d.is_finite() && !(1e-4..=1e8).contains(&d) {
        errln!(
            "fold-run: warning: the run takes {d:.3e} s of simulated time, far from the seconds to minutes a physical chain takes: check the design's parameters (remanence, drag, sizes)"
        );
    }
}

/// The summary as JSON with the directory its files went to.
fn with_out_dir(s: &Summary, out_dir: &Path) -> anyhow::Result<serde_json::Value> {
    let mut v = serde_json::to_value(s)?;
    if let Some(m) = v.as_object_mut() {
        m.insert("out_dir".into(), out_dir.display().to_string().into());
    }
    Ok(v)
}

/// Prints a run's summary: one line (and the reason), or JSON with `out_dir`.
fn print_summary(name: &str, s: &Summary, out_dir: &Path, json: bool) -> anyhow::Result<()> {
    if json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&with_out_dir(s, out_dir)?)?
        );
        return Ok(());
    }
    outln!(
        "{}: {} tiles, {} in {:.4} s of simulated time, {} events, {} folds, at most {} magnets moving; wrote {}",
        name,
        s.tiles,
        s.result,
        s.duration_s,
        s.events,
        s.folds.len(),
        s.max_moving_magnets,
        out_dir.display()
    );
    if let Some(r) = &s.reason {
        outln!("  {r}");
    }
    if let Some(f) = &s.free_motion {
        if let (Some(tile), Some(at)) = (f.fastest_tile, f.fastest_at_s) {
            outln!(
                "  on the water: fastest tile {tile} at {:.3} m/s ({:.4} s); the first tile turned {:.1} degrees, the last {:.1}",
                f.max_tile_speed_m_s,
                at,
                f.first_tile_turn_deg,
                f.last_tile_turn_deg
            );
        }
    }
    Ok(())
}

/// 0 when every run completed, 1 otherwise.
fn exit_code(summaries: &[&Summary]) -> u8 {
    if summaries.iter().all(|s| s.completed) {
        0
    } else {
        1
    }
}
