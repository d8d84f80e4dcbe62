//! The physics flags on the command line (issue 11): `--force-law` on `fold-run` and
//! `fold-validate`, and `fold-validate --experiments`.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;
use common::{absent, assert_exit, run, stderr, stdout_json, validate_quick};

#[test]
fn both_force_laws_fold_the_three_tile_experiments() {
    // the thesis' four three-tile configurations complete in the reference with either law;
    // the cylinders pull less (0.90x the dipole at the rest distances), so they take longer
    for word in ["SS", "SL", "LS", "LL"] {
        let mut durations = Vec::new();
        for law in ["dipole", "cylinder"] {
            let out = absent(&format!("{word}-{law}"));
            let o = run(
                "fold-run",
                &[
                    &format!("word:{word}"),
                    "--reference",
                    "--force-law",
                    law,
                    "--frames",
                    "2",
                    "--json",
                    "--out",
                    out.to_str().unwrap(),
                ],
            );
            assert_eq!(o.status.code(), Some(0), "{word} {law}: {}", stderr(&o));
            let s = stdout_json(&o);
            assert_eq!(s["result"], "completed", "{word} {law}");
            durations.push(s["duration_s"].as_f64().unwrap());
            std::fs::remove_dir_all(&out).unwrap();
        }
        assert!(durations[1] > durations[0], "{word}: {durations:?}");
    }
    let o = run("fold-run", &["SL", "--force-law", "coulomb"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("coulomb"));
}

#[test]
fn fold_validate_takes_the_force_law() {
    let out = absent("validate-cylinder");
    let v = validate_quick("3-tile SL", &["--force-law", "cylinder"], &out);
    assert_eq!(v["scenes"][0]["reference_outcome"], "completed");
    // the same scene with the dipole takes less time: the law reached the reference
    let d = validate_quick("3-tile SL", &[], &out.join("dipole"));
    let dur = |v: &serde_json::Value| v["scenes"][0]["reference_duration_s"].as_f64().unwrap();
    assert!(dur(&v) > dur(&d), "{} {}", dur(&v), dur(&d));
    let bad = run("fold-validate", &["--force-law", "coulomb"]);
    assert_eq!(bad.status.code(), Some(2));
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn experiments_agree_with_the_thesis() {
    let out = absent("experiments");
    let o = run(
        "fold-validate",
        &["--experiments", "--json", "--out", out.to_str().unwrap()],
    );
    assert_exit(&o, 0);
    let v = stdout_json(&o);
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
