//! `fold-tolerance` end to end, and the margins `fold-run` writes: exit codes, messages for
//! bad tolerances, reproducibility with a seed, shards that add up, the search's plot.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

mod common;
use common::{run, scratch, stderr, stdout, stdout_json};

#[test]
fn bad_tolerances_are_named_with_exit_2() {
    for (args, says) in [
        (vec!["SL", "--tol", "q=0.1"], "unknown key 'q'"),
        (vec!["SL", "--tol", "s=-0.1"], "bad value '-0.1'"),
        (vec!["SL", "--tol", "s=abc"], "bad value 'abc'"),
        (vec!["SL", "--tol", "br=80%"], "percentage"),
        (vec!["SL", "--tol", "wall"], "expected KEY=VALUE"),
        (vec!["SL", "--shard", "3/2"], "--shard \"3/2\""),
        (vec!["SL", "--samples", "0"], "--samples 0"),
        (vec!["SL", "--optimize", "--target", "1.5"], "--target 1.5"),
        (vec!["SL", "--tiles", "9"], "only to a SHAPE.svg"),
        (vec!["SXL"], "SXL"),
    ] {
        let o = run("fold-tolerance", &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("fold-tolerance: ") && err.contains(says),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn a_seed_reproduces_a_study_and_shards_add_up() {
    let base = ["LL", "--samples", "600", "--json", "--tol", "s=0.15"];
    let study = |extra: &[&str]| {
        let mut a = base.to_vec();
        a.extend(extra);
        stdout_json(&run("fold-tolerance", &a))
    };
    let a = study(&["--seed", "5"]);
    let b = study(&["--seed", "5"]);
    assert_eq!(a["study"], b["study"]);
    let c = study(&["--seed", "6"]);
    assert_ne!(a["study"]["smallest_margin"], c["study"]["smallest_margin"]);
    // some samples fail and some fold at these tolerances, so the count says something
    let folded = a["study"]["folded"].as_u64().unwrap();
    assert!(folded > 0 && folded < 600, "{folded}");
    let parts: Vec<serde_json::Value> = ["1/3", "2/3", "3/3"]
        .iter()
        .map(|s| study(&["--seed", "5", "--shard", s]))
        .collect();
    let sum = |key: &str| -> u64 {
        parts
            .iter()
            .map(|p| p["study"][key].as_u64().unwrap())
            .sum()
    };
    assert_eq!(sum("samples"), 600);
    assert_eq!(sum("folded"), folded);
    // the text report says the same
    let o = run(
        "fold-tolerance",
        &["LL", "--samples", "600", "--tol", "s=0.15", "--seed", "5"],
    );
    let text = stdout(&o);
    assert!(
        text.contains(&format!("folds in {folded} of 600 samples")),
        "{text}"
    );
    assert!(text.contains("sensitivity"), "{text}");
}

#[test]
fn no_tolerance_means_the_nominal_verdict() {
    // with every tolerance 0 each sample is the nominal chain: all fold or none
    let mut args = vec!["SLLS", "--samples", "50", "--json"];
    for k in ["s", "e", "wall", "width", "br", "diameter", "height"] {
        args.push("--tol");
        args.push(Box::leak(format!("{k}=0").into_boxed_str()));
    }
    let v = stdout_json(&run("fold-tolerance", &args));
    let nominal_ok = v["nominal_margins"]["starts"]
        .as_array()
        .unwrap()
        .iter()
        .chain(v["nominal_margins"]["folds"].as_array().unwrap())
        .chain(v["nominal_margins"]["holds"].as_array().unwrap())
        .all(|m| m["margin"].as_f64().unwrap() > 0.0);
    let folded = v["study"]["folded"].as_u64().unwrap();
    assert_eq!(folded, if nominal_ok { 50 } else { 0 });
}

#[test]
fn the_search_writes_its_plot() {
    let d = scratch("search");
    let plot = d.join("t.svg");
    let search = |plot: &std::path::Path| {
        run(
            "fold-tolerance",
            &[
                "SLS",
                "--optimize",
                "--search-samples",
                "20",
                "--samples",
                "40",
                "--plot",
                plot.to_str().unwrap(),
            ],
        )
    };
    let o = search(&plot);
    let text = stdout(&o);
    assert!(
        matches!(o.status.code(), Some(0) | Some(1)),
        "{}",
        stderr(&o)
    );
    assert!(text.contains("trade-off over s"), "{text}");
    assert_eq!(
        o.status.code() == Some(0),
        text.contains("fastest design with P >= 0.99"),
        "{text}"
    );
    if o.status.code() == Some(0) {
        // the chosen design's file is a design the tools read
        let design = d.join("t-chosen.json");
        let v = stdout_json(&run(
            "fold-tolerance",
            &[
                "SLS",
                "--samples",
                "10",
                "--json",
                "--design",
                design.to_str().unwrap(),
            ],
        ));
        assert_eq!(v["study"]["samples"], 10);
    }
    let svg = std::fs::read_to_string(&plot).unwrap();
    usvg::Tree::from_str(&svg, &usvg::Options::default()).unwrap();
    assert!(svg.contains("folding probability"));
    // the search's own plot is replaced by a second search; a user's drawing is not
    assert!(matches!(search(&plot).status.code(), Some(0) | Some(1)));
    let mine = d.join("mine.svg");
    std::fs::write(&mine, "<svg xmlns=\"http://www.w3.org/2000/svg\"/>").unwrap();
    let o = search(&mine);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("refusing to overwrite"),
        "{}",
        stderr(&o)
    );
    assert!(std::fs::read_to_string(&mine)
        .unwrap()
        .starts_with("<svg xmlns"));
}

#[test]
fn fold_run_writes_margins() {
    let d = scratch("run");
    let out = d.join("r");
    let o = run(
        "fold-run",
        &["SLLS", "--frames", "2", "--out", out.to_str().unwrap()],
    );
    let text = stdout(&o);
    assert!(text.contains("smallest margin"), "{text}");
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("margins.json")).unwrap()).unwrap();
    // every magnet but the last starts; both joints of the U-turn fold
    assert_eq!(m["starts"].as_array().unwrap().len(), 9);
    assert_eq!(m["folds"].as_array().unwrap().len(), 2);
    let smallest = m["smallest"]["margin"].as_f64().unwrap();
    assert_eq!(m["holds"].as_array().unwrap().len(), 10);
    let all = m["starts"]
        .as_array()
        .unwrap()
        .iter()
        .chain(m["folds"].as_array().unwrap())
        .chain(m["holds"].as_array().unwrap())
        .map(|x| x["margin"].as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    assert_eq!(smallest, all);
}
