//! Timeline of long chains: the event engine alone (`engine::run`), n = 1e3 .. 1e6 tiles,
//! thesis design, overdamped law, a serpentine word (rows of about sqrt(n) straight tiles
//! joined by tight U-turns). Prints the median time of a few runs, ns per tile, the events,
//! and the peak RSS. Run: `cargo bench --bench engine_timeline`.

use std::time::Instant;

use foldchain::engine::{run, EngineMethod, EngineOptions};
use foldchain::timeline::TileDesigns;
use foldchain::{Fold, FoldWord};

fn serpentine(n: usize) -> FoldWord {
    let row = (n as f64).sqrt().max(2.0) as usize;
    let mut folds = Vec::with_capacity(n - 1);
    let mut left = true;
    while folds.len() < n - 1 {
        for _ in 0..row {
            folds.push(Fold::S);
        }
        let f = if left { Fold::L } else { Fold::R };
        folds.push(f);
        folds.push(f);
        left = !left;
    }
    folds.truncate(n - 1);
    FoldWord::from_folds(folds)
}

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    println!("| tiles | timeline (median) | ns/tile | events | outcome | peak RSS |");
    println!("|---:|---:|---:|---:|---|---:|");
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        let chain = serpentine(n).to_chain();
        let designs = TileDesigns::default();
        let reps = if n >= 1_000_000 { 3 } else { 5 };
        let mut times = Vec::new();
        let mut events = 0;
        let mut outcome = String::new();
        for _ in 0..reps {
            let t0 = Instant::now();
            let tl = run(
                &chain,
                &designs,
                &EngineOptions::default().with_method(EngineMethod::Kinematic),
            )
            .expect("runs");
            times.push(t0.elapsed().as_secs_f64());
            events = tl.events.len();
            outcome = format!("{:?}", tl.outcome);
        }
        times.sort_by(f64::total_cmp);
        let med = times[times.len() / 2];
        println!(
            "| {n} | {:.1} ms | {:.0} | {events} | {outcome} | {:.0} MB |",
            med * 1e3,
            med * 1e9 / n as f64,
            peak_rss_mb()
        );
    }
}
