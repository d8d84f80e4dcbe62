//! The animated viewer: one self-contained HTML page (no network, no external script or
//! font; it opens from disk) that plays a run from its [`RunSource`]: tiles turning at their
//! hinges, magnets sliding along their paths coloured by pole, the RI, the target outline,
//! the first collision at its time and place; play, pause, a time scrubber, playback speed,
//! jumps between events, zoom and pan. One page can hold several runs side by side on one
//! clock (the event engine and the reference on the same chain, [`viewer_html`] with two
//! [`RunView`]s).
//!
//! The page computes the chain itself, as the library does: joint angles and magnet travel
//! from [`Track`]s (piecewise linear within [`Track::ANGLE_TOLERANCE`] and [`Track::TRAVEL_TOLERANCE`]),
//! tile poses by composing the octagon chain's hinge turns ([`foldchain::Pose::compose_at_angles`]), magnets
//! from their paths in closed form ([`PathForm`]). The data is packed small ([`RunData`]):
//! about 28 bytes per tile on the event engine's serpentines.
//!
//! The camera follows the fold unless told otherwise: it frames the part of the chain that
//! has folded with the next few tiles, grows with it and ends framed on the final shape;
//! while playing it glides, and a paused page shows the same view at the same time. Any pan
//! or zoom, the `fit` button (the whole run) or a `view=` box takes the camera over. The
//! caption says what has happened up to the shown time (`folding: 3 of 9 folds done, 2
//! magnets moving`), then the outcome once the run has ended.
//!
//! State for tests and people: the URL hash `#t=SECONDS` (or `#t=end`) opens the page paused
//! at that time, `view=X0,Y0,X1,Y1` (world mm) on that box, `follow=0` on the whole run
//! without following; `<body>` carries `data-time`, `data-folded` (joints at 90 degrees),
//! `data-moving` (magnets moving), `data-collision` (the two tiles, once they have met),
//! `data-status` (the caption's words), `data-follow`, `data-render-ms` (the drawing time of
//! the last full redraw: at load the opening frame is drawn, then, once the page is idle,
//! drawn again in full and flushed to pixels, so this is what each later redraw costs;
//! while playing, each frame's), `data-first-render-ms` (the opening frame, flushed to
//! pixels, which also pays for compiling the script), `data-renderer`, `data-view` (CSS
//! pixels per mm and the pixel position of the world origin in the first panel) and
//! `data-panel` (the first panel's left, top, width and height, CSS pixels), updated on
//! every frame; each panel (`<section data-run=...>`) carries its own `data-folded`,
//! `data-moving`, `data-collision` and `data-status`. Hash options for tests: `poses=1` puts
//! every tile's pose on each panel's `data-poses`, `probe=T1,T2,...` the poses at those
//! times on `data-poses-1`, `data-poses-2`, ..., `views=T1,T2,...` the following camera's
//! view at those times on `<body>`'s `data-view-1`, ... (as `data-view`), `detail=all` draws every part of every tile
//! whatever its size on screen, `renderer=2d|raster` chooses the drawing, and `bench=N`
//! draws `N` frames on load, each flushed to pixels, and reports their median and slowest.
//!
//! Drawing: with many tiles in view the page rasterises the chain itself into a pixel buffer
//! (Chromium's canvas and its software WebGL are far too slow for 10^4 tiles on a headless
//! machine: `BENCHMARKS.md`), each tile's octagon stamped from a sprite made once per
//! frame size and turn; with few, the canvas draws them with smooth edges.

mod path_form;
mod run_data;
mod typed_arrays;

use foldchain::timeline::RunSource;
#[cfg(doc)]
use foldchain::timeline::Track;

pub use path_form::PathForm;
pub use run_data::{PackedInts, RunData};

const TEMPLATE: &str = include_str!("assets/viewer.html");
const STYLE: &str = include_str!("assets/viewer.css");
/// The page's script, in four parts: data and kinematics, drawing with the canvas (few
/// tiles in view), drawing into a pixel buffer (many tiles in view), the page itself (concatenated inside one function scope by the template).
const SCRIPTS: [&str; 4] = [
    include_str!("assets/viewer-data.js"),
    include_str!("assets/viewer-2d.js"),
    include_str!("assets/viewer-raster.js"),
    include_str!("assets/viewer-ui.js"),
];

/// One run as the viewer shows it: its source, a title, the outcome in words, the first
/// collision and the target outline.
pub struct RunView<'a> {
    source: &'a dyn RunSource,
    label: String,
    title: String,
    note: String,
    collision: Option<(Option<f64>, (usize, usize))>,
    target: Vec<Vec<(f64, f64)>>,
}

impl<'a> RunView<'a> {
    /// The run of `source` titled `title`; no label, note, collision or target.
    pub fn new(source: &'a dyn RunSource, title: impl Into<String>) -> RunView<'a> {
        RunView {
            source,
            label: String::new(),
            title: title.into(),
            note: String::new(),
            collision: None,
            target: Vec::new(),
        }
    }

    /// A short label over the panel (`engine`, `reference`); default none.
    pub fn with_label(mut self, label: impl Into<String>) -> RunView<'a> {
        self.label = label.into();
        self
    }

    /// The outcome in words, shown under the title; default none.
    pub fn with_note(mut self, note: impl Into<String>) -> RunView<'a> {
        self.note = note.into();
        self
    }

    /// The first collision: its time (`None` when found only in the final shape, then shown
    /// at the end) and the two tiles; default none.
    pub fn with_collision(mut self, time: Option<f64>, tiles: (usize, usize)) -> RunView<'a> {
        self.collision = Some((time, tiles));
        self
    }

    /// Tiles in the run.
    pub fn tiles(&self) -> usize {
        self.source.tiles()
    }

    /// The target outline, rings of points in the chain's world frame (mm, tile 0 at the
    /// origin heading +x, y up); default none.
    pub fn with_target(mut self, rings: Vec<Vec<(f64, f64)>>) -> RunView<'a> {
        self.target = rings;
        self
    }
}

/// The page playing `runs` side by side on one clock, titled `title`.
pub fn viewer_html(title: &str, runs: &[RunView<'_>]) -> String {
    let data: Vec<RunData> = runs.iter().map(RunData::from_view).collect();
    viewer_html_of(title, &data)
}

/// The page playing the runs of `data` side by side on one clock, titled `title`: the page
/// of [`viewer_html`] from data made beforehand ([`RunData::from_view`], with
/// [`RunData::with_outcome_of`] once the outcome is known).
pub fn viewer_html_of(title: &str, data: &[RunData]) -> String {
    let json = serde_json::to_string(&data).unwrap_or_else(|_| "[]".to_string());
    // inside <script>, "</" could close the element: JSON allows "<\/" for it
    let json = json.replace("</", "<\\/");
    let title = escape_html(title);
    let script = SCRIPTS.join("\n");
    fill_template(
        TEMPLATE,
        &[
            ("TITLE", &title),
            ("STYLE", STYLE),
            ("SCRIPT", &script),
            ("DATA", &json),
        ],
    )
}

/// `template` with each `{{NAME}}` replaced by its value, in one pass (values are never
/// scanned for placeholders); unknown names are left as they are.
fn fill_template(template: &str, values: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some(i) = rest.find("{{") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let value = after
            .find("}}")
            .and_then(|j| values.iter().find(|v| v.0 == &after[..j]).map(|v| (j, v.1)));
        match value {
            Some((j, v)) => {
                out.push_str(v);
                rest = &after[j + 2..];
            }
            None => {
                out.push_str("{{");
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// Text for HTML content and attributes.
fn escape_html(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn template_is_filled_in_one_pass() {
        let t = "a{{X}}b{{Y}}c{{Z}}d{{";
        assert_eq!(
            fill_template(t, &[("X", "{{Y}}"), ("Y", "<y>")]),
            "a{{Y}}b<y>c{{Z}}d{{"
        );
        assert_eq!(escape_html("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
    }
}
