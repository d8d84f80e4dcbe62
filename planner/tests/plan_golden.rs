//! The planner's output must not drift: every sample shape is planned through the library
//! with the options `tests/golden/record.sh` gave `fold-plan --json`, and the plan's JSON is
//! compared with the file recorded before the refactor of issue 10. Numbers must agree to
//! 1e-12 relative (a refactor may reorder a sum; anything larger is a change of behaviour);
//! every string, count, key and array length must be equal.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};

#[path = "common/drawings.rs"]
mod drawings;

use foldchain_planner::{plan_svg_str, PlanOptions, Turns};
use serde_json::Value;

/// Relative tolerance on numbers (absolute below 1e-300 in size, where relative means nothing).
const REL: f64 = 1e-12;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The differences between `got` and `want` at `at`, one line each.
fn diff(at: &str, got: &Value, want: &Value, out: &mut Vec<String>) {
    match (got, want) {
        (Value::Number(a), Value::Number(b)) => {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            let scale = a.abs().max(b.abs());
            if (a - b).abs() > REL * scale && scale > 1e-300 {
                out.push(format!("{at}: {a} != {b}"));
            }
        }
        (Value::Array(a), Value::Array(b)) => {
            if a.len() != b.len() {
                out.push(format!("{at}: length {} != {}", a.len(), b.len()));
            } else {
                for (i, (x, y)) in a.iter().zip(b).enumerate() {
                    diff(&format!("{at}[{i}]"), x, y, out);
                }
            }
        }
        (Value::Object(a), Value::Object(b)) => {
            let keys_a: Vec<&String> = a.keys().collect();
            let keys_b: Vec<&String> = b.keys().collect();
            if keys_a != keys_b {
                out.push(format!("{at}: keys {keys_a:?} != {keys_b:?}"));
            } else {
                for (k, x) in a {
                    diff(&format!("{at}.{k}"), x, &b[k], out);
                }
            }
        }
        _ => {
            if got != want {
                out.push(format!("{at}: {got} != {want}"));
            }
        }
    }
}

/// Plans `shapes/{shape}.svg` with `opts` and compares with `tests/golden/{golden}.json`.
fn check(shape: &str, opts: &PlanOptions, golden: &str) -> Vec<String> {
    let name = format!("shapes/{shape}.svg");
    let svg = std::fs::read_to_string(root().join(&name)).unwrap();
    let file = root().join("tests/golden").join(format!("{golden}.json"));
    let want: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let got: Value = match plan_svg_str(&svg, &name, opts) {
        Ok(plan) => serde_json::from_str(&plan.to_json()).unwrap(),
        // recorded as fold-plan's exit code
        Err(e) => serde_json::json!({ "exit": e.exit_code() }),
    };
    let mut out = Vec::new();
    diff(golden, &got, &want, &mut out);
    out
}

/// The square with the options `record.sh` gave: its recorded file and the options.
fn square_cases() -> Vec<(String, PlanOptions, String)> {
    vec![
        (
            "square".into(),
            PlanOptions::default(),
            "plan-square".into(),
        ),
        (
            "square".into(),
            PlanOptions::default()
                .with_tiles(107)
                .with_tiles_tolerance(0.0)
                .with_turns(Turns::Tight),
            "plan-square-107-tight".into(),
        ),
        (
            "square".into(),
            PlanOptions::default()
                .with_tiles(82)
                .with_tiles_tolerance(0.0)
                .with_turns(Turns::Loose),
            "plan-square-82-loose".into(),
        ),
    ]
}

/// Plans every case and asserts that none differs from its recording.
fn assert_recorded(cases: &[(String, PlanOptions, String)]) {
    let mut all = Vec::new();
    for (shape, opts, golden) in cases {
        let d = check(shape, opts, golden);
        all.extend(d.into_iter().take(10));
    }
    assert!(
        all.is_empty(),
        "{} differences:\n{}",
        all.len(),
        all.join("\n")
    );
}

#[test]
fn the_square_plans_as_recorded() {
    assert_recorded(&square_cases());
}

/// Every sample shape with the default options, against its recording; every recorded plan
/// has its sample.
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn every_sample_plans_as_recorded() {
    let names = drawings::svg_stems(&root().join("shapes"));
    let squares = square_cases();
    let mut recorded: Vec<String> = std::fs::read_dir(root().join("tests/golden"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|f| Some(f.strip_suffix(".json")?.to_string()))
        .filter(|f| f.starts_with("plan-") && !squares[1..].iter().any(|c| &c.2 == f))
        .map(|f| f["plan-".len()..].to_string())
        .collect();
    recorded.sort();
    assert_eq!(names, recorded, "sample shapes against recorded plans");
    let cases: Vec<(String, PlanOptions, String)> = names
        .iter()
        .map(|n| (n.clone(), PlanOptions::default(), format!("plan-{n}")))
        .collect();
    assert_recorded(&cases);
}

/// The comparison itself finds a change in the last digits that matter.
#[test]
fn the_comparison_sees_small_changes() {
    let a: Value = serde_json::json!({"x": 1.0, "v": [1, 2], "s": "a"});
    let mut out = Vec::new();
    diff("t", &a, &a, &mut out);
    assert!(out.is_empty());
    let b: Value = serde_json::json!({"x": 1.0 + 1e-10, "v": [1, 2], "s": "a"});
    diff("t", &a, &b, &mut out);
    let c: Value = serde_json::json!({"x": 1.0, "v": [1, 2, 3], "s": "b"});
    diff("t", &a, &c, &mut out);
    assert_eq!(out.len(), 3, "{out:?}");
}
