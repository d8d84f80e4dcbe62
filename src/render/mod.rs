//! SVG pictures of a run: step frames and the final shape ([`frame_svg`]), the transition
//! diagram (magnet position against time, thesis figure 6.3, [`transition_svg`]) and the
//! energy curve (thesis figure 7.5, [`energy_svg`]). Documents are built with the [`svg`]
//! crate, which escapes every text and attribute; world coordinates are millimetres seen from
//! above, y up (so L folds turn left on the page).
//!
//! The pictures draw plain data ([`ChainState`], [`TransitionData`], energy samples and fold
//! windows), so the event engine and the force-integrated reference draw the same pictures
//! from their own results.

mod frame;
mod pair_energy;
pub(crate) mod plot;
mod source;
mod state;
mod transition;

pub use frame::{frame_svg, FrameOptions, FrameView, DETAIL_TILES};
pub use pair_energy::pair_energy_svg;
pub use plot::energy_svg;
pub use source::{RunSource, TrackKey};
pub use state::ChainState;
pub use transition::{transition_svg, MagnetTrack, TransitionData};

use std::fmt::Write;

use svg::node::element::Rectangle;
use svg::Document;

/// A number as the pictures write it: two decimals, no trailing zeros (pixel coordinates need
/// no more, and long chains keep their frames small).
pub(crate) fn num(x: f64) -> String {
    let mut s = String::new();
    push_num(&mut s, x);
    s
}

/// Appends `x` to `out` as [`num`] writes it.
fn push_num(out: &mut String, x: f64) {
    let start = out.len();
    let _ = write!(out, "{x:.2}");
    // "{:.2}" always writes a point: trim the zeros after it, then the point itself
    let kept = out[start..]
        .trim_end_matches('0')
        .trim_end_matches('.')
        .len();
    out.truncate(start + kept);
    if matches!(&out[start..], "-0" | "") {
        out.truncate(start);
        out.push('0');
    }
}

/// A `points` attribute: `x,y x,y ...`, each number as [`num`] writes it.
pub(crate) fn points(pts: impl IntoIterator<Item = (f64, f64)>) -> String {
    let mut s = String::new();
    for (x, y) in pts {
        if !s.is_empty() {
            s.push(' ');
        }
        push_num(&mut s, x);
        s.push(',');
        push_num(&mut s, y);
    }
    s
}

/// An empty picture `width` by `height` pixels (user units are pixels), in a sans-serif font,
/// filled with the colour `background`.
pub(crate) fn document(width: f64, height: f64, background: &str) -> Document {
    Document::new()
        .set("width", num(width))
        .set("height", num(height))
        .set("viewBox", format!("0 0 {} {}", num(width), num(height)))
        .set("font-family", "sans-serif")
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", background),
        )
}

/// The text of a picture, ending in a newline.
pub(crate) fn to_text(doc: &Document) -> String {
    format!("{doc}\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(2.504), "2.5");
        assert_eq!(num(-12.5), "-12.5");
        assert_eq!(num(100.0), "100");
        assert_eq!(num(0.004), "0");
        assert_eq!(points([(0.0, 1.5), (2.25, -3.0)]), "0,1.5 2.25,-3");
    }

    #[test]
    fn text_is_escaped_once() {
        let doc = document(10.0, 20.0, "white")
            .add(svg::node::element::Text::new("a < b & \"c\"").set("x", 1));
        let text = to_text(&doc);
        assert!(text.contains("a &lt; b &amp; \"c\""), "{text}");
        assert!(
            text.starts_with("<svg") && text.ends_with("</svg>\n"),
            "{text}"
        );
        assert!(text.contains(r#"viewBox="0 0 10 20""#), "{text}");
    }
}
