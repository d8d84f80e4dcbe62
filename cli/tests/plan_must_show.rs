//! Issue 26's must-shows for the planner other than empty parts and speed, on the real
//! `fold-plan` and `fold-check` binaries: the letter A's crossbar and the key's teeth hold
//! tiles, bars and arms within 1.25 times the turns of a hand plan, a clipped logo planned
//! on what a renderer draws, honest counts (within the tolerance or said in a warning, on
//! stderr and in the JSON), short refusals whose detail `--verbose` and `--json` give, and
//! drawings read as drawn (spikes, slivers and repeated points dropped, a mask applied, a
//! stroke-only drawing refused saying why). Every plan made here folds by `fold-check`.
//! (The thesis squares are pinned in `plan_quality_cli.rs`.)

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::Path;
use std::process::{Command, Output};

use foldchain_planner::Plan;

mod common;
use common::{on_path, root, scratch, stderr, tool};

/// `fold-plan FILE --tiles N ARGS --json --quiet` (FILE relative to the workspace root).
fn fold_plan_json(file: &str, tiles: usize, args: &[&str]) -> Output {
    tool("fold-plan")
        .current_dir(root())
        .arg(file)
        .args(["--tiles", &tiles.to_string()])
        .args(args)
        .args(["--json", "--quiet"])
        .output()
        .unwrap()
}

/// The plan of `file` at `tiles` (default options), after asserting what every plan must
/// show: it folds by `fold-check`, and its count is within the tolerance (3%) or a warning
/// says so with both numbers, in the JSON and on stderr.
fn planned(file: &str, tiles: usize) -> Plan {
    let o = fold_plan_json(file, tiles, &[]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{file} at {tiles}: {e}");
    let p = Plan::from_json(&String::from_utf8(o.stdout).unwrap()).unwrap();
    let check = tool("fold-check")
        .args(["--quiet", &p.word])
        .output()
        .unwrap();
    assert!(
        check.status.success(),
        "{file} at {tiles}: fold-check: {}",
        stderr(&check)
    );
    let said = format!("the plan has {} tiles", p.tiles);
    let warned: Vec<&String> = p.warnings.iter().filter(|w| w.contains(&said)).collect();
    if p.tiles.abs_diff(tiles) * 100 > 3 * tiles {
        assert_eq!(warned.len(), 1, "{file} at {tiles}: {:?}", p.warnings);
        assert!(warned[0].contains(&format!("{tiles} asked")), "{warned:?}");
        assert!(
            e.contains(&format!("fold-plan: warning: {}", warned[0])),
            "{e}"
        );
    } else {
        assert!(warned.is_empty(), "{file} at {tiles}: {warned:?}");
    }
    p
}

/// Tile centres of `p` (SVG user units) for which `inside` holds.
fn centres_where(p: &Plan, inside: impl Fn(f64, f64) -> bool) -> usize {
    p.poses.iter().filter(|q| inside(q.x, q.y)).count()
}

/// How many tiles rows of tight U-turns (a tile per w by sqrt2 w) would put in `area`.
fn full_rows(p: &Plan, area: f64) -> f64 {
    area / (p.tile_size * p.tile_size * 2f64.sqrt())
}

/// The letter A (`letters/A.svg`, DejaVu Sans Bold, drawn with y = 1901 - y_font) at 100
/// and 300 tiles: its crossbar, between the legs' inner edges (font units: y 272 to 549, x
/// from the line (492, 272)-(588, 549) to the line (1094, 272)-(997, 549)), holds at least
/// half the tiles that full rows would put there (at main 668c427: 11 of 11.7 and 30 of 35).
#[test]
fn the_letter_a_tiles_its_crossbar() {
    for tiles in [100, 300] {
        let p = planned("planner/corpus/letters/A.svg", tiles);
        let n = centres_where(&p, |x, y| {
            let fy = 1901.0 - y;
            let t = (fy - 272.0) / (549.0 - 272.0);
            (0.0..1.0).contains(&t) && x > 492.0 + 96.0 * t && x < 1094.0 - 97.0 * t
        });
        let full = full_rows(&p, (602.0 + 409.0) / 2.0 * 277.0);
        assert!(
            n as f64 >= 0.5 * full,
            "{tiles}: {n} tiles in the crossbar, full rows {full:.1}: {}",
            p.summary()
        );
    }
}

/// The key (`shapes/key.svg`, thesis figure 5.6c) at 171 tiles: no more than 10 U-turns, a
/// quarter turn at least, and the longer tooth (x 255 to 280, y 82 to 112) holds tiles.
/// Not yet met (the cell planner's, reported to the lead): the first tooth (x 215 to 233, y
/// 82 to 104) holds no tile and the plan takes 3 quarter turns, not one.
#[test]
fn the_key_keeps_its_turns_and_tiles_a_tooth() {
    let p = planned("shapes/key.svg", 171);
    assert!(p.u_turns <= 10, "{}", p.summary());
    assert!(p.quarter_turns >= 1, "{}", p.summary());
    let tooth = centres_where(&p, |x, y| x > 255.0 && x < 280.0 && y > 82.0 && y < 112.0);
    assert!(tooth >= 2, "{tooth} tiles in the tooth: {}", p.summary());
}

/// A U and a plus at 300 tiles: at most 1.25 times the turns (U-turns and quarter turns) of
/// the hand plans, 17 for a U and 15 for the plus (issue 26): 21 and 18. At main 668c427:
/// the U shape 14, the letter U 17, the plus 18.
#[test]
fn bars_and_arms_take_few_turns() {
    for (file, hand) in [
        ("planner/corpus/shapes/u-shape.svg", 17),
        ("planner/corpus/letters/U.svg", 17),
        ("planner/corpus/shapes/plus.svg", 15),
    ] {
        let p = planned(file, 300);
        let turns = p.u_turns + p.quarter_turns;
        assert!(
            turns * 4 <= hand * 5,
            "{file}: {turns} turns, hand plan {hand}: {}",
            p.summary()
        );
    }
}

/// The alpha channel of `svg` rendered by rsvg-convert `px` pixels wide (librsvg, a renderer
/// independent of the planner's usvg), as (width, height, alpha); `None` without
/// rsvg-convert outside CI.
fn rendered_alpha(svg: &Path, px: u32, test: &str) -> Option<(usize, usize, Vec<u8>)> {
    let rsvg = on_path(&["rsvg-convert"], "rsvg-convert", test)?;
    let d = scratch(test);
    let png = d.join("drawing.png");
    let o = Command::new(rsvg)
        .args(["-w", &px.to_string(), "-o"])
        .arg(&png)
        .arg(svg)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let file = std::io::BufReader::new(std::fs::File::open(&png).unwrap());
    let mut reader = png::Decoder::new(file).read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let (w, h) = (info.width as usize, info.height as usize);
    std::fs::remove_dir_all(&d).unwrap();
    Some((w, h, buf[..w * h * 4].chunks(4).map(|c| c[3]).collect()))
}

/// The logo clipped by `clip-path` to a letter G at 300 tiles: at least 97% of the tile
/// centres lie on pixels rsvg-convert paints (at main 668c427: 299 of 302; without the clip
/// the square logo around the letter would be planned).
#[test]
fn a_clipped_logo_is_planned_as_drawn() {
    let file = "planner/corpus/inkscape/ink-clip-logo.svg";
    let p = planned(file, 300);
    // viewBox 0 0 80 80: 10 pixels a user unit
    let Some((w, h, alpha)) = rendered_alpha(&root().join(file), 800, "clip-logo") else {
        return;
    };
    let on = centres_where(&p, |x, y| {
        let (i, j) = ((x * 10.0) as usize, (y * 10.0) as usize);
        i < w && j < h && alpha[j * w + i] > 127
    });
    assert!(
        on * 100 >= 97 * p.tiles,
        "{on} of {} tile centres on the drawn area",
        p.tiles
    );
}

/// The disc under a mask that bites a disc out of it (`ink-mask-crescent.svg`: the bite is
/// centred at (66, 40), radius 33) at 300 tiles: no tile centre lies more than half a tile
/// inside the bite (at main 668c427: none; 4 of 309 lie within half a tile of its edge).
#[test]
fn a_masked_disc_is_planned_as_its_crescent() {
    let p = planned("planner/corpus/inkscape/ink-mask-crescent.svg", 300);
    let bitten = centres_where(&p, |x, y| {
        (x - 66.0).hypot(y - 40.0) < 33.0 - 0.5 * p.tile_size
    });
    assert_eq!(bitten, 0, "{}", p.summary());
}

/// A count the plan misses by more than the tolerance: the disc with several holes at 300
/// tiles (at main 668c427: 261 tiles) carries the warning on stderr and in the JSON
/// (`planned` asserts it whichever way the count falls).
#[test]
fn a_missed_count_is_said_on_stderr_and_in_the_json() {
    let p = planned("planner/corpus/shapes/disc-several-holes.svg", 300);
    assert!(p.tiles > 0, "{}", p.summary());
}

/// The corpus' counts missed by more than 3% at main 668c427 (disc-several-holes 1000 ->
/// 879, the gear 1000 -> 967, O 1000 -> 1056; at 3000: the frog 2838, the clipped logo
/// 2876, C 2854, G 3128, the annulus 2822): each plan folds and is within the tolerance or
/// carries the warning on stderr and in the JSON (`planned`). About 50 s of CPU.
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn large_counts_are_within_the_tolerance_or_warned() {
    for (file, tiles) in [
        ("shapes/disc-several-holes.svg", 1000),
        ("icons/fa-gear.svg", 1000),
        ("letters/O.svg", 1000),
        ("icons/fa-frog.svg", 3000),
        ("inkscape/ink-clip-logo.svg", 3000),
        ("letters/C.svg", 3000),
        ("letters/G.svg", 3000),
        ("shapes/annulus.svg", 3000),
    ] {
        planned(&format!("planner/corpus/{file}"), tiles);
    }
}

/// The plan file `fold-plan --out` writes is a chain `fold-check` reads (before, it was
/// refused: "bad chain JSON: unknown field `source`"), and its verdict is the word's.
#[test]
fn fold_check_reads_a_plan_file() {
    let d = scratch("plan-file");
    let out = d.join("key.json");
    let o = tool("fold-plan")
        .current_dir(root())
        .args(["shapes/key.svg", "--tiles", "171", "--quiet", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let check = |arg: &str| {
        let o = tool("fold-check")
            .args(["--quiet", "--json", arg])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{arg}: {}", stderr(&o));
        serde_json::from_slice::<serde_json::Value>(&o.stdout).unwrap()
    };
    let p = Plan::from_json(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(check(out.to_str().unwrap()), check(&p.word));
    std::fs::remove_dir_all(&d).unwrap();
}

/// A drawing in two parts (`two-discs.svg`) is refused in at most three lines saying what
/// (separate parts), where (drawing units and mm) and what to try; `--verbose` adds a line
/// per part, and `--json` prints the reason and the same detail as JSON on stdout.
#[test]
fn a_refusal_is_short_and_its_detail_is_under_verbose_and_json() {
    let file = "planner/corpus/shapes/two-discs.svg";
    let run = |args: &[&str]| {
        tool("fold-plan")
            .current_dir(root())
            .arg(file)
            .args(["--tiles", "300", "--quiet"])
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&[]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(o.stdout.is_empty());
    assert!(e.trim_end().lines().count() <= 3, "{e}");
    for word in ["separate parts", " mm", "x 5.00 to 65.0", "join the parts"] {
        assert!(e.contains(word), "no {word:?}: {e}");
    }
    let v = stderr(&run(&["--verbose"]));
    let tried: Vec<&str> = v
        .lines()
        .filter_map(|l| l.strip_prefix("fold-plan: tried: "))
        .collect();
    assert_eq!(tried.len(), 2, "{v}");
    let j = run(&["--json"]);
    assert_eq!(j.status.code(), Some(1), "{}", stderr(&j));
    let refusal: serde_json::Value = serde_json::from_slice(&j.stdout).unwrap();
    assert_eq!(refusal["planned"], false);
    assert!(e.contains(refusal["reason"].as_str().unwrap()), "{refusal}");
    let detail: Vec<&str> = refusal["detail"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d.as_str().unwrap())
        .collect();
    assert_eq!(detail, tried);
}

/// Writes `dir/name`, a 100 x 100 drawing holding `body`, and returns its path.
fn drawing(dir: &Path, name: &str, body: &str) -> String {
    let f = dir.join(name);
    let svg =
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">{body}</svg>"#);
    std::fs::write(&f, svg).unwrap();
    f.to_str().unwrap().to_string()
}

/// A drawing of strokes only is refused as bad input, saying why: the sample outline of a
/// heart in the corpus and a stroked circle.
#[test]
fn a_stroke_only_drawing_is_refused_with_the_reason() {
    let d = scratch("stroke");
    let circle = drawing(
        &d,
        "circle.svg",
        r#"<circle cx="50" cy="50" r="30" fill="none" stroke="black" stroke-width="4"/>"#,
    );
    let heart = root().join("planner/corpus/icons/ion-heart-outline.svg");
    for f in [circle.as_str(), heart.to_str().unwrap()] {
        let o = fold_plan_json(f, 100, &[]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{e}");
        assert!(
            e.contains("no filled area") && e.contains("stroke") && e.contains("Stroke to Path"),
            "{e}"
        );
        assert!(e.trim_end().lines().count() <= 3, "{e}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// A square with a frame around the page that paints nothing (opacity 0, as drawing
/// programs leave a page-sized helper) plans as the square alone; before, the frame was read
/// as filled and the square refused as two parts, or planned with the frame.
#[test]
fn what_paints_nothing_is_not_planned() {
    let d = scratch("invisible");
    let write = |name: &str, body: &str| drawing(&d, name, body);
    let square = r#"<rect x="10" y="10" width="80" height="80"/>"#;
    let plain = planned(&write("plain.svg", square), 100);
    for (name, frame) in [
        (
            "opacity.svg",
            r#"<rect width="100" height="100" opacity="0"/>"#,
        ),
        (
            "fill-opacity.svg",
            r#"<rect width="100" height="5" fill-opacity="0"/>"#,
        ),
        (
            "transparent.svg",
            r#"<rect width="100" height="5" fill="transparent"/>"#,
        ),
    ] {
        let p = planned(&write(name, &format!("{frame}{square}")), 100);
        assert_eq!(
            (p.tiles, p.metrics.shape_area.round()),
            (plain.tiles, plain.metrics.shape_area.round()),
            "{name}: {}",
            p.summary()
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// Text, which the planner does not read (it loads no fonts), is refused as bad input in
/// a short message naming the element and what to do; before, a square with a letter
/// beside it was planned as the square alone, and a drawing of text alone was said to have
/// no filled area.
#[test]
fn text_is_refused_saying_to_convert_it_to_paths() {
    let d = scratch("text");
    for (name, body) in [
        ("word.svg", r#"<text x="5" y="60" font-size="40">Hi</text>"#),
        (
            "beside.svg",
            r#"<rect x="10" y="10" width="40" height="80"/><text id="label" x="50" y="90" font-size="80">L</text>"#,
        ),
    ] {
        let o = fold_plan_json(&drawing(&d, name, body), 100, &[]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {e}");
        assert!(o.stdout.is_empty(), "{name}");
        assert!(
            e.contains("holds text") && e.contains("Object to Path"),
            "{e}"
        );
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// Zero-width spikes (out and back along one line, outwards and inwards), a sliver a
/// millionth of a unit wide and repeated points are dropped before the simplicity check:
/// each such square plans as the plain square does (the same area read, count, turns and
/// fit; a spike may turn the tie between the square's two row directions, so the word may
/// be the plain one's mirror image).
#[test]
fn spikes_slivers_and_repeated_points_are_dropped() {
    let d = scratch("spikes");
    let square = "M10 10 L90 10 L90 90 L10 90 Z";
    let plan_of = |name: &str, path: &str| {
        planned(&drawing(&d, name, &format!(r#"<path d="{path}"/>"#)), 100)
    };
    let plain = plan_of("plain.svg", square);
    for (name, path) in [
        (
            "spike-out.svg",
            "M10 10 L90 10 L90 50 L99 50 L90 50 L90 90 L10 90 Z",
        ),
        (
            "spike-in.svg",
            "M10 10 L90 10 L90 50 L50 50 L90 50 L90 90 L10 90 Z",
        ),
        (
            "spike-up.svg",
            "M10 10 L50 10 L50 2 L50 10 L90 10 L90 90 L10 90 Z",
        ),
        (
            "sliver.svg",
            "M10 10 L90 10 L90 50 L99 50.000001 L90 50.000002 L90 90 L10 90 Z",
        ),
        (
            "repeats.svg",
            "M10 10 L90 10 L90 10 L90 10 L90 90 L90 90 L10 90 L10 10 Z",
        ),
    ] {
        let p = plan_of(name, path);
        let m = |p: &Plan| {
            (
                p.tiles,
                p.u_turns,
                p.quarter_turns,
                (p.metrics.shape_area * 1e6).round(),
                (p.metrics.covered_share * 1e9).round(),
                (p.metrics.outside_share * 1e9).round(),
            )
        };
        assert_eq!(m(&p), m(&plain), "{name}: {}", p.summary());
    }
    std::fs::remove_dir_all(&d).unwrap();
}
