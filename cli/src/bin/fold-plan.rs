//! `fold-plan`: from a target shape in an SVG file to a tile sequence.
//!
//! Exit codes: 0 planned, 1 the shape cannot be planned (the message says why), 2 bad input
//! (unreadable file, bad SVG, no filled area, self-intersecting outline, bad option).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Parser;
use foldchain_cli::inputs::refuse_overwrite;
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::message;
use foldchain_planner::{
    plan_svg_file_reporting, preview_svg_file, preview_svg_rejected, PlanError, PlanOptions, Turns,
    DEFAULT_TILES_TOLERANCE, DEFAULT_TURN_COST,
};

/// Plan a self-folding tile chain that fills the shape drawn in an SVG file.
#[derive(Parser, Debug)]
#[command(
    name = "fold-plan",
    version,
    about = "Plans the chain of tiles that folds into a shape drawn in SVG: serpentine rows joined by U-turns, monotone cells joined by turns; every plan is checked to fold without self-intersection.",
    after_help = "Examples:
  fold-plan shapes/square.svg --tiles 107 --turns tight
  fold-plan shapes/key.svg --tiles 171 --preview key-plan.svg --out key-plan.json
  fold-plan shapes/ring.svg --tiles 300 --json
  fold-run --plan key-plan.json     fold the planned chain

Prints the run-length tile list and a summary line (or the plan JSON with --json).
Progress goes to stderr (plain lines every few seconds when stderr is not a terminal;
--quiet silences). Limits: at most 2,000,000 tiles and 10,000,000 outline points; outlines of many points are simplified to 1/1000 of the drawing first.
Exit codes: 0 planned, 1 the shape cannot be planned (the reason is given), 2 bad input."
)]
struct Args {
    /// The target shape: an SVG file; its filled areas are the shape.
    shape: PathBuf,
    /// About this many tiles (default 200 when no tile width is given).
    #[arg(long, conflicts_with_all = ["tile_size", "tile_mm"], value_parser = tiles_arg, allow_hyphen_values = true)]
    tiles: Option<usize>,
    /// The share by which the tile count may miss --tiles when that buys a better fit.
    #[arg(long, default_value_t = DEFAULT_TILES_TOLERANCE, allow_hyphen_values = true)]
    tiles_tolerance: f64,
    /// Tile width (across flats) in SVG user units.
    #[arg(long, conflicts_with = "tile_mm", allow_hyphen_values = true)]
    tile_size: Option<f64>,
    /// Tile width (across flats) in millimetres, by the drawing's width/height units and
    /// viewBox (96 user units per inch when it states none); the thesis' tiles are 30 mm.
    #[arg(long, allow_hyphen_values = true)]
    tile_mm: Option<f64>,
    /// The price of a U-turn or quarter turn, in tile areas of misfit.
    #[arg(long, default_value_t = DEFAULT_TURN_COST, allow_hyphen_values = true)]
    turn_cost: f64,
    /// U-turn style: tight (LL/RR tiles), loose (no LL/RR tiles) or auto (better fit).
    #[arg(long, default_value = "auto")]
    turns: Turns,
    /// Write the plan JSON here (what fold-run --plan reads).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write a preview SVG here: the outline, the tiles over it and the fold order (when the
    /// shape cannot be planned, the best rejected plan, marked as no plan, if there is one).
    #[arg(long)]
    preview: Option<PathBuf>,
    /// Print the plan JSON instead of the tile list and summary.
    #[arg(long)]
    json: bool,
    /// No progress lines on stderr.
    #[arg(long)]
    quiet: bool,
}

/// A tile count on the command line: a whole number >= 1.
fn tiles_arg(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("expected a whole number of tiles >= 1".into()),
    }
}

fn main() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fold-plan: {}", message(&e));
            let code = e
                .downcast_ref::<PlanError>()
                .map_or(2, |p| p.exit_code() as u8);
            ExitCode::from(code)
        }
    }
}

fn run(args: &Args) -> anyhow::Result<()> {
    if let Some(out) = &args.out {
        refuse_overwrite(&[&args.shape], out, "--out")?;
    }
    if let Some(p) = &args.preview {
        refuse_overwrite(&[&args.shape], p, "--preview")?;
        if let Some(out) = &args.out {
            refuse_overwrite(&[out], p, "--preview")?;
        }
    }
    let opts = PlanOptions {
        tiles: args.tiles,
        tile_size: args.tile_size,
        tile_mm: args.tile_mm,
        tiles_tolerance: args.tiles_tolerance,
        turn_cost: args.turn_cost,
        turns: args.turns,
    };
    let progress = Progress::new("fold-plan", "steps", ProgressMode::detect(args.quiet));
    let plan = plan_svg_file_reporting(&args.shape, &opts, &|stage, done, total| {
        progress.update(stage, done, total)
    });
    progress.finish();
    let plan = match plan {
        Ok(p) => p,
        Err(PlanError::Unplannable {
            name,
            reason,
            rejected,
        }) => {
            // the best rejected plan still shows where it falls short
            let mut reason = reason;
            if let (Some(p), Some(r)) = (&args.preview, &rejected) {
                let svg = preview_svg_rejected(&args.shape, r).context("drawing the preview")?;
                foldchain_cli::output::write_atomic(p, svg.as_bytes())
                    .context("writing the preview")?;
                reason.push_str(&format!(
                    " (the best rejected plan is drawn in {}, marked as no plan)",
                    p.display()
                ));
            }
            return Err(PlanError::Unplannable {
                name,
                reason,
                rejected,
            }
            .into());
        }
        Err(e) => return Err(e.into()),
    };
    if let Some(out) = &args.out {
        foldchain_cli::output::write_atomic(out, plan.to_json().as_bytes())
            .context("writing the plan")?;
    }
    if let Some(p) = &args.preview {
        let svg = preview_svg_file(&args.shape, &plan).context("drawing the preview")?;
        foldchain_cli::output::write_atomic(p, svg.as_bytes()).context("writing the preview")?;
    }
    for w in &plan.warnings {
        eprintln!("fold-plan: warning: {w}");
    }
    if args.json {
        println!("{}", plan.to_json());
    } else {
        println!("{}", plan.tile_list);
        println!("{}", plan.summary());
    }
    Ok(())
}
