//! Issue 26: "the tile count within 3% of the request (or a warning)". Where no plan both
//! holds the count and leaves no part of the shape larger than 20 tile areas empty, the
//! plan returned is the one that falls least short of the asked chain, the count's miss
//! and the part left empty priced in one unit, tiles of the asked chain (`rank.rs`). Until
//! then rejected plans ranked by their empty part in their own tile areas, so the plan of
//! the fewest, widest tiles won: `glyphs/narrowb-at.svg` planned 13 tiles for 100 asked
//! and 74 for 300, `icons/mdi-anchor.svg` 49 for 100 and 202 for 300,
//! `glyphs/libsi-A.svg` 1137 for 1000. Each of these now plans within 3% of the count,
//! with the warning naming its empty part.
//!
//! `glyphs/xlight-O.svg` at 100 tiles (a ring thinner than a tile at that count) planned 23
//! tiles until no two rows fit across it were replaced by a single-file walk round the ring
//! (`planner/src/walk.rs`): now in the band too.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use common::plan_corpus;

/// Plans `name` at `n` tiles: within 3% of the count, and with a warning naming the part
/// left empty when it leaves more than 2 tile areas.
fn in_the_band(name: &str, n: usize) {
    let plan = plan_corpus(name, n);
    assert!(
        plan.tiles.abs_diff(n) * 100 <= 3 * n,
        "{name} at {n}: {} tiles ({:?})",
        plan.tiles,
        plan.warnings
    );
    if plan.metrics.largest_empty_tiles > 2.0 {
        assert!(
            plan.warnings.iter().any(|w| w.contains("empty")),
            "{name} at {n}: {:?}",
            plan.warnings
        );
    }
}

#[test]
fn narrowb_at_plans_the_count_asked() {
    in_the_band("glyphs/narrowb-at.svg", 100);
    in_the_band("glyphs/narrowb-at.svg", 300);
}

#[test]
fn mdi_anchor_plans_the_count_asked() {
    in_the_band("icons/mdi-anchor.svg", 100);
    in_the_band("icons/mdi-anchor.svg", 300);
}

#[test]
fn libsi_a_plans_the_count_asked_at_1000() {
    in_the_band("glyphs/libsi-A.svg", 1000);
}

/// A ring thinner than two rows of tiles: walked round its hole, in the band (22 tiles
/// before the walks), its empty part warned about if it leaves one.
#[test]
fn xlight_o_plans_the_count_asked_at_100() {
    in_the_band("glyphs/xlight-O.svg", 100);
}
