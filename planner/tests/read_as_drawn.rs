//! Drawings read as a browser draws them (issue 26): the corpus' logo clipped by
//! `clip-path` to a letter plans on the clipped area, checked against the drawing as
//! `rsvg-convert` (librsvg, an SVG renderer independent of usvg) renders it; the masked
//! crescent is read as the crescent.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;

use std::path::Path;
use std::process::Command;

use common::corpus;
use foldchain_planner::kurbo::Point;
use foldchain_planner::{plan_svg_file, PlanOptions, Shape};

/// The drawing rendered by rsvg-convert at `px` pixels per user unit, as (width, height,
/// alpha per pixel); `None` where rsvg-convert is missing (an error under CI, whose
/// `.ci/run` installs it).
fn render(svg: &Path, width_px: u32) -> Option<(usize, usize, Vec<u8>)> {
    let out = std::env::temp_dir().join(format!(
        "foldchain-read-as-drawn-{}.png",
        std::process::id()
    ));
    let status = Command::new("rsvg-convert")
        .arg("-w")
        .arg(width_px.to_string())
        .arg("-o")
        .arg(&out)
        .arg(svg)
        .status();
    match status {
        Ok(s) if s.success() => {}
        _ if std::env::var_os("CI").is_none() => {
            eprintln!("rsvg-convert not found: skipped (apt-get install librsvg2-bin)");
            return None;
        }
        other => panic!("rsvg-convert failed: {other:?}"),
    }
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let _ = std::fs::remove_file(&out);
    assert_eq!(info.color_type, png::ColorType::Rgba, "{info:?}");
    let (w, h) = (info.width as usize, info.height as usize);
    let alpha = buf[..w * h * 4].chunks(4).map(|p| p[3]).collect();
    Some((w, h, alpha))
}

/// At least 97% of the tile centres lie on pixels the renderer paints (the bar);
/// without the clip most of the square logo around the letter would be planned too.
#[test]
fn a_logo_clipped_to_a_letter_plans_on_the_letter() {
    let svg = corpus("inkscape/ink-clip-logo.svg");
    let plan = plan_svg_file(&svg, &PlanOptions::default().with_tiles(100)).unwrap();
    // the drawing is 80 user units wide (viewBox 0 0 80 80): 10 pixels per unit
    let Some((w, h, alpha)) = render(&svg, 800) else {
        return;
    };
    assert_eq!(w, 800, "{h}");
    let on = plan
        .poses
        .iter()
        .filter(|p| {
            let (x, y) = ((p.x * 10.0) as usize, (p.y * 10.0) as usize);
            x < w && y < h && alpha[y * w + x] > 127
        })
        .count();
    let share = on as f64 / plan.poses.len() as f64;
    assert!(
        share >= 0.97,
        "{on} of {} tile centres on the drawn area",
        plan.poses.len()
    );
    // and the area read is the drawn one: painted pixels against the shape's area
    let painted = alpha.iter().filter(|&&a| a > 127).count() as f64 / 100.0;
    let shape = Shape::from_svg_data(&std::fs::read(&svg).unwrap(), "logo").unwrap();
    let rel = (shape.area() - painted).abs() / painted;
    assert!(
        rel < 0.02,
        "read {} units^2, rendered {painted}",
        shape.area()
    );
}

/// The crescent under its mask (a white square with a black disc): the disc's bitten part
/// is not in the shape.
#[test]
fn a_masked_disc_is_read_as_its_crescent() {
    let svg = corpus("inkscape/ink-mask-crescent.svg");
    let shape = Shape::from_svg_data(&std::fs::read(&svg).unwrap(), "moon").unwrap();
    // the disc: centre (50, 50), radius 42; the bite: centre (66, 40), radius 33
    assert!(shape.contains(Point::new(20.0, -50.0)));
    assert!(!shape.contains(Point::new(66.0, -40.0)));
    let disc = std::f64::consts::PI * 42.0 * 42.0;
    assert!(shape.area() < 0.6 * disc, "{} of {disc}", shape.area());
    if let Some((w, h, alpha)) = render(&svg, 1000) {
        assert_eq!(w, 1000, "{h}");
        let painted = alpha.iter().filter(|&&a| a > 127).count() as f64 / 100.0;
        let rel = (shape.area() - painted).abs() / painted;
        assert!(
            rel < 0.02,
            "read {} units^2, rendered {painted}",
            shape.area()
        );
    }
}
