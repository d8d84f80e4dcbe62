//! What every CLI integration test needs once: the tools' binaries and what they print,
//! scratch directories of this test binary, and the JSON files a run writes. A test file
//! declares `mod common;` and uses its own part.

#![allow(dead_code)] // each test file uses its own part
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary of tool `name` (`fold-run`, `fold-plan`, ...) that Cargo built for the tests.
pub fn exe(name: &str) -> &'static str {
    match name {
        "fold-run" => env!("CARGO_BIN_EXE_fold-run"),
        "fold-plan" => env!("CARGO_BIN_EXE_fold-plan"),
        "fold-check" => env!("CARGO_BIN_EXE_fold-check"),
        "fold-enum" => env!("CARGO_BIN_EXE_fold-enum"),
        "fold-tolerance" => env!("CARGO_BIN_EXE_fold-tolerance"),
        "fold-validate" => env!("CARGO_BIN_EXE_fold-validate"),
        "fold-print" => env!("CARGO_BIN_EXE_fold-print"),
        _ => panic!("no tool named {name}"),
    }
}

/// A command for tool `name`.
pub fn tool(name: &str) -> Command {
    Command::new(exe(name))
}

/// Runs tool `name` with `args` to its end.
pub fn run(name: &str, args: &[&str]) -> Output {
    tool(name).args(args).output().unwrap()
}

/// What a tool printed on standard output.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What a tool printed on standard error.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts that a tool exited with `code`, showing its standard error otherwise.
pub fn assert_exit(o: &Output, code: i32) {
    assert_eq!(o.status.code(), Some(code), "{}", stderr(o));
}

/// Asserts that `text` holds every one of `words`, naming the first one missing.
pub fn assert_mentions(text: &str, words: &[&str]) {
    for w in words {
        assert!(text.contains(w), "missing {w:?} in: {text}");
    }
}

/// Asserts that a tool exited with `code` and said every one of `words` on standard error.
pub fn assert_exit_saying(o: &Output, code: i32, words: &[&str]) {
    assert_exit(o, code);
    assert_mentions(&stderr(o), words);
}

/// The JSON a tool printed on standard output, after asserting that it exited with 0.
pub fn stdout_json(o: &Output) -> serde_json::Value {
    assert_exit(o, 0);
    serde_json::from_slice(&o.stdout).unwrap()
}

/// The workspace's root directory.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The sample drawing `name` of `shapes/`.
pub fn shape(name: &str) -> PathBuf {
    root().join("shapes").join(name)
}

/// Runs `fold-plan` on sample shape `name` (in `shapes/`) for `tiles` tiles, with the
/// further arguments `more`.
pub fn plan_sample(name: &str, tiles: usize, more: &[&str]) -> Output {
    let file = shape(name);
    let tiles = tiles.to_string();
    let mut args = vec![file.to_str().unwrap(), "--tiles", &tiles];
    args.extend_from_slice(more);
    run("fold-plan", &args)
}

/// A path for this test binary's `tag` in the temporary directory, with nothing there (what
/// an earlier run left is removed).
pub fn absent(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "foldchain-{}-{}-{tag}",
        env!("CARGO_CRATE_NAME"),
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// A new empty directory for this test binary's `tag` (see [`absent`]).
pub fn scratch(tag: &str) -> PathBuf {
    let d = absent(tag);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The names of the entries of `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The text of the file at `path`.
pub fn text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}

/// The JSON file at `path`.
pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The `summary.json` of the run written in `dir`.
pub fn summary(dir: &Path) -> serde_json::Value {
    read_json(&dir.join("summary.json"))
}

/// The JSON of `fold-validate --scene SCENE --quick --json` with the `extra` arguments,
/// writing into `out`, after asserting that it exited with 0.
pub fn validate_quick(scene: &str, extra: &[&str], out: &Path) -> serde_json::Value {
    let o = tool("fold-validate")
        .args(["--scene", scene, "--quick", "--json"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    stdout_json(&o)
}

/// The first of the programs `names` found on PATH, or `None` with a note on standard error
/// (`what` names the program, `test` the test skipped) when there is none outside CI; under
/// `CI=true` a missing program fails the test (`.ci/run` installs it).
pub fn on_path(names: &[&str], what: &str, test: &str) -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        names.iter().find_map(|name| {
            std::env::split_paths(&paths)
                .map(|d| d.join(name))
                .find(|p| p.is_file())
        })
    });
    if found.is_none() {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no {what} on PATH: CI must have it (.ci/run installs it with apt-get)"
        );
        eprintln!("note: no {what} on PATH; {test} test skipped");
    }
    found
}

/// `fold-plan`'s options for the thesis' two squares of `shapes/square.svg`: exactly 107
/// tiles with tight U-turns (9 rows of 11), and exactly 82 with loose ones (6 rows of 12).
pub const THESIS_SQUARES: [[&str; 6]; 2] = [
    [
        "--tiles",
        "107",
        "--turns",
        "tight",
        "--tiles-tolerance",
        "0",
    ],
    [
        "--tiles",
        "82",
        "--turns",
        "loose",
        "--tiles-tolerance",
        "0",
    ],
];
