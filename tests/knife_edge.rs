//! Bounded work at knife edges (issue 27, item 5): a design balanced so finely that a magnet
//! creeps towards a balance it neither passes nor settles on. Every run's work is bounded
//! by a budget proportional to the chain (the engine: steps per joint's solve; the
//! reference: steps per tile), and a balance not decided within it is `undecided`, with the
//! balance and its margin, never `completed`, `stalled` or both "came to rest" and "gave up".

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::collision::CheckOptions;
use foldchain::engine::EngineOptions;
use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::{run_reference, ReferenceOptions};
use foldchain::timeline::{RunResult, TileDesigns};
use foldchain::{simulate, Chain};

/// The design of issue 27: a wall on the knife edge between starting magnet 4 and not.
const KNIFE_EDGE: &str = r#"{"wall": 1.2715684370696545}"#;

fn designs() -> TileDesigns {
    TileDesigns::from_json(KNIFE_EDGE, "knife-edge design").unwrap()
}

fn assert_undecided(what: &str, result: RunResult, reason: &str) {
    assert_eq!(result, RunResult::Undecided, "{what}: {reason}");
    assert!(reason.contains("work budget"), "{what}: {reason}");
    assert!(reason.contains("a margin of"), "{what}: {reason}");
    assert!(!reason.contains("came to rest"), "{what}: {reason}");
}

#[test]
fn the_engine_says_undecided_within_its_budget() {
    let chain = Chain::parse("SL").unwrap();
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let (_, s) = simulate(
        &chain,
        &designs(),
        &EngineOptions::default().with_model(model),
        &CheckOptions::default(),
    )
    .unwrap();
    assert_undecided("engine", s.result, s.reason.as_deref().unwrap_or(""));
    assert!(!s.completed);
    assert_eq!(s.stalled_at, None);
}

#[test]
fn the_reference_says_undecided_within_its_budget() {
    let chain = Chain::parse("SL").unwrap();
    let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
    let opts = ReferenceOptions::default().with_model(model);
    let run = run_reference(&chain, &designs(), &opts).unwrap();
    // the budget: steps proportional to the chain
    assert!(run.stats.accepted + run.stats.rejected <= opts.step_budget(3));
    assert_eq!(
        opts.step_budget(3),
        3 * ReferenceOptions::DEFAULT_STEPS_PER_TILE
    );
    assert!(run.undecided);
    let s = run.checked_summary(&CheckOptions::default()).unwrap();
    assert_undecided("reference", s.result, s.reason.as_deref().unwrap_or(""));
    assert_eq!(run.result(), RunResult::Undecided);
}

#[test]
fn a_budget_of_a_few_steps_leaves_the_reference_undecided() {
    // the thesis design folds SLLS in a few thousand steps; a budget of 10 steps a tile
    // cannot: undecided, not stopped and not completed
    let chain = Chain::parse("SLLS").unwrap();
    let opts = ReferenceOptions::default().with_steps_per_tile(10);
    let run = run_reference(&chain, &TileDesigns::default(), &opts).unwrap();
    assert_eq!(run.result(), RunResult::Undecided, "{:?}", run.stopped);
    let full = run_reference(
        &chain,
        &TileDesigns::default(),
        &ReferenceOptions::default(),
    )
    .unwrap();
    assert_eq!(full.result(), RunResult::Completed, "{:?}", full.stopped);
}
