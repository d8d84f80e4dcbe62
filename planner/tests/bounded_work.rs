//! Work bounded on hostile outlines (issue 26): `Shape::is_monotone_for_rows` (each call
//! the planner makes per candidate row direction) on outlines of hundreds of thousands of
//! points. It asked every slab between vertex heights for its row intervals through an
//! index of the edges by height in which a tall edge sat in every bucket it spanned: a fine
//! zigzag of 200,000 tall edges filled 5 GB and did not finish in minutes. It is now a sweep
//! that keeps the edges across the line as it rises, and the index holds at most eight
//! entries an edge. These tests check the answers; the times are in BENCHMARKS.md.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use foldchain_planner::kurbo::Point;
use foldchain_planner::{Ring, Shape};

/// A square of side 100 whose right side is a zigzag of `teeth` teeth `depth` deep
/// (pointing right): every horizontal line meets it once, a vertical line through the
/// teeth many times.
fn comb_square(teeth: usize, depth: f64) -> Shape {
    let mut points = vec![Point::new(0.0, 0.0), Point::new(100.0, 0.0)];
    for k in 0..2 * teeth {
        let y = 100.0 * (k as f64 + 0.5) / (2 * teeth) as f64;
        let x = 100.0 + depth * (k % 2 == 0) as u8 as f64;
        points.push(Point::new(x, y));
    }
    points.push(Point::new(100.0, 100.0));
    points.push(Point::new(0.0, 100.0));
    Shape::from_rings(vec![Ring { points }])
}

/// A disc of radius 40 on `n` points, zigzagging out to `40 + amp` at every other point.
fn zigzag_disc(n: usize, amp: f64) -> Shape {
    let points = (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            let r = 40.0 + amp * (k % 2) as f64;
            Point::new(r * a.cos(), r * a.sin())
        })
        .collect();
    Shape::from_rings(vec![Ring { points }])
}

#[test]
fn a_comb_of_100000_teeth_is_monotone_along_its_teeth_only() {
    let comb = comb_square(100_000, 0.5);
    assert!(comb.is_monotone_for_rows(0.0), "rows along the teeth");
    assert!(
        !comb.is_monotone_for_rows(FRAC_PI_2),
        "rows across the teeth"
    );
    assert!(
        !comb.is_monotone_for_rows(FRAC_PI_4),
        "rows slanted across the teeth"
    );
}

#[test]
fn discs_of_200000_points_smooth_and_zigzag() {
    let smooth = zigzag_disc(200_000, 0.0);
    for a in [0.0, 0.3, FRAC_PI_2] {
        assert!(smooth.is_monotone_for_rows(a), "smooth disc at {a}");
    }
    // a line near the top runs along the teeth and meets many of them
    let zigzag = zigzag_disc(200_000, 0.5);
    for a in [0.0, 0.3, FRAC_PI_2] {
        assert!(!zigzag.is_monotone_for_rows(a), "zigzag disc at {a}");
    }
}

/// The sweep gives the answers of rows at many heights, on outlines that do not cross
/// themselves: a square with a hole, an L, two squares apart, a comb. (Overlapping rings
/// whose edges cross split a row between vertex heights, which neither this sweep nor the
/// slab test it replaced looks at: two overlapping squares at 5 degrees.)
#[test]
fn the_sweep_agrees_with_the_row_intervals() {
    let square = |x0: f64, y0: f64, s: f64, ccw: bool| {
        let mut p = vec![
            Point::new(x0, y0),
            Point::new(x0 + s, y0),
            Point::new(x0 + s, y0 + s),
            Point::new(x0, y0 + s),
        ];
        if !ccw {
            p.reverse();
        }
        Ring { points: p }
    };
    let shapes = [
        Shape::from_rings(vec![
            square(0.0, 0.0, 10.0, true),
            square(3.0, 3.0, 4.0, false),
        ]),
        Shape::from_rings(vec![Ring {
            points: [
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 4.0),
                (4.0, 4.0),
                (4.0, 10.0),
                (0.0, 10.0),
            ]
            .iter()
            .map(|&(x, y)| Point::new(x, y))
            .collect(),
        }]),
        Shape::from_rings(vec![
            square(0.0, 0.0, 10.0, true),
            square(12.0, 2.0, 3.0, true),
        ]),
        comb_square(50, 2.0),
    ];
    for (i, s) in shapes.iter().enumerate() {
        for k in 0..36 {
            let a = k as f64 * PI / 36.0;
            // a brute force: rows at many heights of the rotated shape, each meeting one piece
            let r = s.rotated(-a);
            let b = r.bbox();
            let one = (1..4000).all(|j| {
                let y = b.y0 + b.height() * j as f64 / 4000.0;
                r.intervals_at(y).len() <= 1
            });
            assert_eq!(s.is_monotone_for_rows(a), one, "shape {i} at {k} x 5 deg");
        }
    }
}
