//! `fold-run`: derive when every magnet moves and every joint folds, check the folding for
//! self-intersection, and draw it. Exit 0 when the chain folds completely and cleanly, 1 when
//! it collides, is inhibited or stalls, 2 for bad input, 3 when the disk is full.
//!
//! Thin: the arguments become a checked [`RunRequest`], [`foldchain_cli::fold_run::run`]
//! does the work, and the report is printed here.

// the options' doc comments are clap's help text, where `<name>` is a placeholder, not HTML
#![allow(rustdoc::invalid_html_tags)]

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context};
use clap::Parser;
use foldchain::collision::CheckOptions;
use foldchain::engine::{StartRule, Summary, TileDesigns};
use foldchain::model::ModelOptions;
use foldchain::physics::ForceLaw;
const FORCE_LAW_NAMES: [&str; 2] = ForceLaw::NAMES;
use foldchain::timeline::SpeedLaw;
use foldchain_cli::choices::{
    DynamicsChoice, EngineChoice, FramesViewChoice, SpeedChoice, StartRuleChoice,
};
use foldchain_cli::fold_run::{run, EngineRequest, ReferenceModel, RunMode, RunReport, RunRequest};
use foldchain_cli::help::{RUN_ABOUT, RUN_AFTER_HELP};
use foldchain_cli::inputs::{
    read_designs, refuse_overwrite_in, resolve_chain, ChainArgs, ChainInput,
};
use foldchain_cli::numbers::{count_in, in_range, number_in, thousands};
use foldchain_cli::physics_args::PhysicsArgs;
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args};
use foldchain_cli::run_dir::install_interrupt_cleanup;
use foldchain_cli::run_files::{is_run_file, FramesView, RunFilesOptions, MAX_FRAMES};
use foldchain_cli::{errln, outln};
use foldchain_planner::Turns;

/// Simulate a self-folding tile chain: event timeline, collision check, SVG frames.
#[derive(Parser, Debug)]
#[command(name = "fold-run", version, about = RUN_ABOUT, after_help = RUN_AFTER_HELP)]
struct Args {
    #[command(flatten)]
    input: ChainInput,
    /// s for every tile: millimetres (0.3, 0.3mm) or a fraction of e (e/3, 0.25e); from 0 to
    /// the design's largest (4.7 mm for the thesis design).
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
    /// No progress on stderr.
    #[arg(long)]
    quiet: bool,
    /// How the engine times its events: local (solves of the reference's physics with
    /// --dynamics, one joint at a time from the RI end: the reference's events within 0.5%
    /// of the run; a few ms for each distinct neighbourhood of a joint, repeated ones cached:
    /// 100,000 straight tiles in about 2 s of CPU, a serpentine's inertial U-turns about 0.05
    /// s each), kinematic (the baseline: a start rule and a closed-form speed law, --speed
    /// and --start-rule; microseconds per tile, its times 7-9x early and folds that overlap
    /// in time), or auto (the default: local up to 2,000 distinct joint neighbourhoods, as in
    /// a 2,000-tile random word, kinematic beyond, said on stderr).
    #[arg(long, value_enum)]
    engine: Option<EngineChoice>,
    /// The kinematic baseline's speed law: overdamped (seconds, the default) or unit (1 mm/s,
    /// the transition diagram's timeline). Giving it selects the kinematic engine.
    #[arg(long, value_enum)]
    speed: Option<SpeedChoice>,
    /// The kinematic baseline's start rule: distance (the thesis' inequalities, nearest
    /// neighbours; the default) or force (the pair forces of every magnet within 3 in chain
    /// index, as the reference integrator weighs them; about 0.4 us per tile). Giving it
    /// selects the kinematic engine.
    #[arg(long, value_enum)]
    start_rule: Option<StartRuleChoice>,
    /// The pair law of the reference and of the force start rule (and the energy plot):
    /// dipole (point dipoles, thesis 6.11/6.12) or cylinder (the design's magnets as
    /// uniformly magnetised cylinders, tabulated).
    #[arg(long, default_value = "dipole", value_parser = FORCE_LAW_NAMES)]
    force_law: String,
    /// The physics of the event engine's local solves and of the reference (--reference,
    /// --compare): inertial (the default: magnets of 0.265 g with a drag of 0.05 N s/m,
    /// tiles of 3 g on water, both sides of a fold turning, bouncing at path ends;
    /// docs/physics.md) or overdamped (first order, magnet drag 5 N s/m unless --drag: the
    /// stiff limit of negligible mass). Refused with
    /// the kinematic engine, which does not use it.
    #[arg(long, value_enum)]
    dynamics: Option<DynamicsChoice>,
    /// The reference's distance cutoff, mm (0.001 to 10000): pairs nearer than this interact
    /// too, however far apart in chain index (a ring's first and last tiles); default: none,
    /// pairs up to 3 apart in chain index only. With --reference or --compare.
    #[arg(long, value_name = "MM", value_parser = in_range(1e-3, 1e4, "mm", ""), allow_hyphen_values = true)]
    distance_cutoff: Option<f64>,
    /// The physical parameters (each overrides the design file's, for every model the run
    /// uses).
    #[command(flatten)]
    physics: PhysicsArgs,
    /// Threads of the local solves' sweeps (1 to 256): 1 one sweep after the other, 2 two at
    /// once (the events are the same to the last bit); default: the machine's cores, one
    /// thread under 500 tiles.
    #[arg(long, value_name = "N", value_parser = threads_arg)]
    threads: Option<usize>,
    /// Tiles shown in the transition diagram, `A..B` (inclusive; default 0..5).
    #[arg(long, value_name = "A..B")]
    transition: Option<String>,
    /// Run the force-integrated reference (Dormand-Prince 5(4), tolerance 1e-8) instead of the
    /// event engine: writes the same files drawn from the reference's recorded states
    /// (default out/<name>-reference/), its fold schedule checked for collisions by the
    /// engine's checker. For chains up to 2,000 tiles.
    #[arg(long, conflicts_with = "compare")]
    reference: bool,
    /// Which reference --reference and --compare run: joint-angle (every magnet on its path
    /// and every folding joint's angle, the part upstream of a fold held still; up to 2,000
    /// tiles) or free-body (every tile a rigid body floating on water, nothing anchored,
    /// both sides of a fold turning against their inertia and the water's drag; inertial
    /// dynamics only; docs/free-body.md; up to 100,000 tiles), or coupled (the joint-angle
    /// model with the joints turning at once integrated together, the free body's equations
    /// with the chain's momentum held at zero; inertial dynamics only; up to 2,000 tiles).
    #[arg(long, value_enum, default_value_t = ReferenceModel::JointAngle)]
    model: ReferenceModel,
    /// Run both the event engine and the reference on the chain: both runs' files in
    /// DIR/engine and DIR/reference, and DIR/index.html playing them side by side on one
    /// clock (default out/<name>-compare/). For chains up to 2,000 tiles.
    #[arg(long)]
    compare: bool,
    /// The deepest overlap of two tiles, mm (0 to 1), that counts as touching: a graze,
    /// reported with its clearance ("closest approach") instead of a collision. Default 0.01
    /// (the runs' numerical resolution of a contact: docs/clearances.md).
    #[arg(long, value_name = "MM", value_parser = in_range(0.0, 1.0, "mm", ""), allow_hyphen_values = true)]
    overlap_tolerance: Option<f64>,
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
            finish("fold-run", main_run(&args))
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
    count_in(s, 1, 256, "threads").map(|n| n as usize)
}

fn tile_size_arg(s: &str) -> Result<f64, String> {
    match number_in(s, 0.0, 1e9, "SVG user units", "") {
        Ok(w) if w > 0.0 => Ok(w),
        Ok(_) => Err("expected a tile width above 0 SVG user units".into()),
        Err(e) => Err(e),
    }
}

fn main_run(args: &Args) -> anyhow::Result<u8> {
    let progress = Progress::new("fold-run", "", ProgressMode::detect(args.quiet));
    let req = request(args, &progress)?;
    let report = run(&req, &progress);
    progress.finish();
    let report = report?;
    print_report(&report, args.json)?;
    Ok(report.exit_code())
}

/// `--model free-body` and `--model coupled` refused where they do not apply (the engine, the overdamped
/// dynamics, a distance cutoff).
fn refuse_free_body_misuse(args: &Args, mode: RunMode) -> anyhow::Result<()> {
    if args.model == ReferenceModel::JointAngle {
        return Ok(());
    }
    let m = args.model.name();
    if mode == RunMode::Engine {
        bail!("--model {m}: the reference's model; give --reference or --compare");
    }
    if args.dynamics == Some(DynamicsChoice::Overdamped) {
        bail!("--model {m} --dynamics overdamped: the {m} reference integrates tiles with mass (use --dynamics inertial, the default)");
    }
    if args.distance_cutoff.is_some() {
        bail!("--model {m} --distance-cutoff: the {m} reference weighs pairs by chain index only");
    }
    Ok(())
}

/// The pair law `--force-law` names for `designs`, and the model's options with it
/// (`--dynamics`, `--distance-cutoff`).
fn model_options(args: &Args, designs: &TileDesigns) -> anyhow::Result<(ForceLaw, ModelOptions)> {
    let force_law =
        ForceLaw::named(&args.force_law, &designs.global_design()).with_context(|| {
            format!(
                "--force-law {}: expected one of {}",
                args.force_law,
                FORCE_LAW_NAMES.join(", ")
            )
        })?;
    let mut model = ModelOptions::default()
        .with_force_law(force_law)
        .with_dynamics(
            args.dynamics
                .unwrap_or(DynamicsChoice::Inertial)
                .to_dynamics(),
        );
    model.distance_cutoff = args.distance_cutoff;
    Ok((force_law, model))
}

/// The arguments, checked and converted once.
fn request(args: &Args, progress: &Progress) -> anyhow::Result<RunRequest> {
    let mode = if args.compare {
        RunMode::Compare
    } else if args.reference {
        RunMode::Reference
    } else {
        RunMode::Engine
    };
    let engine = engine_request(args, mode)?;
    refuse_unused(args, mode, &engine)?;
    let engine = match engine {
        // the kinematic baseline's overdamped speed law takes the design's magnet drag
        EngineRequest::Kinematic {
            speed: SpeedLaw::Overdamped { .. },
            start,
        } => EngineRequest::Kinematic {
            speed: SpeedLaw::Overdamped {
                drag: kinematic_drag(args)?,
            },
            start,
        },
        other => other,
    };
    refuse_free_body_misuse(args, mode)?;
    let input = resolve_chain(
        &ChainArgs {
            chain: args.input.chain.as_deref(),
            plan: args.input.plan.as_deref(),
            tiles: args.tiles,
            tile_size: args.tile_size,
            turns: args.turns,
        },
        progress,
    )?;
    let (chain, name) = (input.chain, input.name);
    if chain.len() > MAX_RUN_TILES {
        bail!(
            "{name}: {} tiles; fold-run takes at most {} (its memory grows with the chain; fold-check checks longer chains)",
            thousands(chain.len() as u64),
            thousands(MAX_RUN_TILES as u64)
        );
    }
    let mut designs = read_designs(args.input.design.as_deref(), args.s.as_deref())?;
    designs = args.physics.apply(designs);
    designs.check_ranges("command line")?;
    let (force_law, model) = model_options(args, &designs)?;
    let out_dir = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("out").join(match mode {
            RunMode::Engine => name.clone(),
            RunMode::Reference if args.model == ReferenceModel::FreeBody => {
                format!("{name}-free-body")
            }
            RunMode::Reference => format!("{name}-reference"),
            RunMode::Compare => format!("{name}-compare"),
        })
    });
    let mut inputs: Vec<&Path> = input.files.iter().map(PathBuf::as_path).collect();
    inputs.extend(args.input.design.as_deref());
    refuse_overwrite_in(&inputs, &out_dir, &is_run_file, "--out")?;
    if mode == RunMode::Compare {
        for sub in ["engine", "reference"] {
            refuse_overwrite_in(&inputs, &out_dir.join(sub), &is_run_file, "--out")?;
        }
    }
    let files = RunFilesOptions {
        margins_json: None,
        name: match (mode, args.model) {
            (RunMode::Reference, ReferenceModel::FreeBody) => {
                format!("{name} (free-body reference)")
            }
            (RunMode::Reference, _) => format!("{name} (reference)"),
            _ => name.clone(),
        },
        frames: args.frames,
        transition_tiles: args.transition.as_deref().map(transition).transpose()?,
        target: input.target,
        frames_view: match args.frames_view {
            FramesViewChoice::Fixed => FramesView::Fixed,
            FramesViewChoice::Auto => FramesView::Auto,
        },
    };
    Ok(RunRequest {
        chain,
        name,
        designs,
        mode,
        reference_model: args.model,
        engine,
        model,
        force_law,
        threads: args.threads.unwrap_or(0),
        overlap_mm: args
            .overlap_tolerance
            .unwrap_or(CheckOptions::default().overlap_mm),
        files,
        out_dir,
    })
}

/// The engine as asked: `--speed` or `--start-rule` select the kinematic baseline.
fn engine_request(args: &Args, mode: RunMode) -> anyhow::Result<EngineRequest> {
    let kinematic_options = args.speed.is_some() || args.start_rule.is_some();
    if mode == RunMode::Reference {
        for (given, flag) in [
            (args.engine.is_some(), "--engine"),
            (args.speed.is_some(), "--speed"),
            (args.start_rule.is_some(), "--start-rule"),
            (args.threads.is_some(), "--threads"),
        ] {
            if given {
                bail!("{flag} is an option of the event engine, which --reference does not run (use --compare to run both)");
            }
        }
    }
    let kinematic = || EngineRequest::Kinematic {
        speed: match args.speed.unwrap_or(SpeedChoice::Overdamped) {
            SpeedChoice::Unit => SpeedLaw::Unit,
            // the drag is set from the design once it is read ([`kinematic_drag`])
            SpeedChoice::Overdamped => SpeedLaw::Overdamped { drag: f64::NAN },
        },
        start: match args.start_rule.unwrap_or(StartRuleChoice::Distance) {
            StartRuleChoice::Force => StartRule::Force {
                cutoff: ModelOptions::DEFAULT_CUTOFF,
            },
            StartRuleChoice::Distance => StartRule::Distance,
        },
    };
    Ok(match args.engine {
        Some(EngineChoice::Local) if kinematic_options => bail!(
            "--speed and --start-rule are the kinematic engine's options; the local solves move magnets by the reference's forces (use --engine kinematic, or leave them out)"
        ),
        Some(EngineChoice::Local) => EngineRequest::Local,
        Some(EngineChoice::Kinematic) => kinematic(),
        Some(EngineChoice::Auto) | None if kinematic_options => kinematic(),
        Some(EngineChoice::Auto) | None => EngineRequest::Auto,
    })
}

/// Refuses an option nothing in this run would use.
fn refuse_unused(args: &Args, mode: RunMode, engine: &EngineRequest) -> anyhow::Result<()> {
    let kinematic_only =
        mode == RunMode::Engine && matches!(engine, EngineRequest::Kinematic { .. });
    if kinematic_only && args.dynamics.is_some() {
        bail!("--dynamics sets the physics of the local solves and of the reference; the kinematic engine has its own speed law (--speed): leave --dynamics out, or use --engine local");
    }
    if kinematic_only && args.threads.is_some() {
        bail!("--threads sets the local solves' threads; the kinematic engine runs on one: leave it out");
    }
    if mode == RunMode::Engine && args.distance_cutoff.is_some() {
        bail!("--distance-cutoff applies to the reference: add --reference or --compare, or leave it out");
    }
    if args.physics.drag.is_some()
        && args.speed == Some(SpeedChoice::Unit)
        && mode == RunMode::Engine
    {
        bail!("--drag is a magnet's drag in its channel; --speed unit moves every magnet at 1 mm/s: leave one of them out");
    }
    if kinematic_only {
        // the kinematic baseline moves magnets at the overdamped speed law's pace: it uses the
        // magnet drag alone
        let unused: Vec<&str> = args
            .physics
            .given()
            .into_iter()
            .filter(|f| *f != "--drag")
            .collect();
        if let Some(first) = unused.first() {
            bail!("{first}: the kinematic engine moves magnets at a speed law and uses no masses, friction, restitution or water ({}): leave {} out, or use --engine local", unused.join(", "), if unused.len() == 1 { "it" } else { "them" });
        }
    }
    Ok(())
}

/// The kinematic baseline's overdamped drag: the design file's or `--drag`, else the
/// overdamped model's default (5 N s/m).
fn kinematic_drag(args: &Args) -> anyhow::Result<f64> {
    let designs = args.input.designs()?;
    Ok(args
        .physics
        .apply(designs)
        .global_design()
        .channel_drag(false))
}

/// `--transition A..B`.
fn transition(t: &str) -> anyhow::Result<(usize, usize)> {
    t.split_once("..")
        .and_then(|(a, b)| {
            Some((
                a.trim().parse::<usize>().ok()?,
                b.trim().parse::<usize>().ok()?,
            ))
        })
        .filter(|(a, b)| a <= b)
        .with_context(|| format!("--transition '{t}': expected A..B with whole numbers A <= B"))
}

/// The report: notes on stderr, each run's summary line (or JSON) on stdout.
fn print_report(report: &RunReport, json: bool) -> anyhow::Result<()> {
    for note in &report.notes {
        errln!("fold-run: note: {note}");
    }
    if json {
        let value = match report.runs.as_slice() {
            [one] => with_dir(&one.summary, &one.dir)?,
            runs => {
                let mut v = serde_json::Map::new();
                for r in runs {
                    v.insert(r.label.into(), with_dir(&r.summary, &r.dir)?);
                }
                v.insert(
                    "out_dir".into(),
                    report.out_dir.display().to_string().into(),
                );
                v.into()
            }
        };
        outln!("{}", serde_json::to_string_pretty(&value)?);
        return Ok(());
    }
    for r in &report.runs {
        summary_line(&r.name, &r.summary, &r.dir);
    }
    if let (Some(w), Some(first)) = (&report.weakest_margin, report.runs.first()) {
        outln!(
            "  smallest margin {w} ({})",
            first.dir.join("margins.json").display()
        );
    }
    if report.runs.len() > 1 {
        outln!(
            "  side by side: {}",
            report.out_dir.join("index.html").display()
        );
    }
    Ok(())
}

/// The summary as JSON with the directory its files went to.
fn with_dir(s: &Summary, dir: &Path) -> anyhow::Result<serde_json::Value> {
    let mut v = serde_json::to_value(s)?;
    if let Some(m) = v.as_object_mut() {
        m.insert("out_dir".into(), dir.display().to_string().into());
    }
    Ok(v)
}

/// One run's summary line, and the reason on the next.
fn summary_line(name: &str, s: &Summary, dir: &Path) {
    let plural = |n: usize, one: &str, many: &str| {
        format!(
            "{} {}",
            thousands(n as u64),
            if n == 1 { one } else { many }
        )
    };
    outln!(
        "{name}: {}, {} in {:.4} s of simulated time, {}, {}, at most {} moving; wrote {}",
        plural(s.tiles, "tile", "tiles"),
        s.result,
        s.duration_s,
        plural(s.events, "event", "events"),
        plural(s.folds.len(), "fold", "folds"),
        plural(s.max_moving_magnets, "magnet", "magnets"),
        dir.display()
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
    // a near miss, a touch, a graze or an overlap (summary.json always has it)
    if let Some(c) = s.clearance.filter(|c| c.mm < NEAR_MISS_MM) {
        outln!("  {}", clearance_words(&c));
    }
}

/// The closest approach the text summary tells: under 1 mm (summary.json has every run's).
const NEAR_MISS_MM: f64 = 1.0;

/// How close two tiles that are not neighbours came, in words.
fn clearance_words(c: &foldchain::timeline::Clearance) -> String {
    let (a, b) = c.tiles;
    let how = if c.mm >= 0.0 {
        format!("{:.4} mm apart", c.mm)
    } else if c.graze {
        format!(
            "overlapping by {:.4} mm, a graze (within the {} mm overlap tolerance: touching)",
            -c.mm, c.overlap_tolerance_mm
        )
    } else {
        format!("overlapping by {:.4} mm", -c.mm)
    };
    let when = match c.joint {
        Some(j) => format!("at t = {:.4} s while joint {j} folds", c.time),
        None => format!("at t = {:.4} s", c.time),
    };
    format!("closest approach: tiles {a} and {b}, {how}, {when}")
}
