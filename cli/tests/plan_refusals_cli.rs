//! `fold-plan`'s refusals a user can act on (issue 26): every refusal, of a drawing that
//! cannot be one chain or of a hostile file, is at most three lines of a 100-column
//! terminal (the file's name aside), names what to change, keeps its exit code (1: a shape
//! that cannot be planned, 2: bad input), and under `--verbose` adds what each planner
//! tried.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::process::Output;

mod common;
#[path = "../../planner/tests/common/drawings.rs"]
mod drawings;
use common::{assert_mentions, root, scratch, stderr, tool};

/// Characters a refusal may take, its file's name left out: three lines of 100 columns.
const MAX_CHARS: usize = 300;

/// Words that say what to change; a refusal holds at least one.
const ACTIONS: [&str; 9] = [
    "try ",
    "join the parts",
    "draw ",
    "simplify the drawing",
    "decompress",
    "save the drawing",
    "expected",
    "cannot read",
    "plan each",
];

fn fold_plan(args: &[&str]) -> Output {
    tool("fold-plan")
        .current_dir(root())
        .args(args)
        .arg("--quiet")
        .output()
        .unwrap()
}

/// The refusal of `file` (a path as given on the command line): exit `code`, nothing on
/// stdout, at most three lines and [`MAX_CHARS`] characters once the file's name is taken
/// out, no panic, and something to change. Returns stderr.
fn short_refusal(o: &Output, file: &str, code: i32) -> String {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(code), "{file}: {e}");
    assert!(o.stdout.is_empty(), "{file}: stdout not empty");
    assert!(!e.contains("panicked"), "{e}");
    assert!(
        e.trim_end().lines().count() <= 3,
        "{file}: more than 3 lines: {e}"
    );
    let without_name = e.replace(file, "");
    assert!(
        without_name.chars().count() <= MAX_CHARS,
        "{file}: {} characters (at most {MAX_CHARS}): {e}",
        without_name.chars().count()
    );
    assert!(
        ACTIONS.iter().any(|a| e.contains(a)),
        "{file}: names nothing to change: {e}"
    );
    e
}

/// Hostile and broken files: each refused as bad input (exit 2) in a short message naming
/// the file and what to change.
#[test]
fn hostile_files_are_refused_briefly_with_what_to_change() {
    let d = scratch("hostile");
    let svg = |body: &str| {
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">{body}</svg>"#)
    };
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty.svg", Vec::new()),
        ("garbage.svg", (0..=255u8).cycle().take(4096).collect()),
        (
            "truncated.svg",
            b"<svg xmlns=\"http://www.w3.org/2000/svg\"><rect".to_vec(),
        ),
        ("html.svg", b"<html><body>not a drawing</body></html>".to_vec()),
        (
            "stroke-only.svg",
            svg(r#"<circle cx="50" cy="50" r="30" fill="none" stroke="black" stroke-width="4"/>"#)
                .into_bytes(),
        ),
        (
            "zero-size.svg",
            svg(r#"<rect x="10" y="10" width="0" height="0"/>"#).into_bytes(),
        ),
        (
            "clipped-away.svg",
            svg(r#"<defs><clipPath id="c"><rect x="200" y="200" width="5" height="5"/></clipPath></defs><rect width="50" height="50" clip-path="url(#c)"/>"#)
                .into_bytes(),
        ),
        (
            "bow-tie.svg",
            svg(r#"<path d="M10 10 L90 90 L90 10 L10 90 Z"/>"#).into_bytes(),
        ),
        (
            "deep.svg",
            svg(&format!(
                "{}<rect width=\"1e300\" height=\"nan\"/>{}",
                "<g>".repeat(2000),
                "</g>".repeat(2000)
            ))
            .into_bytes(),
        ),
    ];
    for (name, data) in &cases {
        let f = d.join(name);
        std::fs::write(&f, data).unwrap();
        let path = f.to_str().unwrap();
        let o = fold_plan(&[path, "--tiles", "100"]);
        // a drawing nothing can be read from is bad input; one that reads (deep groups may)
        // must still end in a plan or a short refusal
        match o.status.code() {
            Some(0) => {}
            Some(c) => {
                let e = short_refusal(&o, path, c);
                assert_eq!(c, 2, "{name}: bad input exits 2: {e}");
            }
            None => panic!("{name}: killed"),
        }
    }
    // a missing file, a directory, a compressed drawing
    let missing = d.join("missing.svg");
    let m = missing.to_str().unwrap();
    short_refusal(&fold_plan(&[m]), m, 2);
    let dir = d.to_str().unwrap();
    let o = fold_plan(&[dir]);
    short_refusal(&o, dir, 2);
    let z = d.join("shape.svgz");
    std::fs::write(&z, b"\x1f\x8b").unwrap();
    let z = z.to_str().unwrap();
    short_refusal(&fold_plan(&[z]), z, 2);
    std::fs::remove_dir_all(&d).unwrap();
}

/// The corpus drawings that are not one piece (its README says which): each is refused at
/// once with exit 1, in a short message naming the parts and what to do; `--verbose` adds
/// the list of parts, one line each.
#[test]
fn drawings_in_separate_parts_are_refused_briefly() {
    let readme = std::fs::read_to_string(root().join("planner/corpus/README.md")).unwrap();
    let apart: Vec<String> = readme
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            (*cells.get(2)? == "no").then(|| format!("planner/corpus/{name}"))
        })
        .collect();
    assert!(apart.len() >= 5, "{apart:?}");
    let mut refused = 0;
    for file in &apart {
        let o = fold_plan(&[file, "--tiles", "300"]);
        match o.status.code() {
            // a part below the raster's reach may join (the corpus README says which)
            Some(0) => continue,
            Some(2) => {
                // the stroke-only drawing: no filled area
                short_refusal(&o, file, 2);
            }
            _ => {
                let e = short_refusal(&o, file, 1);
                assert_mentions(&e, &["separate parts", " mm"]);
                refused += 1;
                let v = fold_plan(&[file, "--tiles", "300", "--verbose"]);
                let ve = stderr(&v);
                assert_eq!(v.status.code(), Some(1));
                assert!(ve.contains("fold-plan: tried: part 1: x "), "{ve}");
                assert!(ve.trim_end().lines().count() > e.trim_end().lines().count());
            }
        }
    }
    assert!(refused >= 5, "{refused} of {} refused", apart.len());
}

/// A map with islands (Natural Earth's Ecuador: the mainland and 8 islands, 3.2% of its
/// area; Kuwait: the mainland and Bubiyan, 3.9%) plans at every count with the islands left
/// out, and says so in the same warning at every count, on stderr and in the JSON: before,
/// Ecuador planned at 100 tiles (its islands then under half a tile) and was refused at
/// 300 and 1000, and Kuwait was refused at every count.
#[test]
fn islands_are_left_out_at_every_count_with_the_same_warning() {
    for (file, islands, west_of_mainland) in [
        (
            "planner/corpus/countries/ecuador.svg",
            "8 islands",
            Some(600.0),
        ),
        ("planner/corpus/countries/kuwait.svg", "1 island", None),
    ] {
        let mut warnings = Vec::new();
        for tiles in [100, 300, 1000] {
            let o = fold_plan(&[file, "--tiles", &tiles.to_string(), "--json"]);
            let e = stderr(&o);
            assert_eq!(o.status.code(), Some(0), "{file} at {tiles}: {e}");
            let plan: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            let n = plan["tiles"].as_u64().unwrap() as usize;
            assert!(
                n.abs_diff(tiles) <= tiles * 3 / 100,
                "{file}: {n} of {tiles}"
            );
            let w: Vec<String> = plan["warnings"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(|w| w.as_str())
                .filter(|w| w.contains("left out"))
                .map(String::from)
                .collect();
            assert_eq!(w.len(), 1, "{file} at {tiles}: {w:?}");
            assert!(
                w[0].starts_with(&format!("{islands} apart from the rest"))
                    && w[0].contains(" mm)")
                    && w[0].contains("join "),
                "{}",
                w[0]
            );
            assert!(e.contains(&format!("fold-plan: warning: {}", w[0])), "{e}");
            // no tile on the islands (Ecuador's lie west of x = 600, the mainland east)
            if let Some(x) = west_of_mainland {
                let poses = plan["poses"].as_array().unwrap();
                assert!(poses.iter().all(|p| p["x"].as_f64().unwrap() > x));
            }
            warnings.push(w[0].clone());
        }
        warnings.dedup();
        assert_eq!(
            warnings.len(),
            1,
            "{file}: the warning changes with the count"
        );
    }
}

/// Pieces that touch are one part: ionicons' leaf, whose stalk ends 0.03 units (of 512) from
/// the leaf's outline, plans at every count with nothing left out. Before, it planned at
/// 100 and 300 tiles and was refused at 1000 as "in 2 separate parts" (the raster at that
/// count saw the stalk apart).
#[test]
fn pieces_that_touch_are_one_part_at_every_count() {
    let file = "planner/corpus/icons/ion-leaf.svg";
    for tiles in [100, 300, 1000] {
        let o = fold_plan(&[file, "--tiles", &tiles.to_string(), "--json"]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "{tiles}: {e}");
        assert!(!e.contains("left out"), "{tiles}: {e}");
        let plan: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let n = plan["tiles"].as_u64().unwrap() as usize;
        assert!(n.abs_diff(tiles) <= tiles * 3 / 100, "{n} of {tiles}");
    }
}

/// A drawing of two large parts (Natural Earth's Estonia: the mainland, Saaremaa, 6.1% of
/// its area, and two islands, 2.7% together) is refused at every count, with the same short message
/// naming both parts' boxes and what to do; `--verbose` adds each part's share and the
/// islands. Before, the count of parts named changed with the tiles (3 at 100 and 300, 4
/// at 1000).
#[test]
fn several_large_parts_are_refused_at_every_count_naming_them() {
    let file = "planner/corpus/countries/estonia.svg";
    let mut reasons = Vec::new();
    for tiles in ["100", "1000", "3000"] {
        let e = short_refusal(&fold_plan(&[file, "--tiles", tiles]), file, 1);
        assert_mentions(
            &e,
            &[
                "2 separate parts: x 250 to 1000, y 178 to 822 (198 x 171 mm) and x 0 to 233",
                "join the parts",
            ],
        );
        reasons.push(e);
    }
    reasons.dedup();
    assert_eq!(reasons.len(), 1, "{reasons:?}");
    let v = stderr(&fold_plan(&[file, "--tiles", "300", "--verbose"]));
    assert_mentions(
        &v,
        &[
            "tried: part 2: x 0 to 233, y 491 to 701 (61.7 x 55.6 mm), 6.1% of the area",
            "tried: and 2 islands (2.7% of the area together), which a plan would leave out",
        ],
    );
}

/// Drawings whose best plan (today) leaves a part empty at 300 tiles: refused in a short
/// message naming where (drawing units and mm) and a tile count that plans (checked) or
/// what to draw; `--verbose` adds what each planner tried. (Should the planner learn to
/// plan one of them, that case has nothing to check.)
#[test]
fn a_part_left_empty_is_refused_briefly_naming_where_and_what_to_try() {
    for file in [
        "planner/corpus/icons/fa-gear.svg",
        "planner/corpus/letters/Q.svg",
    ] {
        let o = fold_plan(&[file, "--tiles", "300"]);
        if o.status.code() == Some(0) {
            continue;
        }
        let e = short_refusal(&o, file, 1);
        assert_mentions(&e, &["cannot plan", " mm", "try "]);
        // a count named as planning does plan
        if let Some(n) = e
            .split("try ")
            .nth(1)
            .and_then(|t| t.split(" tiles: that plans").next())
            .and_then(|n| n.parse::<usize>().ok())
        {
            let again = fold_plan(&[file, "--tiles", &n.to_string()]);
            assert_eq!(again.status.code(), Some(0), "{file} at {n}: {e}");
        }
        let v = fold_plan(&[file, "--tiles", "300", "--verbose"]);
        let ve = stderr(&v);
        assert_eq!(v.status.code(), Some(1), "{ve}");
        assert!(ve.contains("fold-plan: tried: "), "{ve}");
    }
}

/// A drawing no tile fits in (a strip narrower than a tile at the count asked) is refused
/// at once (before any width search: a 2000-to-1 strip took minutes), in a short message
/// naming the tile width and the count from which tiles fit; at that count the 100-to-1
/// strip plans. A tile width that fits nowhere names a width that does.
#[test]
fn a_drawing_no_tile_fits_in_is_refused_naming_a_count_that_fits() {
    let d = scratch("narrow");
    let strip = |name: &str, w: f64, h: f64| {
        let f = d.join(name);
        std::fs::write(
            &f,
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {w}"><rect width="{w}" height="{h}"/></svg>"#
            ),
        )
        .unwrap();
        f.to_str().unwrap().to_string()
    };
    let long = strip("long.svg", 1000.0, 0.5);
    let e = short_refusal(&fold_plan(&[&long, "--tiles", "100"]), &long, 1);
    assert!(
        e.contains("no part of the drawing is wide enough for a tile")
            && e.contains("at 100 tiles a tile is 1.88 units")
            && e.contains("try 1600 tiles or more"),
        "{e}"
    );
    let e = short_refusal(&fold_plan(&[&long, "--tile-size", "2"]), &long, 1);
    assert!(e.contains("try a tile width of 0.500 units"), "{e}");
    let short = strip("short.svg", 100.0, 1.0);
    let e = short_refusal(&fold_plan(&[&short, "--tiles", "50"]), &short, 1);
    let n = e
        .split("try ")
        .nth(1)
        .and_then(|t| t.split(" tiles or more").next())
        .and_then(|n| n.parse::<usize>().ok())
        .unwrap_or_else(|| panic!("no count named: {e}"));
    assert_eq!(n, 100, "{e}");
    let o = fold_plan(&[&short, "--tiles", &n.to_string()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::fs::remove_dir_all(&d).unwrap();
}

/// A tile count the plan misses by more than the tolerance is said in a warning with both
/// numbers, on stderr and in the plan JSON; a count within it is not.
#[test]
fn a_missed_tile_count_is_warned_about() {
    for (tolerance, asked) in [("0", 300), ("0.03", 300)] {
        let o = fold_plan(&[
            "shapes/ring.svg",
            "--tiles",
            &asked.to_string(),
            "--tiles-tolerance",
            tolerance,
            "--json",
        ]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "{e}");
        let plan: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let tiles = plan["tiles"].as_u64().unwrap() as usize;
        let allowed = (tolerance.parse::<f64>().unwrap() * asked as f64) as usize;
        let warned: Vec<&str> = plan["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|w| w.as_str())
            .filter(|w| w.contains("asked"))
            .collect();
        if tiles.abs_diff(asked) > allowed {
            assert_eq!(warned.len(), 1, "{tiles} of {asked}: {warned:?}");
            let w = warned[0];
            assert!(
                w.contains(&format!("{tiles} tiles")) && w.contains(&format!("{asked} asked")),
                "{w}"
            );
            assert!(e.contains(&format!("fold-plan: warning: {w}")), "{e}");
        } else {
            assert!(warned.is_empty(), "{tiles} of {asked}: {warned:?}");
        }
    }
}

/// Every drawing of the corpus at 300 tiles: each refusal (of a drawing in separate
/// parts, or one the planner cannot fill) is short and names something to change.
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn every_corpus_refusal_is_short_and_says_what_to_change() {
    let files: Vec<String> = drawings::corpus_files(&root().join("planner/corpus"))
        .into_iter()
        .map(|f| format!("planner/corpus/{f}"))
        .collect();
    assert!(files.len() >= 40);
    let mut refusals = 0;
    for file in &files {
        let o = fold_plan(&[file, "--tiles", "300"]);
        match o.status.code() {
            Some(0) => {}
            Some(c) => {
                short_refusal(&o, file, c);
                refusals += 1;
            }
            None => panic!("{file}: killed"),
        }
    }
    // the drawings in separate parts at least
    assert!(refusals >= 5, "{refusals} refusals");
}
