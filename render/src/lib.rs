//! # foldchain-render
//!
//! Pictures of a folding run, apart from the numerics that make it: step frames and the final
//! shape ([`frame_svg`]), the transition diagram (magnet position against time, thesis
//! figure 6.3, [`transition_svg`]), the energy curve (thesis figure 7.5, [`energy_svg`]), the
//! pair energies of an experiment (figures 7.7 and 7.8, [`pair_energy_svg`]), the design
//! search's trade-off ([`tradeoff_svg`]) and the animated page that plays runs
//! ([`viewer`]).
//!
//! Every picture reads a run through [`foldchain::timeline::RunSource`] (or the plain data it
//! returns), which the event engine's timeline and the reference integrator's run both
//! implement: this crate imports neither simulation, and the core library does not import
//! this crate. Documents are built with the [`svg`] crate, which escapes every text and
//! attribute; world coordinates are millimetres seen from above, y up (so L folds turn left
//! on the page).
//!
//! ```
//! use foldchain::engine::{run, EngineOptions};
//! use foldchain::timeline::{RunSource, TileDesigns};
//! use foldchain::Chain;
//! use foldchain_render::{frame_svg, FrameOptions, FrameView};
//!
//! let chain = Chain::parse("SLLS").unwrap();
//! let tl = run(&chain, &TileDesigns::default(), &EngineOptions::default()).unwrap();
//! let last = tl.final_state();
//! let view = FrameView::around(last.poses.iter().copied(), tl.geometry().w);
//! let svg = frame_svg(tl.geometry(), &last, &view, &FrameOptions::default());
//! assert!(svg.starts_with("<svg"));
//! ```

mod axes;
mod energy_plot;
mod pair_energy;
mod step_frame;
mod tradeoff;
mod transition;
pub mod viewer;

pub use energy_plot::energy_svg;
pub use pair_energy::pair_energy_svg;
pub use step_frame::{frame_svg, FrameOptions, FrameView};
pub use tradeoff::tradeoff_svg;
pub use transition::transition_svg;

use std::fmt::Write;

use svg::node::element::{Polyline, Rectangle};
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

/// A plotted curve: an unfilled line through `pts` (pixels, as [`points`] writes them) in
/// `colour`, `width` pixels wide (an SVG length, written as given).
pub(crate) fn plot_line(
    pts: impl IntoIterator<Item = (f64, f64)>,
    colour: &str,
    width: &str,
) -> Polyline {
    Polyline::new()
        .set("points", points(pts))
        .set("fill", "none")
        .set("stroke", colour)
        .set("stroke-width", width)
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
