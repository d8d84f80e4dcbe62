//! Thin rings (issue 26, "no part left empty"): a ring whose hole is 0.8 or 0.9 of its outer
//! diameter (`tests/rings/`, not in the corpus) has no slab decomposition at the cuts where
//! the runs change that sweeps both sides of the hole along their length; cut across the
//! hole's middle, its halves are laid one after the other, the second swept along the cut.
//! Slow in debug builds: `.ci/run` runs them (`--include-ignored`).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use std::path::Path;

use foldchain_planner::{plan_svg_file, Plan, PlanOptions};

/// The plan of `tests/rings/{name}` for about `tiles` tiles with the default options.
fn plan_ring(name: &str, tiles: usize) -> Plan {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/rings")
        .join(name);
    plan_svg_file(&path, &PlanOptions::default().with_tiles(tiles))
        .unwrap_or_else(|e| panic!("{name} at {tiles}: {e}"))
}

/// Ring 0.8 (outer radius 100, inner 80) at 300 and 1000 tiles and ring 0.9 at 1000: at
/// main ec52d45 their largest empty parts were 205.8, 837.5 and 961.7 tile areas (a side of
/// the hole swept across its width, the rest of the ring left empty); now below 150, 500
/// and 800, the count within 3%, the plan sound.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_thin_ring_is_cut_across_its_hole_and_swept_along_both_halves() {
    for (name, tiles, bound) in [
        ("ring0.8.svg", 300, 150.0),
        ("ring0.8.svg", 1000, 500.0),
        ("ring0.9.svg", 1000, 800.0),
    ] {
        let p = plan_ring(name, tiles);
        common::assert_sound(&p);
        assert!(
            p.tiles.abs_diff(tiles) * 100 <= 3 * tiles,
            "{name} at {tiles}: {} tiles",
            p.tiles
        );
        assert!(
            p.metrics.largest_empty_tiles < bound,
            "{name} at {tiles}: {} tile areas empty (bound {bound})",
            p.metrics.largest_empty_tiles
        );
    }
}

/// The corpus' bi-gear-wide-connected (a toothed ring round a hole cut by three spokes) at
/// 3000 tiles: the serpentine sized for the count left 2688 tile areas empty (the rows'
/// phase let the fold check fill one side of the hole only) and a loose plan leaving 3202
/// was returned; the serpentine tried again 1-2% wider leaves about 1352, the count within
/// 3%, the plan sound.
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_gear_whose_serpentine_leaves_half_of_it_empty_is_tried_at_other_widths() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/icons/bi-gear-wide-connected.svg");
    let p = plan_svg_file(&path, &PlanOptions::default().with_tiles(3000)).unwrap();
    common::assert_sound(&p);
    assert!(p.tiles.abs_diff(3000) <= 90, "{} tiles", p.tiles);
    assert!(
        p.metrics.largest_empty_tiles < 2000.0,
        "{} tile areas empty",
        p.metrics.largest_empty_tiles
    );
}

/// Thin rings at low counts, where no two rows fit across the band: ring 0.9 at 100 tiles
/// and the corpus' thin letter O (xlight-O) at 100 were planned with 13 and 22 tiles (a
/// corner of the ring in rows of tiny tiles, the count 78-87% short, with a warning); a
/// single-file walk along the band ([`foldchain_planner`]'s `walk.rs`) lays the count round
/// most of the hole: within 3% of it, sound, and for the O less than 10 tile areas empty
/// (59.7 before).
#[test]
#[ignore = "slow in debug builds: .ci/run runs it"]
fn a_thin_ring_at_a_low_count_is_walked_round_its_hole() {
    let p = plan_ring("ring0.9.svg", 100);
    common::assert_sound(&p);
    assert!(p.tiles.abs_diff(100) <= 3, "ring0.9: {} tiles", p.tiles);
    assert!(
        p.metrics.largest_empty_tiles < 45.0,
        "ring0.9: {} tile areas empty",
        p.metrics.largest_empty_tiles
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus/glyphs/xlight-O.svg");
    let p = plan_svg_file(&path, &PlanOptions::default().with_tiles(100)).unwrap();
    common::assert_sound(&p);
    assert!(p.tiles.abs_diff(100) <= 3, "xlight-O: {} tiles", p.tiles);
    assert!(
        p.metrics.largest_empty_tiles < 10.0,
        "xlight-O: {} tile areas empty",
        p.metrics.largest_empty_tiles
    );
}
