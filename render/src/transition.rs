//! The transition diagram (thesis figure 6.3): each magnet's position along the chain
//! against time, for a range of tiles. Positions are in the straight frame, arc length along
//! the path from the rest point (so a curved path shows its full travel); dashed lines mark
//! tile edges, dots where a magnet starts and ticks where it starts the next one.

use svg::node::element::{Circle, Line, Text};

use foldchain::timeline::{Geometry, TransitionData};

use crate::axes::Axes;
use crate::{num, plot_line, to_text};

/// The diagram of `data`, with paths and tile width from `geometry`.
pub fn transition_svg(geometry: &Geometry, data: &TransitionData, title: &str) -> String {
    let (first, last) = (data.first, data.last);
    let w = geometry.w;
    let t1 = data.t1;
    let ax = Axes {
        x0: 0.0,
        x1: t1,
        y0: first as f64 * w - 0.5 * w,
        y1: last as f64 * w + 0.5 * w,
        left: 80.0,
        top: 34.0,
        width: 640.0,
        height: (60.0 * (last - first + 1) as f64).clamp(240.0, 900.0),
    };
    let mut doc = ax.open(title, "time (s)", "position along the chain (mm)");
    for i in first..=last + 1 {
        let y = num(ax.py(i as f64 * w - 0.5 * w));
        doc = doc.add(
            Line::new()
                .set("x1", num(ax.left))
                .set("y1", y.clone())
                .set("x2", num(ax.left + ax.width))
                .set("y2", y)
                .set("stroke", "#888")
                .set("stroke-dasharray", "4 3"),
        );
    }
    // position along the chain of magnet `k` after travelling `u` from its rest point
    let position = |k: usize, u: f64| {
        let dir = if k % 2 == 0 { -1.0 } else { 1.0 };
        (k / 2) as f64 * w + geometry.path(k).rest().0 + dir * u
    };
    for (i, track) in data.tracks.iter().enumerate() {
        let k = 2 * first + i;
        let colour = if k % 2 == 0 { "#d93025" } else { "#188038" };
        let pts = track
            .travel
            .iter()
            .map(|&(t, u)| (ax.px(t), ax.py(position(k, u))));
        doc = doc.add(plot_line(pts, colour, "2"));
        if let Some(s0) = track.start {
            doc = doc.add(
                Circle::new()
                    .set("cx", num(ax.px(s0)))
                    .set("cy", num(ax.py(position(k, 0.0))))
                    .set("r", "3.5")
                    .set("fill", colour),
            );
        }
    }
    for &(k, time, u) in &data.triggers {
        let (x, y) = (num(ax.px(time)), ax.py(position(k, u)));
        doc = doc.add(
            Line::new()
                .set("x1", x.clone())
                .set("y1", num(y - 6.0))
                .set("x2", x)
                .set("y2", num(y + 6.0))
                .set("stroke", "#7b1fa2")
                .set("stroke-width", "2"),
        );
    }
    doc = doc.add(
        Text::new(
            "red/green: magnets by pole; dot: starts; purple tick: starts the next magnet; \
             dashed: tile edges",
        )
        .set("x", num(ax.left))
        .set("y", num(ax.top + ax.height + 48.0))
        .set("fill", "#444"),
    );
    to_text(&doc)
}
