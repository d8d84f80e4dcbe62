//! The energy picture of the thesis' figures 7.7 and 7.8: on the left the energy of each pair
//! of adjacent magnets against time, on the right the chain's total, both with dashed lines
//! at the phase boundaries (a magnet starting or arriving, a fold starting or ending).

use svg::node::element::{Line, Text};
use svg::Document;

use foldchain::timeline::PairEnergies;

use crate::axes::Axes;
use crate::{document, num, plot_line, to_text};

/// Colours of the pair curves, in turn.
const COLOURS: [&str; 8] = [
    "#1a56b8", "#c5221f", "#188038", "#e37400", "#8430ce", "#007b83", "#b31412", "#5f6368",
];

/// The two-panel picture of `e` titled `title`.
pub fn pair_energy_svg(e: &PairEnergies, title: &str) -> String {
    let t1 = e.times.last().copied().unwrap_or(1.0).max(1e-9);
    let range = |series: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = series.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        if hi.partial_cmp(&lo) == Some(std::cmp::Ordering::Greater) {
            let pad = 0.05 * (hi - lo);
            (lo - pad, hi + pad)
        } else {
            (lo - 1.0, hi + 1.0)
        }
    };
    let (plo, phi) = range(&mut e.pairs.iter().flatten().map(|v| v * 1e3));
    let (tlo, thi) = range(&mut e.total.iter().map(|v| v * 1e3));
    let panel = |y0: f64, y1: f64| Axes {
        x0: 0.0,
        x1: t1,
        y0,
        y1,
        left: 80.0,
        top: 34.0,
        width: 440.0,
        height: 320.0,
    };
    let left = panel(plo, phi);
    let right = panel(tlo, thi);
    let mut a = left.open(
        "each pair of adjacent magnets",
        "time (s)",
        "pair energy (mJ)",
    );
    let mut b = right.open("total", "time (s)", "total dipole energy (mJ)");
    let dashed = |doc: Document, ax: &Axes| {
        e.phases.iter().fold(doc, |doc, &t| {
            let x = num(ax.px(t));
            doc.add(
                Line::new()
                    .set("x1", x.clone())
                    .set("y1", num(ax.top))
                    .set("x2", x)
                    .set("y2", num(ax.top + ax.height))
                    .set("stroke", "#888")
                    .set("stroke-width", "0.7")
                    .set("stroke-dasharray", "4 3"),
            )
        })
    };
    a = dashed(a, &left);
    b = dashed(b, &right);
    for (k, series) in e.pairs.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let pts = e
            .times
            .iter()
            .zip(series)
            .map(|(&t, &v)| (left.px(t), left.py(v * 1e3)));
        let label = if k == 0 {
            "RI-0".to_string()
        } else {
            format!("{}-{}", k - 1, k)
        };
        a = a.add(plot_line(pts, colour, "1.6")).add(
            Text::new(label)
                .set("x", num(left.left + left.width - 8.0))
                .set("y", num(left.top + 16.0 + 14.0 * k as f64))
                .set("text-anchor", "end")
                .set("fill", colour),
        );
    }
    let pts = e
        .times
        .iter()
        .zip(&e.total)
        .map(|(&t, &v)| (right.px(t), right.py(v * 1e3)));
    b = b.add(plot_line(pts, "#c5221f", "2"));
    let (w, h) = (left.left + left.width + 30.0, left.top + left.height + 50.0);
    let doc: Document = document(2.0 * w, h + 30.0, "white")
        .set("font-size", "12")
        .add(
            Text::new(title)
                .set("x", num(w))
                .set("y", "20")
                .set("font-size", "15")
                .set("text-anchor", "middle"),
        )
        .add(a.set("x", "0").set("y", "30"))
        .add(b.set("x", num(w)).set("y", "30"));
    to_text(&doc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_panels_with_a_curve_per_pair_and_dashed_phases() {
        let e = PairEnergies {
            times: vec![0.0, 0.5, 1.0],
            pairs: vec![vec![-1e-3, -2e-3, -3e-3], vec![-4e-3, -4e-3, -5e-3]],
            total: vec![-5e-3, -6e-3, -8e-3],
            phases: vec![0.2, 0.7],
        };
        let svg = pair_energy_svg(&e, "SL & test");
        assert_eq!(svg.matches("<polyline").count(), 3);
        assert_eq!(svg.matches("stroke-dasharray").count(), 4);
        assert_eq!(
            svg.matches("<svg").count(),
            3,
            "one picture holding two panels"
        );
        assert!(svg.contains("SL &amp; test"));
    }
}
