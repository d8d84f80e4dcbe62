//! Outlines of more detail than the planner can use (issue 26, hostile files): a ring of
//! tens of thousands of points whose zigzag is coarser than the flattening tolerance used to
//! reach the planner whole, whose work grows faster than the points (a 200,000-point zigzag
//! took 5 GB of memory and did not finish in minutes; 50,000 points over a minute). The
//! reading now thins such an outline to at most `OUTLINE_BUDGET` points at a tolerance of
//! at most 1% of the drawing, and refuses one with more detail than that, naming what to do.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain_planner::{plan_svg_str, PlanError, PlanOptions, Shape};

/// A disc of radius 40 in a 100-unit drawing whose outline zigzags between radius 40 and
/// `40 + amplitude` at every one of its `n` points.
fn zigzag_disc(n: usize, amplitude: f64) -> String {
    let mut d = String::from("M90 50");
    for k in 1..n {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        let r = 40.0 + amplitude * (k % 2) as f64;
        d.push_str(&format!(
            " L{:.7} {:.7}",
            50.0 + r * a.cos(),
            50.0 + r * a.sin()
        ));
    }
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><path d="{d} Z"/></svg>"#
    )
}

fn points(shape: &Shape) -> usize {
    shape.rings().map(|r| r.points.len()).sum()
}

/// A 50,000-point zigzag of 0.5% of the drawing (five times the flattening tolerance, so
/// the usual thinning keeps every point) is read as a few thousand points at most, and plans.
#[test]
fn a_fine_zigzag_of_50000_points_is_thinned_and_plans() {
    let svg = zigzag_disc(50_000, 0.5);
    let shape = Shape::from_svg_data(svg.as_bytes(), "zigzag.svg").unwrap();
    assert!(points(&shape) <= 5_000, "{} points kept", points(&shape));
    // the thinned outline is the disc within the thinning tolerance (1% of 100 units)
    let b = shape.bbox();
    assert!((b.width() - 80.5).abs() < 1.5, "{b:?}");
    let plan = plan_svg_str(&svg, "zigzag.svg", &PlanOptions::default().with_tiles(300)).unwrap();
    assert!(plan.tiles.abs_diff(300) <= 9, "{} tiles", plan.tiles);
}

/// A zigzag of 2% of the drawing on 20,000 points: plain Douglas-Peucker kept most of its
/// points (it was refused as too detailed), the bounded one (`simplify.rs`) finds a coarser
/// zigzag within 1% of the drawing, every point within that of it, and the drawing is read.
#[test]
fn a_coarse_zigzag_of_20000_points_is_thinned_within_one_percent() {
    let svg = zigzag_disc(20_000, 2.0);
    let shape = Shape::from_svg_data(svg.as_bytes(), "coarse.svg").unwrap();
    assert!(points(&shape) <= 5_000, "{} points kept", points(&shape));
    let b = shape.bbox();
    assert!((b.width() - 82.0).abs() < 3.0, "{b:?}");
}

/// A square with 2,500 square holes (10,004 points, none of them on a ring long enough to
/// thin) is more detail than thinning to 1% can take away: refused as bad input, saying
/// how many points and what to do.
#[test]
fn a_sieve_of_2500_holes_is_refused_saying_what_to_do() {
    let mut d = String::from("M0 0 H100 V100 H0 Z");
    for i in 0..50 {
        for j in 0..50 {
            let (x, y) = (0.5 + 2.0 * i as f64, 0.5 + 2.0 * j as f64);
            d.push_str(&format!(" M{x} {y} v1 h1 v-1 Z"));
        }
    }
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100"><path fill-rule="evenodd" d="{d}"/></svg>"#
    );
    let err = Shape::from_svg_data(svg.as_bytes(), "sieve.svg").unwrap_err();
    assert!(matches!(err, PlanError::TooDetailed { .. }), "{err}");
    assert_eq!(err.exit_code(), 2);
    let text = err.to_string();
    for w in ["sieve.svg", "points", "Path > Simplify"] {
        assert!(text.contains(w), "missing {w:?} in {text}");
    }
}

/// A drawing within the budget is read as before: a smooth 100,000-point circle is
/// simplified by the usual tolerance only, to far fewer points than the budget.
#[test]
fn a_smooth_outline_is_not_thinned_further() {
    let svg = zigzag_disc(100_000, 0.0);
    let shape = Shape::from_svg_data(svg.as_bytes(), "smooth.svg").unwrap();
    let n = points(&shape);
    assert!((20..1_000).contains(&n), "{n} points");
}
