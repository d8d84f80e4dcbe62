//! Axes of a line plot: data ranges mapped to pixels, a frame with round ticks and light grid
//! lines, shared by every plot of the crate (energy curves, transition diagram, trade-off).

use svg::node::element::{Line, Rectangle, Text};
use svg::Document;

use crate::{document, num};

/// A plot area: data ranges mapped to pixels.
pub(crate) struct Axes {
    /// Data x at the left edge of the plot area.
    pub x0: f64,
    /// Data x at the right edge.
    pub x1: f64,
    /// Data y at the bottom edge.
    pub y0: f64,
    /// Data y at the top edge.
    pub y1: f64,
    /// Pixels from the picture's left edge to the plot area.
    pub left: f64,
    /// Pixels from the picture's top edge to the plot area.
    pub top: f64,
    /// Width of the plot area, pixels.
    pub width: f64,
    /// Height of the plot area, pixels.
    pub height: f64,
}

impl Axes {
    /// The pixel column of data x.
    pub fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x0) / (self.x1 - self.x0).max(1e-300) * self.width
    }

    /// The pixel row of data y.
    pub fn py(&self, y: f64) -> f64 {
        self.top + self.height - (y - self.y0) / (self.y1 - self.y0).max(1e-300) * self.height
    }

    /// A document holding the frame, grid, ticks, labels and title, to draw the data on.
    pub fn open(&self, title: &str, xlabel: &str, ylabel: &str) -> Document {
        let (wt, ht) = (self.left + self.width + 30.0, self.top + self.height + 50.0);
        let mut doc = document(wt, ht, "white")
            .set("font-size", "12")
            .add(
                Text::new(title)
                    .set("x", num(self.left + 0.5 * self.width))
                    .set("y", "20")
                    .set("font-size", "14")
                    .set("text-anchor", "middle"),
            )
            .add(
                Rectangle::new()
                    .set("x", num(self.left))
                    .set("y", num(self.top))
                    .set("width", num(self.width))
                    .set("height", num(self.height))
                    .set("fill", "none")
                    .set("stroke", "#333"),
            );
        for v in ticks(self.x0, self.x1) {
            let x = self.px(v);
            doc = doc
                .add(grid_line((x, self.top), (x, self.top + self.height)))
                .add(
                    Text::new(fmt_tick(v))
                        .set("x", num(x))
                        .set("y", num(self.top + self.height + 16.0))
                        .set("text-anchor", "middle"),
                );
        }
        for v in ticks(self.y0, self.y1) {
            let y = self.py(v);
            doc = doc
                .add(grid_line((self.left, y), (self.left + self.width, y)))
                .add(
                    Text::new(fmt_tick(v))
                        .set("x", num(self.left - 6.0))
                        .set("y", num(y + 4.0))
                        .set("text-anchor", "end"),
                );
        }
        doc.add(
            Text::new(xlabel)
                .set("x", num(self.left + 0.5 * self.width))
                .set("y", num(self.top + self.height + 36.0))
                .set("text-anchor", "middle"),
        )
        .add(
            Text::new(ylabel)
                .set(
                    "transform",
                    format!(
                        "translate(16,{}) rotate(-90)",
                        num(self.top + 0.5 * self.height)
                    ),
                )
                .set("text-anchor", "middle"),
        )
    }
}

/// A light grid line between two pixel positions.
fn grid_line(from: (f64, f64), to: (f64, f64)) -> Line {
    Line::new()
        .set("x1", num(from.0))
        .set("y1", num(from.1))
        .set("x2", num(to.0))
        .set("y2", num(to.1))
        .set("stroke", "#ddd")
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
