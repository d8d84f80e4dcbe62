//! Property tests of the SVG-facing code: arbitrary text and arbitrary polygons never
//! panic; every accepted polygon plans to a chain that folds without collision.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain_planner::{plan_svg_str, PlanOptions, Shape};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn arbitrary_text_never_panics(s in "\\PC{0,200}") {
        let _ = Shape::from_svg_data(s.as_bytes(), "fuzz.svg");
    }

    #[test]
    fn arbitrary_svg_fragments_never_panic(
        d in "[MLHVCQAZmlhvcqaz0-9 .,-]{0,80}",
        rule in prop_oneof![Just("nonzero"), Just("evenodd")],
    ) {
        let svg = format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><path fill-rule="{rule}" d="{d}"/></svg>"#);
        let _ = Shape::from_svg_data(svg.as_bytes(), "fuzz.svg");
    }

}

proptest! {
    // each case plans a shape (serpentine and cells): 16 cases keep the test to seconds
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Star-shaped polygons around the origin (never self-intersecting): planned or refused
    /// with a reason, never a panic, and a returned plan always folds.
    #[test]
    fn star_polygons_plan_or_explain(radii in proptest::collection::vec(20.0f64..50.0, 3..12)) {
        let n = radii.len();
        let pts: Vec<String> = radii.iter().enumerate().map(|(i, r)| {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            format!("{:.3},{:.3}", 50.0 + r * a.cos(), 50.0 + r * a.sin())
        }).collect();
        let svg = format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><polygon points="{}"/></svg>"#, pts.join(" "));
        match plan_svg_str(&svg, "star.svg", &PlanOptions::default().with_tiles(40)) {
            Ok(p) => {
                let w = p.fold_word().unwrap();
                prop_assert!(foldchain::collision::check_word(&w, &Default::default()).is_ok());
            }
            Err(e) => prop_assert!(!e.is_bad_input(), "{}", e),
        }
    }
}
