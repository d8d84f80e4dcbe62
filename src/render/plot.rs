//! Line plots with axes: the energy curve (thesis figure 7.5), and the axes shared with the
//! transition diagram.

use std::fmt::Write;

use crate::engine::{EnergySample, FoldRecord};
use crate::render::{esc, n};

/// A plot area: data ranges mapped to pixels.
pub(crate) struct Axes {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
    pub left: f64,
    pub top: f64,
    pub width: f64,
    pub height: f64,
}

impl Axes {
    pub fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x0) / (self.x1 - self.x0).max(1e-300) * self.width
    }
    pub fn py(&self, y: f64) -> f64 {
        self.top + self.height - (y - self.y0) / (self.y1 - self.y0).max(1e-300) * self.height
    }

    /// Frame, ticks, labels and title, opening an SVG document.
    pub fn open(&self, title: &str, xlabel: &str, ylabel: &str) -> String {
        let (wt, ht) = (self.left + self.width + 30.0, self.top + self.height + 50.0);
        let mut s = String::new();
        let _ = writeln!(
            s,
            r##"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif" font-size="12">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="20" font-size="14" text-anchor="middle">{}</text>
<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
            n(wt),
            n(ht),
            n(wt),
            n(ht),
            n(self.left + 0.5 * self.width),
            esc(title),
            n(self.left),
            n(self.top),
            n(self.width),
            n(self.height)
        );
        for (v, along_x) in ticks(self.x0, self.x1)
            .into_iter()
            .map(|v| (v, true))
            .chain(ticks(self.y0, self.y1).into_iter().map(|v| (v, false)))
        {
            if along_x {
                let x = self.px(v);
                let _ = writeln!(
                    s,
                    r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">{}</text>"##,
                    n(self.top),
                    n(self.top + self.height),
                    n(self.top + self.height + 16.0),
                    fmt_tick(v),
                    x = n(x)
                );
            } else {
                let y = self.py(v);
                let _ = writeln!(
                    s,
                    r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">{}</text>"##,
                    n(self.left),
                    n(self.left + self.width),
                    n(self.left - 6.0),
                    n(y + 4.0),
                    fmt_tick(v),
                    y = n(y)
                );
            }
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text><text transform="translate(16,{}) rotate(-90)" text-anchor="middle">{}</text>"#,
            n(self.left + 0.5 * self.width),
            n(self.top + self.height + 36.0),
            esc(xlabel),
            n(self.top + 0.5 * self.height),
            esc(ylabel)
        );
        s
    }
}

/// About six round tick values covering `[a, b]`.
pub(crate) fn ticks(a: f64, b: f64) -> Vec<f64> {
    if b.partial_cmp(&a) != Some(std::cmp::Ordering::Greater) || !a.is_finite() || !b.is_finite() {
        return vec![a];
    }
    let raw = (b - a) / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let mut v = (a / step).ceil() * step;
    let mut out = Vec::new();
    while v <= b + 1e-9 * step && out.len() < 20 {
        out.push(if v.abs() < 1e-12 * step { 0.0 } else { v });
        v += step;
    }
    out
}

fn fmt_tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

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
    let mut s = ax.open(title, "time (s)", "total dipole energy (mJ)");
    // shade at most 200 fold windows
    for f in folds.iter().take(200) {
        let end = if f.end.is_nan() { t1 } else { f.end };
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#1a56b8" fill-opacity="0.08"/>"##,
            n(ax.px(f.start)),
            n(ax.top),
            n((ax.px(end) - ax.px(f.start)).max(0.5)),
            n(ax.height)
        );
    }
    let pts: Vec<String> = curve
        .iter()
        .zip(&ys)
        .map(|(c, &y)| format!("{},{}", n(ax.px(c.time)), n(ax.py(y))))
        .collect();
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#c5221f" stroke-width="2"/>"##,
        pts.join(" ")
    );
    if !folds.is_empty() {
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" fill="#1a56b8">shaded: folds turning</text>"##,
            n(ax.left + 8.0),
            n(ax.top + 16.0)
        );
    }
    s.push_str("</svg>\n");
    s
}
