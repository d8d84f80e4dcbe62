//! `fold-plan`: from a target shape in an SVG file to a tile sequence.
//!
//! Exit codes: 0 planned, 1 the shape cannot be planned (the message says why), 2 bad input
//! (unreadable file, bad SVG, no filled area, self-intersecting outline, bad option).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Parser;
use foldchain_cli::help::{PLAN_ABOUT, PLAN_AFTER_HELP};
use foldchain_cli::inputs::{refuse_foreign, refuse_overwrite};
use foldchain_cli::numbers::{count_in, number_in, open_range};
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args};
use foldchain_cli::{errln, outln};
use foldchain_planner::{
    plan_svg_file_reporting, preview_svg_file, preview_svg_rejected, PlanError, PlanOptions,
    Rejected, Turns, DEFAULT_TILES_TOLERANCE, DEFAULT_TURN_COST,
};

/// Plan a self-folding tile chain that fills the shape drawn in an SVG file.
#[derive(Parser, Debug)]
#[command(name = "fold-plan", version, about = PLAN_ABOUT, after_help = PLAN_AFTER_HELP)]
struct Args {
    /// The target shape: an SVG file; its filled areas are the shape.
    shape: PathBuf,
    /// About this many tiles (default 200 when no tile width is given).
    #[arg(long, conflicts_with_all = ["tile_size", "tile_mm"], value_parser = tiles_arg, allow_hyphen_values = true)]
    tiles: Option<usize>,
    /// The share by which the tile count may miss --tiles when that buys a better fit.
    #[arg(long, default_value_t = DEFAULT_TILES_TOLERANCE, allow_hyphen_values = true, value_parser = tiles_tolerance_arg)]
    tiles_tolerance: f64,
    /// Tile width (across flats) in SVG user units.
    #[arg(long, conflicts_with = "tile_mm", allow_hyphen_values = true, value_parser = tile_size_arg)]
    tile_size: Option<f64>,
    /// Tile width (across flats) in millimetres, by the drawing's width/height units and
    /// viewBox (96 user units per inch when it states none); the thesis' tiles are 30 mm.
    #[arg(long, allow_hyphen_values = true, value_parser = tile_mm_arg)]
    tile_mm: Option<f64>,
    /// The price of a U-turn or quarter turn, in tile areas of misfit (0 to 10).
    #[arg(long, default_value_t = DEFAULT_TURN_COST, allow_hyphen_values = true, value_parser = turn_cost_arg)]
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
    /// Print the plan JSON instead of the tile list and summary (when the shape cannot be
    /// planned: the reason, what each planner tried and the best rejected plan's figures).
    #[arg(long)]
    json: bool,
    /// No progress lines on stderr.
    #[arg(long)]
    quiet: bool,
    /// When the shape cannot be planned, also print what each planner tried and why it
    /// failed (one line each, before the short reason).
    #[arg(long, short = 'v')]
    verbose: bool,
}

fn tiles_arg(s: &str) -> Result<usize, String> {
    count_in(s, 1, 2_000_000, "tiles").map(|n| n as usize)
}

fn tiles_tolerance_arg(s: &str) -> Result<f64, String> {
    number_in(s, 0.0, 0.5, "", "a share of --tiles")
}

fn tile_size_arg(s: &str) -> Result<f64, String> {
    open_range(
        number_in(s, 0.0, 1e9, "SVG user units", ""),
        |w| w > 0.0,
        "a tile width above 0 SVG user units",
    )
}

fn tile_mm_arg(s: &str) -> Result<f64, String> {
    number_in(
        s,
        0.01,
        1000.0,
        "mm",
        "tiles from 10 um to 1 m; the thesis' are 30 mm",
    )
}

fn turn_cost_arg(s: &str) -> Result<f64, String> {
    number_in(
        s,
        0.0,
        10.0,
        "tile areas",
        "above 10 a turn outweighs any misfit and the search only grows",
    )
}

fn main() -> ExitCode {
    match parse_args::<Args>("fold-plan") {
        Ok(args) => finish("fold-plan", run(&args).map(|()| 0)),
        Err(code) => code,
    }
}

fn run(args: &Args) -> anyhow::Result<()> {
    if args
        .shape
        .extension()
        .is_some_and(|x| x.eq_ignore_ascii_case("svgz"))
    {
        anyhow::bail!(
            "{}: a compressed SVG; decompress it first (gunzip -c {} > shape.svg) and plan the .svg",
            args.shape.display(),
            args.shape.display()
        );
    }
    if let Some(out) = &args.out {
        refuse_overwrite(&[&args.shape], out, "--out")?;
    }
    if let Some(out) = &args.out {
        refuse_foreign(out, "--out", "a plan JSON fold-plan wrote", |head, _| {
            head.trim_start().starts_with('{') && head.contains("\"tile_list\"")
        })?;
    }
    if let Some(p) = &args.preview {
        refuse_overwrite(&[&args.shape], p, "--preview")?;
        if let Some(out) = &args.out {
            if resolved_eq(out, p) {
                anyhow::bail!(
                    "--preview {}: is also the --out file; give the preview and the plan different names",
                    p.display()
                );
            }
        }
        refuse_foreign(p, "--preview", "a preview fold-plan drew", |head, tail| {
            head.trim_start().starts_with("<svg") && tail.contains(PREVIEW_MARK)
        })?;
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
            detail,
            rejected,
        }) => {
            if args.verbose {
                for d in &detail {
                    errln!("fold-plan: tried: {d}");
                }
            }
            if args.json {
                outln!(
                    "{}",
                    refusal_json(&name, &reason, &detail, rejected.as_deref())
                );
            }
            // the best rejected plan still shows where it falls short
            let mut reason = reason;
            if let (Some(p), Some(r)) = (&args.preview, &rejected) {
                let svg = preview_svg_rejected(&args.shape, r).context("drawing the preview")?;
                foldchain_cli::output::write_atomic(p, svg.as_bytes())
                    .context("writing the preview")?;
                reason.push_str(&format!(" (drawn in {}, marked as no plan)", p.display()));
            } else if !args.verbose && !detail.is_empty() {
                reason.push_str(" (more with --verbose)");
            }
            return Err(PlanError::Unplannable {
                name,
                reason,
                detail,
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
    foldchain_cli::report::print_plan_warnings("fold-plan", &plan.warnings);
    foldchain_cli::report::print_plan_warnings(
        "fold-plan",
        &empty_advice(&plan, args.preview.is_some()),
    );
    if args.json {
        outln!("{}", plan.to_json());
    } else {
        outln!("{}", plan.tile_list);
        outln!("{}", plan.summary());
    }
    Ok(())
}

/// Issue 26's rule: a plan leaves no part of the shape over two tile areas empty. When the
/// returned plan does (the planner found none that does not), the two lines printed under
/// the planner's warning of where that part is: how much of the shape it is, and what to
/// try. Not in the plan's JSON (its warnings say where; these say what to do).
fn empty_advice(plan: &foldchain_planner::Plan, preview: bool) -> Vec<String> {
    let m = &plan.metrics;
    if m.largest_empty_tiles <= 2.0 || plan.tiles == 0 || m.shape_area <= 0.0 {
        return Vec::new();
    }
    let tile_area = m.chain_area / plan.tiles as f64;
    let share = (m.largest_empty_tiles * tile_area / m.shape_area).min(1.0);
    let see = if preview {
        "the preview frames it in red"
    } else {
        "--preview FILE.svg frames it in red"
    };
    vec![
        format!(
            "that is {:.0}% of the shape, more than the 2 tile areas a plan may leave empty: \
             no plan found lays rows (parallel strips joined by turns) into it",
            100.0 * share
        ),
        format!(
            "to try: {see}; another --tiles or --turns; or draw that part wider or \
             straighter, or as a drawing of its own planned as a second chain"
        ),
    ]
}

/// Words every preview ends with (its legend's note on coverage): how an existing file is
/// recognised as a preview this tool drew, which it may replace.
const PREVIEW_MARK: &str = "near that is a full plan";

/// Whether two paths name the same file (after resolving links; a file not yet made by
/// its directory and name).
fn resolved_eq(a: &std::path::Path, b: &std::path::Path) -> bool {
    refuse_overwrite(&[a], b, "").is_err()
}

/// A refusal as JSON (`--json`): the short reason stderr shows, what each planner tried (the
/// `--verbose` lines) and, when one folded but left a part empty, the best rejected plan's
/// figures and that part (SVG user units, y down).
fn refusal_json(
    name: &str,
    reason: &str,
    detail: &[String],
    rejected: Option<&Rejected>,
) -> String {
    let rejected = rejected.map(|r| {
        let b = r.empty.bbox;
        serde_json::json!({
            "tiles": r.plan.tiles,
            "word": r.plan.word,
            "u_turns": r.plan.u_turns,
            "quarter_turns": r.plan.quarter_turns,
            "metrics": r.plan.metrics,
            "empty": {
                "tile_areas": r.empty.tiles,
                "centre": [r.empty.centre.x, r.empty.centre.y],
                "bbox": [b.x0, b.y0, b.x1, b.y1],
            },
        })
    });
    let v = serde_json::json!({
        "source": name,
        "planned": false,
        "reason": reason,
        "detail": detail,
        "rejected": rejected,
    });
    serde_json::to_string_pretty(&v).unwrap_or_default()
}
