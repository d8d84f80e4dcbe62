//! `fold-validate` on bad input: exit 2, a message naming the value, nothing written.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;
use common::{absent, run, stderr, validate_quick};

#[test]
fn bad_input_exits_2() {
    let dir = absent("bad");
    let out = dir.to_str().unwrap();
    let o = run("fold-validate", &["--scene", "no such scene", "--out", out]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains("unknown scene 'no such scene'"), "{err}");
    assert!(err.contains("3-tile SL"), "{err}");
    let o = run(
        "fold-validate",
        &["--reference-tolerance", "0.5", "--out", out],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("0.5"));
    assert!(!dir.exists());
}

#[test]
fn json_rows_for_one_scene() {
    let dir = absent("json");
    let v = validate_quick("3-tile SL", &[], &dir);
    let rows = v["rows"].as_array().unwrap();
    // the engine with both start rules, then the quick ladders
    let ladder: Vec<(String, Option<f64>)> = rows
        .iter()
        .map(|r| {
            (
                r["method"].as_str().unwrap().to_string(),
                r["tolerance"].as_f64(),
            )
        })
        .collect();
    let want: Vec<(String, Option<f64>)> = [
        ("event", None),
        ("event-force", None),
        ("event-dist", None),
        ("dopri5", Some(1e-3)),
        ("dopri5", Some(1e-4)),
        ("dopri5", Some(1e-5)),
        ("dopri5", Some(1e-6)),
        ("ros2", Some(1e-2)),
        ("ros2", Some(1e-3)),
        ("ros2", Some(1e-4)),
    ]
    .iter()
    .map(|&(m, t)| (m.to_string(), t))
    .collect();
    assert_eq!(ladder, want);
    assert!(rows.iter().all(|r| r["scene"] == "3-tile SL"));
    // the reference completes the three-tile fold (its final point against the 0.8 mm
    // wall); so do the integrators at every tolerance and the engine with both rules
    let scene = &v["scenes"][0];
    assert_eq!(scene["tiles"], 3);
    assert_eq!(scene["reference_outcome"], "completed");
    assert_eq!(scene["engine_outcome"], "completed");
    let outcome = |r: &serde_json::Value| r["outcome"].as_str().unwrap().to_string();
    for r in &rows[..3] {
        assert_eq!(outcome(r), "completed", "{r}");
    }
    for r in &rows[3..] {
        assert_eq!(outcome(r), "completed", "{r}");
        // the same events as the reference, in the same order, their times within a
        // hundred times the tolerance of the reference's: magnet 3 passes close to a
        // balance before magnet 4 starts, which amplifies errors (measured: 3 to 80 times)
        // (ROS2 at 1e-2 misses one event: measured)
        let (err, tol) = (
            r["error_time"].as_f64().unwrap(),
            r["tolerance"].as_f64().unwrap(),
        );
        assert_eq!(r["inversions"].as_u64(), Some(0), "{r}");
        if tol <= 1e-3 {
            assert_eq!(r["missing"].as_u64(), Some(0), "{r}");
        }
        assert!(err >= 0.0 && err < 100.0 * tol, "{r}");
        assert!(r["error_pose"].as_f64().unwrap() < 1e-2, "{r}");
    }
    // tighter tolerances: more steps, and smaller errors for a tolerance 100 times tighter
    // (one rung apart the event-time error, dominated by a start near a balance, may not
    // fall: Dormand-Prince at 1e-3 and 1e-4 measured 1.4e-3 and 1.7e-3)
    for ladder in [&rows[3..7], &rows[7..]] {
        for w in ladder.windows(2) {
            assert!(w[1]["steps"].as_u64() > w[0]["steps"].as_u64(), "{w:?}");
        }
        for (a, b) in ladder.iter().zip(ladder.iter().skip(2)) {
            assert!(
                b["error_time"].as_f64() < a["error_time"].as_f64(),
                "{a} {b}"
            );
        }
    }
    // the files: the same JSON, and the plot with one panel (two ladders, two diamonds)
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("work-precision.json")).unwrap())
            .unwrap();
    assert_eq!(written["rows"].as_array().unwrap().len(), rows.len());
    assert_eq!(written["scenes"], v["scenes"]);
    let svg = std::fs::read_to_string(dir.join("work-precision.svg")).unwrap();
    let doc = usvg::roxmltree::Document::parse(&svg).unwrap();
    let count = |tag: &str| {
        doc.descendants()
            .filter(|n| n.tag_name().name() == tag)
            .count()
    };
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    assert_eq!(
        (count("polyline"), count("circle"), count("path")),
        (2, 7, 2)
    );
    assert!(svg.contains("3-tile SL (ref: completed)"));
    std::fs::remove_dir_all(&dir).unwrap();
}
