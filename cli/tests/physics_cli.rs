//! The physics flags on the command line (issue 11): `--force-law` on `fold-run` and
//! `fold-validate`, and `fold-validate --experiments`.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::PathBuf;
use std::process::{Command, Output};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("fold-physics-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn fold_run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_fold-run"))
        .args(args)
        .output()
        .unwrap()
}

fn summary(out: &[u8]) -> serde_json::Value {
    serde_json::from_slice(out).unwrap()
}

#[test]
fn both_force_laws_fold_the_three_tile_experiments() {
    // the thesis' four three-tile configurations complete in the reference with either law;
    // the cylinders pull less (0.90x the dipole at the rest distances), so they take longer
    for word in ["SS", "SL", "LS", "LL"] {
        let mut durations = Vec::new();
        for law in ["dipole", "cylinder"] {
            let out = tmp(&format!("{word}-{law}"));
            let o = fold_run(&[
                &format!("word:{word}"),
                "--reference",
                "--force-law",
                law,
                "--frames",
                "2",
                "--json",
                "--out",
                out.to_str().unwrap(),
            ]);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{word} {law}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            let s = summary(&o.stdout);
            assert_eq!(s["result"], "completed", "{word} {law}");
            durations.push(s["duration_s"].as_f64().unwrap());
            std::fs::remove_dir_all(&out).unwrap();
        }
        assert!(durations[1] > durations[0], "{word}: {durations:?}");
    }
    let o = fold_run(&["SL", "--force-law", "coulomb"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("coulomb"));
}

#[test]
fn fold_validate_takes_the_force_law() {
    let out = tmp("validate-cylinder");
    let o = Command::new(env!("CARGO_BIN_EXE_fold-validate"))
        .args([
            "--scene",
            "3-tile SL",
            "--quick",
            "--json",
            "--force-law",
            "cylinder",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v = summary(&o.stdout);
    assert_eq!(v["scenes"][0]["reference_outcome"], "completed");
    // the same scene with the dipole takes less time: the law reached the reference
    let dipole = Command::new(env!("CARGO_BIN_EXE_fold-validate"))
        .args(["--scene", "3-tile SL", "--quick", "--json", "--out"])
        .arg(out.join("dipole"))
        .output()
        .unwrap();
    let d = summary(&dipole.stdout);
    let dur = |v: &serde_json::Value| v["scenes"][0]["reference_duration_s"].as_f64().unwrap();
    assert!(dur(&v) > dur(&d), "{} {}", dur(&v), dur(&d));
    let bad = Command::new(env!("CARGO_BIN_EXE_fold-validate"))
        .args(["--force-law", "coulomb"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn experiments_agree_with_the_thesis() {
    let out = tmp("experiments");
    let o = Command::new(env!("CARGO_BIN_EXE_fold-validate"))
        .args(["--experiments", "--json", "--out", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v = summary(&o.stdout);
    let rows = v.as_array().unwrap();
    // five experiments, each with two laws and two dynamics
    assert_eq!(rows.len(), 20);
    for r in rows {
        assert_eq!(r["agrees"], true, "{r}");
        assert_eq!(r["outcome"], "completed", "{r}");
        assert_eq!(r["folds"], r["observed_folds"], "{r}");
    }
    // inertial runs take a fraction of a second, overdamped ones seconds
    let dur = |dynamics: &str| {
        rows.iter()
            .filter(|r| r["dynamics"] == dynamics)
            .map(|r| r["duration_s"].as_f64().unwrap())
            .fold(0.0, f64::max)
    };
    assert!(dur("inertial") < 1.0 && dur("overdamped") > 1.0);
    // the energy pictures of the four three-tile scenes: two panels, six pair curves and
    // the total
    for name in ["7-3-ss", "7-3-sl", "7-3-ls", "7-3-ll"] {
        let svg = std::fs::read_to_string(out.join(format!("experiment-{name}.svg"))).unwrap();
        let doc = usvg::roxmltree::Document::parse(&svg).unwrap();
        let lines = doc
            .descendants()
            .filter(|n| n.tag_name().name() == "polyline")
            .count();
        assert_eq!(lines, 7, "{name}");
    }
    std::fs::remove_dir_all(&out).unwrap();
}
