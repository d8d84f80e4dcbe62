//! Collision verdicts (issue 12): the event engine's (local solves, its fold schedule
//! checked) against the reference's (its recorded fold schedule checked by the same
//! checker, [`foldchain::check_reference`]), both with the same dynamics (overdamped, and
//! inertial, the one fold-run uses by default): the same result, the same first collision
//! (joint and tiles; its time within 0.5% of the run).
//!
//! The quick tests run a sample of words with each dynamics; the full scan, every fold word
//! of up to 7 letters at s = 0, 0.05, 0.1 and 0.3 mm with both dynamics, is `cargo test
//! --release -p foldchain --test verdicts -- --ignored --nocapture` (BENCHMARKS.md).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use rayon::prelude::*;

use foldchain::collision::CheckOptions;
use foldchain::engine::EngineOptions;
use foldchain::physics::Inertia;
use foldchain::reference::{
    run_reference, state_budget, Dynamics, ModelOptions, Recording, ReferenceOptions,
};
use foldchain::timeline::{Summary, TileDesigns};
use foldchain::{check_reference, simulate, Chain, Design};

/// The inertial dynamics with the default parameters (fold-run's default).
fn inertial() -> Dynamics {
    Dynamics::Inertial(Inertia::default())
}

/// The two verdicts of `word` at `s` mm with `dynamics`, and whether they agree.
fn verdicts(word: &str, s: f64, dynamics: Dynamics) -> (Summary, Summary, bool) {
    let chain = Chain::parse(word).unwrap();
    let designs = TileDesigns::global(Design::thesis().with_s(s));
    let model = ModelOptions::default().with_dynamics(dynamics);
    let (_, e) = simulate(
        &chain,
        &designs,
        &EngineOptions::default().with_model(model),
        &CheckOptions::default(),
    )
    .unwrap();
    let ro = ReferenceOptions::default()
        .with_model(model)
        .with_record(Recording::Grid {
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

/// The disagreements among `words` at the four s with `dynamics`.
fn disagreements(words: &[String], dynamics: Dynamics) -> Vec<String> {
    let cases: Vec<(String, f64)> = words
        .iter()
        .flat_map(|w| [0.0, 0.05, 0.1, 0.3].map(|s| (w.clone(), s)))
        .collect();
    cases
        .par_iter()
        .filter_map(|(w, s)| {
            let (e, r, agree) = verdicts(w, *s, dynamics);
            (!agree).then(|| {
                format!(
                    "{w} s={s} {}: engine {} {:?} ({:.4} s), reference {} {:?} ({:.4} s)",
                    dynamics.name(),
                    e.result,
                    e.first_collision,
                    e.duration_s,
                    r.result,
                    r.first_collision,
                    r.duration_s
                )
            })
        })
        .collect()
}

/// Collisions (overdamped: the sequential sweep of LSLLSR hits tile 0 with tile 6; inertial:
/// LLLL and LLSLLS, whose folds overlap, hit tile 0 with the last tile), a ring that closes
/// touching, U-turns, an inhibited joint, straight and mixed words.
const SAMPLE: [&str; 10] = [
    "LSLLSR", "LLL", "LLLL", "SLLS", "LLSLL", "RSRRSL", "LRS", "SLSLSL", "LLRR", "LLSLLS",
];

fn sample() -> Vec<String> {
    SAMPLE.iter().map(|w| w.to_string()).collect()
}

#[test]
fn engine_and_reference_give_the_same_collision_verdicts_on_a_sample() {
    let bad = disagreements(&sample(), Dynamics::Overdamped);
    assert!(bad.is_empty(), "{bad:#?}");
    // and the sample does hold a collision
    let (e, _, _) = verdicts("LSLLSR", 0.3, Dynamics::Overdamped);
    assert_eq!(e.result, "collided");
}

#[test]
fn engine_and_reference_give_the_same_inertial_collision_verdicts_on_a_sample() {
    let bad = disagreements(&sample(), inertial());
    assert!(bad.is_empty(), "{bad:#?}");
    // and the sample does hold collisions (LSLLSR's folds, quicker under inertia, do not
    // collide)
    for w in ["LLLL", "LLSLLS"] {
        let (e, _, _) = verdicts(w, 0.3, inertial());
        assert_eq!(e.result, "collided", "{w}");
    }
}

#[test]
#[ignore = "every word of up to 7 letters at four s, both dynamics: some 26,000 reference runs (BENCHMARKS.md)"]
fn full_scan_of_words_up_to_7_letters() {
    let words = all_words(7);
    let mut failed = 0;
    // the dynamics fold-run uses by default first
    for dynamics in [inertial(), Dynamics::Overdamped] {
        let t0 = std::time::Instant::now();
        let bad = disagreements(&words, dynamics);
        println!(
            "{}: {} cases ({} words x 4 s), {} disagree ({:.1} s)",
            dynamics.name(),
            4 * words.len(),
            words.len(),
            bad.len(),
            t0.elapsed().as_secs_f64()
        );
        for b in &bad {
            println!("  {b}");
        }
        failed += bad.len();
    }
    assert_eq!(failed, 0);
}
