//! `fold-plan`: from a target shape in an SVG file to a tile sequence.
//!
//! Exit codes: 0 planned, 1 the shape cannot be planned (the message says why), 2 bad input
//! (unreadable file, bad SVG, no filled area, self-intersecting outline, bad option).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Parser;
use foldchain_planner::{plan_svg_file, preview_svg_file, PlanError, PlanOptions, Turns};

/// Plan a self-folding tile chain that fills the shape drawn in an SVG file.
#[derive(Parser, Debug)]
#[command(name = "fold-plan", version)]
struct Args {
    /// The target shape: an SVG file; its filled areas are the shape.
    shape: PathBuf,
    /// About this many tiles (default 200 when --tile-size is not given).
    #[arg(long, conflicts_with = "tile_size")]
    tiles: Option<usize>,
    /// Tile width (across flats) in SVG user units.
    #[arg(long)]
    tile_size: Option<f64>,
    /// U-turn style: tight (LL/RR tiles), loose (no LL/RR tiles) or auto (better fit).
    #[arg(long, default_value = "auto")]
    turns: Turns,
    /// Write the plan JSON here (what fold-run --plan reads).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write a preview SVG here: the outline, the tiles over it and the fold order.
    #[arg(long)]
    preview: Option<PathBuf>,
    /// Print the plan JSON instead of the tile list and summary.
    #[arg(long)]
    json: bool,
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
            eprintln!("fold-plan: {e:#}");
            let code = e
                .downcast_ref::<PlanError>()
                .map_or(2, |p| p.exit_code() as u8);
            ExitCode::from(code)
        }
    }
}

fn run(args: &Args) -> anyhow::Result<()> {
    let opts = PlanOptions {
        tiles: args.tiles,
        tile_size: args.tile_size,
        turns: args.turns,
    };
    let plan = plan_svg_file(&args.shape, &opts)?;
    if let Some(out) = &args.out {
        foldchain_cli::output::write_atomic(out, plan.to_json().as_bytes())
            .context("writing the plan")?;
    }
    if let Some(p) = &args.preview {
        let svg = preview_svg_file(&args.shape, &plan).context("drawing the preview")?;
        foldchain_cli::output::write_atomic(p, svg.as_bytes()).context("writing the preview")?;
    }
    if args.json {
        println!("{}", plan.to_json());
    } else {
        println!("{}", plan.tile_list);
        println!("{}", plan.summary());
    }
    Ok(())
}
