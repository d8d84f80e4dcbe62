//! Shapes that are monotone in no direction or have holes: planned by monotone cells joined
//! by turns (or by one serpentine where that fits better), and every plan is sound (checked
//! by plain geometry in `common`); a shape one chain cannot fill is refused with a reason.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use common::{assert_sound, row_density, sample as shape};
use foldchain_planner::{plan_svg_file, plan_svg_str, Plan, PlanOptions, Turns};

/// A quarter turn joins two cells: a plan has fewer quarter turns than cells.
fn assert_cells_joined(p: &Plan) {
    assert!(p.cells >= 1);
    assert!(
        p.quarter_turns < p.cells.max(1),
        "a quarter turn joins two cells"
    );
}

/// The sizes of the full sweep, tiles.
const SIZES: [usize; 3] = [150, 300, 600];

/// Plans at each of `sizes` tiles: each size either plans soundly, near the count, within
/// fit bounds, or is refused (exit 1) because every plan found leaves a part of the shape
/// empty, the error saying where (issue 13: never a plan with an empty part); at least one
/// size plans.
fn plan_sizes(name: &str, sizes: &[usize]) -> Vec<Plan> {
    let mut out = Vec::new();
    for &n in sizes {
        let opts = PlanOptions::default()
            .with_tiles(n)
            .with_turns(Turns::Tight);
        let p = match plan_svg_file(&shape(name), &opts) {
            Ok(p) => p,
            Err(e) => {
                let m = e.to_string();
                assert_eq!(e.exit_code(), 1, "{name} {n}: {m}");
                assert!(
                    m.contains("empty") && m.contains("around ("),
                    "{name} {n}: {m}"
                );
                continue;
            }
        };
        assert_sound(&p);
        assert_cells_joined(&p);
        // a plan that leaves a part larger than REFUSE_EMPTY_TILES (20 tile areas) empty is
        // returned only when no other plan is found, and says so as the refusal did; the
        // fit bounds below are for plans that leave nothing that large empty
        if p.metrics.largest_empty_tiles > 20.0 {
            assert!(
                p.warnings
                    .iter()
                    .any(|w| w.contains("empty") && w.contains("around (")),
                "{name} {n}: {:?}",
                p.warnings
            );
            out.push(p);
            continue;
        }
        assert!(
            p.tiles.abs_diff(n) * 10 <= n,
            "{name}: {} tiles for {n}",
            p.tiles
        );
        // at least 80% of what rows can cover with at most 9% of the chain outside (the
        // area-true fit of issue 13 lays a tile only when most of it is inside: the dog at
        // 150 tiles went from 85% / 12.3% outside to 81% / 5.8%; measured exactly since
        // issue 26, not on 25 points a tile, its plan at 150 has 8.8% outside)
        let reach = p.metrics.covered_share / row_density(false);
        assert!(reach > 0.80, "{name} {n}: {reach:.3}: {}", p.summary());
        assert!(
            p.metrics.outside_share < 0.09,
            "{name} {n}: {}",
            p.summary()
        );
        out.push(p);
    }
    // a shape of one piece with room for every size is not refused at every size
    assert!(!out.is_empty(), "{name}: refused at {sizes:?} tiles");
    out
}

#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn dog_plans_or_says_which_part_is_left_empty() {
    plan_sizes("dog.svg", &SIZES);
}

#[test]
fn ring_plans_around_its_hole_at_150_tiles() {
    assert_around_the_hole(&plan_sizes("ring.svg", &SIZES[..1]));
}

#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn ring_plans_around_its_hole() {
    assert_around_the_hole(&plan_sizes("ring.svg", &SIZES));
}

/// The ring (a square with a 30 x 40 hole at x 45..75, y 40..80): planned around the hole,
/// never across it.
fn assert_around_the_hole(plans: &[Plan]) {
    for p in plans {
        let w = p.tile_size;
        // centres more than a tile width inside the hole: a row along the hole's edge may
        // lean into it by part of a tile, a chain crossing the hole lands here
        let inside = p
            .poses
            .iter()
            .filter(|q| q.x > 45.0 + w && q.x < 75.0 - w && q.y > 40.0 + w && q.y < 80.0 - w)
            .count();
        assert!(
            inside * 50 <= p.tiles,
            "{} of {} tile centres in the hole: {}",
            inside,
            p.tiles,
            p.summary()
        );
    }
}

const TWO_DISCS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100"><circle cx="30" cy="50" r="25"/><circle cx="270" cy="50" r="25"/></svg>"#;

#[test]
fn separate_parts_are_unplannable_with_a_reason() {
    let e = plan_svg_str(
        TWO_DISCS,
        "two.svg",
        &PlanOptions::default().with_tiles(200),
    )
    .map(|p| p.summary())
    .unwrap_err();
    assert!(!e.is_bad_input());
    assert_eq!(e.exit_code(), 1);
    let m = e.to_string();
    assert!(m.contains("two.svg") && m.contains("separate parts"), "{m}");
}

/// A drawing of one piece that one chain can fill is planned, not refused, even where every
/// plan found leaves a part of it empty (issue 26: refused only when one chain cannot do it):
/// the letter Q and the gear at 300 tiles were refused before. The plan is sound, folds in
/// sequence, holds the asked count within 3%, and says in a warning and its metrics which
/// part it leaves empty.
#[test]
fn a_plan_that_leaves_a_part_empty_beats_a_refusal() {
    let corpus = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus");
    for name in ["letters/Q.svg", "icons/fa-gear.svg"] {
        let p = plan_svg_file(&corpus.join(name), &PlanOptions::default().with_tiles(300))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_sound(&p);
        foldchain::collision::check_word(
            &p.fold_word().unwrap(),
            &foldchain::collision::CheckOptions::default(),
        )
        .unwrap_or_else(|c| panic!("{name}: {c}"));
        assert!(
            p.tiles.abs_diff(300) * 100 <= 3 * 300,
            "{name}: {}",
            p.tiles
        );
        let warned = p.warnings.iter().any(|w| w.contains("empty"));
        assert_eq!(
            warned,
            p.metrics.largest_empty_tiles > 0.0,
            "{name}: {:?} {:?}",
            p.warnings,
            p.metrics
        );
        // what the planner may not do: bridge a gap with much of the chain outside
        assert!(p.metrics.outside_share <= 0.10, "{name}: {}", p.summary());
    }
}
