//! `fold-tolerance`: will the chain fold when printed? Its margins, the probability that it
//! folds when every tile is printed and every magnet bought within tolerances, where failures
//! begin, each parameter's sensitivity, and (`--optimize`) a search of the design. Exit 0
//! with a report, 1 when `--optimize` finds no design reaching the target, 2 for bad input.

// the options' doc comments are clap's help text, where `<name>` is a placeholder, not HTML
#![allow(rustdoc::invalid_html_tags)]

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{anyhow, bail};
use clap::Parser;
use foldchain::count::Shard;
use foldchain::engine::EngineOptions;
use foldchain::margins::{MarginOptions, Margins};
use foldchain::physics::ForceLaw;
const FORCE_LAW_NAMES: [&str; 2] = ForceLaw::NAMES;
use foldchain::tolerance::{
    Candidate, Parameter, Search, SearchOptions, Sensitivity, Study, StudyOptions, Tolerances,
};
use foldchain::{Chain, Design};
use foldchain_cli::choices::PrinterChoice;
use foldchain_cli::inputs::{
    read_designs, refuse_foreign, refuse_overwrite, resolve_chain, ChainArgs,
};
use foldchain_cli::numbers::{count_in, number_in, thousands};
use foldchain_cli::outln;
use foldchain_cli::output::{create_dir_all, write_atomic};
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args};
use foldchain_planner::Turns;
use foldchain_render::tradeoff_svg;

/// Will it fold when printed? Margins, manufacturing tolerances and a design search.
#[derive(Parser, Debug)]
#[command(
    name = "fold-tolerance",
    version,
    after_help = "Examples:
  fold-tolerance SL                          margins and folding probability of word SL
  fold-tolerance SL --printer resin --tol br=2%
  fold-tolerance \"S*99\" --samples 10000 --seed 7 --json
  fold-tolerance S*99 --shard 2/4 --json     the second of four parts of one study
  fold-tolerance shapes/square.svg --tiles 107 --turns tight --optimize --target 0.99

Tolerances (--tol KEY=VALUE, uniform within +-VALUE on every tile independently): s, e,
wall, width (lengths, mm; d=X is width=2X since d = w/2), br (remanence, relative or %),
diameter, height (magnet, mm). Defaults: printed dimensions +-0.1 mm (--printer fdm) or
+-0.05 mm (resin), remanence +-2.5%, magnet dimensions +-0.05 mm (sources in docs/tolerances.md).

A sample folds when every magnet's start and every fold has a positive margin
(quasi-static: see docs/tolerances.md).

Exit codes: 0 report printed, 1 --optimize found no design reaching --target, 2 bad input."
)]
struct Args {
    /// The chain: a tile list, a fold word, a file holding one, or a target shape SHAPE.svg.
    chain: String,
    /// Samples in the study (1e6 is accepted), at most 1,000,000 per part (--shard).
    #[arg(long, default_value_t = 10_000, value_name = "N", value_parser = samples_arg)]
    samples: u64,
    /// A tolerance, KEY=VALUE (repeatable), over the printer's defaults.
    #[arg(long = "tol", value_name = "KEY=VALUE")]
    tol: Vec<String>,
    /// The printer whose tolerances are the defaults of printed dimensions: fdm or resin.
    #[arg(long, value_enum, default_value_t = PrinterChoice::Fdm)]
    printer: PrinterChoice,
    /// The seed of the study's draws.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Draw only part K of M of the samples (sample i belongs to part i mod M + 1).
    #[arg(long, value_name = "K/M")]
    shard: Option<String>,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Tile design JSON (a design object, or {"global": ..., "tiles": [...]}); default: the
    /// thesis design.
    #[arg(long, value_name = "DESIGN.json")]
    design: Option<PathBuf>,
    /// s for every tile: millimetres (0.3) or a fraction of e (e/3).
    #[arg(long, value_name = "MM")]
    s: Option<String>,
    /// The pair law: dipole (point dipoles, thesis 6.12) or cylinder (finite cylinders).
    #[arg(long, default_value = "dipole", value_parser = FORCE_LAW_NAMES)]
    force_law: String,
    /// Search the design (s on straight runs and on turns, the wall) for the fastest
    /// assembly whose folding probability stays at or above --target.
    #[arg(long)]
    optimize: bool,
    /// The folding probability the search must keep (0 to 1; default 0.99).
    #[arg(long, value_parser = target_arg)]
    target: Option<f64>,
    /// Samples per candidate of the search (1 to 100,000; default 500).
    #[arg(long, value_name = "N", value_parser = search_samples_arg)]
    search_samples: Option<u64>,
    /// Where the search draws its trade-off (default out/<name>-tradeoff.svg).
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// SHAPE.svg only: about this many tiles.
    #[arg(long, value_parser = tiles_arg)]
    tiles: Option<usize>,
    /// No progress on stderr.
    #[arg(long)]
    quiet: bool,
    /// SHAPE.svg only: tight, loose or auto.
    #[arg(long)]
    turns: Option<Turns>,
}

fn main() -> ExitCode {
    match parse_args::<Args>("fold-tolerance") {
        Ok(args) => finish("fold-tolerance", run(&args)),
        Err(code) => code,
    }
}

/// The most samples one part of a study draws: each is kept until the end (for the
/// percentiles of the smallest margin), about 50 bytes.
/// `--target`'s default.
const DEFAULT_TARGET: f64 = 0.99;

/// `--search-samples`' default.
const DEFAULT_SEARCH_SAMPLES: u64 = 500;

const MAX_SAMPLES_PER_PART: u64 = 1_000_000;

fn samples_arg(s: &str) -> Result<u64, String> {
    count_in(s, 1, u64::MAX, "samples")
}

fn search_samples_arg(s: &str) -> Result<u64, String> {
    count_in(s, 1, 100_000, "samples")
}

fn target_arg(s: &str) -> Result<f64, String> {
    match number_in(s, 0.0, 1.0, "", "a probability") {
        Ok(p) if p > 0.0 => Ok(p),
        Ok(_) => Err("expected a probability above 0 and at most 1".into()),
        Err(e) => Err(e),
    }
}

fn tiles_arg(s: &str) -> Result<usize, String> {
    count_in(s, 1, 2_000_000, "tiles").map(|n| n as usize)
}

fn run(args: &Args) -> anyhow::Result<u8> {
    let progress = Progress::new(
        "fold-tolerance",
        "samples",
        ProgressMode::detect(args.quiet),
    );
    let code = work(args, &progress);
    progress.finish();
    code
}

/// The study or the search; `progress` is finished before anything is printed.
fn work(args: &Args, progress: &Progress) -> anyhow::Result<u8> {
    // options checked before any work (a drawing is planned first)
    let shard = match &args.shard {
        Some(s) => Some(s.parse::<Shard>().map_err(|_| {
            anyhow!("--shard {s:?}: expected K/M with whole numbers 1 <= K <= M, e.g. 2/8")
        })?),
        None => None,
    };
    let input = resolve_chain(
        &ChainArgs {
            chain: Some(&args.chain),
            tiles: args.tiles,
            turns: args.turns,
            ..ChainArgs::default()
        },
        progress,
    )?;
    let (chain, name) = (input.chain, input.name);
    if args.optimize {
        let inputs: Vec<&Path> = input
            .files
            .iter()
            .map(PathBuf::as_path)
            .chain(args.design.as_deref())
            .collect();
        refuse_search_outputs(&plot_path(args, &name), &inputs)?;
    }
    let printer = args.printer.to_printer();
    let mut tolerances = Tolerances::printed(printer);
    for t in &args.tol {
        tolerances.set(t)?;
    }
    let parts = shard.map_or(1, |s| s.m as u64);
    if args.samples.div_ceil(parts) > MAX_SAMPLES_PER_PART {
        bail!(
            "--samples {}: at most {} per part (each sample is kept for the percentiles); split the study with --shard K/M, at least --shard K/{}",
            thousands(args.samples),
            thousands(MAX_SAMPLES_PER_PART),
            args.samples.div_ceil(MAX_SAMPLES_PER_PART)
        );
    }
    if !args.optimize {
        for (given, flag) in [
            (args.target.is_some(), "--target"),
            (args.search_samples.is_some(), "--search-samples"),
            (args.plot.is_some(), "--plot"),
        ] {
            if given {
                bail!("{flag} applies only to --optimize (the design search); add --optimize or leave {flag} out");
            }
        }
    }
    let designs = read_designs(args.design.as_deref(), args.s.as_deref())?;
    let dynamic = designs.global_design().dynamic_fields_set();
    if let Some(field) = dynamic.first() {
        bail!(
            "{}: design parameter `{field}` is set, but the tolerance study is quasi-static (the margins of the forces at rest) and uses no masses, drags, friction, restitution or water: leave {} out here, or run fold-run, whose dynamics use them",
            args.design
                .as_deref()
                .map_or("design".to_string(), |p| p.display().to_string()),
            dynamic.join(", ")
        );
    }
    let (list, index) = designs.resolve(chain.len());
    let nominal: Vec<Design> = if index.is_empty() {
        vec![list[0]]
    } else {
        index.iter().map(|&i| list[i as usize]).collect()
    };
    let force_law = ForceLaw::named(&args.force_law, &nominal[0]).ok_or_else(|| {
        anyhow!(
            "--force-law {}: expected one of {FORCE_LAW_NAMES:?}",
            args.force_law
        )
    })?;
    let opts = StudyOptions::default()
        .with_samples(args.samples)
        .with_seed(args.seed)
        .with_shard(shard)
        .with_tolerances(tolerances)
        .with_margins(MarginOptions::default().with_force_law(force_law));
    if args.optimize {
        if designs.has_overrides() {
            bail!("--optimize searches per-tile s itself: give a plain design (no \"tiles\")");
        }
        return search(args, &chain, &name, &nominal[0], &opts, progress);
    }
    // the margins' own errors (a design whose curved path cannot be built) are bad input
    Margins::of(&chain, &nominal, &opts.margins)?;
    let started = Instant::now();
    let result = Study::run_reporting(&chain, &nominal, &opts, progress)?;
    progress.stage("sensitivities");
    let sens = Sensitivity::all(&chain, &nominal, &tolerances, &opts.margins)?;
    let secs = started.elapsed().as_secs_f64();
    progress.finish();
    if args.json {
        let report = Report {
            chain: chain.to_tile_list(),
            tiles: chain.len(),
            seed: args.seed,
            shard: args.shard.clone(),
            tolerances,
            study: &result,
            nominal_margins: &result.nominal,
            weakest: result.nominal.weakest().map(|w| w.to_string()),
            sensitivity: &sens,
            criterion: CRITERION,
        };
        outln!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(&name, &chain, &tolerances, args, &result, &sens, secs);
    }
    Ok(0)
}

const CRITERION: &str = "a sample folds when every hold, start and fold margin is positive (quasi-static poses, docs/tolerances.md)";

#[derive(serde::Serialize)]
struct Report<'a> {
    chain: String,
    tiles: usize,
    seed: u64,
    shard: Option<String>,
    tolerances: Tolerances,
    study: &'a Study,
    nominal_margins: &'a Margins,
    weakest: Option<String>,
    sensitivity: &'a [Sensitivity],
    criterion: &'static str,
}

fn tolerance_text(t: &Tolerances) -> String {
    Parameter::ALL
        .iter()
        .map(|&p| match p {
            Parameter::Br => format!("br +-{:.1}%", 100.0 * t.get(p)),
            _ => format!("{p} +-{} mm", t.get(p)),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn print_report(
    name: &str,
    chain: &Chain,
    tol: &Tolerances,
    args: &Args,
    s: &Study,
    sens: &[Sensitivity],
    secs: f64,
) {
    let shard = args
        .shard
        .as_ref()
        .map(|k| format!(", shard {k}"))
        .unwrap_or_default();
    outln!(
        "{name}: {} tiles, {} samples (seed {}{shard}) in {secs:.1} s",
        chain.len(),
        s.samples,
        args.seed
    );
    outln!(
        "tolerances ({}, uniform, per tile): {}",
        args.printer,
        tolerance_text(tol)
    );
    match s.nominal.weakest() {
        Some(w) => outln!("nominal design: smallest margin {w}"),
        None => outln!("nominal design: nothing to start"),
    }
    outln!(
        "folds in {} of {} samples: P = {:.4} (95% interval {:.4} to {:.4})",
        s.folded,
        s.samples,
        s.probability,
        s.interval.0,
        s.interval.1
    );
    if !s.first_failures.is_empty() {
        let list: Vec<String> = s
            .first_failures
            .iter()
            .take(5)
            .map(|f| format!("joint {} ({})", f.joint, f.count))
            .collect();
        outln!("failures begin at: {}", list.join(", "));
    }
    outln!(
        "smallest margin over the samples: min {:+.2}%, 5th percentile {:+.2}%, median {:+.2}%",
        100.0 * s.smallest_margin.min,
        100.0 * s.smallest_margin.p05,
        100.0 * s.smallest_margin.median
    );
    outln!("sensitivity of the nominal smallest margin (every tile moved at once):");
    for x in sens {
        let unit = if x.parameter == Parameter::Br {
            "per 1% of Br"
        } else {
            "per 0.1 mm"
        };
        let per = if x.parameter == Parameter::Br {
            x.per_unit * 0.01
        } else {
            x.per_unit * 0.1
        };
        outln!(
            "  {:<9} {:+8.2}% {unit:<13} (the tolerance moves it +-{:.2}%)",
            x.parameter.key(),
            100.0 * per,
            100.0 * x.over_tolerance.abs()
        );
    }
    outln!("criterion: {CRITERION}");
}

fn search(
    args: &Args,
    chain: &Chain,
    name: &str,
    base: &Design,
    opts: &StudyOptions,
    progress: &Progress,
) -> anyhow::Result<u8> {
    let target = args.target.unwrap_or(DEFAULT_TARGET);
    let so = SearchOptions::default()
        .with_target(target)
        .with_study(opts.with_samples(args.search_samples.unwrap_or(DEFAULT_SEARCH_SAMPLES)))
        .with_engine(EngineOptions::default().with_force_law(opts.margins.force_law));
    let started = Instant::now();
    progress.stage("design search");
    let result = Search::run(chain, base, &so)?;
    let plot = plot_path(args, name);
    if let Some(dir) = plot.parent().filter(|d| !d.as_os_str().is_empty()) {
        create_dir_all(dir)?;
    }
    let title = format!(
        "{name}: folding probability against assembly time ({} samples per design)",
        so.study.samples
    );
    write_atomic(&plot, tradeoff_svg(&result, target, &title).as_bytes())?;
    if args.json {
        progress.finish();
        outln!("{}", serde_json::to_string_pretty(&result)?);
        return Ok(if result.best.is_some() { 0 } else { 1 });
    }
    // the base, the chosen and the most probable design again, with the study's full sample
    // count, and the last two as design files
    let confirm = |c: &Candidate| -> anyhow::Result<Study> {
        Ok(Study::run_reporting(
            chain,
            &c.designs(chain, base),
            opts,
            progress,
        )?)
    };
    let base_study = confirm(&result.base)?;
    let mut confirmed = Vec::new();
    for ((label, c), file) in [
        ("chosen", &result.best),
        ("most probable", &result.most_probable),
    ]
    .into_iter()
    .zip(DESIGN_FILES)
    {
        let Some(c) = c else { continue };
        let s = confirm(c)?;
        let path = design_file_path(&plot, file);
        let mut text = serde_json::to_string_pretty(&c.design_file(chain, base))?;
        text.push('\n');
        write_atomic(&path, text.as_bytes())?;
        confirmed.push((label, s, path));
    }
    progress.finish();
    outln!(
        "{name}: {} tiles, {} designs tried, {} samples each, in {:.1} s",
        chain.len(),
        result.candidates.len(),
        so.study.samples,
        started.elapsed().as_secs_f64()
    );
    outln!("trade-off over s (one s for every tile):");
    outln!("  wall     s mm   P       95% interval      assembly s  margin");
    for c in result
        .candidates
        .iter()
        .filter(|c| c.s_straight == c.s_turn)
    {
        outln!("  {}", row(c));
    }
    outln!("base design:  {}", row(&result.base));
    match &result.best {
        Some(b) => outln!(
            "fastest design with P >= {}: s {} mm on straight runs, {} mm on turns, wall {:+.2} mm: {}",
            target, b.s_straight, b.s_turn, b.wall_step, row(b)
        ),
        None => outln!("no design tried reaches P >= {target}"),
    }
    if let Some(m) = &result.most_probable {
        outln!(
            "most probable: s {} / {} mm, wall {:+.2} mm: {}",
            m.s_straight,
            m.s_turn,
            m.wall_step,
            row(m)
        );
    }
    outln!(
        "with {} samples: base design P = {:.4} ({:.4} to {:.4})",
        base_study.samples,
        base_study.probability,
        base_study.interval.0,
        base_study.interval.1
    );
    for (label, s, path) in confirmed {
        outln!(
            "with {} samples: {label} design P = {:.4} ({:.4} to {:.4}); design file {}",
            s.samples,
            s.probability,
            s.interval.0,
            s.interval.1,
            path.display()
        );
    }
    outln!("wrote {}", plot.display());
    Ok(if result.best.is_some() { 0 } else { 1 })
}

fn row(c: &Candidate) -> String {
    let time = c
        .assembly_s
        .map_or("   -   ".to_string(), |t| format!("{t:9.2}"));
    let bounds = c
        .infeasible
        .as_ref()
        .map(|_| "  outside (6.x)")
        .unwrap_or("");
    format!(
        "{:+.2}  {:5.2}  {:.4}  {:.4}-{:.4}  {time}  {:+.2}%{bounds}",
        c.wall_step,
        c.s_straight,
        c.probability,
        c.interval.0,
        c.interval.1,
        100.0 * c.nominal_margin
    )
}

/// The design files the search writes beside its plot: `PLOT-chosen.json` and
/// `PLOT-most-probable.json` (PLOT without `.svg`).
const DESIGN_FILES: [&str; 2] = ["chosen", "most-probable"];

/// Where the search draws its trade-off: `--plot`, or `out/NAME-tradeoff.svg`.
fn plot_path(args: &Args, name: &str) -> PathBuf {
    args.plot
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("out/{name}-tradeoff.svg")))
}

/// The design file `file` (one of [`DESIGN_FILES`]) beside `plot`.
fn design_file_path(plot: &Path, file: &str) -> PathBuf {
    PathBuf::from(format!("{}-{file}.json", plot.with_extension("").display()))
}

/// Refuses, before the search, to write its plot or the design files beside it over an input
/// or over files it did not write (a plot it did not draw; design files beside a plot that is
/// not its own).
fn refuse_search_outputs(plot: &Path, inputs: &[&Path]) -> anyhow::Result<()> {
    refuse_overwrite(inputs, plot, "--plot")?;
    refuse_foreign(
        plot,
        "--plot",
        "a trade-off fold-tolerance drew",
        |head, _| head.contains(": folding probability against assembly time ("),
    )?;
    // the design files beside the plot go with it: kept only where the plot is ours
    let plot_is_ours = plot.exists();
    for file in DESIGN_FILES {
        let path = design_file_path(plot, file);
        refuse_overwrite(inputs, &path, "--plot")?;
        if path.exists() && !plot_is_ours {
            bail!(
                "--plot {}: {} exists beside it and fold-tolerance did not draw the plot there; refusing to overwrite it (remove it first, or choose another --plot)",
                plot.display(),
                path.display()
            );
        }
    }
    Ok(())
}
