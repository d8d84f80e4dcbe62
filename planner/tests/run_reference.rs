//! `fold-run --reference`: the force-integrated reference writes the engine's summary format.

use std::process::Command;

#[test]
fn reference_run_writes_the_engine_summary() {
    let dir = std::env::temp_dir().join(format!("foldchain-run-ref-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_fold-run"))
        .args(["SLLS", "--reference", "--json", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["tiles"], 5);
    assert_eq!(v["completed"], true);
    assert_eq!(v["folds"], serde_json::json!([1, 2]));
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(written, v);
    assert!(dir.join("timeline.json").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn reference_refuses_long_chains() {
    let out = Command::new(env!("CARGO_BIN_EXE_fold-run"))
        .args(["S*3000", "--reference"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("at most 2000"));
}
