//! `fold-check CHAIN`: does a chain fold without hitting itself?
//!
//! Exit 0 valid, 1 collides or inhibited, 2 bad input.

use std::process::ExitCode;

use clap::Parser;
use foldchain::collision::{check_chain, CheckOptions, Verdict};
use foldchain_cli::inputs::read_chain;
use foldchain_cli::report::print_error;

/// Checks that a chain of tiles folds sequentially from the reaction-initiator end without
/// any two tiles overlapping, at every moment of every fold and in the final shape.
#[derive(Parser, Debug)]
#[command(
    name = "fold-check",
    version,
    about = "Does a chain of tiles fold without hitting itself? Checks every fold sweep (sequential folding from the reaction-initiator end) and the final shape.",
    after_help = "Examples:
  fold-check SLLS                  a tight U-turn: valid
  fold-check LSLLSR                collision: tiles 0 and 6 meet while joint 3 folds
  fold-check --final-only LSLLSR   valid: the final shape is clean, the sweep is not
  fold-check 'SS SL LL LS SS' --json
  fold-check chain.txt             a file holding a word, a tile list or JSON

Exit codes: 0 valid, 1 collides or propagation inhibited, 2 bad input."
)]
struct Args {
    /// The chain: a fold word (`SLLS`), a tile list (`SS SL LL LS SS`, `SS*12`), JSON, or a
    /// file holding one of them.
    chain: String,
    /// Check only the final shape, not the fold sweeps.
    #[arg(long)]
    final_only: bool,
    /// Overlap depth, in tile widths, below which tiles count as touching.
    #[arg(long, default_value_t = CheckOptions::default().tolerance)]
    tolerance: f64,
    /// Print the verdict as JSON.
    #[arg(long)]
    json: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(code) => code,
        Err(e) => {
            print_error("fold-check", &e);
            ExitCode::from(2)
        }
    }
}

fn run(args: &Args) -> anyhow::Result<ExitCode> {
    if !(args.tolerance.is_finite() && args.tolerance >= 0.0 && args.tolerance < 0.01) {
        anyhow::bail!(
            "--tolerance {}: expected a number from 0 up to 0.01 tile widths",
            args.tolerance
        );
    }
    let chain = read_chain(&args.chain)?;
    let opts = CheckOptions::default()
        .with_final_only(args.final_only)
        .with_tolerance(args.tolerance);
    let verdict = check_chain(&chain, &opts);
    if args.json {
        let out = serde_json::json!({ "tiles": chain.len(), "final_only": args.final_only, "result": verdict });
        println!("{out}");
    } else {
        match &verdict {
            Verdict::Valid => println!("valid"),
            Verdict::Inhibited { joint } => {
                println!(
                    "inhibited: propagation stops at joint {joint} (tiles {joint} and {})",
                    joint + 1
                )
            }
            Verdict::Collides(c) => println!("collision: {c}"),
        }
    }
    Ok(if verdict == Verdict::Valid {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
