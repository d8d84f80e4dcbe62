//! The drawing corpus (`planner/corpus/`, issue 26): its README lists every drawing, every
//! drawing is read by the planner's reader without a panic (one-piece drawings as a shape,
//! the stroke-only one refused as bad input), and the corpus report's own empty-region
//! measure (`benches/corpus/empty_region.rs`) finds what a hand-made plan leaves empty. The
//! report itself (every drawing planned at four counts) is a benchmark, too slow for tests.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

#[path = "common/drawings.rs"]
mod drawings;
#[path = "../benches/corpus/empty_region.rs"]
#[allow(dead_code)]
mod empty_region;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use foldchain_planner::kurbo::Point;
use foldchain_planner::{PlanError, Ring, Shape};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus")
}

/// The README's table rows: (file, one piece).
fn listed() -> Vec<(String, bool)> {
    let readme = std::fs::read_to_string(corpus().join("README.md")).unwrap();
    readme
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((name.to_string(), *cells.get(2)? == "yes"))
        })
        .collect()
}

/// Every SVG file under the corpus (but its tools).
fn files() -> BTreeSet<String> {
    drawings::corpus_files(&corpus())
}

#[test]
fn the_readme_lists_every_drawing_once() {
    let listed = listed();
    let names: BTreeSet<String> = listed.iter().map(|(n, _)| n.clone()).collect();
    assert_eq!(names.len(), listed.len(), "a drawing listed twice");
    assert_eq!(names, files(), "README and files differ");
    assert!(names.len() >= 40, "{} drawings", names.len());
    let letters = names.iter().filter(|n| n.starts_with("letters/")).count();
    assert_eq!(letters, 26);
}

#[test]
fn every_drawing_is_read_without_a_panic() {
    for (name, one_piece) in listed() {
        let data = std::fs::read(corpus().join(&name)).unwrap();
        match Shape::from_svg_data(&data, &name) {
            Ok(shape) => assert!(shape.area() > 0.0, "{name}"),
            // a one-piece drawing must be read; the others may be refused, as bad input
            Err(e) => {
                assert!(!one_piece, "{name}: {e}");
                assert!(e.is_bad_input(), "{name}: {e}");
            }
        }
    }
}

#[test]
fn a_stroke_only_drawing_is_refused_with_the_reason() {
    let name = "icons/ion-heart-outline.svg";
    let data = std::fs::read(corpus().join(name)).unwrap();
    let e = Shape::from_svg_data(&data, name).unwrap_err();
    assert!(matches!(e, PlanError::NoFilledArea { .. }), "{e}");
    assert!(e.to_string().contains("strokes do not count"), "{e}");
}

/// Tile centres in SVG user units (y down) on a square grid of spacing `w` over
/// `[x0, x1] x [y0, y1]`.
fn grid(x0: f64, x1: f64, y0: f64, y1: f64, w: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut y = y0;
    while y <= y1 + 1e-9 {
        let mut x = x0;
        while x <= x1 + 1e-9 {
            out.push((x, y));
            x += w;
        }
        y += w;
    }
    out
}

/// A rectangle 20 w by 10 w drawn in SVG (y down from 0 to 10 w); tiles over its left half
/// only. The empty region is the right half less the margins: x from the last column plus
/// 0.95 w (less the scallops between centres) to 19.5 w, y from 0.5 w to 9.5 w.
#[test]
fn the_measure_finds_the_half_a_plan_leaves_empty() {
    let w = 3.0;
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{a}" height="{b}"><rect width="{a}" height="{b}"/></svg>"#,
        a = 20.0 * w,
        b = 10.0 * w
    );
    let shape = Shape::from_svg_data(svg.as_bytes(), "rect.svg").unwrap();
    let half = grid(0.5 * w, 9.5 * w, 0.5 * w, 9.5 * w, w);
    let r = empty_region::measure(&shape, &half, w, false)
        .largest
        .unwrap();
    let tile = empty_region::tile_area() * w * w;
    // the whole band right of the last column's reach; the scallops add at most a strip
    let x_from = 9.5 * w + empty_region::REACH * w;
    let exact = (19.5 * w - x_from) * 9.0 * w / tile;
    let with_scallops = (19.5 * w - 9.5 * w - (0.95f64.powi(2) - 0.25).sqrt() * w) * 9.0 * w / tile;
    // grid points stand for squares of side w/8: the area is good to the region's perimeter
    // (about 36 w) times w/16, under 3 tile areas
    assert!(
        r.tiles > exact - 3.0 && r.tiles < with_scallops + 3.0,
        "{} tile areas, expected {exact:.1} to {with_scallops:.1}",
        r.tiles
    );
    // the region's centre is on the right, in SVG coordinates (y down, mid-height)
    assert!(
        r.centre.0 > 14.0 * w && r.centre.0 < 15.5 * w,
        "{:?}",
        r.centre
    );
    assert!((r.centre.1 - 5.0 * w).abs() < 0.2 * w, "{:?}", r.centre);
    // tiles over all of it leave nothing empty
    let full = grid(0.5 * w, 19.5 * w, 0.5 * w, 9.5 * w, w);
    assert_eq!(empty_region::measure(&shape, &full, w, false).largest, None);
}

/// Two squares 10 w wide, 10 w apart, tiles over the left one only: measured as one
/// drawing the right square is the largest empty region; measured as a drawing with
/// islands it is left out, its area reported apart, and nothing is empty. A piece that a
/// tile centre lies in stays measured: tiles over the left square and one in the right one
/// leave the rest of the right one empty either way.
#[test]
fn the_measure_leaves_out_islands_only_when_asked() {
    let w = 2.0;
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{c}" height="{a}"><rect width="{a}" height="{a}"/><rect x="{b}" width="{a}" height="{a}"/></svg>"#,
        a = 10.0 * w,
        b = 20.0 * w,
        c = 30.0 * w
    );
    let shape = Shape::from_svg_data(svg.as_bytes(), "two.svg").unwrap();
    let left = grid(0.5 * w, 9.5 * w, 0.5 * w, 9.5 * w, w);
    let tile = empty_region::tile_area();
    // the right square's inner 9 w x 9 w, in tile areas
    let inner = 81.0 / tile;
    let whole = empty_region::measure(&shape, &left, w, false);
    let r = whole.largest.unwrap();
    assert!(
        (r.tiles - inner).abs() < 0.05 * inner,
        "{} vs {inner}",
        r.tiles
    );
    assert_eq!(whole.left_out_tiles, 0.0);
    let islands = empty_region::measure(&shape, &left, w, true);
    assert_eq!(islands.largest, None);
    let square = 100.0 / tile;
    assert!(
        (islands.left_out_tiles - square).abs() < 0.05 * square,
        "{} vs {square}",
        islands.left_out_tiles
    );
    // one tile at the right square's corner: that piece is measured
    let mut reached = left.clone();
    reached.push((20.5 * w, 0.5 * w));
    let m = empty_region::measure(&shape, &reached, w, true);
    assert_eq!(m.left_out_tiles, 0.0);
    assert!(m.largest.unwrap().tiles > 0.8 * inner, "{:?}", m.largest);
}

/// The shape held y-up and the poses y-down: centres given in the wrong frame (y up) lie
/// outside the shape and leave all of it empty, so the frames are told apart.
#[test]
fn the_measure_maps_poses_into_the_shape_frame() {
    let w = 1.0;
    // the rectangle [0, 12] x [0, 6] in SVG units, held y-up as [0, 12] x [-6, 0]
    let shape = Shape::from_rings(vec![Ring {
        points: vec![
            Point::new(0.0, -6.0),
            Point::new(12.0, -6.0),
            Point::new(12.0, 0.0),
            Point::new(0.0, 0.0),
        ],
    }]);
    let svg_frame = grid(0.5, 11.5, 0.5, 5.5, w);
    assert_eq!(
        empty_region::measure(&shape, &svg_frame, w, false).largest,
        None
    );
    let wrong: Vec<(f64, f64)> = svg_frame.iter().map(|&(x, y)| (x, -y)).collect();
    let r = empty_region::measure(&shape, &wrong, w, false)
        .largest
        .unwrap();
    // all of the inner 11 x 5 rectangle
    let inner = 11.0 * 5.0 / empty_region::tile_area();
    assert!(
        (r.tiles - inner).abs() < 0.05 * inner,
        "{} vs {inner}",
        r.tiles
    );
}

/// A hole is not an empty region: the margin is kept from every outline, holes' too.
#[test]
fn holes_are_not_counted_as_empty() {
    let w = 1.0;
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="20"><path fill-rule="evenodd" d="M0 0H20V20H0Z M6 6H14V14H6Z"/></svg>"#;
    let shape = Shape::from_svg_data(svg.as_bytes(), "frame.svg").unwrap();
    // tiles on the frame only (rows 0.5..5.5 and 14.5..19.5, columns likewise)
    let centres: Vec<(f64, f64)> = grid(0.5, 19.5, 0.5, 19.5, w)
        .into_iter()
        .filter(|&(x, y)| !(6.0..=14.0).contains(&x) || !(6.0..=14.0).contains(&y))
        .collect();
    assert_eq!(
        empty_region::measure(&shape, &centres, w, false).largest,
        None
    );
}
