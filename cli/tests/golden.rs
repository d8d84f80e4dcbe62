//! The tools' JSON outputs against files recorded before a change that must not alter them
//! (`tests/golden/`, written by `tests/golden/record.sh`; first recorded before the issue-10
//! refactor): counts, collision verdicts, plans, run summaries and timelines, and the
//! validation table. Numbers must agree to 1e-12 relative, everything else exactly; wall-clock
//! fields are left out. A change that is meant to alter these outputs re-records them with
//! `record.sh` and says so in its commit.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::process::Command;

use serde_json::Value;

mod common;
#[path = "../../planner/tests/common/drawings.rs"]
mod drawings;
use common::{absent, root, THESIS_SQUARES};

/// Relative tolerance on numbers: far above the rounding a reordered sum may change, far
/// below any change of model or algorithm.
const RELATIVE: f64 = 1e-12;

/// Fields that measure the machine or name its paths, not the model.
const WALL_CLOCK: [&str; 4] = ["wall_s", "reference_wall_s", "seconds", "out_dir"];

fn golden(name: &str) -> String {
    std::fs::read_to_string(root().join("tests/golden").join(name))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn run(bin: &str, args: &[&str]) -> (Option<i32>, String) {
    let o = Command::new(bin)
        .current_dir(root())
        .args(args)
        .output()
        .unwrap();
    (o.status.code(), String::from_utf8(o.stdout).unwrap())
}

/// Where `a` and `b` differ (numbers beyond [`RELATIVE`]), as a path into the document.
fn differ(a: &Value, b: &Value, at: &str) -> Option<String> {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            let scale = x.abs().max(y.abs());
            ((x - y).abs() > RELATIVE * scale).then(|| format!("{at}: {x} != {y}"))
        }
        (Value::Array(x), Value::Array(y)) => {
            if x.len() != y.len() {
                return Some(format!("{at}: {} items != {}", x.len(), y.len()));
            }
            x.iter()
                .zip(y)
                .enumerate()
                .find_map(|(i, (p, q))| differ(p, q, &format!("{at}[{i}]")))
        }
        (Value::Object(x), Value::Object(y)) => {
            let keys = |m: &serde_json::Map<String, Value>| {
                let mut k: Vec<String> = m
                    .keys()
                    .filter(|k| !WALL_CLOCK.contains(&k.as_str()))
                    .cloned()
                    .collect();
                k.sort();
                k
            };
            if keys(x) != keys(y) {
                return Some(format!("{at}: keys {:?} != {:?}", keys(x), keys(y)));
            }
            keys(x)
                .iter()
                .find_map(|k| differ(&x[k], &y[k], &format!("{at}.{k}")))
        }
        _ => (a != b).then(|| format!("{at}: {a} != {b}")),
    }
}

fn assert_same(name: &str, recorded: &str, now: &str) {
    let (a, b): (Value, Value) = (
        serde_json::from_str(recorded).unwrap_or_else(|e| panic!("{name} (recorded): {e}")),
        serde_json::from_str(now).unwrap_or_else(|e| panic!("{name} (now): {e}\n{now}")),
    );
    if let Some(d) = differ(&a, &b, name) {
        panic!("output changed: {d}");
    }
}

#[test]
fn the_comparison_sees_a_change() {
    let a: Value = serde_json::from_str(r#"{"x": [1.0, 2.0], "wall_s": 1}"#).unwrap();
    let same: Value =
        serde_json::from_str(r#"{"x": [1.0, 2.0000000000000004], "wall_s": 9}"#).unwrap();
    let moved: Value = serde_json::from_str(r#"{"x": [1.0, 2.000000001], "wall_s": 1}"#).unwrap();
    assert_eq!(differ(&a, &same, "a"), None);
    assert!(differ(&a, &moved, "a").unwrap().contains("a.x[1]"));
}

#[test]
fn counts_are_unchanged() {
    let enumerate = env!("CARGO_BIN_EXE_fold-enum");
    let (code, out) = run(enumerate, &["--max-tiles", "12", "--json"]);
    assert_eq!(code, Some(0));
    assert_same("enum-12.json", &golden("enum-12.json"), &out);
    let (code, out) = run(enumerate, &["--max-tiles", "9", "--random", "--json"]);
    assert_eq!(code, Some(0));
    assert_same("enum-9-random.json", &golden("enum-9-random.json"), &out);
}

#[test]
fn collision_verdicts_are_unchanged() {
    let recorded = golden("check-words.jsonl");
    let words = golden("check-words.txt");
    let lines: Vec<&str> = recorded.lines().collect();
    assert_eq!(lines.len(), words.lines().count());
    for (line, word) in lines.iter().zip(words.lines()) {
        let want: Value = serde_json::from_str(line).unwrap();
        assert_eq!(want["word"], word);
        let (code, out) = run(env!("CARGO_BIN_EXE_fold-check"), &["--json", word]);
        assert_eq!(code.map(i64::from), want["exit"].as_i64(), "{word}");
        assert_same(word, &want["stdout"].to_string(), &out);
    }
}

/// The square planned with options: the recorded file and the options.
const OPTION_PLANS: [(&str, [&str; 6]); 2] = [
    ("plan-square-107-tight.json", THESIS_SQUARES[0]),
    ("plan-square-82-loose.json", THESIS_SQUARES[1]),
];

/// `fold-plan --json` of `shapes/{stem}.svg` with `args`, against `tests/golden/{file}`; an
/// unplannable shape is recorded as its exit code (the reason goes to stderr).
fn assert_plan_unchanged(stem: &str, args: &[&str], file: &str) {
    let relative = format!("shapes/{stem}.svg");
    let mut a = vec![relative.as_str(), "--json", "--quiet"];
    a.extend(args);
    let (code, out) = run(env!("CARGO_BIN_EXE_fold-plan"), &a);
    let out = if out.trim().is_empty() {
        format!("{{\"exit\": {}}}", code.unwrap_or(-1))
    } else {
        assert_eq!(code, Some(0), "{file}");
        out
    };
    assert_same(file, &golden(file), &out);
}

/// The binary's plans of the square (quick): the planner's own golden test
/// (`planner/tests/plan_golden.rs`) compares every sample through the library.
#[test]
fn plans_of_the_square_are_unchanged() {
    assert_plan_unchanged("square", &[], "plan-square.json");
    for (file, args) in OPTION_PLANS {
        assert_plan_unchanged("square", &args, file);
    }
}

/// Every sample shape has its recorded plan and every recorded plan its shape, and the
/// binary plans each as recorded.
#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn plans_of_every_sample_are_unchanged() {
    let stems = drawings::svg_stems(&root().join("shapes"));
    let mut recorded: Vec<String> = std::fs::read_dir(root().join("tests/golden"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_str().unwrap().to_string())
        .filter(|f| !OPTION_PLANS.iter().any(|(o, _)| *o == f.as_str()))
        .filter_map(|f| Some(f.strip_prefix("plan-")?.strip_suffix(".json")?.to_string()))
        .collect();
    recorded.sort();
    assert_eq!(stems, recorded, "sample shapes against recorded plans");
    for stem in &stems {
        assert_plan_unchanged(stem, &[], &format!("plan-{stem}.json"));
    }
}

#[test]
fn runs_are_unchanged() {
    let chains = golden("run-chains.txt");
    for (i, line) in chains.lines().enumerate() {
        let i = i + 1;
        let (chain, opts) = line.split_once('|').unwrap();
        let dir = std::env::temp_dir().join(format!("foldchain-golden-{}-{i}", std::process::id()));
        let mut args = vec![chain];
        args.extend(opts.split_whitespace());
        let dir_s = dir.to_str().unwrap();
        args.extend(["--out", dir_s, "--json"]);
        let (code, out) = run(env!("CARGO_BIN_EXE_fold-run"), &args);
        let want: i32 = golden(&format!("run-{i}-exit.txt")).trim().parse().unwrap();
        assert_eq!(code, Some(want), "{line}");
        assert_same(
            &format!("run {i} summary"),
            &golden(&format!("run-{i}-summary.json")),
            &out,
        );
        let timeline = std::fs::read_to_string(dir.join("timeline.json")).unwrap();
        assert_same(
            &format!("run {i} timeline"),
            &golden(&format!("run-{i}-timeline.json")),
            &timeline,
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
#[ignore = "slow: .ci/run runs it (cargo test --workspace --release -- --include-ignored)"]
fn validation_is_unchanged() {
    let dir = absent("validate");
    let (code, out) = run(
        env!("CARGO_BIN_EXE_fold-validate"),
        &["--quick", "--json", "--out", dir.to_str().unwrap()],
    );
    assert_eq!(code, Some(0));
    assert_same("validate-quick.json", &golden("validate-quick.json"), &out);
    std::fs::remove_dir_all(&dir).unwrap();
}
