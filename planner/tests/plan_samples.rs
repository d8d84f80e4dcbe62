//! The sample shapes, planned through the library: sound plans (checked by plain geometry in
//! `common`), the thesis' square, and fit bounds the planner meets today.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use common::{
    assert_sound, deepest_overlap, octagon, overlap_depth, row_density, sample as shape,
    OVERLAP_TOLERANCE,
};
use foldchain_planner::{plan_svg_file, plan_svg_str, Plan, PlanOptions, Shape, Turns};

fn plan(name: &str, opts: &PlanOptions) -> Plan {
    plan_svg_file(&shape(name), opts).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The overlap test itself: tiles one width apart touch (depth 0), closer ones overlap by
/// the difference, and a tile turned by 45 degrees is still the same octagon.
#[test]
fn the_overlap_test_sees_overlaps() {
    let a = octagon(0.0, 0.0, 0.0, 2.0);
    assert!(overlap_depth(&a, &octagon(2.0, 0.0, 90.0, 2.0)).abs() < 1e-12);
    assert!((overlap_depth(&a, &octagon(1.8, 0.0, 0.0, 2.0)) - 0.2).abs() < 1e-12);
    let diag = 2.0 / 2f64.sqrt();
    assert!(overlap_depth(&a, &octagon(diag, diag, 45.0, 2.0)).abs() < 1e-12);
    assert!(overlap_depth(&a, &octagon(0.9 * diag, diag, 45.0, 2.0)) > 0.1);
    assert!(overlap_depth(&a, &octagon(5.0, 5.0, 0.0, 2.0)) < 0.0);
    // a real plan passes; moving one tile 0.7 w from another makes it fail
    let mut p = plan("square.svg", &PlanOptions::default().with_tiles(60));
    assert!(deepest_overlap(&p).0 <= OVERLAP_TOLERANCE);
    let (a, w) = (p.poses[10], p.tile_size);
    p.poses[40].x = a.x + 0.7 * w;
    p.poses[40].y = a.y;
    let (depth, i, j) = deepest_overlap(&p);
    assert!(depth > 0.2 && j == 40, "{depth} {i} {j}");
}

#[test]
fn square_at_the_thesis_sizes() {
    // thesis figure 7.2: 107 tiles with tight turns; figure 7.3: 82 with loose turns
    let square = |n: usize, turns: Turns| {
        let p = plan(
            "square.svg",
            &PlanOptions::default().with_tiles(n).with_turns(turns),
        );
        assert_sound(&p);
        p
    };
    let t = square(107, Turns::Tight);
    assert!(t.tiles.abs_diff(107) <= 5, "tight: {} tiles", t.tiles);
    assert!(t.bom.get("RR").copied().unwrap_or(0) > 0);
    let l = square(82, Turns::Loose);
    // loose rows are (1 + sqrt2) w apart, so the count moves in steps of a whole row of
    // about 13 tiles: the thesis' 82 (6 rows of 12) is not the best fit of a square, 88
    // (6 rows of 13) is, and is the nearest count the fit allows
    assert!(l.tiles.abs_diff(82) <= 7, "loose: {} tiles", l.tiles);
    assert_eq!(l.bom.get("RR"), None, "loose turns use no LL/RR tiles");
    // a square is filled with rows parallel to its sides
    for p in [&t, &l] {
        assert!(
            p.axis_deg.abs() < 1e-6 || (p.axis_deg - 90.0).abs() < 1e-6,
            "{}",
            p.axis_deg
        );
        assert!(p.metrics.outside_share < 0.08, "{:?}", p.metrics);
    }
}

#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn every_sample_plans_and_folds() {
    for name in [
        "square.svg",
        "disc.svg",
        "crescent.svg",
        "rotated-crescent.svg",
        "key.svg",
        "ring.svg",
    ] {
        for turns in [Turns::Tight, Turns::Loose] {
            let opts = PlanOptions::default().with_tiles(120).with_turns(turns);
            let p = match plan_svg_file(&shape(name), &opts) {
                Ok(p) => p,
                // the ring may be refused: every plan found leaves a part of it empty
                Err(e) if name == "ring.svg" => {
                    assert!(e.to_string().contains("empty"), "{e}");
                    continue;
                }
                Err(e) => panic!("{name}: {e}"),
            };
            assert_sound(&p);
            // rows cover at most row_density of the shape; the plans of the area-true fit
            // (issue 13) reach 85% of that or more (key, tight: 0.890, its bits left empty
            // for two long shaft rows) with less than 6% of the chain outside (before issue
            // 13: 91% and up to 10.4% outside)
            let reach = p.metrics.covered_share / row_density(turns == Turns::Loose);
            assert!(
                reach > 0.85,
                "{name} {turns}: {reach:.3} of the rows' cover, {:?}",
                p.metrics
            );
            assert!(
                p.metrics.outside_share < 0.06,
                "{name} {turns}: {:?}",
                p.metrics
            );
        }
    }
}

#[test]
fn dog_is_monotone_in_no_direction() {
    let data = std::fs::read(shape("dog.svg")).unwrap();
    let s = Shape::from_svg_data(&data, "dog.svg").unwrap();
    assert!(s.monotone_row_angles().is_empty());
    // planned all the same (tests/plan_cells.rs covers it at several sizes)
}

#[test]
fn crescent_is_monotone_for_one_axis_only() {
    let data = std::fs::read(shape("crescent.svg")).unwrap();
    let s = Shape::from_svg_data(&data, "crescent.svg").unwrap();
    assert!(s.is_monotone_for_rows(0.0), "rows along x (vertical axis)");
    assert!(
        !s.is_monotone_for_rows(std::f64::consts::FRAC_PI_2),
        "rows along y"
    );
}

/// A thin C shape is monotone only for rows within a few degrees of its arms; turned by 30
/// degrees with a group transform, the planner finds the turned axis (or its frame, by cells).
#[test]
fn rotated_monotone_shape_is_found_along_its_rotated_axis() {
    let c = r#"<path d="M0 0H100V10H10V20H100V30H0Z"/>"#;
    for deg in [0.0f64, 30.0, 117.0] {
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="300" viewBox="-150 -150 300 300"><g transform="rotate({deg})">{c}</g></svg>"#
        );
        let p = plan_svg_str(&svg, "c.svg", &PlanOptions::default().with_tiles(60)).unwrap();
        assert_sound(&p);
        // one serpentine stacks its rows across the arms; a plan by cells (which may fit
        // better: the arms as cells) sweeps along either axis of the turned frame
        let want = (deg + 90.0).rem_euclid(180.0);
        let d = (p.axis_deg - want).rem_euclid(180.0);
        let d = if p.cells > 1 {
            d.min((d - 90.0).abs())
        } else {
            d
        };
        assert!(
            d.min(180.0 - d) < 6.0,
            "rotated {deg}: axis {} want {want} ({})",
            p.axis_deg,
            p.summary()
        );
    }
}
