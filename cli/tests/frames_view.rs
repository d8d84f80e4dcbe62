//! `fold-run --frames-view`: fixed frames share one view holding the whole run; automatic
//! frames of a long chain show the part that moves, tiles wide enough to see.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::Path;

mod common;
use common::{names, scratch, stderr, tool};

fn run(chain: &str, out: &Path, extra: &[&str]) {
    let o = tool("fold-run")
        .args([chain, "--out", out.to_str().unwrap()])
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}

/// The numbers of attribute `name` on every element that has it.
fn attribute_numbers(svg: &str, name: &str) -> Vec<Vec<f64>> {
    let key = format!(" {name}=\"");
    svg.match_indices(&key)
        .map(|(i, _)| {
            let rest = &svg[i + key.len()..];
            rest[..rest.find('"').unwrap()]
                .split([' ', ','])
                .filter(|s| !s.is_empty())
                .filter_map(|s| s.parse().ok())
                .collect()
        })
        .collect()
}

fn size(svg: &str) -> (f64, f64) {
    (
        attribute_numbers(svg, "width")[0][0],
        attribute_numbers(svg, "height")[0][0],
    )
}

fn frames(dir: &Path) -> Vec<String> {
    names(dir)
        .iter()
        .filter(|n| n.starts_with("step-"))
        .map(|n| std::fs::read_to_string(dir.join(n)).unwrap())
        .collect()
}

#[test]
fn fixed_frames_share_one_view_that_holds_every_tile() {
    let d = scratch("fixed");
    run("SSLLSS", &d, &["--frames", "6", "--frames-view", "fixed"]);
    let all = frames(&d);
    assert_eq!(all.len(), 6);
    let first = size(&all[0]);
    for svg in &all {
        assert_eq!(size(svg), first);
        // every tile outline inside the picture (the last 40 px hold the time stamp)
        for pts in attribute_numbers(svg, "points") {
            for xy in pts.chunks(2) {
                assert!((0.0..=first.0).contains(&xy[0]), "x {}", xy[0]);
                assert!((0.0..=first.1 - 40.0).contains(&xy[1]), "y {}", xy[1]);
            }
        }
    }
    // automatic frames of the same run follow the chain: their sizes differ
    let a = scratch("auto-short");
    run("SSLLSS", &a, &["--frames", "6"]);
    let sizes: Vec<_> = frames(&a).iter().map(|s| size(s)).collect();
    assert!(sizes.iter().any(|s| *s != sizes[0]), "{sizes:?}");
    std::fs::remove_dir_all(&d).unwrap();
    std::fs::remove_dir_all(&a).unwrap();
}

#[test]
fn automatic_frames_of_a_long_chain_show_the_part_that_moves() {
    let d = scratch("auto-long");
    // 1,000 tiles: seen whole, a tile would be under 1 px wide in a 900 px frame
    run("S*400 L L S*400 R R S*195", &d, &["--frames", "4"]);
    let all = frames(&d);
    assert_eq!(all.len(), 4);
    for svg in &all[..3] {
        assert!(
            svg.contains("the part that moves: tiles"),
            "{}",
            &svg[..200]
        );
        let (w, _) = size(svg);
        // octagon outlines drawn in detail, each at least 8 px across
        let outlines: Vec<Vec<f64>> = attribute_numbers(svg, "points")
            .into_iter()
            .filter(|p| p.len() == 16)
            .collect();
        assert!(
            outlines.len() >= 20 && outlines.len() <= 400,
            "{}",
            outlines.len()
        );
        for o in &outlines {
            let xs: Vec<f64> = o.iter().step_by(2).copied().collect();
            let span = xs.iter().cloned().fold(f64::MIN, f64::max)
                - xs.iter().cloned().fold(f64::MAX, f64::min);
            assert!(span >= 8.0 && span < w, "{span}");
        }
        // magnets are drawn (circles beyond the RI)
        assert!(svg.matches("<circle").count() > 20);
    }
    std::fs::remove_dir_all(&d).unwrap();
}
