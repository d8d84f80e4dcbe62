//! The design search's trade-off as a picture: folding probability against assembly time,
//! one line per wall over the grid's `s` (one `s` for every tile), the base design and the
//! chosen design marked.

use svg::node::element::{Circle, Polyline, Text};
use svg::Document;

use foldchain::tolerance::{Candidate, Search};

use crate::axes::Axes;
use crate::{num, plot_line, points, to_text};

const COLOURS: [&str; 5] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"];

/// The SVG text of the trade-off of `search` (target probability `target`).
pub fn tradeoff_svg(search: &Search, target: f64, title: &str) -> String {
    let diagonal: Vec<&Candidate> = search
        .candidates
        .iter()
        .filter(|c| c.s_straight == c.s_turn && c.assembly_s.is_some())
        .collect();
    let axes = time_axes(search, &diagonal);
    let mut doc = axes.open(
        title,
        "assembly time (event engine), s",
        "folding probability",
    );
    // the target
    doc = doc.add(
        Polyline::new()
            .set(
                "points",
                points([
                    (axes.px(axes.x0), axes.py(target)),
                    (axes.px(axes.x1), axes.py(target)),
                ]),
            )
            .set("stroke", "#888")
            .set("stroke-dasharray", "6 4")
            .set("fill", "none"),
    );
    doc = wall_lines(doc, &axes, &diagonal);
    doc = mark(doc, &axes, &search.base, "base design", "#000");
    if let Some(b) = &search.best {
        let label = format!(
            "chosen: s {} / {} mm, wall {:+.2}",
            b.s_straight, b.s_turn, b.wall_step
        );
        doc = mark(doc, &axes, b, &label, "#e377c2");
    }
    to_text(&doc)
}

/// The axes: assembly time over every candidate drawn (and the base and best), probability
/// from 0 to 1.
fn time_axes(search: &Search, diagonal: &[&Candidate]) -> Axes {
    let times = diagonal
        .iter()
        .copied()
        .chain(search.best.iter())
        .filter_map(|c| c.assembly_s);
    let (mut t0, mut t1) = (f64::INFINITY, f64::NEG_INFINITY);
    for t in times.chain(search.base.assembly_s) {
        t0 = t0.min(t);
        t1 = t1.max(t);
    }
    if !t0.is_finite() {
        (t0, t1) = (0.0, 1.0);
    }
    let pad = 0.05 * (t1 - t0).max(1e-9);
    Axes {
        x0: (t0 - pad).max(0.0),
        x1: t1 + pad,
        y0: 0.0,
        y1: 1.0,
        left: 70.0,
        top: 40.0,
        width: 640.0,
        height: 400.0,
    }
}

/// One line per wall over the grid's `s`, its points labelled with `s` (an infeasible one
/// hollow), and the legend.
fn wall_lines(mut doc: Document, axes: &Axes, diagonal: &[&Candidate]) -> Document {
    let mut walls: Vec<f64> = diagonal.iter().map(|c| c.wall_step).collect();
    walls.sort_by(f64::total_cmp);
    walls.dedup();
    for (i, w) in walls.iter().enumerate() {
        let colour = COLOURS[i % COLOURS.len()];
        let mut line: Vec<&&Candidate> = diagonal.iter().filter(|c| c.wall_step == *w).collect();
        line.sort_by(|a, b| a.s_straight.total_cmp(&b.s_straight));
        let pts: Vec<(f64, f64)> = line
            .iter()
            .filter_map(|c| Some((axes.px(c.assembly_s?), axes.py(c.probability))))
            .collect();
        doc = doc.add(plot_line(pts.iter().copied(), colour, "1.5"));
        for (c, p) in line.iter().zip(&pts) {
            doc = doc
                .add(
                    Circle::new()
                        .set("cx", num(p.0))
                        .set("cy", num(p.1))
                        .set("r", "3")
                        .set(
                            "fill",
                            if c.infeasible.is_some() {
                                "white"
                            } else {
                                colour
                            },
                        )
                        .set("stroke", colour),
                )
                .add(
                    Text::new(format!("{}", c.s_straight))
                        .set("x", num(p.0 + 5.0))
                        .set("y", num(p.1 - 5.0))
                        .set("font-size", "10")
                        .set("fill", colour),
                );
        }
        doc = doc.add(
            Text::new(format!("wall {w:+.2} mm (labels: s, mm)"))
                .set("x", num(axes.left + 10.0))
                .set("y", num(axes.top + 0.45 * axes.height + 16.0 * i as f64))
                .set("fill", colour),
        );
    }
    doc
}

/// A ringed candidate with its label (left of it near the right edge).
fn mark(mut doc: Document, axes: &Axes, c: &Candidate, label: &str, colour: &str) -> Document {
    if let Some(t) = c.assembly_s {
        let (x, y) = (axes.px(t), axes.py(c.probability));
        doc = doc.add(
            Circle::new()
                .set("cx", num(x))
                .set("cy", num(y))
                .set("r", "7")
                .set("fill", "none")
                .set("stroke", colour)
                .set("stroke-width", "2"),
        );
        let right = x > axes.left + 0.6 * axes.width;
        doc = doc.add(
            Text::new(label.to_string())
                .set("x", num(if right { x - 9.0 } else { x + 9.0 }))
                .set("y", num(y + 20.0))
                .set("text-anchor", if right { "end" } else { "start" })
                .set("font-size", "11")
                .set("fill", colour),
        );
    }
    doc
}
