//! Sizes no run could finish are refused up front as bad input, never a panic or a hang;
//! the error names the option and the value (the library knows no command-line flags).

use foldchain_planner::{plan_svg_str, PlanError, PlanOption, PlanOptions, MAX_PLAN_TILES};

const SQUARE: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><rect x="10" y="10" width="80" height="80"/></svg>"#;

/// The error of planning the square with `opts`, which must be a bad `option`.
fn refused(opts: &PlanOptions, option: PlanOption) -> String {
    let e = plan_svg_str(SQUARE, "square.svg", opts).expect_err("refused");
    assert!(e.is_bad_input(), "{e}");
    assert!(
        matches!(e, PlanError::BadOption { option: o, .. } if o == option),
        "{e:?}"
    );
    let m = e.to_string();
    assert!(m.contains(&option.to_string()) && !m.contains("--"), "{m}");
    m
}

#[test]
fn too_many_tiles_is_bad_input() {
    let n = MAX_PLAN_TILES + 1;
    let m = refused(&PlanOptions::default().with_tiles(n), PlanOption::Tiles);
    assert!(m.contains(&n.to_string()), "{m}");
    let m = refused(&PlanOptions::default().with_tiles(0), PlanOption::Tiles);
    assert!(m.contains("at least 1"), "{m}");
}

#[test]
fn tiny_tile_size_is_bad_input() {
    for w in [1e-9, 1e-300, 0.01] {
        let m = refused(
            &PlanOptions::default().with_tile_size(w),
            PlanOption::TileSize,
        );
        assert!(m.contains(&w.to_string()) && m.contains("more than"), "{m}");
    }
    for w in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let m = refused(
            &PlanOptions::default().with_tile_size(w),
            PlanOption::TileSize,
        );
        assert!(m.contains("positive"), "{w}: {m}");
    }
}

/// The planner reports its progress through the callback (stages, done of total), and a
/// drawing of 200,000 outline points is simplified before planning: it plans like the same
/// circle drawn with 200.
#[test]
fn progress_is_reported_and_dense_outlines_are_simplified() {
    let circle = |n: usize| {
        let pts: Vec<String> = (0..n)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                format!("{:.6},{:.6}", 50.0 + 45.0 * a.cos(), 50.0 + 45.0 * a.sin())
            })
            .collect();
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><path d="M {} Z"/></svg>"#,
            pts.join(" ")
        )
    };
    let dir = std::env::temp_dir().join(format!("plan-progress-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("dense.svg");
    std::fs::write(&path, circle(200_000)).unwrap();
    let stages = std::sync::Mutex::new(Vec::<String>::new());
    let opts = foldchain_planner::PlanOptions::default().with_tiles(150);
    let dense = foldchain_planner::plan_svg_file_reporting(&path, &opts, &|s, done, total| {
        assert!(done <= total);
        stages.lock().unwrap().push(s.to_string());
    })
    .unwrap();
    let stages = stages.into_inner().unwrap();
    assert!(stages.iter().any(|s| s.starts_with("sizing")), "{stages:?}");
    assert!(
        stages.iter().any(|s| s.starts_with("checking")),
        "{stages:?}"
    );
    let sparse = foldchain_planner::plan_svg_str(&circle(2_000), "sparse.svg", &opts).unwrap();
    assert!(
        dense.tiles.abs_diff(sparse.tiles) <= 8,
        "{} vs {}",
        dense.tiles,
        sparse.tiles
    );
    let _ = std::fs::remove_dir_all(&dir);
}
