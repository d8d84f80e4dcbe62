//! SVG pictures of a run: step frames and the final shape ([`frame_svg`]), the transition
//! diagram (magnet position against time, thesis figure 6.3, [`transition_svg`]) and the
//! energy curve (thesis figure 7.5, [`energy_svg`]). Written as plain SVG text; world
//! coordinates are millimetres seen from above, y up (so L folds turn left on the page).
//!
//! The pictures draw plain data ([`ChainState`], [`TransitionData`], energy samples and fold
//! windows), so the event engine and the force-integrated reference draw the same pictures
//! from their own results.

mod frame;
mod plot;
mod source;
mod state;
mod transition;

pub use frame::{frame_svg, FrameOptions, FrameView, DETAIL_TILES};
pub use plot::energy_svg;
pub use source::RunSource;
pub use state::ChainState;
pub use transition::{transition_svg, MagnetTrack, TransitionData};

/// Escapes text for SVG.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number for SVG attributes: two decimals, no trailing zeros.
pub(crate) fn n(x: f64) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" || s.is_empty() {
        "0".to_string()
    } else {
        s.to_string()
    }
}
