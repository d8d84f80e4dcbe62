//! `fold-tolerance`: will the chain fold when printed? Its margins, the probability that it
//! folds when every tile is printed and every magnet bought within tolerances, where failures
//! begin, each parameter's sensitivity, and (`--optimize`) a search of the design. Exit 0
//! with a report, 1 when `--optimize` finds no design reaching the target, 2 for bad input.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{anyhow, bail, Context};
use clap::Parser;
use foldchain::count::Shard;
use foldchain::engine::EngineOptions;
use foldchain::margins::{ChainModel, MarginOptions, Margins};
use foldchain::physics::{ForceLaw, FORCE_LAW_NAMES};
use foldchain::timeline::{SValue, TileDesigns};
use foldchain::tolerance::{
    candidate_design_json, candidate_designs, optimize, sensitivities, study, Candidate, Parameter,
    SearchOptions, Sensitivity, Study, StudyOptions, Tolerances,
};
use foldchain::{Chain, Design};
use foldchain_cli::choices::PrinterChoice;
use foldchain_cli::inputs::read_chain;
use foldchain_cli::report::print_error;
use foldchain_planner::{plan_svg_file, PlanOptions, Turns};
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
+-0.05 mm (resin), remanence +-2.5%, magnet dimensions +-0.05 mm (sources in README).

A sample folds when every magnet's start and every fold has a positive margin
(quasi-static: see README, \"Margins\").

Exit codes: 0 report printed, 1 --optimize found no design reaching --target, 2 bad input."
)]
struct Args {
    /// The chain: a tile list, a fold word, a file holding one, or a target shape SHAPE.svg.
    chain: String,
    /// Samples in the study.
    #[arg(long, default_value_t = 10_000, value_name = "N")]
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
    /// The folding probability the search must keep.
    #[arg(long, default_value_t = 0.99)]
    target: f64,
    /// Samples per candidate of the search.
    #[arg(long, default_value_t = 500, value_name = "N")]
    search_samples: u64,
    /// Where the search draws its trade-off (default out/<name>-tradeoff.svg).
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
    /// SHAPE.svg only: about this many tiles.
    #[arg(long)]
    tiles: Option<usize>,
    /// SHAPE.svg only: tight, loose or auto.
    #[arg(long)]
    turns: Option<Turns>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(code) => ExitCode::from(code),
        Err(e) => {
            print_error("fold-tolerance", &e);
            ExitCode::from(2)
        }
    }
}

/// The chain and a name for it.
fn read_input(args: &Args) -> anyhow::Result<(Chain, String)> {
    let arg = &args.chain;
    if arg.to_ascii_lowercase().ends_with(".svg") {
        let path = Path::new(arg);
        let mut po = PlanOptions::default();
        if let Some(n) = args.tiles {
            po = po.with_tiles(n);
        }
        if let Some(t) = args.turns {
            po = po.with_turns(t);
        }
        let plan = plan_svg_file(path, &po).map_err(|e| anyhow!(e))?;
        let word = plan
            .fold_word()
            .with_context(|| format!("plan of {}", path.display()))?;
        let name = path
            .file_stem()
            .map_or("shape".into(), |s| s.to_string_lossy().into_owned());
        return Ok((word.to_chain(), name));
    }
    if args.tiles.is_some() || args.turns.is_some() {
        bail!("--tiles and --turns apply only to a SHAPE.svg");
    }
    let chain = read_chain(arg)?;
    let name = match chain.to_word() {
        Ok(w) if w.to_string().len() <= 40 => w.to_string(),
        _ => format!("chain-{}-tiles", chain.len()),
    };
    Ok((chain, name))
}

fn run(args: &Args) -> anyhow::Result<u8> {
    let (chain, name) = read_input(args)?;
    let printer = args.printer.to_printer();
    let mut tolerances = Tolerances::printed(printer);
    for t in &args.tol {
        tolerances.set(t)?;
    }
    if args.samples == 0 {
        bail!("--samples 0: expected at least 1");
    }
    let shard = match &args.shard {
        Some(s) => Some(s.parse::<Shard>().map_err(|_| {
            anyhow!("--shard {s:?}: expected K/M with whole numbers 1 <= K <= M, e.g. 2/8")
        })?),
        None => None,
    };
    let mut designs = match &args.design {
        Some(p) => TileDesigns::from_file(p)?,
        None => TileDesigns::default(),
    };
    if let Some(s) = &args.s {
        designs = designs.with_s(SValue::parse(s)?);
        designs.validate("--s")?;
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
    let opts = StudyOptions {
        samples: args.samples,
        seed: args.seed,
        shard,
        tolerances,
        margins: MarginOptions {
            force_law,
            ..MarginOptions::default()
        },
    };
    if args.optimize {
        if !(args.target > 0.0 && args.target <= 1.0) {
            bail!("--target {}: expected a probability in (0, 1]", args.target);
        }
        if designs.has_overrides() {
            bail!("--optimize searches per-tile s itself: give a plain design (no \"tiles\")");
        }
        return search(args, &chain, &name, &nominal[0], &opts);
    }
    // the margins' own errors (a design whose curved path cannot be built) are bad input
    ChainModel::new(&chain, &nominal)?;
    let started = Instant::now();
    let result = study(&chain, &nominal, &opts)?;
    let sens = sensitivities(&chain, &nominal, &tolerances, &opts.margins)?;
    let secs = started.elapsed().as_secs_f64();
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
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(&name, &chain, &tolerances, args, &result, &sens, secs);
    }
    Ok(0)
}

const CRITERION: &str = "a sample folds when every hold, start and fold margin is positive (quasi-static poses, README \"Margins\")";

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
    println!(
        "{name}: {} tiles, {} samples (seed {}{shard}) in {secs:.1} s",
        chain.len(),
        s.samples,
        args.seed
    );
    println!(
        "tolerances ({}, uniform, per tile): {}",
        args.printer,
        tolerance_text(tol)
    );
    match s.nominal.weakest() {
        Some(w) => println!("nominal design: smallest margin {w}"),
        None => println!("nominal design: nothing to start"),
    }
    println!(
        "folds in {} of {} samples: P = {:.4} (95% interval {:.4} to {:.4})",
        s.folded, s.samples, s.probability, s.interval.0, s.interval.1
    );
    if !s.first_failures.is_empty() {
        let list: Vec<String> = s
            .first_failures
            .iter()
            .take(5)
            .map(|f| format!("joint {} ({})", f.joint, f.count))
            .collect();
        println!("failures begin at: {}", list.join(", "));
    }
    println!(
        "smallest margin over the samples: min {:+.2}%, 5th percentile {:+.2}%, median {:+.2}%",
        100.0 * s.smallest_margin.min,
        100.0 * s.smallest_margin.p05,
        100.0 * s.smallest_margin.median
    );
    println!("sensitivity of the nominal smallest margin (every tile moved at once):");
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
        println!(
            "  {:<9} {:+8.2}% {unit:<13} (the tolerance moves it +-{:.2}%)",
            x.parameter.key(),
            100.0 * per,
            100.0 * x.over_tolerance.abs()
        );
    }
    println!("criterion: {CRITERION}");
}

fn search(
    args: &Args,
    chain: &Chain,
    name: &str,
    base: &Design,
    opts: &StudyOptions,
) -> anyhow::Result<u8> {
    let so = SearchOptions {
        target: args.target,
        study: StudyOptions {
            samples: args.search_samples.max(1),
            ..*opts
        },
        engine: EngineOptions::default().with_force_law(opts.margins.force_law),
        ..SearchOptions::default()
    };
    let started = Instant::now();
    let result = optimize(chain, base, &so)?;
    let plot = args
        .plot
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("out/{name}-tradeoff.svg")));
    if let Some(dir) = plot.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    let title = format!(
        "{name}: folding probability against assembly time ({} samples per design)",
        so.study.samples
    );
    std::fs::write(&plot, tradeoff_svg(&result, args.target, &title))
        .with_context(|| format!("cannot write {}", plot.display()))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&result)?);
    } else {
        println!(
            "{name}: {} tiles, {} designs tried, {} samples each, in {:.1} s",
            chain.len(),
            result.candidates.len(),
            so.study.samples,
            started.elapsed().as_secs_f64()
        );
        println!("trade-off over s (one s for every tile):");
        println!("  wall     s mm   P       95% interval      assembly s  margin");
        for c in result
            .candidates
            .iter()
            .filter(|c| c.s_straight == c.s_turn)
        {
            println!("  {}", row(c));
        }
        println!("base design:  {}", row(&result.base));
        match &result.best {
            Some(b) => println!(
                "fastest design with P >= {}: s {} mm on straight runs, {} mm on turns, wall {:+.2} mm: {}",
                args.target, b.s_straight, b.s_turn, b.wall_step, row(b)
            ),
            None => println!("no design tried reaches P >= {}", args.target),
        }
        if let Some(m) = &result.most_probable {
            println!(
                "most probable: s {} / {} mm, wall {:+.2} mm: {}",
                m.s_straight,
                m.s_turn,
                m.wall_step,
                row(m)
            );
        }
        // the base, the chosen and the most probable design again, with the study's full
        // sample count, and the last two as design files
        let confirm = |c: &Candidate| -> anyhow::Result<Study> {
            Ok(study(chain, &candidate_designs(chain, base, c), opts)?)
        };
        let b = confirm(&result.base)?;
        println!(
            "with {} samples: base design P = {:.4} ({:.4} to {:.4})",
            b.samples, b.probability, b.interval.0, b.interval.1
        );
        let stem = plot.with_extension("");
        for (label, file, c) in [
            ("chosen", "chosen", &result.best),
            ("most probable", "most-probable", &result.most_probable),
        ] {
            let Some(c) = c else { continue };
            let s = confirm(c)?;
            let path = PathBuf::from(format!("{}-{file}.json", stem.display()));
            let mut text = serde_json::to_string_pretty(&candidate_design_json(chain, base, c))?;
            text.push('\n');
            std::fs::write(&path, text)
                .with_context(|| format!("cannot write {}", path.display()))?;
            println!(
                "with {} samples: {label} design P = {:.4} ({:.4} to {:.4}); design file {}",
                s.samples,
                s.probability,
                s.interval.0,
                s.interval.1,
                path.display()
            );
        }
        println!("wrote {}", plot.display());
    }
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
