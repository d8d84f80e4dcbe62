//! The viewer `fold-run` writes (`index.html`), opened in headless Chromium from Debian's
//! packages: the state it reports on `<body>`, its screenshots, its tile poses against the
//! library's, the collision, engine and reference side by side.
//!
//! Without a browser these tests print a note and pass, except under `CI=true`, where a
//! missing browser fails them (`.ci/run` installs Chromium).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod browser;

use std::path::Path;

use browser::{attr, attributes, browser, chromium, serpentine, tmp, url, WINDOW};

use foldchain::collision::CheckOptions;
use foldchain::engine::{EngineOptions, TileDesigns, Timeline};
use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::Recording;
use foldchain::reference::{run_reference, ReferenceOptions};
use foldchain::timeline::RunSource;
use foldchain::{simulate, Chain, Pose};

mod common;
use common::{run, shape, stderr, summary};

/// The page's background colour.
const BACKGROUND: [u8; 3] = [0xfb, 0xfb, 0xf8];

/// The library's engine run of `word` with the thesis design, as `fold-run` makes it.
fn engine_run(word: &str) -> Timeline {
    let chain = Chain::parse(word).unwrap();
    let opts = (EngineOptions::default(), CheckOptions::default());
    simulate(&chain, &TileDesigns::default(), &opts.0, &opts.1)
        .unwrap()
        .0
}

/// `fold-run` on `chain` with `extra` options, writing its files and page into `d` (two
/// frames).
fn fold_run_page(chain: &str, d: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![chain, "--out", d.to_str().unwrap(), "--frames", "2"];
    args.extend(extra);
    run("fold-run", &args)
}

/// The events of the run written into `d` (`timeline.json`): time, kind, index.
fn timeline_events(d: &Path) -> Vec<(f64, String, u64)> {
    let text = std::fs::read_to_string(d.join("timeline.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["events"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            (
                e[0].as_f64().unwrap(),
                e[1].as_str().unwrap().to_string(),
                e[2].as_u64().unwrap(),
            )
        })
        .collect()
}

/// The page at `hash` as Chromium shows it after 3 s (virtual time): its DOM.
fn dump_dom(exe: &Path, page: &Path, hash: &str) -> String {
    chromium(
        exe,
        &url(page, hash),
        &["--virtual-time-budget=3000".into(), "--dump-dom".into()],
    )
}

/// The page's `<body>` attributes at `hash`.
fn body(exe: &Path, page: &Path, hash: &str) -> Vec<(String, String)> {
    let dom = dump_dom(exe, page, hash);
    attributes(&dom, "body", "data-time")
}

/// A screenshot of the page at `hash`: width, height and RGBA pixels.
fn screenshot(exe: &Path, page: &Path, hash: &str, name: &str) -> (usize, usize, Vec<u8>) {
    let png = page.parent().unwrap().join(format!("{name}.png"));
    let _ = chromium(
        exe,
        &url(page, hash),
        &[
            "--virtual-time-budget=3000".into(),
            format!("--screenshot={}", png.display()),
        ],
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&png).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let rgba: Vec<u8> = buf[..info.buffer_size()]
        .chunks(channels)
        .flat_map(|c| [c[0], c[1], c[2], if channels == 4 { c[3] } else { 255 }])
        .collect();
    (info.width as usize, info.height as usize, rgba)
}

/// Where the page draws the world point `(x, y)` mm: `data-view` is pixels per mm and the
/// pixel position of the world origin.
fn to_pixel(view: &str, (x, y): (f64, f64)) -> (usize, usize) {
    let v: Vec<f64> = view.split(',').map(|s| s.parse().unwrap()).collect();
    ((v[1] + x * v[0]) as usize, (v[2] - y * v[0]) as usize)
}

fn pixel(shot: &(usize, usize, Vec<u8>), (x, y): (usize, usize)) -> [u8; 3] {
    let i = 4 * (y * shot.0 + x);
    [shot.2[i], shot.2[i + 1], shot.2[i + 2]]
}

fn poses_of(attrs: &[(String, String)], name: &str) -> Vec<Pose> {
    attr(attrs, name)
        .split(';')
        .map(|p| {
            let v: Vec<f64> = p.split(',').map(|s| s.parse().unwrap()).collect();
            Pose::new(v[0], v[1], v[2])
        })
        .collect()
}

/// Page poses against the library's: positions within `joints * 1e-5 rad * chain length`
/// (the angle tracks' tolerance, foldchain::viewer::ANGLE_TOLERANCE, at every joint) plus
/// f32 rounding, angles within `joints * 1e-5` rad.
fn assert_poses_match(page: &[Pose], lib: &[Pose], w: f64, what: &str) {
    assert_eq!(page.len(), lib.len(), "{what}");
    let joints = lib.len().saturating_sub(1) as f64;
    let tol_angle = joints * 1.1e-5;
    let tol_pos = tol_angle * lib.len() as f64 * w + 1e-6 * w;
    for (i, (a, b)) in page.iter().zip(lib).enumerate() {
        let d = (a.x - b.x).hypot(a.y - b.y);
        let da = (a.angle - b.angle + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(
            d <= tol_pos,
            "{what}: tile {i} is {d} mm off (tolerance {tol_pos})"
        );
        assert!(
            da.abs() <= tol_angle,
            "{what}: tile {i} turned {da} rad off"
        );
    }
}

#[test]
fn opens_at_the_start_and_at_the_end_with_the_summarys_folds() {
    let Some(exe) = browser() else { return };
    let d = tmp("start-end");
    let o = fold_run_page("SSLLSS", &d, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let page = d.join("index.html");
    let html = std::fs::read_to_string(&page).unwrap();
    // self-contained: nothing to fetch
    for bad in ["http:", "https:", "<link", "@import", "src=", "url("] {
        assert!(!html.contains(bad), "index.html holds {bad}");
    }
    let folds = summary(&d)["folds"].as_array().unwrap().len();
    assert_eq!(folds, 2);
    let start = body(&exe, &page, "t=0");
    assert_eq!(attr(&start, "data-time"), "0");
    assert_eq!(attr(&start, "data-folded"), "0");
    // the RI touches tile 0 at t = 0: its first magnet starts then
    assert_eq!(attr(&start, "data-moving"), "1");
    let end = body(&exe, &page, "t=end");
    assert_eq!(attr(&end, "data-folded"), folds.to_string());
    assert_eq!(attr(&end, "data-moving"), "0");
    let t_end: f64 = attr(&end, "data-time").parse().unwrap();
    let duration = summary(&d)["duration_s"].as_f64().unwrap();
    assert!(
        (t_end - duration).abs() < 1e-9 * duration,
        "{t_end} {duration}"
    );
    // mid-run, something moves. Half the duration is no such moment: both sides of a fold
    // turn against their inertia on the water, so the magnets have all arrived long before
    // the folds end (SSLLSS: the last magnet at 0.32 s, the folds at 0.63 and 0.80 s). The
    // moments come from the run's own timeline instead: half way through the last magnet's
    // move, and half way through the first fold
    let events = timeline_events(&d);
    let at = |kind: &str, index: u64, after: f64| {
        events
            .iter()
            .find(|(t, k, i)| k == kind && *i == index && *t >= after)
            .map(|e| e.0)
            .unwrap_or_else(|| panic!("no {kind} {index} after {after} s"))
    };
    let (t0, last) = events
        .iter()
        .rev()
        .find(|e| e.1 == "magnet_starts")
        .map(|e| (e.0, e.2))
        .unwrap();
    let magnet_mid = 0.5 * (t0 + at("magnet_arrives", last, t0));
    let moving = body(&exe, &page, &format!("t={magnet_mid}"));
    assert!(attr(&moving, "data-moving").parse::<usize>().unwrap() > 0);
    assert!(attr(&moving, "data-render-ms").parse::<f64>().unwrap() > 0.0);
    let (f0, joint) = events
        .iter()
        .find(|e| e.1 == "fold_starts")
        .map(|e| (e.0, e.2))
        .unwrap();
    let f1 = at("fold_ends", joint, f0);
    let fold_mid = 0.5 * (f0 + f1);
    let mid = body(&exe, &page, &format!("t={fold_mid}"));
    assert!(attr(&mid, "data-status").starts_with("folding"));
    assert!(attr(&mid, "data-folded").parse::<usize>().unwrap() < folds);
    // the fold is part way and turning: the tile after the joint, against the tile before
    // it, between its start and its quarter turn, and further on 1% of the fold later
    let later = fold_mid + 0.01 * (f1 - f0);
    let dom = dump_dom(
        &exe,
        &page,
        &format!("t={fold_mid}&probe={fold_mid},{later}"),
    );
    let panel = attributes(&dom, "section", "data-poses-1");
    let turn = |name: &str| {
        let p = poses_of(&panel, name);
        let j = joint as usize;
        (p[j + 1].angle - p[j].angle + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI
    };
    let (a, b) = (turn("data-poses-1").abs(), turn("data-poses-2").abs());
    let quarter = std::f64::consts::FRAC_PI_2;
    assert!(
        a > 0.02 * quarter && a < 0.98 * quarter,
        "joint {joint} at {a} rad"
    );
    assert!(b > a + 1e-4, "joint {joint}: {a} then {b} rad");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn screenshots_at_the_start_and_the_end_differ_and_show_the_chain() {
    let Some(exe) = browser() else { return };
    let d = tmp("shots");
    let o = fold_run_page("SSLLSS", &d, &[]);
    assert!(o.status.success());
    let page = d.join("index.html");
    let tl = engine_run("SSLLSS");
    let mut shots = Vec::new();
    // the whole run in view (not following), so that the last tile's first place is in the
    // picture at the end too
    for (hash, t) in [("t=0&follow=0", 0.0), ("t=end&follow=0", tl.end_time())] {
        let view = body(&exe, &page, hash);
        let shot = screenshot(&exe, &page, hash, &format!("shot-{t}"));
        assert_eq!((shot.0, shot.1), (WINDOW.0 as usize, WINDOW.1 as usize));
        // every tile centre, where the library puts it, is drawn (not background)
        let poses = tl.state_at(t).poses;
        for (i, p) in poses.iter().enumerate() {
            let at = to_pixel(attr(&view, "data-view"), (p.x, p.y));
            assert_ne!(pixel(&shot, at), BACKGROUND, "{hash}: tile {i} at {at:?}");
        }
        shots.push((shot, poses, view));
    }
    let (a, b) = (&shots[0].0, &shots[1].0);
    let differing =
        a.2.chunks(4)
            .zip(b.2.chunks(4))
            .filter(|(p, q)| p != q)
            .count();
    assert!(differing > 1000, "only {differing} pixels differ");
    // the last tile has left its place: background there at the end
    let last = shots[0].1.last().copied().unwrap();
    let at = to_pixel(attr(&shots[1].2, "data-view"), (last.x, last.y));
    assert_eq!(pixel(b, at), BACKGROUND);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn page_poses_match_the_librarys_for_engine_and_reference() {
    let Some(exe) = browser() else { return };
    let d = tmp("poses");
    // curved paths (L and R folds), a collision and a fold angle law to follow
    let word = "LSLLSR";
    // the library's default dynamics (overdamped) on both sides
    let o = fold_run_page(word, &d, &["--compare", "--dynamics", "overdamped"]);
    assert!(o.status.code().is_some(), "{}", stderr(&o));
    let page = d.join("index.html");
    let chain = Chain::parse(word).unwrap();
    let tl = engine_run(word);
    // the reference as fold-run ran it above (--dynamics overdamped, the library's default)
    let ro = ReferenceOptions::default()
        .with_model(ModelOptions::default().with_dynamics(Dynamics::Overdamped))
        .with_record(Recording::within_budget(chain.len()));
    let reference = run_reference(&chain, &TileDesigns::default(), &ro).unwrap();
    let w = tl.geometry().w;
    // the engine at any time (the fold law is sampled within its tolerance), the reference
    // at its recorded states (between them the page interpolates, the library shows the
    // nearest)
    let engine_times: Vec<f64> = (0..=8).map(|i| tl.end_time() * i as f64 / 8.0).collect();
    let n = reference.states.len();
    let ref_times: Vec<f64> = (0..=6)
        .map(|i| reference.states[(n - 1) * i / 6].0)
        .collect();
    for (run, times) in [("engine", &engine_times), ("reference", &ref_times)] {
        let probe: Vec<String> = times.iter().map(|t| t.to_string()).collect();
        let dom = dump_dom(&exe, &page, &format!("t=0&probe={}", probe.join(",")));
        let panel = attributes(&dom, "section", &format!("data-run=\"{run}\""));
        for (i, &t) in times.iter().enumerate() {
            let lib = if run == "engine" {
                tl.state_at(t).poses
            } else {
                reference.state_at(t).poses
            };
            let page = poses_of(&panel, &format!("data-poses-{}", i + 1));
            assert_poses_match(&page, &lib, w, &format!("{run} t={t}"));
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn the_collision_is_marked_at_its_time_and_place() {
    let Some(exe) = browser() else { return };
    let d = tmp("collision");
    // overdamped, as the library's engine_run below: LSLLSR collides (the inertial folds of
    // fold-run's default pass)
    let o = fold_run_page("LSLLSR", &d, &["--dynamics", "overdamped"]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "LSLLSR collides with the thesis design, overdamped"
    );
    let s = summary(&d);
    let hit = &s["first_collision"];
    let t = hit["time"].as_f64().unwrap();
    let tiles: Vec<usize> = hit["tiles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as usize)
        .collect();
    let page = d.join("index.html");
    let tl = engine_run("LSLLSR");
    let red = |p: [u8; 3]| p[0] > 200 && p[1] < 90 && p[2] < 90;
    for (when, marked) in [(0.9 * t, false), (t, true)] {
        let hash = format!("t={when}");
        let attrs = body(&exe, &page, &hash);
        let expect = if marked {
            format!("{},{}", tiles[0], tiles[1])
        } else {
            String::new()
        };
        assert_eq!(attr(&attrs, "data-collision"), expect, "t={when}");
        let shot = screenshot(&exe, &page, &hash, &format!("hit-{marked}"));
        let poses = tl.state_at(when).poses;
        for (i, p) in poses.iter().enumerate() {
            let colour = pixel(&shot, to_pixel(attr(&attrs, "data-view"), (p.x, p.y)));
            let should = marked && tiles.contains(&i);
            assert_eq!(red(colour), should, "t={when}: tile {i} is {colour:?}");
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn compare_shows_engine_and_reference_side_by_side() {
    let Some(exe) = browser() else { return };
    let d = tmp("compare");
    let o = fold_run_page("SSLLSS", &d, &["--compare"]);
    assert!(o.status.success(), "{}", stderr(&o));
    for run in ["engine", "reference"] {
        assert!(d.join(run).join("summary.json").is_file(), "{run}");
        assert!(d.join(run).join("index.html").is_file(), "{run}");
    }
    let dom = dump_dom(&exe, &d.join("index.html"), "t=end");
    for run in ["engine", "reference"] {
        let panel = attributes(&dom, "section", &format!("data-run=\"{run}\""));
        let folds = summary(&d.join(run))["folds"].as_array().unwrap().len();
        assert_eq!(attr(&panel, "data-folded"), folds.to_string(), "{run}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// The panel's left, top, width and height (CSS pixels) from `data-panel`.
fn panel_rect(attrs: &[(String, String)]) -> [f64; 4] {
    let v: Vec<f64> = attr(attrs, "data-panel")
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    [v[0], v[1], v[2], v[3]]
}

/// The box of the tiles of `poses` on screen under `view` (`data-view`), each tile its
/// centre give or take half its width `w`: `[left, top, right, bottom]`, CSS pixels.
fn screen_box(view: &str, poses: &[Pose], w: f64) -> [f64; 4] {
    let v: Vec<f64> = view.split(',').map(|s| s.parse().unwrap()).collect();
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in poses {
        let (x, y) = (v[1] + p.x * v[0], v[2] - p.y * v[0]);
        let h = 0.5 * w * v[0];
        b = [
            b[0].min(x - h),
            b[1].min(y - h),
            b[2].max(x + h),
            b[3].max(y + h),
        ];
    }
    b
}

/// The key planned from the thesis' shape (`fold-run shapes/key.svg --tiles 171`, the
/// README's first command) into `d`.
fn key_run(d: &Path) -> std::process::Output {
    fold_run_page(shape("key.svg").to_str().unwrap(), d, &["--tiles", "171"])
}

/// A fixed key chain (the 167-tile plan of the cell planner, rows along the shaft, one
/// quarter turn, columns through the head), so that the camera test does not change with the
/// planner's choices.
const KEY_CHAIN: &str = "SS*19 SR RR RS SS*19 SR RS SS*5 SL LL LS SS*12 SR RR RS SS*12 SL LL LS SS*12 SR RR RS SS*12 SL LL LS SS*12 SR RR RS SS*12 SL LL LS SS*11 SR RR RS SS*12";

#[test]
fn the_folded_key_fills_the_view_at_the_end_and_the_caption_tells_the_time() {
    let Some(exe) = browser() else { return };
    let d = tmp("key");
    let o = key_run(&d);
    assert!(o.status.success(), "{}", stderr(&o));
    let page = d.join("index.html");
    let s = summary(&d);
    let folds = s["folds"].as_array().unwrap().len();
    let dom = dump_dom(&exe, &page, "t=end&poses=1");
    let at_end = attributes(&dom, "body", "data-time");
    let panel = attributes(&dom, "section", "data-run=");
    let poses = poses_of(&panel, "data-poses");
    assert!(poses.len() >= 150, "{} tiles", poses.len());
    // the tile width: neighbours' centres are one width apart, straight or folded
    let w = (poses[1].x - poses[0].x).hypot(poses[1].y - poses[0].y);
    let [left, top, width, height] = panel_rect(&at_end);
    let b = screen_box(attr(&at_end, "data-view"), &poses, w);
    // the whole shape in the panel, and at least half of it across or down
    assert!(
        b[0] >= left - 1.0
            && b[1] >= top - 1.0
            && b[2] <= left + width + 1.0
            && b[3] <= top + height + 1.0,
        "shape {b:?} leaves the panel {left},{top} {width}x{height}"
    );
    let fill = ((b[2] - b[0]) / width).max((b[3] - b[1]) / height);
    assert!(fill >= 0.5, "the key fills {fill:.2} of the view");
    assert_eq!(attr(&at_end, "data-follow"), "1");
    // fitting the whole run instead (follow=0), the speck the issue saw: the test can fail
    let dom = dump_dom(&exe, &page, "t=end&follow=0");
    let whole = attributes(&dom, "body", "data-time");
    let b0 = screen_box(attr(&whole, "data-view"), &poses, w);
    let fill0 = ((b0[2] - b0[0]) / width).max((b0[3] - b0[1]) / height);
    assert!(fill0 < fill, "{fill0} {fill}");
    // the screenshot at the end: every tile centre drawn
    let shot = screenshot(&exe, &page, "t=end", "key-end");
    for (i, p) in poses.iter().enumerate() {
        let at = to_pixel(attr(&at_end, "data-view"), (p.x, p.y));
        assert_ne!(pixel(&shot, at), BACKGROUND, "tile {i} at {at:?}");
    }
    // the caption: what has happened by the shown time, the verdict only at the end
    let result = s["result"].as_str().unwrap().to_string();
    let start = body(&exe, &page, "t=0");
    let status = attr(&start, "data-status");
    assert!(
        status.starts_with(&format!("folding: 0 of {folds} folds done")),
        "{status}"
    );
    assert!(!status.contains(&result), "{status}");
    let duration = s["duration_s"].as_f64().unwrap();
    let mid = body(&exe, &page, &format!("t={}", 0.8 * duration));
    let status = attr(&mid, "data-status");
    let done: usize = attr(&mid, "data-folded").parse().unwrap();
    assert!(
        status.starts_with(&format!("folding: {done} of {folds} folds done")),
        "{status}"
    );
    assert!(0 < done && done < folds, "{done} of {folds}");
    let status = attr(&at_end, "data-status");
    assert!(
        status.starts_with(&result) && status.contains(&format!("{folds} of {folds} folds done")),
        "{status}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn the_camera_follows_the_fold_without_jumps() {
    let Some(exe) = browser() else { return };
    let d = tmp("follow");
    let o = fold_run_page(KEY_CHAIN, &d, &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let page = d.join("index.html");
    let duration = summary(&d)["duration_s"].as_f64().unwrap();
    // the view at 301 times over the run, as a paused page shows it at each
    let steps = 300;
    let times: Vec<String> = (0..=steps)
        .map(|i| (duration * i as f64 / steps as f64).to_string())
        .collect();
    let dom = dump_dom(&exe, &page, &format!("t=0&views={}", times.join(",")));
    let b = attributes(&dom, "body", "data-time");
    let [_, _, width, _] = panel_rect(&b);
    let views: Vec<Vec<f64>> = (1..=steps + 1)
        .map(|i| {
            attr(&b, &format!("data-view-{i}"))
                .split(',')
                .map(|s| s.parse().unwrap())
                .collect()
        })
        .collect();
    let (first, last) = (&views[0], &views[steps]);
    // it zooms out as the shape grows: the start shows the first tiles larger
    assert!(first[0] > 1.2 * last[0], "{first:?} {last:?}");
    // between neighbouring times (1/300 of the run) the scale changes by under 10% and the
    // world point at the panel's centre moves by under a twentieth of the panel (framing
    // the turning tiles where they were, the tail whipping round at a fold moved it by a
    // fifth in one step; taking the folded part's reach as it came, a row settling at once
    // changed the scale by 30%)
    let centre = |v: &[f64]| ((0.5 * width - v[1]) / v[0], v[2] / v[0]);
    for (i, pair) in views.windows(2).enumerate() {
        let (a, z) = (&pair[0], &pair[1]);
        let zoom = (z[0] / a[0]).ln().abs();
        assert!(zoom < 0.1, "step {i}: scale {} -> {}", a[0], z[0]);
        let (ca, cz) = (centre(a), centre(z));
        let moved = (ca.0 - cz.0).hypot(ca.1 - cz.1) * a[0];
        assert!(
            moved < 0.05 * width,
            "step {i}: the centre moved {moved} px"
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_long_serpentine_is_rasterised_framed_and_timed() {
    let Some(exe) = browser() else { return };
    let d = tmp("serpentine");
    // 1,600 tiles: past the 1,500 in view above which the page rasterises (RASTER_ABOVE in
    // viewer-raster.js), quick to run
    let word = serpentine(1_600, 50);
    let o = run(
        "fold-run",
        &[&word, "--out", d.to_str().unwrap(), "--frames", "1"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let page = d.join("index.html");
    let dom = dump_dom(&exe, &page, "t=end&poses=1");
    let b = attributes(&dom, "body", "data-time");
    assert_eq!(attr(&b, "data-renderer"), "raster");
    // the drawing times are reported (their size is a benchmark's business: BENCHMARKS.md)
    for name in ["data-render-ms", "data-first-render-ms"] {
        let ms: f64 = attr(&b, name).parse().unwrap();
        assert!(ms.is_finite() && ms > 0.0, "{name} {ms}");
    }
    // framed on the folded block: every tile centre drawn, in the panel
    let poses = poses_of(&attributes(&dom, "section", "data-run="), "data-poses");
    assert_eq!(poses.len(), 1_600);
    let shot = screenshot(&exe, &page, "t=end", "serpentine-end");
    let [left, top, width, height] = panel_rect(&b);
    for (i, p) in poses.iter().enumerate().step_by(7) {
        let at = to_pixel(attr(&b, "data-view"), (p.x, p.y));
        assert!(
            (at.0 as f64) >= left
                && (at.0 as f64) < left + width
                && (at.1 as f64) >= top
                && (at.1 as f64) < top + height,
            "tile {i} at {at:?}"
        );
        assert_ne!(pixel(&shot, at), BACKGROUND, "tile {i} at {at:?}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}
