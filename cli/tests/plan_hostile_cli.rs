//! `fold-plan` on hostile files and outputs (issue 26): huge, tiny and NaN numbers, a
//! `<use>` cycle, deep nesting, an entity loop, bytes that are not UTF-8, a shape drawn at
//! 1e15 (the reader's f32 digits), files that are not SVG, a directory, a missing file, and
//! outputs in a missing directory, on the --out file, or on a file the tool did not write.
//! Each is exit 2 with a message naming the file, never a panic, and leaves what was there.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;
use common::{assert_exit_saying, run, scratch, stderr};

const SVG: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">"#;

fn write(dir: &std::path::Path, name: &str, body: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p.to_str().unwrap().to_string()
}

/// Every hostile drawing: exit 2, its name and the words that say what is wrong.
#[test]
fn hostile_drawings_are_bad_input_naming_the_file() {
    let d = scratch("hostile");
    let deep = format!(
        "{SVG}{}<rect width=\"5\" height=\"5\"/>{}</svg>",
        "<g>".repeat(100_000),
        "</g>".repeat(100_000)
    );
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        ("huge.svg", format!("{SVG}<path d=\"M0 0 L1e300 0 L1e300 1e300 Z\"/></svg>"), vec!["<path>", "1e300"]),
        ("scale.svg", format!("{SVG}<rect width=\"5\" height=\"5\" transform=\"scale(1e300)\"/></svg>"), vec!["transform", "1e300"]),
        ("nan.svg", format!("{SVG}<rect width=\"NaN\" height=\"5\"/></svg>"), vec!["width", "NaN"]),
        ("tiny.svg", format!("{SVG}<path d=\"M0 0 L1e-300 0 L1e-300 1e-300 Z\"/></svg>"), vec!["no filled area"]),
        ("cycle.svg", format!("{SVG}<defs><g id=\"a\"><use xlink:href=\"#b\"/></g><g id=\"b\"><use xlink:href=\"#a\"/></g></defs><use xlink:href=\"#a\"/></svg>"), vec!["not a readable SVG"]),
        ("deep.svg", deep, vec!["not a readable SVG"]),
        ("text.svg", "hello, not a drawing".into(), vec!["not a readable SVG"]),
        ("empty.svg", String::new(), vec!["not a readable SVG"]),
        ("open.svg", format!("{SVG}<rect width=\"5\" height=\"5\"/>"), vec!["not a readable SVG"]),
        ("laughs.svg", format!("<!DOCTYPE svg [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\"><!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\"><!ENTITY d \"&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;\"><!ENTITY e \"&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;\"><!ENTITY f \"&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;\">]>{SVG}<title>&f;&f;&f;&f;</title><rect width=\"5\" height=\"5\"/></svg>"), vec!["not a readable SVG"]),
        ("far.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"1e15 1e15 100 100\"><rect x=\"1e15\" y=\"1e15\" width=\"100\" height=\"100\"/></svg>".into(), vec!["significant digits", "nearer the origin"]),
    ];
    for (name, body, words) in cases {
        let f = write(&d, name, &body);
        let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
        assert!(!stderr(&o).contains("panicked"), "{name}: {}", stderr(&o));
        let mut w = words.clone();
        w.push(name);
        assert_exit_saying(&o, 2, &w);
    }
    // bytes that are not UTF-8 in a comment
    let latin = d.join("latin1.svg");
    let mut bytes = format!("{SVG}<!-- ").into_bytes();
    bytes.extend_from_slice(&[0xff, 0xfe, 0xe9]);
    bytes.extend_from_slice(b" --><rect width=\"5\" height=\"5\"/></svg>");
    std::fs::write(&latin, bytes).unwrap();
    let o = run("fold-plan", &[latin.to_str().unwrap(), "--quiet"]);
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    assert_exit_saying(&o, 2, &["latin1.svg", "not a readable SVG", "UTF-8"]);
    let o = run("fold-plan", &[d.to_str().unwrap(), "--quiet"]);
    assert_exit_saying(&o, 2, &["cannot read", "directory"]);
    let missing = d.join("missing.svg");
    let o = run("fold-plan", &[missing.to_str().unwrap(), "--quiet"]);
    assert_exit_saying(&o, 2, &["cannot read", "missing.svg"]);
}

/// Outputs: a missing directory is exit 2 naming the path; --preview on the --out file says
/// so (not that it is the input); a file the tool did not write is left as it was; a file
/// it wrote (or an empty one) is replaced.
#[test]
fn outputs_never_replace_what_the_tool_did_not_write() {
    let d = scratch("outputs");
    let shape = write(
        &d,
        "square.svg",
        &format!("{SVG}<rect width=\"50\" height=\"50\"/></svg>"),
    );
    let plan = |more: &[&str]| {
        let mut a = vec![shape.as_str(), "--tiles", "60", "--quiet"];
        a.extend_from_slice(more);
        run("fold-plan", &a)
    };
    let nodir = d.join("no-such-dir").join("plan.json");
    assert_exit_saying(
        &plan(&["--out", nodir.to_str().unwrap()]),
        2,
        &["plan.json", "No such file"],
    );
    let same = d.join("same.out");
    let o = plan(&[
        "--out",
        same.to_str().unwrap(),
        "--preview",
        same.to_str().unwrap(),
    ]);
    assert_exit_saying(&o, 2, &["same.out", "also the --out file"]);
    assert!(!same.exists());
    // a user's files under the output names: refused, left as they were
    let notes = write(&d, "notes.json", "my notes");
    let picture = write(&d, "picture.svg", &format!("{SVG}<circle r=\"3\"/></svg>"));
    let o = plan(&["--out", &notes]);
    assert_exit_saying(
        &o,
        2,
        &["notes.json", "not a plan JSON", "refusing to overwrite"],
    );
    let o = plan(&["--preview", &picture]);
    assert_exit_saying(
        &o,
        2,
        &["picture.svg", "not a preview", "refusing to overwrite"],
    );
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "my notes");
    assert!(std::fs::read_to_string(&picture)
        .unwrap()
        .contains("<circle r=\"3\"/>"));
    // the tool's own outputs (and empty files) are replaced, run after run
    let out = write(&d, "plan.json", "");
    let preview = d.join("preview.svg");
    for _ in 0..2 {
        let o = plan(&["--out", &out, "--preview", preview.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    assert!(std::fs::read_to_string(&out)
        .unwrap()
        .contains("\"tile_list\""));
}

/// A viewBox of zero or negative width or height (SVG: zero disables rendering, negative is
/// an error; rsvg-convert refuses both files, "has no dimensions") used to plan at a size
/// usvg chose: exit 2 naming the file, the attribute, its value and what is wrong.
#[test]
fn a_viewbox_of_no_size_is_refused_naming_it() {
    let d = scratch("viewbox");
    let rect = "<rect width=\"50\" height=\"50\"/></svg>";
    let cases = [
        (
            "negw.svg",
            "0 0 -100 100",
            vec!["width is -100", "negative size"],
        ),
        (
            "negh.svg",
            "0,0,100,-1",
            vec!["height is -1", "negative size"],
        ),
        (
            "zerow.svg",
            "0 0 0 100",
            vec!["width is 0", "disables rendering"],
        ),
        (
            "zeroh.svg",
            "0 0 100 0",
            vec!["height is 0", "disables rendering"],
        ),
    ];
    for (name, vb, words) in cases {
        let body = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{vb}\">{rect}");
        let f = write(&d, name, &body);
        let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
        let mut w = words.clone();
        w.extend([name, "viewBox", vb, "positive width and height"]);
        assert_exit_saying(&o, 2, &w);
    }
    // a positive viewBox still plans
    let body = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 100 100\">{rect}");
    let f = write(&d, "ok.svg", &body);
    let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// A shape 1e-30 units across (and one 1e30 across) plans as the same shape 1 unit across
/// (the reader's tolerances are shares of the drawing's size): the same tile list, and the
/// summary says the tile's size in significant digits, not "tile 0.0000 units = 0.00 mm".
#[test]
fn a_shape_of_any_scale_plans_as_drawn_and_says_its_size() {
    let d = scratch("scale");
    let plan = |name: &str, w: &str, h: &str| {
        let body = format!("{SVG}<rect width=\"{w}\" height=\"{h}\"/></svg>");
        let f = write(&d, name, &body);
        let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        let out = common::stdout(&o);
        let mut lines = out.lines();
        (
            lines.next().unwrap().to_string(),
            lines.next().unwrap().to_string(),
        )
    };
    let (one, _) = plan("one.svg", "1", "2");
    let (tiny, tiny_summary) = plan("tiny.svg", "1e-30", "2e-30");
    let (huge, huge_summary) = plan("huge.svg", "1e30", "2e30");
    assert_eq!(tiny, one);
    assert_eq!(huge, one);
    for (s, exp) in [
        (&tiny_summary, "e-31 units = "),
        (&huge_summary, "e29 units = "),
    ] {
        assert!(s.contains(exp), "{s}");
        assert!(!s.contains("0.0000 units") && !s.contains("0.00 mm"), "{s}");
        assert!(s.len() < 260, "{s}");
    }
}

/// A spiral band (three turns, 3 units wide in 100): one chain can fill it, but the
/// planner's rows do not follow it and the plan leaves most of it empty. Issue 26: not
/// refused, but the warning says what is empty, how much of the shape that is and what to
/// try, in at most three lines.
#[test]
fn a_band_the_rows_cannot_follow_is_warned_with_what_to_try() {
    let d = scratch("spiral");
    let (mut outer, mut inner) = (Vec::new(), Vec::new());
    for k in 0..=600 {
        let th = 6.0 * std::f64::consts::PI * f64::from(k) / 600.0;
        let r = 4.0 + 10.0 * th / (2.0 * std::f64::consts::PI);
        let at = |r: f64| format!("{:.3},{:.3}", 50.0 + r * th.cos(), 50.0 + r * th.sin());
        outer.push(at(r + 1.5));
        inner.push(at(r - 1.5));
    }
    inner.reverse();
    outer.extend(inner);
    let body = format!("{SVG}<polygon points=\"{}\"/></svg>", outer.join(" "));
    let f = write(&d, "spiral.svg", &body);
    let o = run("fold-plan", &[&f, "--tiles", "300", "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let err = stderr(&o);
    let lines: Vec<&str> = err.lines().filter(|l| l.contains("warning")).collect();
    assert!(lines.len() <= 3, "{err}");
    let all = lines.join("\n");
    common::assert_mentions(
        &all,
        &[
            "empty",
            "tile areas without a tile",
            "% of the shape",
            "to try:",
            "--preview",
        ],
    );
    // the share said is the largest empty part's (the plan covers under 10% of the band)
    let share: f64 = all
        .split("that is ")
        .nth(1)
        .and_then(|s| s.split('%').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!(share > 20.0, "{all}");
    // a plan that leaves nothing over 2 tile areas empty gets no such lines
    let square = write(
        &d,
        "square.svg",
        &format!("{SVG}<rect width=\"50\" height=\"50\"/></svg>"),
    );
    let o = run("fold-plan", &[&square, "--tiles", "100", "--quiet"]);
    assert!(!stderr(&o).contains("to try:"), "{}", stderr(&o));
}

/// An element whose own transform scales it by 1e-7 or less (here 1e-10): the SVG reader
/// drops it as invisible, where a browser draws it small. Alone it was "no visible element
/// with a fill"; beside another shape it was silently left out of the plan. Refused naming
/// the element, its transform and the scale (exit 2). scale(1e-5) still plans.
#[test]
fn an_element_scaled_below_the_reader_s_digits_is_refused_naming_it() {
    let d = scratch("tinyscale");
    let square = "<rect width=\"50\" height=\"50\"/>";
    for (name, body) in [
        ("alone.svg", "<rect width=\"1\" height=\"2\" transform=\"scale(1e-10)\"/>".to_string()),
        (
            "beside.svg",
            format!("{square}<g id=\"far\" transform=\"translate(60 0) scale(1e-10, 1)\"><rect width=\"5e10\" height=\"50\"/></g>"),
        ),
    ] {
        let f = write(&d, name, &format!("{SVG}{body}</svg>"));
        let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
        assert_exit_saying(&o, 2, &[name, "transform=", "1e-10", "1.000e-10", "drops an element"]);
    }
    let f = write(
        &d,
        "small.svg",
        &format!("{SVG}<rect width=\"1\" height=\"2\" transform=\"scale(1e-5)\"/></svg>"),
    );
    let o = run("fold-plan", &[&f, "--tiles", "100", "--quiet"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
