//! `fold-run` end to end: outputs, exit codes, bad input.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fold-run"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("fold-run-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn folds_a_u_turn_and_writes_everything() {
    let d = tmp("uturn");
    let out = d.join("u");
    let o = bin()
        .args([
            "SSLLSS",
            "--out",
            out.to_str().unwrap(),
            "--frames",
            "5",
            "--json",
        ])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let printed: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let s = summary(&out);
    assert_eq!(printed, s);
    assert_eq!(s["completed"], true);
    assert_eq!(s["folds"], serde_json::json!([2, 3]));
    assert_eq!(s["inhibited_at"], serde_json::Value::Null);
    for f in [
        "step-0000.svg",
        "step-0004.svg",
        "final.svg",
        "transition.svg",
        "energy.svg",
        "timeline.json",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    assert!(!out.join("step-0005.svg").exists());
    let tl: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("timeline.json")).unwrap()).unwrap();
    assert_eq!(
        tl["events"].as_array().unwrap().len() as u64,
        s["events"].as_u64().unwrap()
    );
    // no temporary directories left beside the output
    let left: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}");
}

#[test]
fn stops_exit_1_and_say_where() {
    let d = tmp("stops");
    let o = bin()
        .args([
            "SS SL RS SS",
            "--out",
            d.join("a").to_str().unwrap(),
            "--json",
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(summary(&d.join("a"))["inhibited_at"], 1);
    let o = bin()
        .args(["S*9", "--s", "0.4e", "--out", d.join("b").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(summary(&d.join("b"))["stalled_at"], 0);
    let o = bin()
        .args(["SLLLLS", "--out", d.join("c").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(summary(&d.join("c"))["first_collision"]["time"].is_number());
    let o = bin()
        .args([
            "S*19",
            "--s",
            "e/3",
            "--speed",
            "unit",
            "--out",
            d.join("e").to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(summary(&d.join("e"))["max_moving_magnets"], 1);
}

#[test]
fn reads_a_plan_and_a_design() {
    let d = tmp("plan");
    std::fs::write(
        d.join("p.json"),
        r#"{"source": "x", "word": "S*3 L L S*3", "tiles": 9}"#,
    )
    .unwrap();
    std::fs::write(
        d.join("d.json"),
        r#"{"global": {"s": 0.2}, "tiles": [{"from": 0, "to": 2, "s": 0}]}"#,
    )
    .unwrap();
    let o = bin()
        .args([
            "--plan",
            d.join("p.json").to_str().unwrap(),
            "--design",
            d.join("d.json").to_str().unwrap(),
        ])
        .args(["--out", d.join("o").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(summary(&d.join("o"))["tiles"], 9);
}

#[test]
fn bad_input_exits_2_with_a_clear_message_and_writes_nothing() {
    let d = tmp("bad");
    std::fs::write(d.join("bad-plan.json"), "{\"word\": 3}").unwrap();
    std::fs::write(d.join("nan.json"), "{\"e\": NaN}").unwrap();
    std::fs::write(d.join("neg.json"), "{\"s\": -0.5}").unwrap();
    std::fs::write(d.join("chain.txt"), "SS SX").unwrap();
    std::fs::write(d.join("a-file"), "x").unwrap();
    let out = d.join("out");
    let o = out.to_str().unwrap();
    let p = |f: &str| d.join(f).to_str().unwrap().to_string();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["SLXS".into()], "'X'"),
        (vec![p("chain.txt")], "chain.txt"),
        (vec![p("")], "directory"),
        (vec!["--plan".into(), p("bad-plan.json")], "bad-plan.json"),
        (vec!["--plan".into(), p("missing.json")], "missing.json"),
        (
            vec!["SLLS".into(), "--design".into(), p("nan.json")],
            "nan.json",
        ),
        (
            vec!["SLLS".into(), "--design".into(), p("neg.json")],
            "`s` = -0.5",
        ),
        (vec!["SLLS".into(), "--s".into(), "-1".into()], "'-1'"),
        (vec!["SLLS".into(), "--s".into(), "NaN".into()], "'NaN'"),
        (vec!["SLLS".into(), "--drag=-3".into()], "--drag"),
        (
            vec!["SLLS".into(), "--frames".into(), "0".into()],
            "--frames",
        ),
        (vec![], "no chain"),
    ];
    for (args, needle) in cases {
        let out_o = bin().args(&args).args(["--out", o]).output().unwrap();
        let err = String::from_utf8_lossy(&out_o.stderr);
        assert_eq!(out_o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote output");
    }
    // an output directory that cannot be written: its parent is a file
    let o2 = bin()
        .args(["SLLS", "--out", d.join("a-file/sub").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o2.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o2.stderr).contains("a-file"));
}

#[test]
fn force_start_rule_stalls_a_fold_at_the_last_joint_that_the_distance_rule_folds() {
    let d = tmp("start-rule");
    for (rule, code, result) in [("distance", 0, "completed"), ("force", 1, "stalled")] {
        let out = d.join(rule);
        let o = bin()
            .args(["SL", "--start-rule", rule, "--frames", "2", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(code), "{rule}");
        let s = summary(&out);
        assert_eq!(s["result"], result, "{rule}");
        if rule == "force" {
            assert_eq!(s["stalled_at"], 1);
            assert!(s["reason"]
                .as_str()
                .unwrap()
                .contains("magnet 4 never started"));
        }
    }
    let o = bin()
        .args(["SL", "--start-rule", "nearest"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}
