//! One frame of a run: tiles at their poses, paths, magnets, hinges and the RI, with moving
//! parts and a collision highlighted and a time stamp. It draws a [`ChainState`], so the
//! event engine and the reference integrator share it.
//!
//! Chains longer than [`DETAIL_TILES`] are drawn lean: the chain as one thick polyline
//! through the tile centres (straight runs merged into one segment), the tiles near moving
//! magnets over it, and no magnets or paths, so a frame of a 100,000-tile chain stays a few
//! megabytes at most.

use std::fmt::Write;

use crate::engine::Geometry;
use crate::render::{esc, n, ChainState};
use crate::{Octagon, Pose};

/// Chains up to this many tiles are drawn in detail (outlines, paths, magnets, hinges).
pub const DETAIL_TILES: usize = 400;

/// The view box shared by all frames of a run, in world mm: `(min x, min y, max x, max y)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameView {
    /// Bounds in world mm.
    pub bounds: (f64, f64, f64, f64),
}

impl FrameView {
    /// A view holding every pose in `poses` (tile centres), padded by a tile.
    pub fn around(poses: impl IntoIterator<Item = Pose>, w: f64) -> FrameView {
        let mut b = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for p in poses {
            b = (b.0.min(p.x), b.1.min(p.y), b.2.max(p.x), b.3.max(p.y));
        }
        if !b.0.is_finite() {
            b = (0.0, 0.0, 0.0, 0.0);
        }
        let pad = 1.2 * w;
        FrameView {
            bounds: (b.0 - 2.0 * pad, b.1 - pad, b.2 + pad, b.3 + pad),
        }
    }

    /// Grows the view to hold another.
    pub fn union(self, o: FrameView) -> FrameView {
        let (a, b) = (self.bounds, o.bounds);
        FrameView {
            bounds: (a.0.min(b.0), a.1.min(b.1), a.2.max(b.2), a.3.max(b.3)),
        }
    }
}

/// What to draw in a frame.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct FrameOptions {
    /// Title line (the run's name).
    pub title: String,
    /// Tiles to draw in red (a collision), if any.
    pub collision: Option<(usize, usize)>,
    /// A note under the time stamp (e.g. the outcome on the final frame).
    pub note: Option<String>,
}

/// The SVG of the chain in `state`, with paths and magnet sizes from `geometry`.
pub fn frame_svg(
    geometry: &Geometry,
    state: &ChainState,
    view: &FrameView,
    opts: &FrameOptions,
) -> String {
    let w = geometry.w;
    let poses = &state.poses;
    let (x0, y0, x1, y1) = view.bounds;
    let (vw, vh) = (x1 - x0, y1 - y0);
    // pixel size: 900 px wide at most, at least 1 px per 0.05 mm for small chains
    let px_w = 900.0_f64.min(vw * 6.0).max(300.0);
    let scale = px_w / vw;
    let px_h = (vh * scale).max(120.0);
    let tx = |x: f64| (x - x0) * scale;
    let ty = |y: f64| (y1 - y) * scale;
    let mut s = String::with_capacity(4096);
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif">
<rect width="100%" height="100%" fill="#fbfbf8"/>
"##,
        n(px_w),
        n(px_h + 40.0),
        n(px_w),
        n(px_h + 40.0)
    );
    let moving_tile = |i: usize| state.tile_moving(i);
    let folding_joint = |j: usize| state.joint_folding(j);
    let in_collision = |i: usize| opts.collision.is_some_and(|(a, b)| a == i || b == i);
    let oct = Octagon::new(w);
    let tiles = state.tiles();
    let polygon = |s: &mut String, p: &Pose, fill: &str, stroke: &str| {
        let pts: Vec<String> = oct
            .vertices_at(p)
            .iter()
            .map(|&(x, y)| format!("{},{}", n(tx(x)), n(ty(y))))
            .collect();
        let _ = writeln!(
            s,
            r#"<polygon points="{}" fill="{fill}" stroke="{stroke}" stroke-width="{}"/>"#,
            pts.join(" "),
            n((0.04 * w * scale).clamp(0.3, 1.5))
        );
    };
    if tiles <= DETAIL_TILES {
        for (i, p) in poses.iter().enumerate() {
            let fill = if in_collision(i) {
                "#f28b82"
            } else if (i > 0 && folding_joint(i - 1)) || (i + 1 < tiles && folding_joint(i)) {
                "#c6dbf7"
            } else if moving_tile(i) {
                "#e4eefb"
            } else {
                "#e9e6df"
            };
            polygon(&mut s, p, fill, "#55524c");
        }
        let r = 0.5 * geometry.design(0).magnet_diameter;
        for (i, p) in poses.iter().enumerate() {
            for k in [2 * i, 2 * i + 1] {
                let path = geometry.path(k);
                let pts: Vec<String> = path
                    .polyline(0.5)
                    .into_iter()
                    .map(|q| {
                        let (x, y) = p.transform_point(q);
                        format!("{},{}", n(tx(x)), n(ty(y)))
                    })
                    .collect();
                let _ = writeln!(
                    s,
                    r##"<polyline points="{}" fill="none" stroke="#9c968a" stroke-width="{}" stroke-linecap="round"/>"##,
                    pts.join(" "),
                    n((2.0 * r * scale).max(1.0) * 1.1)
                );
            }
        }
        // hinges of fold joints
        for (j, pose) in poses.iter().enumerate().take(tiles.saturating_sub(1)) {
            if let Some(Some(fold)) = state.folds.get(j) {
                let (hx, hy) = oct.hinge(*fold == crate::Fold::L);
                let (x, y) = pose.transform_point((hx, hy));
                let col = if folding_joint(j) { "#1a56b8" } else { "#333" };
                let _ = writeln!(
                    s,
                    r#"<circle cx="{}" cy="{}" r="{}" fill="{col}"/>"#,
                    n(tx(x)),
                    n(ty(y)),
                    n((0.06 * w * scale).max(1.5))
                );
            }
        }
        for (k, &(x, y)) in state.magnets.iter().enumerate() {
            let fill = if k % 2 == 0 { "#d93025" } else { "#188038" };
            let moving = state.moving.get(k).copied().unwrap_or(false);
            let _ = writeln!(
                s,
                r##"<circle cx="{}" cy="{}" r="{}" fill="{fill}" stroke="{}" stroke-width="{}"/>"##,
                n(tx(x)),
                n(ty(y)),
                n((r * scale).max(1.0)),
                if moving { "#ff9800" } else { "#222" },
                if moving {
                    n((0.5 * r * scale).max(1.5))
                } else {
                    "0.5".into()
                }
            );
        }
    } else {
        // lean: one thick polyline through the centres, collinear runs merged
        let mut pts: Vec<(f64, f64)> = Vec::new();
        for p in poses {
            let q = (p.x, p.y);
            if pts.len() >= 2 {
                let a = pts[pts.len() - 2];
                let b = pts[pts.len() - 1];
                let cross = (b.0 - a.0) * (q.1 - b.1) - (b.1 - a.1) * (q.0 - b.0);
                let dot = (b.0 - a.0) * (q.0 - b.0) + (b.1 - a.1) * (q.1 - b.1);
                if cross.abs() < 1e-9 * w * w && dot > 0.0 {
                    let last = pts.len() - 1;
                    pts[last] = q;
                    continue;
                }
            }
            pts.push(q);
        }
        let d: Vec<String> = pts
            .iter()
            .map(|&(x, y)| format!("{},{}", n(tx(x)), n(ty(y))))
            .collect();
        let _ = writeln!(
            s,
            r##"<polyline points="{}" fill="none" stroke="#b9b3a6" stroke-width="{}" stroke-linejoin="round" stroke-linecap="round"/>"##,
            d.join(" "),
            n((w * scale).max(1.0))
        );
        let mut shown = 0;
        for (i, p) in poses.iter().enumerate() {
            if shown < 2000 && (moving_tile(i) || in_collision(i)) {
                let fill = if in_collision(i) {
                    "#f28b82"
                } else {
                    "#c6dbf7"
                };
                polygon(&mut s, p, fill, "#55524c");
                shown += 1;
            }
        }
    }
    // the RI, held at the outer edge of tile 0
    let (rx, ry) = poses[0].transform_point(geometry.ri_position());
    let r = 0.5 * geometry.design(0).magnet_diameter;
    let _ = writeln!(
        s,
        r##"<circle cx="{}" cy="{}" r="{}" fill="#7b1fa2" stroke="#222" stroke-width="0.5"/><text x="{}" y="{}" font-size="11" text-anchor="end" fill="#7b1fa2">RI</text>"##,
        n(tx(rx)),
        n(ty(ry)),
        n((r * scale).max(1.5)),
        n(tx(rx) - (r * scale).max(1.5) - 2.0),
        n(ty(ry) + 4.0)
    );
    let moving = state.moving_count();
    let _ = writeln!(
        s,
        r##"<text x="8" y="{}" font-size="13" fill="#222">{}  t = {:.4} s  ({} moving)</text>"##,
        n(px_h + 18.0),
        esc(&opts.title),
        state.time,
        moving
    );
    if let Some(note) = &opts.note {
        let _ = writeln!(
            s,
            r##"<text x="8" y="{}" font-size="12" fill="{}">{}</text>"##,
            n(px_h + 34.0),
            if opts.collision.is_some() {
                "#c5221f"
            } else {
                "#444"
            },
            esc(note)
        );
    }
    s.push_str("</svg>\n");
    s
}
