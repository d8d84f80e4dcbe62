//! Physical units of a drawing: how many millimetres one SVG user unit is. The root `<svg>`
//! element's `width` and `height` (with their units: mm, cm, in, pt, pc, px; usvg resolves
//! them to CSS pixels at 96 per inch) give the drawing's size on paper, its `viewBox` the
//! user units across that size. Without a viewBox a user unit is one CSS pixel; without
//! physical units the drawing is taken at 96 user units per inch, as SVG viewers show it.

/// Millimetres per CSS pixel (96 pixels per inch).
pub(crate) const MM_PER_PX: f64 = 25.4 / 96.0;

/// Millimetres per user unit of the drawing (see the module doc). With a viewBox whose
/// aspect differs from the size, the horizontal scale is used.
pub(crate) fn mm_per_unit(data: &[u8], tree: &usvg::Tree) -> f64 {
    let size = tree.size();
    let view_width = std::str::from_utf8(data)
        .ok()
        .and_then(|text| usvg::roxmltree::Document::parse(text).ok())
        .and_then(|doc| {
            let vb = doc.root_element().attribute("viewBox")?.to_string();
            let v: Vec<f64> = vb
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|t| !t.is_empty())
                .filter_map(|t| t.parse().ok())
                .collect();
            (v.len() == 4 && v[2].is_finite() && v[2] > 0.0).then(|| v[2])
        });
    let width_px = f64::from(size.width());
    match view_width {
        Some(vw) if width_px.is_finite() && width_px > 0.0 => width_px * MM_PER_PX / vw,
        _ => MM_PER_PX,
    }
}

/// A size in user units with four decimals, or in scientific notation when those would
/// show nothing of it (under 0.001) or it is ten million or more: the planner reads a
/// drawing at any scale (its tolerances are shares of the drawing's size), so a shape
/// 1e-30 units across plans as the same shape 1 unit across and says its size.
pub(crate) fn figure(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e7).contains(&a) {
        format!("{v:.4e}")
    } else {
        format!("{v:.4}")
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn scale(svg: &str) -> f64 {
        let tree = usvg::Tree::from_data(svg.as_bytes(), &usvg::Options::default()).unwrap();
        mm_per_unit(svg.as_bytes(), &tree)
    }

    #[test]
    fn units_and_viewbox_set_the_scale() {
        let body = r#"<rect width="10" height="10"/></svg>"#;
        let mm = scale(&format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="90mm" viewBox="0 0 120 90">{body}"#
        ));
        assert!((mm - 1.0).abs() < 1e-6, "{mm}");
        let cm = scale(&format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="12cm" height="9cm" viewBox="0 0 1200 900">{body}"#
        ));
        assert!((cm - 0.1).abs() < 1e-7, "{cm}");
        let inch = scale(&format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="2in" height="1in" viewBox="0 0 200 100">{body}"#
        ));
        assert!((inch - 0.254).abs() < 1e-6, "{inch}");
        let px = scale(&format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">{body}"#
        ));
        assert!((px - MM_PER_PX).abs() < 1e-12);
    }
}
