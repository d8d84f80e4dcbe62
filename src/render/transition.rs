//! The transition diagram (thesis figure 6.3): each magnet's position along the chain
//! against time, for a range of tiles. Positions are in the straight frame, arc length along
//! the path from the rest point (so a curved path shows its full travel); dashed lines mark
//! tile edges, dots where a magnet starts and ticks where it starts the next one.

use std::fmt::Write;

use crate::engine::{EventKind, Timeline};
use crate::render::n;
use crate::render::plot::Axes;

/// The diagram for tiles `first..=last` (clamped to the chain).
pub fn transition_svg(tl: &Timeline, first: usize, last: usize, title: &str) -> String {
    let tiles = tl.tiles();
    let last = last.min(tiles - 1);
    let first = first.min(last);
    let w = tl.geometry.w;
    let (k0, k1) = (2 * first, 2 * last + 1);
    let end_time = (k0..=k1)
        .filter_map(|k| tl.arrival_of(k))
        .fold(0.0, f64::max)
        .max(1e-9);
    let t1 = end_time * 1.08;
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
    let mut s = ax.open(title, "time (s)", "position along the chain (mm)");
    for i in first..=last + 1 {
        let y = ax.py(i as f64 * w - 0.5 * w);
        let _ = writeln!(
            s,
            r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#888" stroke-dasharray="4 3"/>"##,
            n(ax.left),
            n(ax.left + ax.width),
            y = n(y)
        );
    }
    for k in k0..=k1 {
        let tile = k / 2;
        let dir = if k % 2 == 0 { -1.0 } else { 1.0 };
        let rest = tile as f64 * w + tl.geometry.path(k).rest().0;
        let pos = |t: f64| rest + dir * tl.travel_at(k, t);
        let colour = if k % 2 == 0 { "#d93025" } else { "#188038" };
        let mut pts = vec![(0.0, rest)];
        if let (Some(s0), Some(a)) = (tl.start_of(k), tl.arrival_of(k)) {
            pts.push((s0, rest));
            for i in 1..=48 {
                let t = s0 + (a - s0) * i as f64 / 48.0;
                pts.push((t, pos(t)));
            }
        }
        pts.push((t1, pos(t1)));
        let d: Vec<String> = pts
            .iter()
            .map(|&(t, y)| format!("{},{}", n(ax.px(t)), n(ax.py(y))))
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="2"/>"#,
            d.join(" ")
        );
        if let Some(s0) = tl.start_of(k) {
            let _ = writeln!(
                s,
                r#"<circle cx="{}" cy="{}" r="3.5" fill="{colour}"/>"#,
                n(ax.px(s0)),
                n(ax.py(rest))
            );
        }
    }
    for e in &tl.events {
        let k = e.index as usize;
        if e.kind == EventKind::TriggerReached && (k0..=k1).contains(&k) {
            let tile = k / 2;
            let dir = if k % 2 == 0 { -1.0 } else { 1.0 };
            let y = tile as f64 * w + tl.geometry.path(k).rest().0 + dir * tl.travel_at(k, e.time);
            let _ = writeln!(
                s,
                r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#7b1fa2" stroke-width="2"/>"##,
                n(ax.py(y) - 6.0),
                n(ax.py(y) + 6.0),
                x = n(ax.px(e.time))
            );
        }
    }
    let _ = writeln!(
        s,
        r##"<text x="{}" y="{}" fill="#444">red/green: magnets by pole; dot: starts; purple tick: starts the next magnet; dashed: tile edges</text>"##,
        n(ax.left),
        n(ax.top + ax.height + 48.0)
    );
    s.push_str("</svg>\n");
    s
}
