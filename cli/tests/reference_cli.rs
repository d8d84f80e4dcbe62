//! `fold-validate` on bad input: exit 2, a message naming the value, nothing written.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::process::Command;

fn validate(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_fold-validate"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn bad_input_exits_2() {
    let dir = std::env::temp_dir().join(format!("fv-bad-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let o = validate(&["--scene", "no such scene", "--out", out]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("unknown scene 'no such scene'"), "{err}");
    assert!(err.contains("3-tile SL"), "{err}");
    let o = validate(&["--reference-tolerance", "0.5", "--out", out]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("0.5"));
    assert!(!dir.exists());
}

#[test]
fn json_rows_for_one_scene() {
    let dir = std::env::temp_dir().join(format!("fv-json-{}", std::process::id()));
    let o = validate(&[
        "--scene",
        "3-tile SL",
        "--quick",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows[0]["method"], "event");
    assert!(rows[0]["tolerance"].is_null());
    for key in [
        "scene",
        "method",
        "tolerance",
        "error_time",
        "error_pose",
        "wall_s",
        "steps",
    ] {
        assert!(rows.iter().all(|r| r.get(key).is_some()), "{key}");
    }
    assert!(rows.iter().any(|r| r["method"] == "dopri5"));
    assert!(rows.iter().any(|r| r["method"] == "ros2"));
    assert!(dir.join("work-precision.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
