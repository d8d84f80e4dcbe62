//! The mark engraved in a tile's top: its type and which side faces the reaction initiator,
//! readable in both ways the part can lie.
//!
//! A part is two tile types, one turned by 180 degrees (SL and RS are one part). Its top
//! carries each name once, each upright when the part lies as that type with the chain
//! running left to right (the RI on the left), and an arrow before each name pointing to the
//! RI. The letters are the Hershey simplex Roman font's strokes
//! (`vector-text-hershey`), stroked into a region with round caps and joins by `i_overlay`.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::mesh::float::stroke::offset::StrokeOffset;
use i_overlay::mesh::float::style::{LineCap, LineJoin, StrokeStyle};
use vector_text_core::Renderer;
use vector_text_hershey::{HersheyFont, HersheyRenderer};

use crate::region::{self, Pt, Region};

/// The polylines of `text` in the Hershey simplex Roman font, baseline at y = 0, capitals
/// `cap` high, starting at x = 0; and the text's width.
pub fn text_strokes(text: &str, cap: f64) -> (Vec<Vec<Pt>>, f64) {
    let points = HersheyRenderer::render_text(text, HersheyFont::Romans);
    // Hershey coordinates run downwards; a capital spans y from -12 to 9 in its units
    let scale = cap / 21.0;
    let mut lines: Vec<Vec<Pt>> = Vec::new();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in &points {
        let q = [f64::from(p.x) * scale, -(f64::from(p.y) - 9.0) * scale];
        lo = lo.min(q[0]);
        hi = hi.max(q[0]);
        match lines.last_mut() {
            Some(line) if p.pen => line.push(q),
            _ => lines.push(vec![q]),
        }
    }
    lines.retain(|l| l.len() >= 2);
    if lines.is_empty() {
        return (lines, 0.0);
    }
    for l in &mut lines {
        for q in l.iter_mut() {
            q[0] -= lo;
        }
    }
    (lines, hi - lo)
}

/// One label: an arrow pointing to -x (the RI's side), then `name`, centred on x = 0 with its
/// baseline at `y`, capitals `cap` high. Returns the polylines.
pub fn label_strokes(name: &str, cap: f64, y: f64) -> Vec<Vec<Pt>> {
    let (mut lines, text_w) = text_strokes(name, cap);
    let arrow_w = 0.8 * cap;
    let gap = 0.35 * cap;
    let total = arrow_w + gap + text_w;
    let x0 = -0.5 * total;
    for l in &mut lines {
        for q in l.iter_mut() {
            q[0] += x0 + arrow_w + gap;
            q[1] += y;
        }
    }
    let mid = y + 0.5 * cap;
    let head = 0.35 * cap;
    lines.push(vec![[x0 + arrow_w, mid], [x0, mid]]);
    lines.push(vec![
        [x0 + head, mid + head],
        [x0, mid],
        [x0 + head, mid - head],
    ]);
    lines
}

/// The width of [`label_strokes`]' polylines (without the stroke), mm.
pub fn label_width(name: &str, cap: f64) -> f64 {
    let (_, text_w) = text_strokes(name, cap);
    0.8 * cap + 0.35 * cap + text_w
}

/// The region of polylines stroked `width` wide with round caps and joins, arcs within
/// `tol`.
pub fn stroked(lines: &[Vec<Pt>], width: f64, tol: f64) -> Region {
    let r = 0.5 * width;
    // i_overlay's round caps and joins take the ratio of a chord to the radius
    let ratio = (8.0 * tol / r).sqrt().clamp(0.05, 1.0);
    let style = StrokeStyle::new(width)
        .line_join(LineJoin::Round(ratio))
        .start_cap(LineCap::Round(ratio))
        .end_cap(LineCap::Round(ratio));
    let mut pieces = Vec::new();
    for l in lines {
        pieces.extend(l.stroke(style.clone(), false));
    }
    region::cleaned(pieces.simplify_shape(FillRule::NonZero), region::MIN_EDGE)
}

/// The two labels of a part lying as `name` (upright, above the centre) and as `turned`
/// (the part turned by 180 degrees: below the centre, upside down), `cap` high with their
/// baselines `gap` from the tile's centre line.
pub fn part_mark(name: &str, turned: &str, cap: f64, gap: f64, width: f64, tol: f64) -> Region {
    let upper = stroked(&label_strokes(name, cap, gap), width, tol);
    let lower = region::rotated(
        &stroked(&label_strokes(turned, cap, gap), width, tol),
        std::f64::consts::PI,
    );
    let mut all = upper;
    all.extend(lower);
    all
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn letters_are_cap_high_and_strokes_make_regions() {
        let (lines, w) = text_strokes("SL", 3.0);
        assert!(!lines.is_empty());
        let ys = lines.iter().flatten().map(|p| p[1]);
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        assert!(lo > -0.2 && (hi - 3.0).abs() < 0.2, "{lo} {hi}");
        assert!(w > 3.0 && w < 7.0, "{w}");
        let r = stroked(&label_strokes("RS", 3.0, 1.0), 0.6, 0.002);
        assert!(region::area(&r) > 3.0, "{}", region::area(&r));
        // 'R' closes a counter: a hole in its shape
        assert!(r.iter().any(|s| s.len() > 1));
    }
}
