//! Preview SVG: the target outline, the planned tiles over it and the fold order.
//!
//! Tiles are drawn as octagons coloured by physical part (SS grey, RS/SR blue, RR red,
//! LR/RL orange); a line through the tile centres shades from green (tile 0, where the
//! reaction initiator starts) to purple (the last tile), with the tile index marked at
//! regular steps.

use std::fmt::Write as _;
use std::path::Path;

use foldchain::{Chain, Part};

use crate::{Plan, PlanError, Shape};

/// The preview of `plan` over the shape in the SVG file `shape_path`.
pub fn to_svg(shape_path: &Path, plan: &Plan) -> Result<String, PlanError> {
    let data = std::fs::read(shape_path).map_err(|source| PlanError::Read {
        path: shape_path.to_path_buf(),
        source,
    })?;
    let shape = Shape::from_svg_data(&data, &shape_path.display().to_string())?;
    Ok(to_svg_with_shape(&shape, plan))
}

/// The preview of `plan` over `shape` (as read by [`Shape::from_svg_data`]).
pub fn to_svg_with_shape(shape: &Shape, plan: &Plan) -> String {
    let w = plan.tile_size;
    let (xmin, ymin, xmax, ymax) = shape.bbox();
    // physical y up -> SVG y down
    let (mut x0, mut y0, mut x1, mut y1) = (xmin, -ymax, xmax, -ymin);
    for p in &plan.poses {
        x0 = x0.min(p.x - w);
        y0 = y0.min(p.y - w);
        x1 = x1.max(p.x + w);
        y1 = y1.max(p.y + w);
    }
    let m = 0.05 * (x1 - x0).max(y1 - y0);
    let (vx, vy, vw, vh) = (x0 - m, y0 - m, x1 - x0 + 2.0 * m, y1 - y0 + 2.0 * m);
    let scale = 800.0 / vw.max(vh);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{:.0}" height="{:.0}" viewBox="{vx} {vy} {vw} {vh}">"#,
        vw * scale,
        vh * scale
    );
    let _ = writeln!(
        s,
        r#"<rect x="{vx}" y="{vy}" width="{vw}" height="{vh}" fill="white"/>"#
    );
    let mut d = String::new();
    for r in shape.rings() {
        for (i, &(x, y)) in r.points.iter().enumerate() {
            let _ = write!(d, "{}{:.4},{:.4} ", if i == 0 { "M" } else { "L" }, x, -y);
        }
        d.push_str("Z ");
    }
    let lw = w * 0.06;
    let _ = writeln!(
        s,
        r##"<path d="{d}" fill="#f2e6b8" fill-rule="evenodd" stroke="#806000" stroke-width="{lw}"/>"##
    );
    let parts: Vec<Part> = Chain::parse_tile_list(&plan.tile_list)
        .map(|c| c.tiles().iter().map(|t| t.part()).collect())
        .unwrap_or_default();
    let k = (2f64.sqrt() - 1.0) * 0.5 * w;
    let h = 0.5 * w;
    let oct = [
        (h, k),
        (k, h),
        (-k, h),
        (-h, k),
        (-h, -k),
        (-k, -h),
        (k, -h),
        (h, -k),
    ];
    let _ = writeln!(s, r##"<g stroke="#333" stroke-width="{:.5}">"##, lw * 0.5);
    for (i, p) in plan.poses.iter().enumerate() {
        let (sn, cs) = p.heading_deg.to_radians().sin_cos();
        let mut pts = String::new();
        for &(ox, oy) in &oct {
            let _ = write!(
                pts,
                "{:.4},{:.4} ",
                p.x + cs * ox - sn * oy,
                p.y + sn * ox + cs * oy
            );
        }
        let fill = match parts.get(i) {
            Some(Part::SS) | None => "#c8c8c8",
            Some(Part::RS) | Some(Part::SR) => "#7aa6e0",
            Some(Part::RR) => "#e06060",
            Some(_) => "#f0a030",
        };
        let _ = writeln!(
            s,
            r#"<polygon points="{pts}" fill="{fill}" fill-opacity="0.85"/>"#
        );
    }
    s.push_str("</g>\n");
    // fold order: centre line shaded green -> purple
    let n = plan.poses.len();
    for (i, pair) in plan.poses.windows(2).enumerate() {
        let t = i as f64 / n.max(2) as f64;
        let (r, g, b) = (
            (40.0 + 120.0 * t) as u8,
            (160.0 * (1.0 - t)) as u8,
            (60.0 + 160.0 * t) as u8,
        );
        let _ = writeln!(
            s,
            r#"<line x1="{:.4}" y1="{:.4}" x2="{:.4}" y2="{:.4}" stroke="rgb({r},{g},{b})" stroke-width="{:.4}"/>"#,
            pair[0].x,
            pair[0].y,
            pair[1].x,
            pair[1].y,
            w * 0.15
        );
    }
    if let Some(p) = plan.poses.first() {
        let _ = writeln!(
            s,
            r##"<circle cx="{:.4}" cy="{:.4}" r="{:.4}" fill="#10a040"/><text x="{:.4}" y="{:.4}" font-size="{:.4}" font-family="sans-serif" fill="#10a040">start (RI)</text>"##,
            p.x,
            p.y,
            0.3 * w,
            p.x + 0.4 * w,
            p.y - 0.6 * w,
            0.8 * w
        );
    }
    let step = (n / 10).max(10);
    for i in (step..n).step_by(step) {
        let p = plan.poses[i];
        let _ = writeln!(
            s,
            r##"<text x="{:.4}" y="{:.4}" font-size="{:.4}" font-family="sans-serif" text-anchor="middle" fill="#000">{i}</text>"##,
            p.x,
            p.y + 0.2 * w,
            0.55 * w
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="{:.4}" y="{:.4}" font-size="{:.4}" font-family="sans-serif" fill="#333">{}</text>"##,
        vx + 0.5 * m,
        vy + 0.7 * m,
        0.6 * vw / 110.0,
        xml_escape(&format!("{}: {}", plan.source, plan.summary()))
    );
    s.push_str("</svg>\n");
    s
}

fn xml_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
