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

use crate::error::PlanError;
use crate::plan::Plan;
use crate::shape::Shape;

/// The preview of `plan` over the shape in the SVG file `shape_path`.
pub fn preview_svg_file(shape_path: &Path, plan: &Plan) -> Result<String, PlanError> {
    let data = std::fs::read(shape_path).map_err(|source| PlanError::Read {
        path: shape_path.to_path_buf(),
        source,
    })?;
    let shape = Shape::from_svg_data(&data, &shape_path.display().to_string())?;
    Ok(preview_svg(&shape, plan))
}

/// A coordinate rounded to 1e-4 user units, for a compact file.
fn r4(v: f64) -> f64 {
    (v * 1e4).round() / 1e4
}

/// The preview of `plan` over `shape` (as read by [`Shape::from_svg_data`]).
pub fn preview_svg(shape: &Shape, plan: &Plan) -> String {
    let w = plan.tile_size;
    let b = shape.bbox();
    // physical y up -> SVG y down; the view holds the shape and every tile
    let mut view = Rect::new(b.x0, -b.y1, b.x1, -b.y0);
    for p in &plan.poses {
        view = view.union(Rect::new(p.x - w, p.y - w, p.x + w, p.y + w));
    }
    let m = 0.05 * view.width().max(view.height());
    let view = view.inflate(m, m);
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
    if let Some(p) = plan.poses.first() {
        doc = doc
            .add(
                Circle::new()
                    .set("cx", r4(p.x))
                    .set("cy", r4(p.y))
                    .set("r", r4(0.3 * w))
                    .set("fill", "#10a040"),
            )
            .add(label("start (RI)", p.x + 0.4 * w, p.y - 0.6 * w, 0.8 * w).set("fill", "#10a040"));
    }
    let n = plan.poses.len();
    let step = (n / 10).max(10);
    for i in (step..n).step_by(step) {
        let p = plan.poses[i];
        doc = doc.add(
            label(&i.to_string(), p.x, p.y + 0.2 * w, 0.55 * w)
                .set("text-anchor", "middle")
                .set("fill", "#000"),
        );
    }
    let title = format!("{}: {}", plan.source, plan.summary());
    doc = doc.add(
        label(
            &title,
            view.x0 + 0.5 * m,
            view.y0 + 0.7 * m,
            0.6 * view.width() / 110.0,
        )
        .set("fill", "#333"),
    );
    format!("{doc}\n")
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
        assert!(usvg::Tree::from_str(&out, &usvg::Options::default()).is_ok());
    }
}
