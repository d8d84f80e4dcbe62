//! Clearances and grazes (issue 27, item 3): every run reports how close two tiles that are
//! not neighbours came (`Summary::clearance`), and the event engine and the reference, which
//! follow the same physics, give the same verdict and clearances within 5 um. SRLSLLSR at
//! s = 0.05 mm was `completed` in the engine and `collided` in the reference: the engine's
//! fold schedule cut joint 4's turn 0.06 degrees short of its peak near the wall; its
//! schedule now keeps every turn of the law and, on chains of up to 100 tiles, follows it
//! within 1e-6 rad.
//!
//! The quick test runs SRLSLLSR and a sample of 8-letter words; the full scan, every
//! 8-letter word at s = 0.05 mm, is `cargo test --release -p foldchain --test clearances
//! full_scan -- --ignored --nocapture` (BENCHMARKS.md).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use rayon::prelude::*;

use foldchain::collision::CheckOptions;
use foldchain::engine::EngineOptions;
use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::{run_reference, Recording, ReferenceOptions};
use foldchain::timeline::{Summary, TileDesigns};
use foldchain::{simulate, Chain, Design};

/// The clearance `fold-run` reports for `chain` with its defaults (the thesis' design,
/// inertial), which must be measured.
fn inertial_clearance(chain: &Chain) -> foldchain::timeline::Clearance {
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let (_, summary) = simulate(
        chain,
        &TileDesigns::global(Design::thesis()),
        &EngineOptions::default().with_model(model),
        &CheckOptions::default(),
    )
    .unwrap();
    summary.clearance.expect("the clearance is measured")
}

/// The clearances of the two simulations agree within this, mm.
const AGREE_MM: f64 = 0.005;

/// Both runs of `word` at `s` mm, inertial (fold-run's default).
fn both(word: &str, s: f64) -> (Summary, Summary) {
    let chain = Chain::parse(word).unwrap();
    let designs = TileDesigns::global(Design::thesis().with_s(s));
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let check = CheckOptions::default();
    let (_, e) = simulate(
        &chain,
        &designs,
        &EngineOptions::default().with_model(model),
        &check,
    )
    .unwrap();
    let ro = ReferenceOptions::default()
        .with_model(model)
        .with_record(Recording::within_budget(chain.len()));
    let run = run_reference(&chain, &designs, &ro).unwrap();
    let r = run.checked_summary(&check).unwrap();
    (e, r)
}

/// What differs between the two runs' verdicts and clearances, if anything: the result, or
/// clearances more than [`AGREE_MM`] apart (plus a hundredth of an overlap's depth, the
/// measurement's precision there). A verdict may differ only where the clearance
/// lies within the agreement of the overlap tolerance (a collision that deep is decided by
/// less than the two simulations' agreement).
fn disagreement(word: &str, e: &Summary, r: &Summary) -> Option<String> {
    let (Some(ce), Some(cr)) = (e.clearance, r.clearance) else {
        return Some(format!("{word}: clearance missing: {e:?} {r:?}"));
    };
    let apart = (ce.mm - cr.mm).abs();
    // a deep overlap is measured to a hundredth of its depth (collision/clearance.rs): two
    // runs of tiles 20 mm into each other differ there by up to 8 um (the first 1,700
    // words of the full scan)
    let within = AGREE_MM + 0.01 * (-ce.mm.min(cr.mm)).max(0.0);
    let at_threshold = (ce.mm + ce.overlap_tolerance_mm).abs() <= AGREE_MM;
    if apart > within || (e.result != r.result && !at_threshold) {
        return Some(format!(
            "{word}: engine {} {:.5} mm (tiles {:?} at {:.4} s), reference {} {:.5} mm (tiles {:?} at {:.4} s)",
            e.result, ce.mm, ce.tiles, ce.time, r.result, cr.mm, cr.tiles, cr.time
        ));
    }
    None
}

#[test]
fn srlsllsr_at_s_005_gets_one_verdict_and_one_clearance() {
    let (e, r) = both("SRLSLLSR", 0.05);
    assert_eq!(disagreement("SRLSLLSR", &e, &r), None);
    let (ce, cr) = (e.clearance.unwrap(), r.clearance.unwrap());
    // with both sides of each fold turning on the water (issue 27 item 2) the chain folds
    // clean in both: the closest approach is tiles 2 and 7 touching face to face (0 mm) at
    // 1.0101 s, when no joint turns. (Main's one-sided model had tiles 1 and 8 overlapping by
    // 54 um while joint 4 turned back short of its wall, a collision in both.)
    assert_eq!(e.result, "completed");
    assert_eq!((ce.tiles, cr.tiles), ((2, 7), (2, 7)));
    assert_eq!((ce.joint, cr.joint), (None, None));
    assert!(
        ce.mm.abs() <= AGREE_MM && cr.mm.abs() <= AGREE_MM,
        "{ce:?} {cr:?}"
    );
    assert!((ce.time - cr.time).abs() < 1e-5, "{ce:?} {cr:?}");
    assert!(!ce.graze && !cr.graze);
}

fn words(len: usize) -> Vec<String> {
    let mut level = vec![String::new()];
    for _ in 0..len {
        level = level
            .iter()
            .flat_map(|w| ['S', 'L', 'R'].map(|c| format!("{w}{c}")))
            .collect();
    }
    level
}

fn scan(words: &[String]) -> Vec<String> {
    let done = std::sync::atomic::AtomicUsize::new(0);
    words
        .par_iter()
        .filter_map(|w| {
            let (e, r) = both(w, 0.05);
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if n % 500 == 0 {
                println!("  {n} of {} words", words.len());
            }
            let bad = disagreement(w, &e, &r);
            if let Some(b) = &bad {
                println!("  disagree: {b}");
            }
            bad
        })
        .collect()
}

#[test]
fn a_sample_of_8_letter_words_gets_one_verdict_and_one_clearance() {
    // every 97th word of 6,561 (68 words)
    let sample: Vec<String> = words(8).into_iter().step_by(97).collect();
    let bad = scan(&sample);
    assert!(bad.is_empty(), "{bad:#?}");
}

#[test]
#[ignore = "every 8-letter word at s = 0.05 mm: 6,561 engine and reference runs (BENCHMARKS.md)"]
fn full_scan_of_8_letter_words_at_s_005() {
    let all = words(8);
    let t0 = std::time::Instant::now();
    let bad = scan(&all);
    println!(
        "8-letter words at s = 0.05: {} words, {} disagree ({:.1} s)",
        all.len(),
        bad.len(),
        t0.elapsed().as_secs_f64()
    );
    assert!(bad.is_empty(), "{bad:#?}");
}

/// A 147-tile serpentine (10 rows of 12 joined by loose U-turns, as fold-run folds it) reports
/// its clearance: the pair walk once spent its whole work budget passing the stretches where
/// none of a pair's joints turns, one time bucket at a time, and gave `None` from about 150
/// tiles on.
#[test]
fn a_147_tile_serpentine_reports_its_clearance() {
    let mut word = String::new();
    for row in 0..10 {
        if row > 0 {
            word.push_str(if row % 2 == 1 {
                " SL LL LS "
            } else {
                " SR RR RS "
            });
        }
        word.push_str("SS*12");
    }
    let chain = Chain::parse(&word).unwrap();
    assert!((140..160).contains(&chain.len()), "{}", chain.len());
    let c = inertial_clearance(&chain);
    // loose rows never come nearer than two tiles one apart along the chain
    assert!(c.mm > 0.0 && c.tiles.1 >= c.tiles.0 + 2, "{c:?}");
}

/// A 1,000-tile serpentine (rows of 20 joined by `LL` and `RR`, fold-run's defaults) reports
/// its clearance: the pair walk followed every pair and gave `None` past 1,000 tiles (and
/// past its work budget from about 200); it now follows only the pairs that come as near as
/// the final shape's nearest (BENCHMARKS.md: about 3 s of CPU).
#[test]
fn a_1000_tile_serpentine_reports_its_clearance() {
    let mut word = String::from("S*19");
    let mut letters = 19;
    let mut row = 0;
    while letters < 999 {
        let r = (999 - letters - 2).min(18);
        word.push_str(if row % 2 == 0 { " LL " } else { " RR " });
        word.push_str(&format!("S*{r}"));
        letters += 2 + r;
        row += 1;
    }
    let chain = Chain::parse(&word).unwrap();
    assert_eq!(chain.len(), 1000);
    let c = inertial_clearance(&chain);
    // the U-turns' corners: tiles two apart, their 45-degree faces sqrt(2) - 1 widths apart
    let w = Design::thesis().tile_width;
    assert!((c.mm / w - (2f64.sqrt() - 1.0)).abs() < 1e-3, "{c:?}");
    assert_eq!(c.tiles.1, c.tiles.0 + 2, "{c:?}");
}

/// This process's CPU time so far (user + system), seconds, from `/proc/self/stat`.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or("", |r| r.1)
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // utime and stime, fields 14 and 15 of stat (11 and 12 after the name), at 100 Hz
    (ticks(11) + ticks(12)) / 100.0
}

/// The cost of the clearance on serpentines of rows of 20 (`S*19 LL S*18 RR S*18 ...`) of
/// `CLEARANCE_TILES` tiles (comma-separated, default 1000,10000), fold-run's defaults:
/// `simulate` with and without the clearance, CPU seconds printed (BENCHMARKS.md):
/// `CLEARANCE_TILES=1000,10000 cargo test --release -p foldchain --test clearances
/// clearance_cost -- --ignored --nocapture --test-threads 1`.
#[test]
#[ignore = "a benchmark: serpentines of 1,000 and 10,000 tiles with and without the clearance"]
fn clearance_cost() {
    let sizes = std::env::var("CLEARANCE_TILES").unwrap_or_else(|_| "1000,10000".into());
    for n in sizes
        .split(',')
        .filter_map(|s| s.trim().parse::<usize>().ok())
    {
        let mut word = String::from("S*19");
        let (mut letters, mut row) = (19, 0);
        while letters + 2 < n {
            let r = (n - 1 - letters - 2).min(18);
            word.push_str(if row % 2 == 0 { " LL " } else { " RR " });
            word.push_str(&format!("S*{r}"));
            letters += 2 + r;
            row += 1;
        }
        let chain = Chain::parse(&word).unwrap();
        let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
        for clearance in [false, true] {
            let t = cpu_seconds();
            let (_, summary) = simulate(
                &chain,
                &TileDesigns::global(Design::thesis()),
                &EngineOptions::default().with_model(model),
                &CheckOptions::default().with_clearance(clearance),
            )
            .unwrap();
            println!(
                "{} tiles, clearance {clearance}: {:.2} s CPU, {:?}, clearance {:?}",
                chain.len(),
                cpu_seconds() - t,
                summary.result,
                summary.clearance.map(|c| (c.mm, c.tiles, c.time))
            );
        }
    }
}
