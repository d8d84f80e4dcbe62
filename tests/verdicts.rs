//! Collision verdicts (issue 12): the event engine's (local solves, its fold schedule
//! checked) against the reference's (overdamped, its recorded fold schedule checked by the
//! same checker, [`foldchain::check_reference`]): the same result, the same first collision
//! (joint and tiles; its time within 0.5% of the run).
//!
//! The quick test runs a sample of words; the full scan, every fold word of up to 7 letters
//! at s = 0, 0.05, 0.1 and 0.3 mm, is `cargo test --release -p foldchain --test verdicts --
//! --ignored --nocapture` (BENCHMARKS.md).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use rayon::prelude::*;

use foldchain::collision::CheckOptions;
use foldchain::engine::EngineOptions;
use foldchain::reference::{run_reference, state_budget, Recording, ReferenceOptions};
use foldchain::timeline::{Summary, TileDesigns};
use foldchain::{check_reference, simulate, Chain, Design};

/// The two verdicts of `word` at `s` mm, and whether they agree.
fn verdicts(word: &str, s: f64) -> (Summary, Summary, bool) {
    let chain = Chain::parse(word).unwrap();
    let designs = TileDesigns::global(Design::thesis().with_s(s));
    let (_, e) = simulate(
        &chain,
        &designs,
        &EngineOptions::default(),
        &CheckOptions::default(),
    )
    .unwrap();
    let ro = ReferenceOptions::default().with_record(Recording::Grid {
        max_states: state_budget(chain.len()),
    });
    let run = run_reference(&chain, &designs, &ro).unwrap();
    let r = check_reference(&run, &CheckOptions::default()).unwrap();
    let same_hit = match (&e.first_collision, &r.first_collision) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.joint == b.joint
                && a.tiles == b.tiles
                && match (a.time, b.time) {
                    (Some(x), Some(y)) => (x - y).abs() <= 0.005 * r.duration_s.max(1e-9),
                    (x, y) => x.is_none() && y.is_none(),
                }
        }
        _ => false,
    };
    let agree = e.result == r.result && same_hit;
    (e, r, agree)
}

fn all_words(max_len: usize) -> Vec<String> {
    let mut out = Vec::new();
    let mut level = vec![String::new()];
    for _ in 0..max_len {
        let mut next = Vec::new();
        for w in &level {
            for c in ['S', 'L', 'R'] {
                next.push(format!("{w}{c}"));
            }
        }
        out.extend(next.iter().cloned());
        level = next;
    }
    out
}

#[test]
fn engine_and_reference_give_the_same_collision_verdicts_on_a_sample() {
    // collisions (the sequential sweep of LSLLSR hits tile 0 with tile 6), a ring that
    // closes touching, U-turns, an inhibited joint, straight and mixed words
    let words = [
        "LSLLSR", "LLL", "LLLL", "SLLS", "LLSLL", "RSRRSL", "LRS", "SLSLSL", "LLRR",
    ];
    let cases: Vec<(String, f64)> = words
        .iter()
        .flat_map(|w| [0.0, 0.05, 0.1, 0.3].map(|s| (w.to_string(), s)))
        .collect();
    let bad: Vec<String> = cases
        .par_iter()
        .filter_map(|(w, s)| {
            let (e, r, agree) = verdicts(w, *s);
            (!agree).then(|| {
                format!(
                    "{w} s={s}: engine {} {:?}, reference {} {:?}",
                    e.result, e.first_collision, r.result, r.first_collision
                )
            })
        })
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    // and the sample does hold a collision
    let (e, _, _) = verdicts("LSLLSR", 0.3);
    assert_eq!(e.result, "collided");
}

#[test]
#[ignore = "every word of up to 7 letters at four s: some 13,000 reference runs (BENCHMARKS.md)"]
fn full_scan_of_words_up_to_7_letters() {
    let words = all_words(7);
    let cases: Vec<(String, f64)> = words
        .iter()
        .flat_map(|w| [0.0, 0.05, 0.1, 0.3].map(|s| (w.clone(), s)))
        .collect();
    let bad: Vec<String> = cases
        .par_iter()
        .filter_map(|(w, s)| {
            let (e, r, agree) = verdicts(w, *s);
            (!agree).then(|| {
                format!(
                    "{w} s={s}: engine {} {:?}, reference {} {:?}",
                    e.result, e.first_collision, r.result, r.first_collision
                )
            })
        })
        .collect();
    println!(
        "{} cases ({} words x 4 s), {} disagree",
        cases.len(),
        words.len(),
        bad.len()
    );
    for b in &bad {
        println!("  {b}");
    }
    assert!(bad.is_empty());
}
