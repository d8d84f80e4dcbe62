//! Plans at thousands of tiles (issue 26: more tiles never turn a plan into a refusal): a
//! sliver of an outline narrower than a tile is not a separate part, a letter whose cheapest
//! cells left a round corner to the next cell (an empty part growing with the tiles) is
//! planned without it, a round annulus plans at 1000 and 10,000 tiles, and a gear is planned
//! round its hole. Slow in debug builds: `.ci/run` runs them (`--include-ignored`).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use common::plan_corpus as plan;

/// Egypt's outline at 3000 tiles: a spit of its coast about a third of a tile thick (x 486
/// to 500, y 68 to 72 in drawing units), which the planner's raster saw cut off from the
/// rest, was a second part and the drawing was refused as "in 2 separate parts". The
/// crescent's tip likewise. Both are one piece: planned, the count within 3%.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_sliver_narrower_than_a_tile_is_not_a_separate_part() {
    for name in ["countries/egypt.svg", "inkscape/ink-mask-crescent.svg"] {
        let p = plan(name, 3000);
        assert!(p.tiles.abs_diff(3000) <= 90, "{name}: {} tiles", p.tiles);
    }
}

/// The letter D at 3000 tiles: its cheapest cells left the corners of the counter (the hole)
/// to the next cell's first row, which reaches a tile of them; at 3000 tiles that left 572
/// tile areas empty (the corpus report at 1c06270) and 12% fewer tiles than asked. The cap
/// search now prices that area, so it is planned with no part over 20 tile areas empty.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn the_letter_d_at_3000_tiles_leaves_no_large_part_empty() {
    let p = plan("letters/D.svg", 3000);
    assert!(p.tiles.abs_diff(3000) <= 90, "{} tiles", p.tiles);
    assert!(
        p.metrics.largest_empty_tiles <= 20.0,
        "{} tile areas empty: {:?}",
        p.metrics.largest_empty_tiles,
        p.warnings
    );
}

/// A round annulus (outer radius twice the inner) is planned at 1000 and 10,000 tiles.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_round_annulus_plans_at_1000_and_10000_tiles() {
    for tiles in [1000, 10_000] {
        let p = plan("shapes/annulus.svg", tiles);
        assert_eq!(p.poses.len(), p.tiles);
        assert!(p.cells >= 2, "{tiles}: {} cells", p.cells);
        // within a tenth of the count (the planner warns beyond its tolerance)
        assert!(
            p.tiles.abs_diff(tiles) <= tiles / 10,
            "{tiles}: {}",
            p.tiles
        );
    }
}

/// The gear (a ring with six teeth) at 1000 and 3000 tiles: no cap decomposition exists (a
/// tooth on every side), and the two cheapest slab decompositions are entered halfway up a
/// slab and leave half the gear empty, so one serpentine that runs its rows right of the hole
/// only was planned, leaving the left part empty (494 tile areas at 3000, the corpus report at
/// 073014b). While every plan leaves a part that large, more slab decompositions are tried:
/// one cut across the hole goes round it.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_gear_is_planned_round_its_hole() {
    for (tiles, most) in [(1000, 20.0), (3000, 100.0)] {
        let p = plan("icons/fa-gear.svg", tiles);
        assert!(p.cells >= 2, "{tiles}: {} cells", p.cells);
        assert!(
            p.tiles.abs_diff(tiles) <= tiles * 3 / 100,
            "{tiles}: {} tiles",
            p.tiles
        );
        assert!(
            p.metrics.largest_empty_tiles <= most,
            "{tiles}: {} tile areas empty: {:?}",
            p.metrics.largest_empty_tiles,
            p.warnings
        );
    }
}
