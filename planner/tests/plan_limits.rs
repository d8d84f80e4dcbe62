//! Sizes no run could finish are refused up front as bad input, never a panic or a hang.

use foldchain_planner::{plan_svg_str, PlanOptions, MAX_PLAN_TILES};

const SQUARE: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><rect x="10" y="10" width="80" height="80"/></svg>"#;

#[test]
fn too_many_tiles_is_bad_input() {
    let e = plan_svg_str(
        SQUARE,
        "square.svg",
        &PlanOptions::default().with_tiles(MAX_PLAN_TILES + 1),
    )
    .unwrap_err();
    assert!(e.is_bad_input(), "{e}");
    assert!(e.to_string().contains("--tiles"), "{e}");
}

#[test]
fn tiny_tile_size_is_bad_input() {
    for w in [1e-9, 1e-300, 0.01] {
        let e = plan_svg_str(
            SQUARE,
            "square.svg",
            &PlanOptions::default().with_tile_size(w),
        )
        .unwrap_err();
        assert!(e.is_bad_input(), "{w}: {e}");
        assert!(e.to_string().contains("--tile-size"), "{w}: {e}");
    }
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = plan_svg_str(
            SQUARE,
            "square.svg",
            &PlanOptions::default().with_tile_size(w),
        )
        .unwrap_err();
        assert!(e.is_bad_input(), "{w}: {e}");
    }
}
