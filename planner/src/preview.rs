//! Preview SVG: the target outline, the planned tiles over it and the fold order, written
//! with the `svg` crate (which escapes every attribute and text).
//!
//! Tiles are drawn as octagons coloured by physical part (SS grey, RS/SR blue, RR red,
//! LR/RL orange); a line through the tile centres shades from green (tile 0, where the
//! reaction initiator starts) to purple (the last tile), with the tile index marked at
//! regular steps.

use std::path::Path;

use foldchain::{Chain, Part};
use kurbo::{Affine, Point, Rect};
use svg::node::element::path::Data;
use svg::node::element::{Circle, Group, Line, Path as SvgPath, Polygon, Rectangle, Text};
use svg::Document;

use crate::empty::EmptyPart;
use crate::error::{PlanError, Rejected};
use crate::options::Turns;
use crate::plan::{mm, plural, Plan};
use crate::shape::Shape;

/// The preview of `plan` over the shape in the SVG file `shape_path`.
pub fn preview_svg_file(shape_path: &Path, plan: &Plan) -> Result<String, PlanError> {
    let shape = read_shape(shape_path)?;
    Ok(preview_svg(&shape, plan))
}

/// The shape in the SVG file `shape_path`, named by the path as given.
fn read_shape(shape_path: &Path) -> Result<Shape, PlanError> {
    let data = crate::read_drawing_file(shape_path)?;
    Shape::from_svg_data(&data, &shape_path.display().to_string())
}

/// A coordinate rounded to 1e-4 user units, for a compact file.
fn r4(v: f64) -> f64 {
    (v * 1e4).round() / 1e4
}

/// The preview of `plan` over `shape` (as read by [`Shape::from_svg_data`]).
pub fn preview_svg(shape: &Shape, plan: &Plan) -> String {
    preview(shape, plan, None)
}

/// The preview of a plan that was rejected (see [`PlanError::Unplannable`]) over the shape
/// in the SVG file `shape_path`: marked in red as no plan, with the empty part it leaves
/// framed.
pub fn preview_svg_rejected(shape_path: &Path, rejected: &Rejected) -> Result<String, PlanError> {
    let shape = read_shape(shape_path)?;
    Ok(preview(&shape, &rejected.plan, Some(&rejected.empty)))
}

fn preview(shape: &Shape, plan: &Plan, rejected: Option<&EmptyPart>) -> String {
    let w = plan.tile_size;
    let b = shape.bbox();
    // physical y up -> SVG y down; the view holds the shape and every tile
    let mut view = Rect::new(b.x0, -b.y1, b.x1, -b.y0);
    for p in &plan.poses {
        view = view.union(Rect::new(p.x - w, p.y - w, p.x + w, p.y + w));
    }
    let m = 0.05 * view.width().max(view.height());
    let view = view.inflate(m, m);
    // text is sized in pixels of the 800-pixel picture, whatever the drawing's units
    // (13 and 12 pixels, smaller in a narrow picture so that a line of about 75 characters
    // fits its width)
    let px = view.width().max(view.height()) / 800.0;
    let (title_size, legend_size) = (
        (13.0 * px).min(view.width() / 42.0),
        (12.0 * px).min(view.width() / 40.0),
    );
    let header_lines = if rejected.is_some() { 5.0 } else { 3.0 };
    let header = header_lines * 1.5 * title_size;
    let footer = 8.0 * 1.5 * legend_size + 0.5 * m;
    let view = Rect::new(view.x0, view.y0 - header, view.x1, view.y1 + footer);
    let scale = 800.0 / view.width().max(view.height());
    let lw = w * 0.06;
    let mut doc = Document::new()
        .set("width", (view.width() * scale).round())
        .set("height", (view.height() * scale).round())
        .set("viewBox", (view.x0, view.y0, view.width(), view.height()))
        .add(
            Rectangle::new()
                .set("x", view.x0)
                .set("y", view.y0)
                .set("width", view.width())
                .set("height", view.height())
                .set("fill", "white"),
        )
        .add(outline(shape, lw))
        .add(tiles(plan, lw));
    for line in fold_order(plan) {
        doc = doc.add(line);
    }
    doc = mark_start_and_indices(doc, plan, view, legend_size);
    let x0 = view.x0 + 0.5 * m;
    let lines = caption_lines(plan, rejected);
    if let Some(e) = rejected {
        doc = doc.add(
            Rectangle::new()
                .set("x", r4(e.bbox.x0))
                .set("y", r4(e.bbox.y0))
                .set("width", r4(e.bbox.width()))
                .set("height", r4(e.bbox.height()))
                .set("fill", "#d00000")
                .set("fill-opacity", 0.15)
                .set("stroke", "#d00000")
                .set("stroke-width", r4(2.0 * lw)),
        );
    }
    for (i, t) in lines.iter().enumerate() {
        let colour = if rejected.is_some() && i < 2 {
            "#d00000"
        } else {
            "#333"
        };
        doc = doc.add(
            label(
                t,
                x0,
                view.y0 + (1.2 + 1.5 * i as f64) * title_size,
                title_size,
            )
            .set("fill", colour),
        );
    }
    doc = legend(doc, x0, view.y1 - footer + 0.5 * m, legend_size);
    format!("{doc}\n")
}

/// The start of the chain (the RI end) marked and labelled, and every tenth tile or so
/// numbered.
fn mark_start_and_indices(
    mut doc: Document,
    plan: &Plan,
    view: Rect,
    legend_size: f64,
) -> Document {
    let w = plan.tile_size;
    if let Some(p) = plan.poses.first() {
        // the label: at most the text size of the legend, at least readable next to small
        // tiles, on the side of the start that faces the middle of the picture
        let size = (0.8 * w).min(legend_size).max(0.6 * legend_size);
        let right = p.x < 0.5 * (view.x0 + view.x1);
        let x = if right { p.x + 0.5 * w } else { p.x - 0.5 * w };
        doc = doc
            .add(
                Circle::new()
                    .set("cx", r4(p.x))
                    .set("cy", r4(p.y))
                    .set("r", r4(0.3 * w))
                    .set("fill", "#10a040"),
            )
            .add(
                label("start (RI)", x, p.y - 0.6 * w, size)
                    .set("fill", "#10a040")
                    .set("font-weight", "bold")
                    .set("text-anchor", if right { "start" } else { "end" }),
            );
    }
    let n = plan.poses.len();
    let step = (n / 10).max(10);
    let number = (0.55 * w).min(legend_size);
    for i in (step..n).step_by(step) {
        let p = plan.poses[i];
        doc = doc.add(
            label(&i.to_string(), p.x, p.y + 0.2 * w, number)
                .set("text-anchor", "middle")
                .set("fill", "#000"),
        );
    }
    doc
}

/// The lines above the picture: the plan's summary and fit, after the rejection's two lines
/// when it was rejected.
fn caption_lines(plan: &Plan, rejected: Option<&EmptyPart>) -> Vec<String> {
    // short lines: a tall drawing makes a narrow picture
    let lines = [
        format!(
            "{}: {}, {}, {}, {}",
            plan.source,
            plural(plan.tiles, "tile", "tiles"),
            plural(plan.u_turns, &format!("{} U-turn", plan.turns), &format!("{} U-turns", plan.turns)),
            plural(plan.quarter_turns, "quarter turn", "quarter turns"),
            plural(plan.cells, "cell", "cells")
        ),
        format!(
            "tile {} mm, folded {:.0} x {:.0} mm",
            mm(plan.tile_mm),
            plan.extent_mm[0],
            plan.extent_mm[1]
        ),
        format!(
            "fit: {:.1}% of the shape covered (rows this far apart cover {:.1}% of a long band), {:.1}% of the chain outside it",
            100.0 * plan.metrics.covered_share,
            100.0 * row_band_share(plan),
            100.0 * plan.metrics.outside_share
        ),
    ];
    let mut lines = lines.to_vec();
    if let Some(e) = rejected {
        lines.insert(
            0,
            "REJECTED, NOT A PLAN: the chain folds but leaves the part".to_string(),
        );
        lines.insert(
            1,
            format!(
                "framed in red empty: about {:.0} tile areas without a tile",
                e.tiles
            ),
        );
    }
    lines
}

/// The share of a band of rows that octagons can cover: a tile's area `2 (sqrt2 - 1) w^2`
/// over the row's share of the band, `w` times the row pitch (`sqrt2 w` for tight turns,
/// `(1 + sqrt2) w` for loose): 58.6% and 34.3%.
fn row_band_share(plan: &Plan) -> f64 {
    let oct = 2.0 * (2f64.sqrt() - 1.0);
    let pitch = match plan.turns {
        Turns::Loose => 1.0 + 2f64.sqrt(),
        _ => 2f64.sqrt(),
    };
    oct / pitch
}

/// The legend under the drawing, one item a line: what the colours and the line mean, and
/// what rows of octagons can cover (not a bound: a shape whose outline lies flush on the
/// outer rows' faces lacks the half-pitch strips beyond them, and the thesis' square of 107
/// tiles in 9 rows covers 58.9%).
fn legend(mut doc: Document, x0: f64, y0: f64, size: f64) -> Document {
    let items = [
        ("#c8c8c8", "straight tile (SS)"),
        ("#7aa6e0", "tile next to a turn (RS, SR)"),
        ("#e06060", "U-turn tile (RR, LL)"),
        ("#f0a030", "other fold tiles"),
    ];
    let line = |i: usize| y0 + 1.5 * size * i as f64;
    for (i, (fill, text)) in items.iter().enumerate() {
        doc = doc
            .add(
                Rectangle::new()
                    .set("x", r4(x0))
                    .set("y", r4(line(i) - 0.8 * size))
                    .set("width", r4(0.9 * size))
                    .set("height", r4(0.9 * size))
                    .set("fill", *fill)
                    .set("stroke", "#333")
                    .set("stroke-width", r4(0.05 * size)),
            )
            .add(label(text, x0 + 1.3 * size, line(i), size).set("fill", "#333"));
    }
    doc = doc
        .add(
            Line::new()
                .set("x1", r4(x0))
                .set("y1", r4(line(4) - 0.35 * size))
                .set("x2", r4(x0 + 0.9 * size))
                .set("y2", r4(line(4) - 0.35 * size))
                .set("stroke", "#10a040")
                .set("stroke-width", r4(0.3 * size)),
        )
        .add(
            label(
                "fold order, from the start (green) to the end (purple)",
                x0 + 1.3 * size,
                line(4),
                size,
            )
            .set("fill", "#333"),
        );
    for (i, t) in [
        "Rows of octagons sqrt2 w apart cover 58.6% of a long band",
        "((1 + sqrt2) w apart, loose turns: 34.3%); near that is a full plan",
        "(a little more where the outline lies flush on the outer rows).",
    ]
    .iter()
    .enumerate()
    {
        doc = doc.add(label(t, x0, line(5 + i), size).set("fill", "#555"));
    }
    doc
}

/// A sans-serif text at `(x, y)` of size `size`.
fn label(text: &str, x: f64, y: f64, size: f64) -> Text {
    Text::new(text)
        .set("x", r4(x))
        .set("y", r4(y))
        .set("font-size", r4(size))
        .set("font-family", "sans-serif")
}

/// The shape's outline, filled, in SVG coordinates (y down).
fn outline(shape: &Shape, lw: f64) -> SvgPath {
    let mut d = Data::new();
    for r in shape.rings() {
        for (i, p) in r.points.iter().enumerate() {
            let q = (r4(p.x), r4(-p.y));
            d = if i == 0 { d.move_to(q) } else { d.line_to(q) };
        }
        d = d.close();
    }
    SvgPath::new()
        .set("d", d)
        .set("fill", "#f2e6b8")
        .set("fill-rule", "evenodd")
        .set("stroke", "#806000")
        .set("stroke-width", lw)
}

/// The tiles: octagons at the plan's poses, coloured by part.
fn tiles(plan: &Plan, lw: f64) -> Group {
    let w = plan.tile_size;
    let parts: Vec<Part> = Chain::parse_tile_list(&plan.tile_list)
        .map(|c| c.tiles().iter().map(|t| t.part()).collect())
        .unwrap_or_default();
    let k = (2f64.sqrt() - 1.0) * 0.5 * w;
    let h = 0.5 * w;
    let octagon = [
        (h, k),
        (k, h),
        (-k, h),
        (-h, k),
        (-h, -k),
        (-k, -h),
        (k, -h),
        (h, -k),
    ];
    let mut g = Group::new()
        .set("stroke", "#333")
        .set("stroke-width", r4(lw * 0.5));
    for (i, p) in plan.poses.iter().enumerate() {
        let pose = Affine::translate((p.x, p.y)) * Affine::rotate(p.heading_deg.to_radians());
        let points: Vec<f64> = octagon
            .iter()
            .flat_map(|&c| {
                let q = pose * Point::from(c);
                [r4(q.x), r4(q.y)]
            })
            .collect();
        let fill = match parts.get(i) {
            Some(Part::SS) | None => "#c8c8c8",
            Some(Part::RS) | Some(Part::SR) => "#7aa6e0",
            Some(Part::RR) => "#e06060",
            Some(_) => "#f0a030",
        };
        g = g.add(
            Polygon::new()
                .set("points", points)
                .set("fill", fill)
                .set("fill-opacity", 0.85),
        );
    }
    g
}

/// The fold order: the centre line, shaded green (tile 0) to purple (the last tile).
fn fold_order(plan: &Plan) -> Vec<Line> {
    let n = plan.poses.len();
    let width = r4(plan.tile_size * 0.15);
    plan.poses
        .windows(2)
        .enumerate()
        .map(|(i, pair)| {
            let t = i as f64 / n.max(2) as f64;
            let (r, g, b) = (
                (40.0 + 120.0 * t) as u8,
                (160.0 * (1.0 - t)) as u8,
                (60.0 + 160.0 * t) as u8,
            );
            Line::new()
                .set("x1", r4(pair[0].x))
                .set("y1", r4(pair[0].y))
                .set("x2", r4(pair[1].x))
                .set("y2", r4(pair[1].y))
                .set("stroke", format!("rgb({r},{g},{b})"))
                .set("stroke-width", width)
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::options::PlanOptions;

    /// The preview is one well-formed SVG document with a tile per pose, and text from the
    /// file name is escaped.
    #[test]
    fn preview_is_well_formed_and_escaped() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><rect x="10" y="10" width="80" height="60"/></svg>"#;
        let shape = Shape::from_svg_data(svg.as_bytes(), "t").unwrap();
        let opts = PlanOptions::default().with_tiles(40);
        let plan = crate::plan_svg_str(svg, "a<b>&\"c\".svg", &opts).unwrap();
        let out = preview_svg(&shape, &plan);
        let doc = usvg::roxmltree::Document::parse(&out).unwrap();
        let polygons = doc
            .descendants()
            .filter(|n| n.has_tag_name("polygon"))
            .count();
        assert_eq!(polygons, plan.tiles);
        let title = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .find(|t| t.contains("tiles"))
            .unwrap()
            .trim();
        assert!(title.starts_with("a<b>&\"c\".svg: "), "{title}");
        // a legend and the note on what rows of octagons can cover
        let texts: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .collect();
        assert!(texts.iter().any(|t| t.contains("U-turn tile")), "{texts:?}");
        assert!(texts.iter().any(|t| t.contains("58.6%")), "{texts:?}");
        assert!(usvg::Tree::from_str(&out, &usvg::Options::default()).is_ok());
    }

    /// A rejected plan's preview says so in red and frames the empty part.
    #[test]
    fn rejected_preview_is_marked() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><rect x="10" y="10" width="80" height="60"/></svg>"#;
        let shape = Shape::from_svg_data(svg.as_bytes(), "t").unwrap();
        let plan =
            crate::plan_svg_str(svg, "t.svg", &PlanOptions::default().with_tiles(40)).unwrap();
        let empty = EmptyPart {
            tiles: 25.0,
            centre: Point::new(50.0, 40.0),
            bbox: Rect::new(30.0, 20.0, 70.0, 60.0),
        };
        let out = preview(&shape, &plan, Some(&empty));
        assert!(out.contains("REJECTED, NOT A PLAN"), "{out}");
        assert!(out.contains("about 25 tile areas"), "{out}");
        let doc = usvg::roxmltree::Document::parse(&out).unwrap();
        assert!(doc.descendants().any(|n| n.has_tag_name("rect")
            && n.attribute("stroke") == Some("#d00000")
            && n.attribute("width") == Some("40")));
        assert!(!preview_svg(&shape, &plan).contains("REJECTED"));
    }
}
