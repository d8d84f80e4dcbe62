//! `fold-check CHAIN`: does a chain fold without hitting itself?
//!
//! Exit 0 valid, 1 collides or inhibited, 2 bad input.

use std::process::ExitCode;

use clap::Parser;
use foldchain::collision::{check_chain, CheckOptions, Verdict};
use foldchain_cli::help::{CHECK_ABOUT, CHECK_AFTER_HELP};
use foldchain_cli::inputs::read_chain;
use foldchain_cli::numbers::{number_in, open_range, thousands};
use foldchain_cli::outln;
use foldchain_cli::progress::{Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args};

/// Checks that a chain of tiles folds sequentially from the reaction-initiator end without
/// any two tiles overlapping, at every moment of every fold and in the final shape.
#[derive(Parser, Debug)]
#[command(name = "fold-check", version, about = CHECK_ABOUT, after_help = CHECK_AFTER_HELP)]
struct Args {
    /// The chain: a fold word (`SLLS`), a tile list (`SS SL LL LS SS`, `SS*12`), JSON, or a
    /// file holding one of them, or a plan written by `fold-plan --out`.
    chain: String,
    /// Check only the final shape, not the fold sweeps.
    #[arg(long)]
    final_only: bool,
    /// Overlap depth, in tile widths, below which tiles count as touching.
    #[arg(long, default_value_t = CheckOptions::default().tolerance, value_parser = tolerance_arg, allow_hyphen_values = true)]
    tolerance: f64,
    /// Print the verdict as JSON.
    #[arg(long)]
    json: bool,
    /// No progress on stderr (long chains take seconds).
    #[arg(long)]
    quiet: bool,
}

fn main() -> ExitCode {
    match parse_args::<Args>("fold-check") {
        Ok(args) => finish("fold-check", run(&args)),
        Err(code) => code,
    }
}

fn tolerance_arg(s: &str) -> Result<f64, String> {
    open_range(
        number_in(s, 0.0, 0.01, "tile widths", ""),
        |t| t < 0.01,
        "a number from 0 up to (not including) 0.01 tile widths",
    )
}

fn run(args: &Args) -> anyhow::Result<u8> {
    let chain = read_chain(&args.chain)?;
    let opts = CheckOptions::default()
        .with_final_only(args.final_only)
        .with_tolerance(args.tolerance);
    let progress = Progress::new("fold-check", "", ProgressMode::detect(args.quiet));
    progress.stage(&format!("checking {} tiles", thousands(chain.len() as u64)));
    let verdict = check_chain(&chain, &opts);
    progress.finish();
    if args.json {
        let out = serde_json::json!({ "tiles": chain.len(), "final_only": args.final_only, "result": verdict });
        outln!("{out}");
    } else {
        match &verdict {
            Verdict::Valid => outln!("valid"),
            Verdict::Inhibited { joint } => {
                outln!(
                    "inhibited: propagation stops at joint {joint} (tiles {joint} and {})",
                    joint + 1
                )
            }
            Verdict::Collides(c) => outln!("collision: {c}"),
        }
    }
    Ok(if verdict == Verdict::Valid { 0 } else { 1 })
}
