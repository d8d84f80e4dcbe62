//! `fold-run --reference --model free-body`: the free-body reference's run files, summary
//! and exit codes, and what it refuses.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;
use common::{absent, assert_exit, assert_exit_saying, run};

#[test]
fn a_free_body_run_writes_the_run_files() {
    let dir = absent("run-files");
    let out = dir.to_str().unwrap();
    let o = run(
        "fold-run",
        &[
            "SLLS",
            "--reference",
            "--model",
            "free-body",
            "--json",
            "--out",
            out,
        ],
    );
    assert_exit(&o, 0);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["result"], "completed");
    assert_eq!(v["folds"], serde_json::json!([1, 2]));
    for f in ["summary.json", "timeline.json", "index.html", "final.svg"] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    // the joint-angle reference on the same chain: the same folds, another duration
    let ja = dir.join("ja");
    let o = run(
        "fold-run",
        &[
            "SLLS",
            "--reference",
            "--json",
            "--out",
            ja.to_str().unwrap(),
        ],
    );
    let w: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(w["folds"], v["folds"]);
    assert_ne!(w["duration_s"], v["duration_s"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn overdamped_free_body_is_refused() {
    let dir = absent("overdamped");
    let o = run(
        "fold-run",
        &[
            "SL",
            "--reference",
            "--model",
            "free-body",
            "--dynamics",
            "overdamped",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_exit_saying(&o, 2, &["free-body", "overdamped"]);
    assert!(!dir.exists());
}
