//! `fold-enum --max-tiles N`: counts the fold words that fold without self-intersection
//! (thesis Table 5.1).

use std::process::ExitCode;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use clap::Parser;
use foldchain::collision::CheckOptions;
use foldchain::count::{count_valid, estimate_random, CountOptions, CountRow};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Counts, for each chain length, the candidate fold words (3^(n-1)) and those that fold
/// sequentially without any two tiles overlapping, from the geometry and the sweep check.
#[derive(Parser, Debug)]
#[command(version, about)]
struct Args {
    /// Longest chain counted, in tiles.
    #[arg(long)]
    max_tiles: usize,
    /// Shortest chain counted, in tiles.
    #[arg(long, default_value_t = 2)]
    min_tiles: usize,
    /// Count words with adjacent opposite folds (L then R), which need LR/RL tiles.
    #[arg(long)]
    allow_lr: bool,
    /// Check only final shapes, not the fold sweeps.
    #[arg(long)]
    final_only: bool,
    /// Add the probability that a chain of uniformly random tiles propagates to its end and
    /// folds cleanly (exact up to --random-exact-max tiles, sampled beyond).
    #[arg(long)]
    random: bool,
    /// Longest chain for which the random-chain probability is computed exactly.
    #[arg(long, default_value_t = 16)]
    random_exact_max: usize,
    /// Chains sampled per length beyond exact reach.
    #[arg(long, default_value_t = 200_000)]
    samples: u64,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Count only part K of M disjoint parts of the search (K from 1 to M); the parts'
    /// counts add up exactly.
    #[arg(long, value_name = "K/M")]
    shard: Option<String>,
    /// Print JSON: {"rows":[{"tiles":n,"candidates":c,"valid":v,...}]}.
    #[arg(long)]
    json: bool,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fold-enum: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn parse_shard(s: &str) -> anyhow::Result<(usize, usize)> {
    let bad =
        || anyhow::anyhow!("--shard {s:?}: expected K/M with whole numbers 1 <= K <= M, e.g. 2/8");
    let (k, m) = s.split_once('/').ok_or_else(bad)?;
    let (k, m): (usize, usize) = (
        k.trim().parse().map_err(|_| bad())?,
        m.trim().parse().map_err(|_| bad())?,
    );
    if k < 1 || k > m {
        return Err(bad());
    }
    Ok((k, m))
}

/// A progress bar on stderr that appears only once a run has taken more than a second and
/// only on a terminal.
struct Progress {
    bar: ProgressBar,
    start: Instant,
    shown: Mutex<bool>,
}

impl Progress {
    fn new() -> Progress {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(
            "{msg} [{bar:40}] {pos}/{len} parts, {elapsed} (eta {eta})",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Progress {
            bar,
            start: Instant::now(),
            shown: Mutex::new(false),
        }
    }

    fn update(&self, msg: &str, done: u64, total: u64) {
        if let Ok(mut shown) = self.shown.lock() {
            if !*shown && self.start.elapsed() > Duration::from_secs(1) {
                *shown = true;
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
            }
        }
        self.bar.set_message(msg.to_string());
        self.bar.set_length(total);
        self.bar.set_position(done);
    }
}

fn run(args: &Args) -> anyhow::Result<()> {
    let mut opts = CountOptions::default()
        .with_tiles(args.min_tiles, args.max_tiles)
        .with_allow_opposite(args.allow_lr)
        .with_final_only(args.final_only);
    if let Some(s) = &args.shard {
        let (k, m) = parse_shard(s)?;
        opts = opts.with_shard(k, m);
    }
    if args.random && opts.shard.is_some() {
        anyhow::bail!(
            "--random cannot be combined with --shard (the probability needs the whole search)"
        );
    }
    if args.random && args.samples == 0 {
        anyhow::bail!("--samples 0: expected at least one sample");
    }
    let progress = Progress::new();
    let start = Instant::now();
    let mut rows = count_valid(&opts, &|d, t| progress.update("counting", d, t))?;
    if args.random {
        let exact_max = args.random_exact_max.min(args.max_tiles);
        if exact_max >= args.min_tiles {
            let exact = count_valid(
                &opts.with_tiles(args.min_tiles, exact_max).with_random(true),
                &|d, t| progress.update("random chains", d, t),
            )?;
            for (row, e) in rows.iter_mut().zip(exact) {
                row.p_random = e.p_random;
                row.p_random_exact = e.p_random_exact;
                row.p_propagates = e.p_propagates;
            }
        }
        let check = CheckOptions::default().with_final_only(args.final_only);
        for row in rows.iter_mut().filter(|r| r.p_random.is_none()) {
            let est = estimate_random(row.tiles, args.samples, args.seed, &check);
            row.p_random = Some(est.p);
            row.p_propagates = Some((7.0f64 / 9.0).powi(row.tiles as i32 - 1));
            row.p_random_exact = Some(format!(
                "~{:.6} (95% {:.6}..{:.6}, {} samples)",
                est.p, est.low, est.high, est.samples
            ));
        }
    }
    progress.bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    if args.json {
        let out = serde_json::json!({ "rows": rows, "seconds": seconds, "shard": args.shard });
        println!("{out}");
    } else {
        print_table(&rows, args);
        eprintln!("{:.2} s", seconds);
    }
    Ok(())
}

fn print_table(rows: &[CountRow], args: &Args) {
    let mode = match (args.allow_lr, args.final_only) {
        (false, false) => "adjacent LR/RL not used, sequential folding",
        (true, false) => "adjacent LR/RL allowed, sequential folding",
        (false, true) => "adjacent LR/RL not used, final shape only",
        (true, true) => "adjacent LR/RL allowed, final shape only",
    };
    println!(
        "# valid fold words ({mode}){}",
        args.shard
            .as_deref()
            .map(|s| format!(", shard {s}"))
            .unwrap_or_default()
    );
    if args.random {
        println!(
            "{:>5} {:>22} {:>16} {:>16} {:>12} {:>12}  exact",
            "tiles", "candidates", "searched", "valid", "p_random", "(7/9)^(n-1)"
        );
    } else {
        println!(
            "{:>5} {:>22} {:>16} {:>16}",
            "tiles", "candidates", "searched", "valid"
        );
    }
    for r in rows {
        if args.random {
            println!(
                "{:>5} {:>22} {:>16} {:>16} {:>12.8} {:>12.8}  {}",
                r.tiles,
                r.candidates,
                r.searched,
                r.valid,
                r.p_random.unwrap_or(f64::NAN),
                r.p_propagates.unwrap_or(f64::NAN),
                r.p_random_exact.as_deref().unwrap_or("")
            );
        } else {
            println!(
                "{:>5} {:>22} {:>16} {:>16}",
                r.tiles, r.candidates, r.searched, r.valid
            );
        }
    }
}
