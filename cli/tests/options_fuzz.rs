//! A fuzz test of the tools' option space (issue 29): for each tool, at least 1,000
//! combinations of its options with values drawn from valid, boundary and bad ones (zero,
//! negative, huge, NaN, text, missing files, files in the way), each run as a process; half
//! the cases use only valid values (the first two of each option's list), so that the work
//! itself is reached in many combinations. Every
//! run must exit 0, 1 or 2, never panic, never hang; a refusal (exit 2) is one line on
//! stderr naming the tool. Valid values are kept small so that a case takes milliseconds.
//!
//! `FOLDCHAIN_FUZZ_CASES` sets the cases per tool (default 1000), `FOLDCHAIN_FUZZ_SEED` the
//! seed. A failure prints the command to run it again; keep it as a named test in
//! `bad_input_cli.rs`.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;

/// One option: its flag, the probability it is given, and its values (`None`: a flag
/// without a value). `@DIR`, `@FILE` and `@...` in a value stand for files of the setup.
struct Opt {
    flag: &'static str,
    p: f64,
    values: &'static [&'static str],
}

const fn opt(flag: &'static str, p: f64, values: &'static [&'static str]) -> Opt {
    Opt { flag, p, values }
}

/// A flag without a value.
const fn flag(flag: &'static str, p: f64) -> Opt {
    Opt {
        flag,
        p,
        values: &[],
    }
}

const NUMBERS: &[&str] = &[
    "0", "-1", "1e308", "-1e308", "NaN", "inf", "x", "", "1e-300",
];

struct Tool {
    name: &'static str,
    positional: &'static [&'static str],
    options: Vec<Opt>,
}

const CHAINS: &[&str] = &[
    "SL",
    "SLLS",
    "LSLLSR",
    "S*3",
    "LR",
    "SLRS",
    "LLLL",
    "tiles:SS",
    "word:L",
    "{\"tiles\":[\"SS\",\"SL\"]}",
    "xyz",
    "",
    "S*0",
    "@CHAINFILE",
    "@MISSING.txt",
    "@SQUARE",
    "@MISSING.svg",
];

/// Every tool, each option list ending in `--bogus`, a flag no tool has, given rarely.
fn tools() -> Vec<Tool> {
    let mut tools = own_options();
    for t in &mut tools {
        t.options.push(flag("--bogus", 0.01));
    }
    tools
}

/// Every tool with its own options.
fn own_options() -> Vec<Tool> {
    vec![
        Tool {
            name: "fold-run",
            positional: CHAINS,
            options: vec![
                opt(
                    "--plan",
                    0.05,
                    &["@PLAN", "@PLAN", "@MISSING.json", "@CHAINFILE"],
                ),
                opt(
                    "--design",
                    0.15,
                    &[
                        "@DESIGN",
                        "@DESIGN",
                        "@BADDESIGN",
                        "@HUGEDESIGN",
                        "@MISSING.json",
                    ],
                ),
                opt(
                    "--s",
                    0.15,
                    &[
                        "0.3", "e/3", "0.25e", "0", "0.3mm", "4.7", "4.8", "1e308", "-1", "NaN",
                        "x", "100",
                    ],
                ),
                opt("--out", 0.97, &["@DIR", "@DIR", "@DIR", "@AFILE", ""]),
                opt(
                    "--frames",
                    0.9,
                    &["1", "2", "3", "0", "-1", "1e9", "100001", "x", "1e0"],
                ),
                opt("--frames-view", 0.1, &["auto", "fixed", "x"]),
                flag("--json", 0.2),
                flag("--quiet", 0.2),
                opt("--engine", 0.2, &["auto", "local", "kinematic", "x"]),
                opt("--speed", 0.1, &["overdamped", "unit", "x"]),
                opt("--start-rule", 0.1, &["distance", "force", "x"]),
                opt("--force-law", 0.1, &["dipole", "cylinder", "x"]),
                opt("--dynamics", 0.15, &["inertial", "overdamped", "x"]),
                opt(
                    "--distance-cutoff",
                    0.1,
                    &["90", "0.001", "0", "-1", "1e308", "x"],
                ),
                opt(
                    "--drag",
                    0.15,
                    &["5", "0.001", "10000", "1e-300", "1e5", "x", "0"],
                ),
                opt("--threads", 0.1, &["1", "2", "0", "300", "x"]),
                opt(
                    "--transition",
                    0.1,
                    &["0..3", "0..100000", "3..1", "x", ".."],
                ),
                flag("--reference", 0.1),
                flag("--compare", 0.05),
                opt("--tiles", 0.15, &["10", "20", "0", "-5", "1e9", "x"]),
                opt(
                    "--tile-size",
                    0.05,
                    &["30", "20", "0", "1e-300", "1e308", "x"],
                ),
                opt("--turns", 0.1, &["tight", "loose", "auto", "x"]),
            ],
        },
        Tool {
            name: "fold-check",
            positional: CHAINS,
            options: vec![
                flag("--final-only", 0.3),
                opt(
                    "--tolerance",
                    0.3,
                    &["0", "0.001", "0.009", "0.01", "-1", "1e308", "x", "NaN"],
                ),
                flag("--json", 0.3),
                flag("--quiet", 0.2),
            ],
        },
        Tool {
            name: "fold-enum",
            positional: &[],
            options: vec![
                opt(
                    "--max-tiles",
                    0.9,
                    &["2", "5", "8", "1", "41", "0", "-3", "x", "1e1"],
                ),
                opt("--min-tiles", 0.2, &["2", "3", "9", "0", "x"]),
                flag("--allow-lr", 0.2),
                flag("--final-only", 0.2),
                flag("--random", 0.3),
                opt("--random-exact-max", 0.2, &["2", "5", "1", "41", "x"]),
                opt("--samples", 0.3, &["10", "100", "0", "1e10", "-1", "x"]),
                opt(
                    "--seed",
                    0.1,
                    &["1", "0", "-1", "18446744073709551616", "x"],
                ),
                opt("--shard", 0.2, &["1/2", "2/2", "3/2", "0/1", "1/0", "x"]),
                opt(
                    "--merge",
                    0.1,
                    &["@ENUMPART", "@ENUMPART", "@MISSING.json", "@CHAINFILE"],
                ),
                flag("--json", 0.3),
                flag("--quiet", 0.3),
            ],
        },
        Tool {
            name: "fold-tolerance",
            positional: &[
                "SL",
                "LL",
                "S*3",
                "SLLS",
                "x",
                "",
                "@SQUARE",
                "@MISSING.svg",
            ],
            options: vec![
                opt(
                    "--samples",
                    0.97,
                    &["1", "10", "40", "0", "-1", "1e12", "x", "1e1"],
                ),
                opt(
                    "--tol",
                    0.3,
                    &[
                        "s=0.05", "br=2%", "wall=0.1", "x=1", "s=-1", "s=1e308", "s=", "br=NaN",
                    ],
                ),
                opt("--printer", 0.2, &["fdm", "resin", "x"]),
                opt(
                    "--seed",
                    0.2,
                    &[
                        "1",
                        "0",
                        "-1",
                        "18446744073709551615",
                        "18446744073709551616",
                    ],
                ),
                opt("--shard", 0.2, &["1/2", "2/2", "3/2", "0/1", "x"]),
                flag("--json", 0.3),
                opt(
                    "--design",
                    0.15,
                    &["@DESIGN", "@OVERRIDES", "@BADDESIGN", "@HUGEDESIGN"],
                ),
                opt("--s", 0.15, &["0.3", "e/3", "0", "4.8", "1e308", "-1", "x"]),
                opt("--force-law", 0.1, &["dipole", "cylinder", "x"]),
                flag("--optimize", 0.08),
                opt("--target", 0.1, &["0.99", "0.5", "0", "1.5", "x"]),
                opt("--search-samples", 0.5, &["1", "3", "0", "100001", "x"]),
                opt("--plot", 0.1, &["@DIR.svg", "@DIR.svg", "@SQUARE", ""]),
                opt("--tiles", 0.1, &["10", "12", "0", "x"]),
                opt("--turns", 0.1, &["tight", "loose", "x"]),
                flag("--quiet", 0.2),
            ],
        },
        Tool {
            name: "fold-plan",
            positional: &[
                "@SQUARE",
                "@SQUARE",
                "@MISSING.svg",
                "@CHAINFILE",
                "x.svgz",
                "",
            ],
            options: vec![
                opt("--tiles", 0.85, &["5", "12", "20", "0", "-5", "1e9", "x"]),
                opt(
                    "--tiles-tolerance",
                    0.2,
                    &["0", "0.03", "0.5", "0.6", "-1", "x"],
                ),
                opt("--tile-size", 0.1, &["30", "0", "1e-300", "1e308", "x"]),
                opt("--tile-mm", 0.1, &["30", "3", "0", "1e308", "x"]),
                opt("--turn-cost", 0.2, &["1", "0", "10", "11", "-1", "x"]),
                opt("--turns", 0.2, &["tight", "loose", "auto", "x"]),
                opt("--out", 0.2, &["@DIR.json", "@DIR.json", "@SQUARE", ""]),
                opt("--preview", 0.2, &["@DIR.svg", "@DIR.svg", "@SQUARE"]),
                flag("--json", 0.2),
                flag("--quiet", 0.3),
            ],
        },
        Tool {
            name: "fold-validate",
            positional: &[],
            options: vec![
                // always a scene: the whole validation takes minutes
                opt(
                    "--scene",
                    1.0,
                    &["3-tile SL", "3-tile LL", "3-tile SL", "nope"],
                ),
                flag("--quick", 0.4),
                flag("--json", 0.3),
                opt("--out", 0.9, &["@DIR", "@DIR", "@AFILE"]),
                opt(
                    "--reference-tolerance",
                    0.2,
                    &["1e-10", "1e-7", "1", "0", "-1", "x"],
                ),
                flag("--stiff", 0.1),
                opt("--case", 0.1, &["SLLS control", "SLLS control", "nope"]),
                flag("--experiments", 0.02),
                opt("--force-law", 0.2, &["dipole", "cylinder", "x"]),
                opt("--dynamics", 0.2, &["overdamped", "inertial", "x"]),
                flag("--quiet", 0.3),
            ],
        },
        Tool {
            name: "fold-print",
            positional: &[
                "SL",
                "SLLS",
                "S*4",
                "@CHAINFILE",
                "LR",
                "x",
                "",
                "@MISSING.txt",
            ],
            options: vec![
                opt("--plan", 0.05, &["@PLAN", "@PLAN", "@MISSING.json"]),
                opt(
                    "--design",
                    0.1,
                    &["@DESIGN", "@DESIGN", "@BADDESIGN", "@HUGEDESIGN"],
                ),
                opt("--printer", 0.2, &["fdm", "resin", "x"]),
                opt(
                    "--clearance",
                    0.2,
                    &["0.25", "0.4", "0", "-1", "1e308", "x"],
                ),
                opt("--height", 0.2, &["7.5", "9", "0", "-1", "1e308", "x"]),
                opt("--floor", 0.2, &["1.2", "2", "0", "-1", "1e308", "x"]),
                opt("--out", 0.95, &["@DIR", "@DIR", "@AFILE"]),
                opt("--format", 0.2, &["3mf", "stl", "x"]),
                opt(
                    "--bed",
                    0.2,
                    &["250,210", "180,180", "0,0", "1e308,1", "x", "100"],
                ),
                opt("--spacing", 0.2, &["5", "3", "0", "-1", "1e308", "x"]),
                flag("--json", 0.2),
                opt("--tiles", 0.1, &["10", "12", "0", "x"]),
                opt("--turns", 0.1, &["tight", "loose", "x"]),
                flag("--quiet", 0.2),
            ],
        },
    ]
}

/// The files the values refer to, made once per tool in its scratch directory.
struct Setup {
    base: PathBuf,
}

impl Setup {
    fn new(tool: &str) -> Setup {
        // one directory per call: the quick pass and a tool's full fuzz run at once
        static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let base = std::env::temp_dir().join(format!(
            "foldchain-fuzz-{}-{tool}-{call}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(&base).unwrap();
        let w = |name: &str, text: &str| std::fs::write(base.join(name), text).unwrap();
        w("chain.txt", "SLLS\n");
        w("afile", "not a directory\n");
        w("design.json", r#"{"s": 0.2, "wall": 0.6}"#);
        w("bad-design.json", r#"{"s": "x"#);
        w("huge-design.json", r#"{"tile_width": 1e308}"#);
        w(
            "overrides.json",
            r#"{"global": {}, "tiles": [{"from": 0, "to": 1, "s": 0.1}]}"#,
        );
        let square = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shapes/square.svg");
        let plan = Command::new(env!("CARGO_BIN_EXE_fold-plan"))
            .args([
                square.to_str().unwrap(),
                "--tiles",
                "12",
                "--quiet",
                "--out",
            ])
            .arg(base.join("plan.json"))
            .output()
            .unwrap();
        assert!(plan.status.success(), "{plan:?}");
        let part = Command::new(env!("CARGO_BIN_EXE_fold-enum"))
            .args(["--max-tiles", "6", "--shard", "1/1", "--json", "--quiet"])
            .output()
            .unwrap();
        std::fs::write(base.join("enum-part.json"), part.stdout).unwrap();
        Setup { base }
    }

    /// A value with its `@` names made paths; `case` keeps outputs of cases apart.
    fn value(&self, v: &str, case: usize) -> String {
        let square = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shapes/square.svg");
        let p = |name: &str| self.base.join(name).to_string_lossy().into_owned();
        match v {
            "@CHAINFILE" => p("chain.txt"),
            "@MISSING.txt" => p("missing.txt"),
            "@MISSING.svg" => p("missing.svg"),
            "@MISSING.json" => p("missing.json"),
            "@SQUARE" => square.to_string_lossy().into_owned(),
            "@PLAN" => p("plan.json"),
            "@DESIGN" => p("design.json"),
            "@BADDESIGN" => p("bad-design.json"),
            "@HUGEDESIGN" => p("huge-design.json"),
            "@OVERRIDES" => p("overrides.json"),
            "@ENUMPART" => p("enum-part.json"),
            "@AFILE" => p("afile"),
            "@DIR" => p(&format!("out-{}", case % 7)),
            "@DIR.svg" => p(&format!("out-{}.svg", case % 7)),
            "@DIR.json" => p(&format!("out-{}.json", case % 7)),
            other => other.to_string(),
        }
    }
}

/// Runs `args` with a deadline; `None` when it had to be killed.
fn run_with_deadline(bin: &str, args: &[String], cwd: &Path) -> Option<(Option<i32>, String)> {
    let mut child = Command::new(bin)
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut stderr, &mut s);
        s
    });
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return Some((status.code(), reader.join().unwrap()));
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn shell_quote(a: &str) -> String {
    if !a.is_empty()
        && a.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_./=:,*".contains(&b))
    {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}

fn fuzz(name: &str, default_cases: usize) {
    let tool = tools().into_iter().find(|t| t.name == name).unwrap();
    let cases: usize = std::env::var("FOLDCHAIN_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    let seed: u64 = std::env::var("FOLDCHAIN_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(29);
    let setup = Setup::new(name);
    // SplitMix64 (the library's generator is crate-private): a deterministic stream per tool
    let mut state = seed ^ name.len() as u64 ^ (name.as_bytes()[5] as u64) << 8;
    let mut next_u64 = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    let mut pick = |n: usize| (next_u64() % n as u64) as usize;
    let mut failures = Vec::new();
    let mut exits = [0usize; 3];
    let mut slowest: Vec<(f64, String)> = Vec::new();
    for case in 0..cases {
        // half the cases are clean: the chain and every value from the first four and two
        // of their lists, which are valid (combinations may still conflict); the other half
        // draws from everything
        let clean = case % 2 == 0;
        let mut args: Vec<String> = Vec::new();
        if !tool.positional.is_empty() && (clean || pick(10) < 9) {
            let n = if clean { 4 } else { tool.positional.len() };
            args.push(setup.value(tool.positional[pick(n)], case));
        }
        for o in &tool.options {
            if (pick(1_000_000) as f64) >= o.p * 1e6 {
                continue;
            }
            args.push(o.flag.to_string());
            if !o.values.is_empty() {
                // mostly the option's own values, sometimes a bad number
                let v = if clean {
                    o.values[pick(o.values.len().min(2))]
                } else if pick(8) == 0 {
                    NUMBERS[pick(NUMBERS.len())]
                } else {
                    o.values[pick(o.values.len())]
                };
                args.push(setup.value(v, case));
            }
        }
        let command = format!(
            "{} {}",
            name,
            args.iter()
                .map(|a| shell_quote(a))
                .collect::<Vec<_>>()
                .join(" ")
        );
        let started = Instant::now();
        let ran = run_with_deadline(common::exe(name), &args, &setup.base);
        slowest.push((started.elapsed().as_secs_f64(), command.clone()));
        slowest.sort_by(|a, b| b.0.total_cmp(&a.0));
        slowest.truncate(3);
        let Some((code, stderr)) = ran else {
            failures.push(format!("hang (killed after 120 s): {command}"));
            continue;
        };
        match code {
            Some(c @ 0..=2) => exits[c as usize] += 1,
            other => failures.push(format!("exit {other:?}: {command}\n  {stderr}")),
        }
        if stderr.contains("panicked") {
            failures.push(format!("panic: {command}\n  {stderr}"));
        }
        if code == Some(2) {
            let lines: Vec<&str> = stderr.lines().collect();
            if lines.len() != 1 || !lines[0].starts_with(&format!("{name}: ")) {
                failures.push(format!("not one line: {command}\n  {stderr}"));
            }
        }
        if failures.len() >= 10 {
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&setup.base);
    eprintln!(
        "{name}: {cases} cases: exit 0 {}, exit 1 {}, exit 2 {}; slowest: {:?}",
        exits[0], exits[1], exits[2], slowest
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // the fuzz reaches both the work and the refusals
    assert!(exits[0] > 0 && exits[2] > 0, "{exits:?}");
}

// A quick pass for every test run: 40 cases per tool, a test per tool (so that they run
// side by side).

#[test]
fn fold_run_options_quick() {
    fuzz("fold-run", 40);
}

#[test]
fn fold_check_options_quick() {
    fuzz("fold-check", 40);
}

#[test]
fn fold_enum_options_quick() {
    fuzz("fold-enum", 40);
}

#[test]
fn fold_tolerance_options_quick() {
    fuzz("fold-tolerance", 40);
}

#[test]
fn fold_plan_options_quick() {
    fuzz("fold-plan", 40);
}

#[test]
fn fold_validate_options_quick() {
    fuzz("fold-validate", 40);
}

#[test]
fn fold_print_options_quick() {
    fuzz("fold-print", 40);
}

// The full fuzz, 1,000 cases per tool: minutes on two cores, run by CI (`.ci/run` runs the
// ignored tests too).

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_run_options() {
    fuzz("fold-run", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_check_options() {
    fuzz("fold-check", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_enum_options() {
    fuzz("fold-enum", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_tolerance_options() {
    fuzz("fold-tolerance", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_plan_options() {
    fuzz("fold-plan", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_validate_options() {
    fuzz("fold-validate", 1000);
}

#[test]
#[ignore = "1,000 cases per tool: CI runs it"]
fn fold_print_options() {
    fuzz("fold-print", 1000);
}
