//! `fold-enum --max-tiles N`: counts the fold words that fold without self-intersection
//! (thesis Table 5.1).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Context};
use clap::Parser;
use foldchain::collision::CheckOptions;
use foldchain::count::{CountOptions, CountReport, CountRow, RandomEstimate, Shard};
const MAX_COUNT_TILES: usize = CountOptions::MAX_TILES;
use foldchain_cli::help::{ENUM_ABOUT, ENUM_AFTER_HELP};
use foldchain_cli::numbers::count_in;
use foldchain_cli::progress::{duration_words, Progress, ProgressMode};
use foldchain_cli::report::{finish, parse_args};
use foldchain_cli::{errln, outln};

/// Counts, for each chain length, the candidate fold words (3^(n-1)) and those that fold
/// sequentially without any two tiles overlapping, from the geometry and the sweep check.
#[derive(Parser, Debug)]
#[command(name = "fold-enum", version, about = ENUM_ABOUT, after_help = ENUM_AFTER_HELP)]
struct Args {
    /// Longest chain counted, in tiles (2 to 40).
    #[arg(long, value_parser = tiles_arg, allow_hyphen_values = true, required_unless_present = "merge")]
    max_tiles: Option<usize>,
    /// Shortest chain counted, in tiles.
    #[arg(long, default_value_t = 2, value_parser = tiles_arg, allow_hyphen_values = true)]
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
    #[arg(long, default_value_t = 16, value_parser = tiles_arg)]
    random_exact_max: usize,
    /// With --random: chains sampled per length beyond exact reach (default 200000; 1e6
    /// is accepted).
    #[arg(long, value_parser = samples_arg, allow_hyphen_values = true)]
    samples: Option<u64>,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Count only part K of M disjoint parts of the search (K from 1 to M); the parts'
    /// counts add up exactly.
    #[arg(long, value_name = "K/M")]
    shard: Option<String>,
    /// Add up the JSON reports of all the parts of one --shard run and print the whole
    /// count; refuses a missing or doubled part, or parts of different searches.
    #[arg(long, num_args = 1.., value_name = "FILE", conflicts_with_all = ["max_tiles", "shard", "random", "allow_lr", "final_only"])]
    merge: Vec<PathBuf>,
    /// Print JSON: {"rows":[{"tiles":n,"candidates":c,"valid":v,...}]}.
    #[arg(long)]
    json: bool,
    /// No progress on stderr, no estimate.
    #[arg(long)]
    quiet: bool,
}

/// A chain length on the command line: a whole number of tiles.
fn tiles_arg(s: &str) -> Result<usize, String> {
    count_in(s, 2, MAX_COUNT_TILES as u64, "tiles").map(|n| n as usize)
}

/// A sample count: a whole number, also written as 1e6.
fn samples_arg(s: &str) -> Result<u64, String> {
    count_in(s, 1, 1_000_000_000, "samples")
}

/// Chains sampled per length beyond exact reach, by default.
const DEFAULT_SAMPLES: u64 = 200_000;

/// A run expected to take longer than this says so before it starts.
const WARN_SECONDS: f64 = 180.0;

fn main() -> ExitCode {
    match parse_args::<Args>("fold-enum") {
        Ok(args) => finish("fold-enum", run(&args).map(|()| 0)),
        Err(code) => code,
    }
}

fn parse_shard(s: &str) -> anyhow::Result<Shard> {
    s.parse().map_err(|_| {
        anyhow::anyhow!("--shard {s:?}: expected K/M with whole numbers 1 <= K <= M, e.g. 2/8")
    })
}

/// The rough cost of counting up to `max` tiles: a calibration run to 22 tiles is timed,
/// and the work grows per tile by the ratio of its last two rows' valid counts (about 2).
/// Returns the expected valid words at `max` and the seconds; `None` when the run is short
/// anyway.
fn estimate_seconds(opts: &CountOptions, max: usize) -> anyhow::Result<Option<(f64, f64)>> {
    const CALIBRATE: usize = 22;
    if max <= 24 {
        return Ok(None);
    }
    let start = Instant::now();
    let rows = opts.with_tiles(2, CALIBRATE).count_valid(&|_, _| {})?;
    let secs = start.elapsed().as_secs_f64();
    let valid: Vec<f64> = rows.iter().map(|r| r.valid as f64).collect();
    let (last, before) = (valid[valid.len() - 1], valid[valid.len() - 2]);
    let ratio = (last / before.max(1.0)).max(1.0);
    // every length up to max is counted: the time is a geometric sum over the lengths
    let growth: f64 = (1..=max - CALIBRATE).map(|k| ratio.powi(k as i32)).sum();
    let share = opts.shard.map_or(1.0, |(_, m)| 1.0 / m as f64);
    let words = last * ratio.powi((max - CALIBRATE) as i32);
    Ok(Some((words, secs * growth * share)))
}

/// `--merge`: the whole count from the parts' reports.
fn merge(args: &Args) -> anyhow::Result<()> {
    let mut files = Vec::with_capacity(args.merge.len());
    for path in &args.merge {
        // a shard report is one JSON object of counts: 64 MiB is far above any
        let bytes = foldchain_planner::read_file_at_most(path, 64 << 20)
            .with_context(|| format!("{}: cannot read the shard report", path.display()))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            anyhow::anyhow!(
                "{}: not a shard report: not UTF-8 text ({e})",
                path.display()
            )
        })?;
        files.push((path.display().to_string(), text));
    }
    let merged = CountReport::merge(&files)?;
    if args.json {
        outln!("{}", serde_json::to_string(&merged)?);
    } else {
        let (allow_lr, final_only) = merged
            .options
            .map_or((false, false), |o| (o.allow_opposite, o.final_only));
        let label = format!(", merged from {} parts", files.len());
        print_table(&merged.rows, allow_lr, final_only, &label, false);
        errln!("{:.2} s in all parts", merged.seconds);
    }
    Ok(())
}

fn run(args: &Args) -> anyhow::Result<()> {
    if !args.merge.is_empty() {
        return merge(args);
    }
    let Some(max_tiles) = args.max_tiles else {
        bail!("--max-tiles N is needed (or --merge FILES to add up shard reports)");
    };
    if !(2..=MAX_COUNT_TILES).contains(&max_tiles) {
        bail!("--max-tiles {max_tiles}: expected a chain length from 2 to {MAX_COUNT_TILES} tiles");
    }
    if args.min_tiles < 2 || args.min_tiles > max_tiles {
        bail!(
            "--min-tiles {}: expected 2 to --max-tiles ({max_tiles})",
            args.min_tiles
        );
    }
    if args.samples.is_some() && !args.random {
        bail!("--samples applies only with --random (the random-chain probability)");
    }
    let samples = args.samples.unwrap_or(DEFAULT_SAMPLES);
    let mut opts = CountOptions::default()
        .with_tiles(args.min_tiles, max_tiles)
        .with_allow_opposite(args.allow_lr)
        .with_final_only(args.final_only);
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    if let Some(s) = shard {
        opts = opts.with_shard(s.k, s.m);
    }
    if args.random && opts.shard.is_some() {
        anyhow::bail!(
            "--random cannot be combined with --shard (the probability needs the whole search)"
        );
    }
    let mode = ProgressMode::detect(args.quiet);
    if mode != ProgressMode::Quiet {
        if let Some((nodes, secs)) = estimate_seconds(&opts, max_tiles)? {
            if secs > WARN_SECONDS {
                errln!(
                    "fold-enum: counting up to {} tiles finds about {nodes:.1e} valid words: roughly {} on this machine (from a timed calibration run to 22 tiles); --shard K/M splits the work",
                    max_tiles,
                    duration_words(secs)
                );
            }
        }
    }
    let progress = Progress::new("fold-enum", "parts", mode);
    let start = Instant::now();
    let mut rows = opts.count_valid(&|d, t| progress.update("counting", d, t))?;
    if args.random {
        let exact_max = args.random_exact_max.min(max_tiles);
        if exact_max >= args.min_tiles {
            let exact = opts
                .with_tiles(args.min_tiles, exact_max)
                .with_random(true)
                .count_valid(&|d, t| progress.update("random chains", d, t))?;
            for (row, e) in rows.iter_mut().zip(exact) {
                row.p_random = e.p_random;
                row.p_random_exact = e.p_random_exact;
                row.p_propagates = e.p_propagates;
            }
        }
        let check = CheckOptions::default().with_final_only(args.final_only);
        let sampled = rows.iter().filter(|r| r.p_random.is_none()).count() as u64;
        if sampled > 0 && mode != ProgressMode::Quiet {
            // time a small sample of the longest chains to say what the full one costs
            let probe = 2_000.min(samples);
            let t0 = Instant::now();
            RandomEstimate::sample(max_tiles, probe, args.seed, &check);
            let secs =
                t0.elapsed().as_secs_f64() * (samples as f64 / probe as f64) * sampled as f64;
            if secs > WARN_SECONDS {
                errln!(
                    "fold-enum: sampling {samples} chains at each of {sampled} lengths takes roughly {} on this machine",
                    duration_words(secs)
                );
            }
        }
        for (i, row) in rows.iter_mut().filter(|r| r.p_random.is_none()).enumerate() {
            progress.update("sampling random chains", i as u64, sampled);
            let est = RandomEstimate::sample(row.tiles, samples, args.seed, &check);
            row.p_random = Some(est.p);
            row.p_propagates = Some((7.0f64 / 9.0).powi(row.tiles as i32 - 1));
            row.p_random_exact = Some(format!(
                "~{:.6} (95% {:.6}..{:.6}, {} samples)",
                est.p, est.low, est.high, est.samples
            ));
        }
    }
    progress.finish();
    let seconds = start.elapsed().as_secs_f64();
    if args.json {
        // a shard carries its options, so that --merge can refuse parts of other searches
        let report = CountReport {
            rows,
            seconds,
            shard,
            options: shard.map(|_| opts),
        };
        outln!("{}", serde_json::to_string(&report)?);
    } else {
        let label = shard.map(|s| format!(", shard {s}")).unwrap_or_default();
        print_table(&rows, args.allow_lr, args.final_only, &label, args.random);
        errln!("{:.2} s", seconds);
    }
    Ok(())
}

fn print_table(rows: &[CountRow], allow_lr: bool, final_only: bool, label: &str, random: bool) {
    let mode = match (allow_lr, final_only) {
        (false, false) => "adjacent LR/RL not used, sequential folding",
        (true, false) => "adjacent LR/RL allowed, sequential folding",
        (false, true) => "adjacent LR/RL not used, final shape only",
        (true, true) => "adjacent LR/RL allowed, final shape only",
    };
    outln!("# valid fold words ({mode}){label}");
    if random {
        outln!(
            "{:>5} {:>22} {:>16} {:>16} {:>12} {:>12}  exact",
            "tiles",
            "candidates",
            "searched",
            "valid",
            "p_random",
            "(7/9)^(n-1)"
        );
    } else {
        outln!(
            "{:>5} {:>22} {:>16} {:>16}",
            "tiles",
            "candidates",
            "searched",
            "valid"
        );
    }
    for r in rows {
        if random {
            outln!(
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
            outln!(
                "{:>5} {:>22} {:>16} {:>16}",
                r.tiles,
                r.candidates,
                r.searched,
                r.valid
            );
        }
    }
}
