//! `fold-run --reference`: the force-integrated reference writes the event engine's files
//! (summary, timeline and the same pictures, drawn from its own states).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::Path;
use std::process::Output;

mod common;
use common::{absent, assert_exit, assert_mentions, names, read_json, stderr, tool};

fn fold_run(args: &[&str], out: &Path) -> Output {
    tool("fold-run")
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// Parses every SVG of `dir` as XML with an `<svg>` root; returns the `<polygon>` count of
/// `final.svg` (one per tile in a detailed frame).
fn check_svgs(dir: &Path) -> usize {
    let mut final_polygons = None;
    for name in names(dir).iter().filter(|n| n.ends_with(".svg")) {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(
            text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
            "{name}"
        );
        let doc = usvg::roxmltree::Document::parse(&text)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.join(name).display()));
        assert_eq!(doc.root_element().tag_name().name(), "svg", "{name}");
        if name == "final.svg" {
            final_polygons = Some(
                doc.descendants()
                    .filter(|n| n.tag_name().name() == "polygon")
                    .count(),
            );
        }
    }
    final_polygons.unwrap()
}

#[test]
fn reference_run_writes_the_engine_summary() {
    let dir = absent("summary");
    let out = fold_run(&["SLLS", "--reference", "--json"], &dir);
    assert_exit(&out, 0);
    let mut v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["out_dir"], dir.to_str().unwrap());
    v.as_object_mut().unwrap().remove("out_dir");
    assert_eq!(v["tiles"], 5);
    assert_eq!(v["completed"], true);
    assert_eq!(v["result"], "completed");
    assert_eq!(v["folds"], serde_json::json!([1, 2]));
    assert_eq!(v["reason"], serde_json::Value::Null);
    assert_eq!(read_json(&dir.join("summary.json")), v);
    // the timeline holds the events the summary counts, the last at its duration, in the
    // reference's law
    let tl = read_json(&dir.join("timeline.json"));
    let events = tl["events"].as_array().unwrap();
    assert_eq!(Some(events.len() as u64), v["events"].as_u64());
    assert_eq!(events.last().unwrap()[0], v["duration_s"]);
    assert!(v["duration_s"].as_f64().unwrap() > 0.0);
    assert_eq!(tl["speed_law"]["reference"]["method"], "dopri5");
    let count = |kind: &str| events.iter().filter(|e| e[1] == kind).count();
    assert_eq!((count("magnet_starts"), count("magnet_arrives")), (9, 9));
    assert_eq!((count("fold_starts"), count("fold_ends")), (2, 2));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn reference_writes_the_engine_files_and_pictures() {
    let (eng, refr) = (absent("files-engine"), absent("files-reference"));
    for (dir, extra) in [(&eng, None), (&refr, Some("--reference"))] {
        let mut args = vec!["SLLS", "--frames", "7", "--transition", "1..3"];
        args.extend(extra);
        let out = fold_run(&args, dir);
        assert_exit(&out, 0);
    }
    let files = names(&eng);
    assert_eq!(names(&refr), files);
    assert!(files.contains(&"step-0006.svg".to_string()), "{files:?}");
    for f in ["final.svg", "transition.svg", "energy.svg", "timeline.json"] {
        assert!(files.contains(&f.to_string()), "{f}: {files:?}");
    }
    // every tile drawn in both final frames, the same shape
    assert_eq!(check_svgs(&eng), 5);
    assert_eq!(check_svgs(&refr), 5);
    let fin = std::fs::read_to_string(refr.join("final.svg")).unwrap();
    assert_mentions(&fin, &["SLLS (reference)", "completed"]);
    // the transition diagram covers the requested tiles
    let tr = std::fs::read_to_string(refr.join("transition.svg")).unwrap();
    assert!(tr.contains("tiles 1 to 3"));
    assert_eq!(tr.matches("<polyline").count(), 6);
    let en = std::fs::read_to_string(refr.join("energy.svg")).unwrap();
    assert_mentions(&en, &["total dipole energy", "folds turning"]);
    // no temporary directory left beside the output
    let parent = refr.parent().unwrap();
    let stem = refr.file_name().unwrap().to_string_lossy().into_owned();
    assert!(!names(parent)
        .iter()
        .any(|n| n.starts_with(&format!(".{stem}.tmp"))));
    std::fs::remove_dir_all(&eng).unwrap();
    std::fs::remove_dir_all(&refr).unwrap();
}

#[test]
fn reference_pictures_show_where_a_stalled_chain_stopped() {
    // the fold word LL (3 tiles, one tight U-turn) with the thesis' layout c = 2.8 mm at the
    // curved final point (a 1.3 mm wall): the engine folds it, the reference stalls
    let (eng, refr) = (absent("stall-engine"), absent("stall-reference"));
    let design =
        std::env::temp_dir().join(format!("foldchain-run-ref-{}-c28.json", std::process::id()));
    std::fs::write(&design, r#"{"c": 2.8}"#).unwrap();
    let design = design.to_str().unwrap();
    // (the kinematic engine: the local engine follows the reference and stalls too)
    let out = fold_run(&["LL", "--engine", "kinematic", "--design", design], &eng);
    assert_eq!(out.status.code(), Some(0));
    let out = fold_run(&["LL", "--reference", "--design", design], &refr);
    assert_exit(&out, 1);
    let summary = read_json(&refr.join("summary.json"));
    assert_eq!(summary["result"], "stalled");
    assert_eq!(summary["stalled_at"], 1);
    assert_eq!(summary["folds"], serde_json::json!([0]));
    assert_eq!(names(&refr), names(&eng));
    assert_eq!(check_svgs(&refr), 3);
    let fin = std::fs::read_to_string(refr.join("final.svg")).unwrap();
    assert!(fin.contains("stalled"), "{fin}");
    // only joint 0 folded: one hinge drawn (the engine folds both)
    let hinges = |svg: &str| {
        let doc = usvg::roxmltree::Document::parse(svg).unwrap();
        doc.descendants()
            .filter(|n| n.has_tag_name("circle") && n.attribute("fill") == Some("#333"))
            .count()
    };
    assert_eq!(hinges(&fin), 1);
    assert_eq!(
        hinges(&std::fs::read_to_string(eng.join("final.svg")).unwrap()),
        2
    );
    std::fs::remove_dir_all(&eng).unwrap();
    std::fs::remove_dir_all(&refr).unwrap();
}

#[test]
fn reference_refuses_long_chains() {
    // refused before any work: the output directory is not even created
    let dir = std::env::temp_dir().join(format!("foldchain-ref-long-{}", std::process::id()));
    let out = tool("fold-run")
        .args(["S*3000", "--reference", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("at most 2,000"));
    assert!(!dir.exists());
}
