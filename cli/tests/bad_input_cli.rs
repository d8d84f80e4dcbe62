//! The crashes and unbounded runs of issue 29, kept as named regression tests: each is
//! refused before any work with exit 2 and one line naming the value and its range, and a
//! closed pipe on stdout ends a tool quietly.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::io::Read;
use std::process::{Output, Stdio};

mod common;
use common::{run, scratch, stderr, tool};

/// Exit 2, nothing on stdout, one line on stderr holding every one of `words`, no panic.
fn refused(o: &Output, words: &[&str]) {
    let e = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(!e.contains("panicked"), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "one line: {e}");
    assert!(e.len() < 400, "short: {e}");
    for w in words {
        assert!(e.contains(w), "missing {w:?} in: {e}");
    }
}

#[test]
fn huge_s_and_tile_width_are_refused_with_their_range() {
    let d = scratch("huge");
    let out = d.join("out");
    let o = run(
        "fold-run",
        &["SLLS", "--s", "1e308", "--out", out.to_str().unwrap()],
    );
    refused(&o, &["--s", "`s` = 1e308 mm", "0 to 4.7 mm"]);
    let o = run(
        "fold-run",
        &["SLLS", "--s", "100", "--out", out.to_str().unwrap()],
    );
    refused(&o, &["`s` = 100 mm", "0 to 4.7 mm"]);
    for (json, words) in [
        (r#"{"s": 1e308}"#, ["`s` = 1e308 mm", "0 to 4.7 mm"]),
        (
            r#"{"tile_width": 1e308}"#,
            ["`tile_width` = 1e308 mm", "1000 mm"],
        ),
        (r#"{"c": 0}"#, ["`c` = 0 mm", "magnet radius, 1.5 mm"]),
        (r#"{"e": 14}"#, ["`e` = 14 mm", "at most d/2 - r = 6 mm"]),
    ] {
        let design = d.join("design.json");
        std::fs::write(&design, json).unwrap();
        for t in ["fold-run", "fold-tolerance"] {
            let mut c = tool(t);
            c.args(["SLLS", "--design", design.to_str().unwrap()]);
            if t == "fold-run" {
                c.args(["--out", out.to_str().unwrap()]);
            }
            refused(&c.output().unwrap(), &words);
        }
    }
    // nothing was written for any of them
    assert!(!out.exists());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn unbounded_counts_and_drags_are_refused() {
    let o = run("fold-tolerance", &["SL", "--samples", "1000000000000"]);
    refused(&o, &["--samples 1,000,000,000,000", "--shard"]);
    // the same count in scientific notation is read the same way
    let o = run("fold-tolerance", &["SL", "--samples", "1e12"]);
    refused(&o, &["--samples 1,000,000,000,000"]);
    let o = run(
        "fold-run",
        &["SLLS", "--dynamics", "overdamped", "--drag", "1e-300"],
    );
    refused(&o, &["--drag 1e-300", "0.001 to 10000 N s/m"]);
    let o = run("fold-run", &["SLLS", "--distance-cutoff=-1"]);
    refused(&o, &["--distance-cutoff -1", "mm"]);
    let o = run("fold-run", &["S*2000001"]);
    refused(&o, &["2,000,002 tiles", "at most 2,000,000"]);
    let o = run("fold-tolerance", &["SL", "--search-samples", "0"]);
    refused(&o, &["--search-samples 0", "from 1 to 100,000"]);
    let o = run("fold-tolerance", &["SL", "--plot", "x.svg"]);
    refused(&o, &["--plot", "--optimize"]);
    let o = run("fold-check", &["SLLS", "--tolerance", "1e308"]);
    refused(&o, &["--tolerance 1e308", "tile widths"]);
    let o = run("fold-plan", &["shape.svgz", "--tiles", "10"]);
    refused(&o, &["shape.svgz", "decompress"]);
}

#[test]
fn a_closed_pipe_ends_a_tool_quietly() {
    let d = scratch("pipe");
    for (t, args) in [
        ("fold-run", vec!["SLLS", "--json", "--out", "OUT"]),
        ("fold-check", vec!["S*40", "--json"]),
        ("fold-enum", vec!["--max-tiles", "9", "--json"]),
        ("fold-print", vec!["SLLS", "--quiet", "--out", "OUT"]),
        ("fold-tolerance", vec!["SL", "--samples", "20"]),
        (
            "fold-plan",
            vec!["../shapes/square.svg", "--tiles", "12", "--quiet"],
        ),
    ] {
        let out = d.join(t);
        let args: Vec<&str> = args
            .iter()
            .map(|a| {
                if *a == "OUT" {
                    out.to_str().unwrap()
                } else {
                    a
                }
            })
            .collect();
        let mut child = tool(t)
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // the reader goes before the tool writes
        drop(child.stdout.take());
        let mut err = String::new();
        child
            .stderr
            .take()
            .unwrap()
            .read_to_string(&mut err)
            .unwrap();
        let status = child.wait().unwrap();
        assert!(!err.contains("panicked"), "{t}: {err}");
        assert!(
            matches!(status.code(), Some(0 | 1)),
            "{t}: {status:?} {err}"
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn fold_print_refuses_a_file_as_out_before_any_work() {
    // found by the options fuzz: the refusal came after the parts were built, below a
    // progress line, so it was not one line
    let d = scratch("print-out-file");
    let file = d.join("afile");
    std::fs::write(&file, "not a directory").unwrap();
    let o = tool("fold-print")
        .env("FOLDCHAIN_PROGRESS_SECONDS", "0")
        .args(["SLLS", "--out"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("not a directory"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a directory");
    std::fs::remove_dir_all(&d).unwrap();
}

/// An input that never ends (`/dev/zero` for a drawing, a plan, a design or a shard report)
/// is refused once the tool has read its limit for that kind of file, instead of filling
/// the memory (found by hand: each of these ran until killed).
#[test]
fn an_endless_input_file_is_refused_at_its_size_limit() {
    let zero = std::path::Path::new("/dev/zero");
    if !zero.exists() {
        eprintln!("no /dev/zero here: skipped");
        return;
    }
    let d = scratch("zero");
    let cases: [(&str, Vec<&str>, &str); 5] = [
        ("fold-plan", vec!["/dev/zero", "--quiet"], "256 MiB"),
        (
            "fold-run",
            vec!["--plan", "/dev/zero", "--quiet"],
            "512 MiB",
        ),
        (
            "fold-run",
            vec!["SL", "--design", "/dev/zero", "--quiet"],
            "256 MiB",
        ),
        (
            "fold-tolerance",
            vec!["SL", "--design", "/dev/zero", "--quiet"],
            "256 MiB",
        ),
        ("fold-enum", vec!["--merge", "/dev/zero"], "64 MiB"),
    ];
    for (name, args, limit) in cases {
        let o = tool(name).current_dir(&d).args(&args).output().unwrap();
        refused(&o, &["/dev/zero", limit]);
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// A short word for a huge chain: fold-print refuses over 100,000 tiles at once (found by
/// hand: `S*5000000` ran on, towards a 16 GB assembly sheet).
#[test]
fn fold_print_refuses_a_chain_too_long_to_print() {
    let d = scratch("print-long");
    let o = tool("fold-print")
        .args(["S*5000000", "--quiet", "--out"])
        .arg(d.join("out"))
        .output()
        .unwrap();
    refused(&o, &["5000001 tiles", "at most 100,000 tiles"]);
    assert!(!d.join("out").exists(), "nothing written");
    std::fs::remove_dir_all(&d).unwrap();
}

/// A path with NaN or 1e400 among its coordinates is refused naming the element and the
/// value (usvg cut the path there and the planner answered "no filled area", or planned the
/// drawing without the element).
#[test]
fn fold_plan_names_a_non_finite_coordinate() {
    let d = scratch("nan-path");
    for (body, words) in [
        (
            r#"<path id="leaf" d="M 0 0 L 100 0 L NaN 100 L 0 100 Z"/>"#,
            ["id=\"leaf\"", "NaN"],
        ),
        (
            r#"<rect width="50" height="50"/><path d="M 0 0 L 100 0 L 1e400 100 L 0 100 Z"/>"#,
            ["<path> #1", "1e400"],
        ),
    ] {
        let svg = d.join("bad.svg");
        std::fs::write(
            &svg,
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">{body}</svg>"#
            ),
        )
        .unwrap();
        let o = run("fold-plan", &[svg.to_str().unwrap(), "--tiles", "100"]);
        refused(&o, &["bad.svg", words[0], words[1], "not a finite number"]);
    }
}
