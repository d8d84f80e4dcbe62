//! The work-precision plot of a validation: one panel per scene, event-time error against
//! wall time, both axes logarithmic; Dormand-Prince and ROS2 along their tolerance ladders,
//! the event engine as diamonds. Written with the `svg` crate.

use svg::node::element::{Circle, Group, Line, Path, Polyline, Rectangle, Text};
use svg::{Document, Node};

use crate::results::{Row, SceneReport, Validation};

/// Panels per row.
const COLUMNS: usize = 3;
/// Panel size, px.
const PANEL: (f64, f64) = (320.0, 250.0);
/// Margins inside a panel: left, top, right, bottom, px.
const MARGIN: (f64, f64, f64, f64) = (58.0, 30.0, 12.0, 40.0);
/// Errors below this are drawn at it (a run that matches to rounding).
const ERROR_FLOOR: f64 = 1e-12;
/// Wall times below this are drawn at it.
const TIME_FLOOR: f64 = 1e-6;

/// A coordinate rounded to 0.1 px.
fn px(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

/// `element` with the numeric attributes `attrs`, in px rounded to 0.1.
fn at<E: Node>(mut element: E, attrs: &[(&str, f64)]) -> E {
    for &(name, value) in attrs {
        element.assign(name, px(value));
    }
    element
}

fn text(x: f64, y: f64, anchor: &str, content: &str) -> Text {
    at(Text::new(content), &[("x", x), ("y", y)]).set("text-anchor", anchor)
}

/// One panel's axes: decades of wall time and error mapped onto the plot area.
struct Axes {
    origin: (f64, f64),
    size: (f64, f64),
    x: (f64, f64),
    y: (f64, f64),
}

impl Axes {
    fn new(origin: (f64, f64), rows: &[&Row]) -> Axes {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for r in rows {
            x0 = x0.min(lx(r.wall_s));
            x1 = x1.max(lx(r.wall_s));
            y0 = y0.min(ly(r.error_time));
            y1 = y1.max(ly(r.error_time));
        }
        let (ml, mt, mr, mb) = MARGIN;
        Axes {
            origin: (origin.0 + ml, origin.1 + mt),
            size: (PANEL.0 - ml - mr, PANEL.1 - mt - mb),
            x: (x0.floor(), x1.ceil().max(x0.floor() + 1.0)),
            y: (y0.floor(), y1.ceil().max(y0.floor() + 1.0)),
        }
    }

    /// The point of a row (wall time, error), px.
    fn at(&self, wall_s: f64, error: f64) -> (f64, f64) {
        (self.xd(lx(wall_s)), self.yd(ly(error)))
    }

    /// The x of decade `d` of wall time.
    fn xd(&self, d: f64) -> f64 {
        self.origin.0 + (d - self.x.0) / (self.x.1 - self.x.0) * self.size.0
    }

    /// The y of decade `d` of error.
    fn yd(&self, d: f64) -> f64 {
        self.origin.1 + (1.0 - (d - self.y.0) / (self.y.1 - self.y.0)) * self.size.1
    }

    /// The frame, the grid with its decade labels and the axis titles.
    fn draw(&self, panel: Group) -> Group {
        let (x, y) = self.origin;
        let (w, h) = self.size;
        let frame = [("x", x), ("y", y), ("width", w), ("height", h)];
        let mut g = panel.add(
            at(Rectangle::new(), &frame)
                .set("fill", "none")
                .set("stroke", "#444"),
        );
        let grid = |x1: f64, y1: f64, x2: f64, y2: f64| {
            at(
                Line::new(),
                &[("x1", x1), ("y1", y1), ("x2", x2), ("y2", y2)],
            )
            .set("stroke", "#ddd")
        };
        let mut d = self.x.0;
        while d <= self.x.1 + 1e-9 {
            let xd = self.xd(d);
            g = g.add(grid(xd, y, xd, y + h)).add(text(
                xd,
                y + h + 14.0,
                "middle",
                &format!("1e{}", d as i64),
            ));
            d += 1.0;
        }
        let step = ((self.y.1 - self.y.0) / 6.0).ceil().max(1.0);
        let mut d = self.y.0;
        while d <= self.y.1 + 1e-9 {
            let yd = self.yd(d);
            g = g.add(grid(x, yd, x + w, yd)).add(text(
                x - 4.0,
                yd + 4.0,
                "end",
                &format!("1e{}", d as i64),
            ));
            d += step;
        }
        g.add(text(x + w / 2.0, y + h + 28.0, "middle", "wall time, s"))
            .add(
                Text::new("error_time")
                    .set(
                        "transform",
                        format!(
                            "translate({},{}) rotate(-90)",
                            px(x - MARGIN.0 + 14.0),
                            px(y + h / 2.0)
                        ),
                    )
                    .set("text-anchor", "middle"),
            )
    }
}

fn lx(v: f64) -> f64 {
    v.max(TIME_FLOOR).log10()
}

fn ly(v: f64) -> f64 {
    v.max(ERROR_FLOOR).log10()
}

/// The panel of scene `sc`, its top left corner at `origin`.
fn panel(sc: &SceneReport, rows: &[&Row], origin: (f64, f64)) -> Group {
    let axes = Axes::new(origin, rows);
    let title = text(
        axes.origin.0 + axes.size.0 / 2.0,
        origin.1 + 18.0,
        "middle",
        &format!("{} (ref: {})", sc.scene, sc.reference_outcome),
    )
    .set("font-size", 12)
    .set("font-weight", "bold");
    let mut g = axes.draw(Group::new().add(title));
    for (method, colour) in [("dopri5", "#1f5fbf"), ("ros2", "#c0392b")] {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.method == method)
            .map(|r| axes.at(r.wall_s, r.error_time))
            .collect();
        if pts.is_empty() {
            continue;
        }
        let points: Vec<String> = pts
            .iter()
            .map(|&(x, y)| format!("{},{}", px(x), px(y)))
            .collect();
        g = g.add(
            Polyline::new()
                .set("points", points.join(" "))
                .set("fill", "none")
                .set("stroke", colour)
                .set("stroke-width", 1.5),
        );
        for (x, y) in pts {
            g = g.add(at(Circle::new(), &[("cx", x), ("cy", y), ("r", 3.0)]).set("fill", colour));
        }
    }
    // the event engine: filled diamond (local solves), open diamond (kinematic baseline,
    // distance rule)
    for r in rows
        .iter()
        .filter(|r| r.method == "event" || r.method == "event-dist")
    {
        let (x, y) = axes.at(r.wall_s, r.error_time);
        let d = format!(
            "M{},{} L{},{} L{},{} L{},{} Z",
            px(x),
            px(y - 6.0),
            px(x + 6.0),
            px(y),
            px(x),
            px(y + 6.0),
            px(x - 6.0),
            px(y)
        );
        let diamond = Path::new().set("d", d);
        g = g.add(if r.method == "event" {
            diamond.set("fill", "black")
        } else {
            diamond.set("fill", "none").set("stroke", "black")
        });
    }
    g
}

impl Validation {
    /// The work-precision plot: one panel per scene, event-time error against wall time,
    /// both axes logarithmic.
    pub fn to_svg(&self) -> String {
        let n = self.scenes.len().max(1);
        let width = COLUMNS as f64 * PANEL.0;
        let height = n.div_ceil(COLUMNS) as f64 * PANEL.1 + 40.0;
        let mut doc = Document::new()
            .set("width", width)
            .set("height", height)
            .set("viewBox", (0, 0, width, height))
            .set("font-family", "sans-serif")
            .set("font-size", 11)
            .add(
                Rectangle::new()
                    .set("width", "100%")
                    .set("height", "100%")
                    .set("fill", "white"),
            )
            .add(text(
                width / 2.0,
                height - 12.0,
                "middle",
                "event-time error (over the duration) against wall time; blue: dopri5, red: ros2 (tolerance ladder), diamonds: event engine (filled: local solves, open: kinematic baseline with the distance rule)",
            ).set("font-size", 12));
        for (i, sc) in self.scenes.iter().enumerate() {
            let origin = (
                (i % COLUMNS) as f64 * PANEL.0,
                (i / COLUMNS) as f64 * PANEL.1,
            );
            let rows: Vec<&Row> = self.rows.iter().filter(|r| r.scene == sc.scene).collect();
            doc = doc.add(panel(sc, &rows, origin));
        }
        format!("{doc}\n")
    }
}
