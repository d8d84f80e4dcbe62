//! One frame of a run: tiles at their poses, paths, magnets, hinges and the RI, with moving
//! parts and a collision highlighted and a time stamp. It draws a [`ChainState`], so the
//! event engine and the reference integrator share it.
//!
//! A frame shows the tiles whose centres lie in its view: up to [`ChainState::DETAIL_TILES`] of them are
//! drawn in detail; more are drawn lean: the chain as one thick polyline through the tile
//! centres (straight runs merged into one segment), the tiles near moving magnets over it,
//! and no magnets or paths, so a frame of a 100,000-tile chain stays a few megabytes at most.
//! A long chain seen whole is a hairline, so its frames can be framed on the part that
//! moves instead ([`FrameView::focus`]), where its tiles are drawn in detail.

use kurbo::{Point, Rect};
use svg::node::element::{Circle, Group, Polygon, Polyline, Text};
use svg::Document;

use foldchain::timeline::{ChainState, Geometry};
use foldchain::{Fold, Octagon, Pose};

use crate::{document, num, points, to_text};

/// Tiles drawn over the lean polyline of a long chain, at most (moving or colliding ones).
const LEAN_TILES_SHOWN: usize = 2000;

/// The width of a frame in pixels for a view of `width` mm: 900 at most, 6 per mm for
/// small chains, 300 at least.
fn page_width(width: f64) -> f64 {
    900.0_f64.min(width * 6.0).max(300.0)
}

/// The view box shared by all frames of a run, in world mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameView {
    /// Bounds in world mm (`x0, y0` the least corner).
    pub bounds: Rect,
}

impl FrameView {
    /// A view holding every pose in `poses` (tile centres), padded by a tile.
    pub fn around(poses: impl IntoIterator<Item = Pose>, w: f64) -> FrameView {
        let empty = Rect::new(
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        let mut b = poses
            .into_iter()
            .fold(empty, |b, p| b.union_pt(Point::new(p.x, p.y)));
        if !b.x0.is_finite() {
            b = Rect::ZERO;
        }
        let pad = 1.2 * w;
        FrameView {
            bounds: Rect::new(b.x0 - 2.0 * pad, b.y0 - pad, b.x1 + pad, b.y1 + pad),
        }
    }

    /// A view holding every point of `rings` (a target outline, world mm), padded by a
    /// tile; `None` when there is no point.
    pub fn around_outline(rings: &[Vec<Point>], w: f64) -> Option<FrameView> {
        let mut pts = rings.iter().flatten();
        let first = *pts.next()?;
        let b = pts.fold(Rect::from_points(first, first), |b, &p| b.union_pt(p));
        let pad = 1.2 * w;
        Some(FrameView {
            bounds: Rect::new(b.x0 - 2.0 * pad, b.y0 - pad, b.x1 + pad, b.y1 + pad),
        })
    }

    /// Grows the view to hold another.
    pub fn union(self, o: FrameView) -> FrameView {
        FrameView {
            bounds: self.bounds.union(o.bounds),
        }
    }

    /// Whether a frame of this view shows the tile at `pose` (its centre within a tile width
    /// `w` of the view).
    pub fn shows(&self, pose: &Pose, w: f64) -> bool {
        self.bounds
            .inflate(w, w)
            .contains(Point::new(pose.x, pose.y))
    }

    /// How many pixels wide a tile of width `w` is drawn in a frame of this view.
    pub fn tile_pixels(&self, w: f64) -> f64 {
        w * page_width(self.bounds.width()) / self.bounds.width()
    }

    /// A view on the part of the chain that moves in `state`: the tiles from `context`
    /// before the first to `context` after the last tile that is moving, turning or in
    /// `collision`, with their range. `None` when nothing moves.
    pub fn focus(
        state: &ChainState,
        w: f64,
        context: usize,
        collision: Option<(usize, usize)>,
    ) -> Option<(FrameView, (usize, usize))> {
        let n = state.tiles();
        let active = |i: usize| {
            state.tile_moving(i)
                || (i > 0 && state.joint_folding(i - 1))
                || state.joint_folding(i)
                || collision.is_some_and(|(a, b)| a == i || b == i)
        };
        let first = (0..n).find(|&i| active(i))?;
        let last = (0..n).rev().find(|&i| active(i))?;
        let range = (first.saturating_sub(context), (last + context).min(n - 1));
        let view = FrameView::around(state.poses[range.0..=range.1].iter().copied(), w);
        Some((view, range))
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
    /// The target outline the chain was planned to fill, in world mm (rings), drawn dashed
    /// under the tiles; empty when there is none.
    pub target: Vec<Vec<Point>>,
}

/// World millimetres to the picture's pixels (y down).
struct PageMap {
    /// The world bounds shown.
    view: Rect,
    /// Pixels per millimetre.
    scale: f64,
}

impl PageMap {
    fn x(&self, x: f64) -> f64 {
        (x - self.view.x0) * self.scale
    }
    fn y(&self, y: f64) -> f64 {
        (self.view.y1 - y) * self.scale
    }
    fn point(&self, (x, y): (f64, f64)) -> (f64, f64) {
        (self.x(x), self.y(y))
    }
}

/// The SVG of the chain in `state`, with paths and magnet sizes from `geometry`.
pub fn frame_svg(
    geometry: &Geometry,
    state: &ChainState,
    view: &FrameView,
    opts: &FrameOptions,
) -> String {
    let w = geometry.w;
    let b = view.bounds;
    let px_w = page_width(b.width());
    let page = PageMap {
        view: b,
        scale: px_w / b.width(),
    };
    let px_h = (b.height() * page.scale).max(120.0);
    let mut doc = document(px_w, px_h + 40.0, "#fbfbf8");
    let in_collision = |i: usize| opts.collision.is_some_and(|(a, b)| a == i || b == i);
    let oct = Octagon::new(w);
    // the target outline, under everything else
    if !opts.target.is_empty() {
        let mut target = Group::new()
            .set("fill", "none")
            .set("stroke", "#2e7d32")
            .set("stroke-width", "1.5")
            .set("stroke-dasharray", "6 4");
        for ring in &opts.target {
            target = target.add(Polygon::new().set(
                "points",
                points(ring.iter().map(|p| page.point((p.x, p.y)))),
            ));
        }
        doc = doc.add(target);
    }
    // tile outlines: filled octagons in a group that strokes them all alike
    let outline = |p: &Pose, fill: &str| {
        Polygon::new()
            .set("points", points(oct.vertices_at(p).map(|v| page.point(v))))
            .set("fill", fill)
    };
    let outlines = Group::new()
        .set("stroke", "#55524c")
        .set("stroke-width", num((0.04 * w * page.scale).clamp(0.3, 1.5)));
    let shown: Vec<usize> = (0..state.tiles())
        .filter(|&i| view.shows(&state.poses[i], w))
        .collect();
    if shown.len() <= ChainState::DETAIL_TILES {
        doc = draw_detail(
            doc,
            geometry,
            state,
            &shown,
            &page,
            &in_collision,
            outlines,
            &outline,
        );
    } else {
        doc = draw_lean(doc, state, w, &page, &in_collision, outlines, &outline);
    }
    // the RI, held at the outer edge of tile 0
    let (rx, ry) = page.point(state.poses[0].transform_point(geometry.ri_position()));
    let r = 0.5 * geometry.design(0).magnet_diameter;
    let ri_r = (r * page.scale).max(1.5);
    doc = doc
        .add(
            Circle::new()
                .set("cx", num(rx))
                .set("cy", num(ry))
                .set("r", num(ri_r))
                .set("fill", "#7b1fa2")
                .set("stroke", "#222")
                .set("stroke-width", "0.5"),
        )
        .add(
            Text::new("RI")
                .set("x", num(rx - ri_r - 2.0))
                .set("y", num(ry + 4.0))
                .set("font-size", "11")
                .set("text-anchor", "end")
                .set("fill", "#7b1fa2"),
        );
    let stamp = format!(
        "{}  t = {:.4} s  ({} moving)",
        opts.title,
        state.time,
        state.moving_count()
    );
    doc = doc.add(
        Text::new(stamp)
            .set("x", "8")
            .set("y", num(px_h + 18.0))
            .set("font-size", "13")
            .set("fill", "#222"),
    );
    if let Some(note) = &opts.note {
        let colour = if opts.collision.is_some() {
            "#c5221f"
        } else {
            "#444"
        };
        doc = doc.add(
            Text::new(note.as_str())
                .set("x", "8")
                .set("y", num(px_h + 34.0))
                .set("font-size", "12")
                .set("fill", colour),
        );
    }
    to_text(&doc)
}

/// The tiles `shown` (at most [`ChainState::DETAIL_TILES`]): outlines, paths, hinges of fold joints and
/// magnets (when the state has them).
#[allow(clippy::too_many_arguments)]
fn draw_detail(
    mut doc: Document,
    geometry: &Geometry,
    state: &ChainState,
    shown: &[usize],
    page: &PageMap,
    in_collision: &impl Fn(usize) -> bool,
    mut outlines: Group,
    outline: &impl Fn(&Pose, &str) -> Polygon,
) -> Document {
    let w = geometry.w;
    let tiles = state.tiles();
    for &i in shown {
        let p = &state.poses[i];
        let fill = if in_collision(i) {
            "#f28b82"
        } else if (i > 0 && state.joint_folding(i - 1)) || (i + 1 < tiles && state.joint_folding(i))
        {
            "#c6dbf7"
        } else if state.tile_moving(i) {
            "#e4eefb"
        } else {
            "#e9e6df"
        };
        outlines = outlines.add(outline(p, fill));
    }
    doc = doc.add(outlines);
    let r = 0.5 * geometry.design(0).magnet_diameter;
    // the magnets' paths: one stroke for all
    let mut paths = Group::new()
        .set("fill", "none")
        .set("stroke", "#9c968a")
        .set("stroke-width", num((2.0 * r * page.scale).max(1.0) * 1.1))
        .set("stroke-linecap", "round");
    for &i in shown {
        let p = &state.poses[i];
        for k in [2 * i, 2 * i + 1] {
            let path = geometry.path(k).polyline(0.5);
            let pts = path.into_iter().map(|q| page.point(p.transform_point(q)));
            paths = paths.add(Polyline::new().set("points", points(pts)));
        }
    }
    doc = doc.add(paths);
    // hinges of fold joints
    for &j in shown.iter().filter(|&&j| j + 1 < tiles) {
        let pose = &state.poses[j];
        if let Some(Some(fold)) = state.folds.get(j) {
            let (x, y) = page.point(pose.transform_point(Octagon::new(w).hinge(*fold == Fold::L)));
            let colour = if state.joint_folding(j) {
                "#1a56b8"
            } else {
                "#333"
            };
            doc = doc.add(
                Circle::new()
                    .set("cx", num(x))
                    .set("cy", num(y))
                    .set("r", num((0.06 * w * page.scale).max(1.5)))
                    .set("fill", colour),
            );
        }
    }
    let magnets = shown
        .iter()
        .flat_map(|&i| [2 * i, 2 * i + 1])
        .filter_map(|k| state.magnets.get(k).map(|&m| (k, m)));
    for (k, m) in magnets {
        let (x, y) = page.point(m);
        let fill = if k % 2 == 0 { "#d93025" } else { "#188038" };
        let moving = state.moving.get(k).copied().unwrap_or(false);
        let (stroke, stroke_width) = if moving {
            ("#ff9800", num((0.5 * r * page.scale).max(1.5)))
        } else {
            ("#222", "0.5".to_string())
        };
        doc = doc.add(
            Circle::new()
                .set("cx", num(x))
                .set("cy", num(y))
                .set("r", num((r * page.scale).max(1.0)))
                .set("fill", fill)
                .set("stroke", stroke)
                .set("stroke-width", stroke_width),
        );
    }
    doc
}

/// A long chain: one thick polyline through the centres, collinear runs merged, and the
/// moving or colliding tiles over it (at most [`LEAN_TILES_SHOWN`]).
fn draw_lean(
    mut doc: Document,
    state: &ChainState,
    w: f64,
    page: &PageMap,
    in_collision: &impl Fn(usize) -> bool,
    mut outlines: Group,
    outline: &impl Fn(&Pose, &str) -> Polygon,
) -> Document {
    let mut line: Vec<Point> = Vec::new();
    for p in &state.poses {
        let q = Point::new(p.x, p.y);
        if let [.., a, b] = line[..] {
            let (ab, bq) = (b - a, q - b);
            if ab.cross(bq).abs() < 1e-9 * w * w && ab.dot(bq) > 0.0 {
                let last = line.len() - 1;
                line[last] = q;
                continue;
            }
        }
        line.push(q);
    }
    doc = doc.add(
        Polyline::new()
            .set("points", points(line.iter().map(|&q| page.point(q.into()))))
            .set("fill", "none")
            .set("stroke", "#b9b3a6")
            .set("stroke-width", num((w * page.scale).max(1.0)))
            .set("stroke-linejoin", "round")
            .set("stroke-linecap", "round"),
    );
    let shown = (0..state.tiles())
        .filter(|&i| state.tile_moving(i) || in_collision(i))
        .take(LEAN_TILES_SHOWN);
    for i in shown {
        let fill = if in_collision(i) {
            "#f28b82"
        } else {
            "#c6dbf7"
        };
        outlines = outlines.add(outline(&state.poses[i], fill));
    }
    doc.add(outlines)
}
