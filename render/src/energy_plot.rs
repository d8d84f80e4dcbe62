//! The energy curve of a run (thesis figure 7.5): the chain's total dipole energy against
//! time, with the folds' windows shaded.

use svg::node::element::{Rectangle, Text};

use foldchain::timeline::{EnergySample, FoldRecord};

use crate::axes::Axes;
use crate::{num, plot_line, to_text};

/// The total dipole energy against time, with the windows of `folds` shaded (a fold that
/// never closed, `end` NaN, to the end of the curve).
pub fn energy_svg(folds: &[FoldRecord], curve: &[EnergySample], title: &str) -> String {
    let t1 = curve.last().map_or(1.0, |c| c.time).max(1e-9);
    // millijoules read better than joules
    let ys: Vec<f64> = curve.iter().map(|c| c.energy_j * 1e3).collect();
    let (mut lo, mut hi) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
            (a.min(y), b.max(y))
        });
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        lo -= 1.0;
        hi += 1.0;
    }
    let pad = 0.05 * (hi - lo);
    let ax = Axes {
        x0: 0.0,
        x1: t1,
        y0: lo - pad,
        y1: hi + pad,
        left: 80.0,
        top: 34.0,
        width: 640.0,
        height: 340.0,
    };
    let mut doc = ax.open(title, "time (s)", "total dipole energy (mJ)");
    // shade at most 200 fold windows
    for f in folds.iter().take(200) {
        let end = if f.end.is_nan() { t1 } else { f.end };
        doc = doc.add(
            Rectangle::new()
                .set("x", num(ax.px(f.start)))
                .set("y", num(ax.top))
                .set("width", num((ax.px(end) - ax.px(f.start)).max(0.5)))
                .set("height", num(ax.height))
                .set("fill", "#1a56b8")
                .set("fill-opacity", "0.08"),
        );
    }
    let pts = curve
        .iter()
        .zip(&ys)
        .map(|(c, &y)| (ax.px(c.time), ax.py(y)));
    doc = doc.add(plot_line(pts, "#c5221f", "2"));
    if !folds.is_empty() {
        doc = doc.add(
            Text::new("shaded: folds turning")
                .set("x", num(ax.left + 8.0))
                .set("y", num(ax.top + 16.0))
                .set("fill", "#1a56b8"),
        );
    }
    to_text(&doc)
}
