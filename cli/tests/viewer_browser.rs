//! The viewer `fold-run` writes (`index.html`), opened in headless Chromium from Debian's
//! packages: the state it reports on `<body>`, its screenshots, its tile poses against the
//! library's, the collision, engine and reference side by side.
//!
//! Without a browser these tests print a note and pass, except under `CI=true`, where a
//! missing browser fails them (`.ci/run` installs Chromium).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod browser;

use std::path::Path;
use std::process::Command;

use browser::{attr, attributes, browser, chromium, tmp, url, WINDOW};

use foldchain::collision::CheckOptions;
use foldchain::engine::{EngineOptions, TileDesigns, Timeline};
use foldchain::model::{Dynamics, ModelOptions};
use foldchain::reference::Recording;
use foldchain::reference::{run_reference, state_budget, ReferenceOptions};
use foldchain::timeline::RunSource;
use foldchain::{simulate, Chain, Pose};

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

fn fold_run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_fold-run"))
        .args(args)
        .output()
        .unwrap()
}

/// The page's `<body>` attributes at `hash`.
fn body(exe: &Path, page: &Path, hash: &str) -> Vec<(String, String)> {
    let dom = chromium(
        exe,
        &url(page, hash),
        &["--virtual-time-budget=3000".into(), "--dump-dom".into()],
    );
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

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
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
    let o = fold_run(&["SSLLSS", "--out", d.to_str().unwrap(), "--frames", "2"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
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
    // half way, something moves; render time is reported
    let mid = body(&exe, &page, &format!("t={}", 0.5 * duration));
    assert!(attr(&mid, "data-moving").parse::<usize>().unwrap() > 0);
    assert!(attr(&mid, "data-render-ms").parse::<f64>().unwrap() > 0.0);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn screenshots_at_the_start_and_the_end_differ_and_show_the_chain() {
    let Some(exe) = browser() else { return };
    let d = tmp("shots");
    let o = fold_run(&["SSLLSS", "--out", d.to_str().unwrap(), "--frames", "2"]);
    assert!(o.status.success());
    let page = d.join("index.html");
    let tl = engine_run("SSLLSS");
    let mut shots = Vec::new();
    for (hash, t) in [("t=0", 0.0), ("t=end", tl.end_time())] {
        let view = body(&exe, &page, hash);
        let shot = screenshot(&exe, &page, hash, hash.trim_start_matches("t="));
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
    let o = fold_run(&[
        word,
        "--compare",
        "--dynamics",
        "overdamped",
        "--out",
        d.to_str().unwrap(),
        "--frames",
        "2",
    ]);
    assert!(
        o.status.code().is_some(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let page = d.join("index.html");
    let chain = Chain::parse(word).unwrap();
    let tl = engine_run(word);
    // the reference as fold-run ran it above (--dynamics overdamped, the library's default)
    let ro = ReferenceOptions::default()
        .with_model(ModelOptions::default().with_dynamics(Dynamics::Overdamped))
        .with_record(Recording::Grid {
            max_states: state_budget(chain.len()),
        });
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
        let dom = chromium(
            &exe,
            &url(&page, &format!("t=0&probe={}", probe.join(","))),
            &["--virtual-time-budget=3000".into(), "--dump-dom".into()],
        );
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
    let o = fold_run(&[
        "LSLLSR",
        "--dynamics",
        "overdamped",
        "--out",
        d.to_str().unwrap(),
        "--frames",
        "2",
    ]);
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
    let o = fold_run(&[
        "SSLLSS",
        "--compare",
        "--out",
        d.to_str().unwrap(),
        "--frames",
        "2",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for run in ["engine", "reference"] {
        assert!(d.join(run).join("summary.json").is_file(), "{run}");
        assert!(d.join(run).join("index.html").is_file(), "{run}");
    }
    let dom = chromium(
        &exe,
        &url(&d.join("index.html"), "t=end"),
        &["--virtual-time-budget=3000".into(), "--dump-dom".into()],
    );
    for run in ["engine", "reference"] {
        let panel = attributes(&dom, "section", &format!("data-run=\"{run}\""));
        let folds = summary(&d.join(run))["folds"].as_array().unwrap().len();
        assert_eq!(attr(&panel, "data-folded"), folds.to_string(), "{run}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}
