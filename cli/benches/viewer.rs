//! The viewer's size and drawing time: `cargo bench -p foldchain-cli --bench viewer [-- MAX]`.
//!
//! For serpentines of 10^3, 10^4 and 10^5 tiles (up to MAX, default 100000): the time to
//! build `index.html` and its size (bytes per tile), then the page in headless Chromium
//! drawing 30 frames at times spread over the run, each flushed to pixels (`#bench=30`):
//! the median and slowest frame, for the whole run in view, with every part of every tile
//! drawn (`detail=all`), and, for 10^4 tiles, the same drawn by the browser's canvas alone
//! (`renderer=2d`); and the page as it opens at the end (`#t=end`, the camera framing the
//! final shape), loaded 5 times: the median of its `data-first-render-ms` (the opening
//! frame, which pays for compiling the script) and of its `data-render-ms` (the same frame
//! redrawn in full once the page is idle), both flushed to pixels. Prints the machine's load
//! average too: the figures are wall times.

#![allow(clippy::unwrap_used)] // a benchmark may unwrap, like a test

#[path = "../tests/browser/mod.rs"]
mod browser;
#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use browser::{attr, attributes, chromium, serpentine, tmp, url};
use foldchain::collision::CheckOptions;
use foldchain::engine::{EngineOptions, TileDesigns};
use foldchain::{simulate, Chain};
use foldchain_render::viewer::{viewer_html, RunView};

fn main() {
    let max: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(100_000);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("load average: {}", load.trim());
    let Some(exe) = browser::browser() else {
        return;
    };
    let dir = tmp("bench");
    for (tiles, row) in [(1_000, 32), (10_000, 100), (100_000, 316)] {
        if tiles > max {
            break;
        }
        let chain = Chain::parse(&serpentine(tiles, row)).unwrap();
        let (tl, summary) = simulate(
            &chain,
            &TileDesigns::default(),
            &EngineOptions::default(),
            &CheckOptions::default(),
        )
        .unwrap();
        let t0 = Instant::now();
        let html = viewer_html("serpentine", &[RunView::new(&tl, "serpentine")]);
        let build = t0.elapsed().as_secs_f64();
        let page = dir.join(format!("serpentine-{tiles}.html"));
        std::fs::write(&page, &html).unwrap();
        println!(
            "{tiles} tiles ({} events): index.html {} bytes ({:.1} per tile, {:.1} per event), built in {build:.3} s",
            summary.events,
            html.len(),
            html.len() as f64 / tiles as f64,
            html.len() as f64 / summary.events as f64
        );
        let mut first = Vec::new();
        let mut redraw = Vec::new();
        let mut renderer = String::new();
        for _ in 0..5 {
            let dom = chromium(&exe, &url(&page, "t=end"), &["--dump-dom".into()]);
            let b = attributes(&dom, "body", "data-time");
            first.push(attr(&b, "data-first-render-ms").parse::<f64>().unwrap());
            redraw.push(attr(&b, "data-render-ms").parse::<f64>().unwrap());
            renderer = attr(&b, "data-renderer").to_string();
        }
        let median = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        println!(
            "  {:<24} renderer {renderer:<8} opening frame median {:>7.2} ms, full redraw median {:>7.2} ms over 5 loads (redraws {:?})",
            "opened at t=end",
            median(&mut first),
            median(&mut redraw),
            redraw
        );
        // the whole run in view (follow=0), as before the camera followed the fold
        let mut cases = vec![
            ("whole run", "&follow=0"),
            ("detail=all", "&follow=0&detail=all"),
        ];
        if tiles == 10_000 {
            cases.push((
                "canvas only, detail=all",
                "&follow=0&detail=all&renderer=2d",
            ));
        }
        for (what, opts) in cases {
            let dom = chromium(
                &exe,
                &url(&page, &format!("t=end&bench=30{opts}")),
                &["--dump-dom".into()],
            );
            let b = attributes(&dom, "body", "data-time");
            println!(
                "  {what:<24} renderer {:<8} median {:>7} ms, slowest {:>7} ms over {} frames",
                attr(&b, "data-renderer"),
                attr(&b, "data-render-ms-median"),
                attr(&b, "data-render-ms-max"),
                attr(&b, "data-render-frames")
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
