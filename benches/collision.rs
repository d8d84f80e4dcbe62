//! Collision benchmark: `cargo bench --bench collision` (median of a few runs each, one core).
//!
//! 1. The sequential check (`check_word`: every fold sweep and the final shape) of serpentine
//!    chains from 1,000 to 1,000,000 tiles, rows of about sqrt(n) tiles.
//! 2. The 10^6-tile serpentine of rows of 1,000 (`S*998 L L S*998 R R ...`): the whole check,
//!    the sweeps alone and the final shape alone (`check_word` with `final_only`, less the
//!    final poses).
//! 3. The timed schedule check of the event engine's fold schedule at `s = 0.1 mm` (the two
//!    folds of each U-turn overlap in time) for serpentines of 1,000 to 100,000 tiles, through
//!    `Timeline::checked_summary` (the schedule's sampling and the summary included, both
//!    small beside the check); the engine's run is not timed.
//!
//! 4. `cargo bench --bench collision -- --local WORD_FILE`: only the timed check of the
//!    default engine's schedule (local solves, inertial, s = 0.1 mm) of the chain in
//!    `WORD_FILE` (e.g. `benches/serpentine-100k.txt`), on one thread and on all.
//!
//! (The counting benchmark is `benches/count.rs`.)

use std::time::Instant;

use foldchain::collision::{check_word, CheckOptions};
use foldchain::engine::{run, EngineMethod, EngineOptions, SValue, TileDesigns};
use foldchain::model::{Dynamics, ModelOptions};
use foldchain::timeline::Summary;
use foldchain::{Fold, FoldWord};

/// Rows of `row` tiles joined by tight U-turns that alternate in direction, `tiles` in all.
fn serpentine(tiles: usize, row: usize) -> FoldWord {
    let mut folds = Vec::with_capacity(tiles);
    let mut left = true;
    while folds.len() + 1 < tiles {
        for _ in 0..row.saturating_sub(1) {
            if folds.len() + 1 >= tiles {
                break;
            }
            folds.push(Fold::S);
        }
        let f = if left { Fold::L } else { Fold::R };
        for _ in 0..2 {
            if folds.len() + 1 < tiles {
                folds.push(f);
            }
        }
        left = !left;
    }
    FoldWord::from_folds(folds)
}

/// The median wall time of `runs` calls of `f`, and its last result.
fn median<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        last = Some(f());
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    match last {
        Some(v) => (times[times.len() / 2], v),
        None => (f64::NAN, f()),
    }
}

fn verdict<E>(r: &Result<(), E>) -> &'static str {
    if r.is_ok() {
        "valid"
    } else {
        "collides"
    }
}

/// A timed check's verdict: `clean`, the collision, or why it could not decide.
fn timed_verdict<E: std::fmt::Display>(summary: &Result<Summary, E>) -> String {
    match summary {
        Ok(s) => match &s.reason {
            Some(reason) if !s.completed => reason.clone(),
            _ => "clean".to_string(),
        },
        Err(e) => e.to_string(),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--local") {
        local_check(&args[i + 1]);
        return;
    }
    let opts = CheckOptions::default();
    println!("Sequential check of serpentines (rows of about sqrt(n) tiles):");
    println!("| tiles | row | seconds (median of 5) | verdict |");
    println!("|---:|---:|---:|---|");
    for tiles in [1_000usize, 10_000, 100_000, 1_000_000] {
        let row = (tiles as f64).sqrt().round() as usize;
        let w = serpentine(tiles, row);
        let (s, r) = median(5, || check_word(&w, &opts));
        println!("| {tiles} | {row} | {s:.4} | {} |", verdict(&r));
    }

    // the 10^6-tile serpentine of rows of 1,000: S*998 L L S*998 R R ... (999,999 letters)
    let mut folds = Vec::with_capacity(1_000_000);
    for r in 0..500 {
        folds.extend(std::iter::repeat_n(Fold::S, 998));
        folds.extend([Fold::L, Fold::L]);
        folds.extend(std::iter::repeat_n(Fold::S, 998));
        folds.extend(if r < 499 {
            vec![Fold::R, Fold::R]
        } else {
            vec![Fold::R]
        });
    }
    let w = FoldWord::from_folds(folds);
    let (all, r) = median(5, || check_word(&w, &opts));
    let (final_check, _) = median(5, || check_word(&w, &opts.with_final_only(true)));
    let (kin, _) = median(5, || w.final_poses());
    let finals = final_check - kin;
    println!();
    println!("The {}-tile serpentine of rows of 1,000:", w.tiles());
    println!("| part | seconds (median of 5) |");
    println!("|---|---:|");
    println!(
        "| `check_word` (final poses, every sweep, final shape; {}) | {all:.4} |",
        verdict(&r)
    );
    println!("| final poses (`kinematics::final_poses`) | {kin:.4} |");
    println!("| final shape (`final_only`, less the final poses) | {finals:.4} |");
    println!("| sweeps (the rest) | {:.4} |", all - kin - finals);

    println!();
    println!("Timed schedule check of the engine's schedule at s = 0.1 mm:");
    println!("| tiles | row | folds | seconds (median of 3) | verdict |");
    println!("|---:|---:|---:|---:|---|");
    let designs = TileDesigns::default().with_s(SValue::Millimetres(0.1));
    for (tiles, row) in [(1_022usize, 32usize), (10_000, 100), (100_000, 316)] {
        let chain = serpentine(tiles, row).to_chain();
        let Ok(tl) = run(
            &chain,
            &designs,
            &EngineOptions::default().with_method(EngineMethod::Kinematic),
        ) else {
            println!("| {tiles} | {row} | - | engine refused the chain | - |");
            continue;
        };
        let (s, r) = median(3, || tl.checked_summary(&opts));
        println!(
            "| {tiles} | {row} | {} | {s:.3} | {} |",
            tl.folds.len(),
            timed_verdict(&r)
        );
    }
}

/// Section 4: the timed check of the local engine's schedule of the chain in `file`.
fn local_check(file: &str) {
    let text = std::fs::read_to_string(file).expect("word file");
    let chain = FoldWord::parse(text.trim()).expect("fold word").to_chain();
    let designs = TileDesigns::default().with_s(SValue::Millimetres(0.1));
    let t = Instant::now();
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let tl = run(
        &chain,
        &designs,
        &EngineOptions::default().with_model(model),
    )
    .expect("engine");
    println!("engine: {:.2} s", t.elapsed().as_secs_f64());
    let opts = CheckOptions::default();
    println!("{} tiles, {} folds", tl.tiles(), tl.folds.len());
    // FOLDCHAIN_BENCH_THREADS=n: only that many threads, one run
    let only: Option<usize> = std::env::var("FOLDCHAIN_BENCH_THREADS")
        .ok()
        .and_then(|v| v.parse().ok());
    let (list, runs) = match only {
        Some(n) => (vec![n], 1),
        None => (vec![1, 0], 3),
    };
    for threads in list {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let (s, r) = median(runs, || pool.install(|| tl.checked_summary(&opts)));
        println!(
            "threads {}: {s:.3} s (median of {runs}): {}",
            pool.current_num_threads(),
            timed_verdict(&r)
        );
    }
}
