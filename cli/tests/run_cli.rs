//! `fold-run` end to end: outputs, exit codes, bad input.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::Path;

mod common;
use common::{assert_exit, scratch, stderr, summary, tool};

#[test]
fn folds_a_u_turn_and_writes_everything() {
    let d = scratch("uturn");
    let out = d.join("u");
    let o = tool("fold-run")
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
    assert_exit(&o, 0);
    let mut printed: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // --json is summary.json and the output directory
    assert_eq!(printed["out_dir"], out.to_str().unwrap());
    printed.as_object_mut().unwrap().remove("out_dir");
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
    let d = scratch("stops");
    let o = tool("fold-run")
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
    let o = tool("fold-run")
        .args(["S*9", "--s", "0.4e", "--out", d.join("b").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(summary(&d.join("b"))["stalled_at"], 0);
    let o = tool("fold-run")
        .args(["SLLLLS", "--out", d.join("c").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(summary(&d.join("c"))["first_collision"]["time"].is_number());
    let o = tool("fold-run")
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
    let d = scratch("plan");
    let plan = tool("fold-plan")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../shapes/square.svg"))
        .args(["--tiles", "30", "--out", d.join("p.json").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(plan.status.success(), "{}", stderr(&plan));
    let planned: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("p.json")).unwrap()).unwrap();
    std::fs::write(
        d.join("d.json"),
        r#"{"global": {"s": 0.2}, "tiles": [{"from": 0, "to": 2, "s": 0}]}"#,
    )
    .unwrap();
    let o = tool("fold-run")
        .args([
            "--plan",
            d.join("p.json").to_str().unwrap(),
            "--design",
            d.join("d.json").to_str().unwrap(),
        ])
        .args(["--out", d.join("o").to_str().unwrap()])
        .output()
        .unwrap();
    assert_exit(&o, 0);
    assert_eq!(summary(&d.join("o"))["tiles"], planned["tiles"]);
    // final.svg draws the chain over the outline it was planned to fill (issue 14); step
    // frames do not
    let fin = std::fs::read_to_string(d.join("o/final.svg")).unwrap();
    assert_eq!(fin.matches("stroke-dasharray").count(), 1, "{fin}");
    let step = std::fs::read_to_string(d.join("o/step-0000.svg")).unwrap();
    assert!(!step.contains("stroke-dasharray"));
}

#[test]
fn bad_input_exits_2_with_a_clear_message_and_writes_nothing() {
    let d = scratch("bad");
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
        let out_o = tool("fold-run")
            .args(&args)
            .args(["--out", o])
            .output()
            .unwrap();
        let err = stderr(&out_o);
        assert_eq!(out_o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote output");
    }
    // an output directory that cannot be written: its parent is a file
    let o2 = tool("fold-run")
        .args(["SLLS", "--out", d.join("a-file/sub").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(o2.status.code(), Some(2));
    assert!(stderr(&o2).contains("a-file"));
}

#[test]
fn force_start_rule_stalls_a_fold_at_the_last_joint_that_the_distance_rule_folds() {
    // with the thesis' layout c = 2.8 mm at the curved final point (a 1.3 mm wall); at the
    // default 0.8 mm wall both rules fold it
    let d = scratch("start-rule");
    std::fs::create_dir_all(&d).unwrap();
    let design = d.join("c28.json");
    std::fs::write(&design, r#"{"c": 2.8}"#).unwrap();
    // SL by the kinematic engine with start rule `rule` and design file `design`, if any
    let fold_sl = |rule: &str, design: Option<&Path>, out: &Path| {
        let mut c = tool("fold-run");
        c.args(["SL", "--engine", "kinematic", "--start-rule", rule]);
        c.args(["--frames", "2"]);
        if let Some(design) = design {
            c.arg("--design").arg(design);
        }
        c.arg("--out").arg(out).output().unwrap()
    };
    for (rule, code, result) in [("distance", 0, "completed"), ("force", 1, "stalled")] {
        let out = d.join(rule);
        let o = fold_sl(rule, Some(&design), &out);
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
    let out = d.join("wall");
    let o = fold_sl("force", None, &out);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(summary(&out)["result"], "completed");
    let o = tool("fold-run")
        .args(["SL", "--start-rule", "nearest"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
}

/// Every file under `dir` (relative path, bytes), sorted.
fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
                files.push((rel, std::fs::read(&p).unwrap()));
            }
        }
    }
    files.sort();
    files
}

/// Puts a user's own files into `dir`: a plain file, a hidden one, one in a subfolder, and
/// files whose names look like the tool's but are not (`step-7.svg`).
fn foreign_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("keep.txt"), "a user's notes").unwrap();
    std::fs::write(dir.join(".hidden"), "hidden").unwrap();
    std::fs::write(dir.join("sub/deep.txt"), "deep").unwrap();
    std::fs::write(dir.join("step-7.svg"), "not one of ours").unwrap();
    std::fs::write(dir.join("summary.json.bak"), "a backup").unwrap();
    tree(dir)
}

fn without_run_files(files: Vec<(String, Vec<u8>)>) -> Vec<(String, Vec<u8>)> {
    files
        .into_iter()
        .filter(|(n, _)| {
            !foldchain_cli::run_files::is_run_file(n) && n != foldchain_cli::record::RECORD
        })
        .collect()
}

/// Runs `fold-run ARGS --out OUT` to exit 0 and asserts that OUT then holds, besides the
/// run's own files, exactly the files `before`.
fn run_keeps(args: &[&str], out: &Path, before: &[(String, Vec<u8>)]) {
    let o = tool("fold-run")
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(without_run_files(tree(out)), before);
}

#[test]
fn an_output_directory_keeps_every_file_the_tool_did_not_write() {
    let d = scratch("foreign");
    let out = d.join("o");
    let before = foreign_files(&out);
    for (chain, frames) in [("SLLS", "12"), ("SSLLSS", "3"), ("LSLLSR", "5")] {
        let o = tool("fold-run")
            .args([chain, "--out", out.to_str().unwrap(), "--frames", frames])
            .output()
            .unwrap();
        assert!(o.status.code().is_some_and(|c| c <= 1), "{chain}");
        assert_eq!(without_run_files(tree(&out)), before, "after {chain}");
        // the frames of this run, and no stale frame of the earlier, longer one
        let n: usize = frames.parse().unwrap();
        let steps = tree(&out)
            .iter()
            .filter(|(f, _)| f.starts_with("step-") && f.len() == 13)
            .count();
        // and one more at the moment of a collision (LSLLSR collides)
        let extra = usize::from(summary(&out)["first_collision"]["time"].is_number());
        assert_eq!(steps, n + extra, "after {chain}");
        assert_eq!(summary(&out)["tiles"], chain.len() + 1);
    }
    // the reference run too
    run_keeps(&["SS", "--reference", "--frames", "2"], &out, &before);
}

#[test]
fn a_run_killed_while_writing_leaves_no_torn_file_and_every_foreign_file() {
    let d = scratch("killed");
    let out = d.join("o");
    let before = foreign_files(&out);
    // a long chain with many frames: writing takes long enough to be interrupted
    for delay_ms in [150u64, 400, 900] {
        let mut child = tool("fold-run")
            .args([
                "S*600 L L S*600",
                "--frames",
                "3000",
                "--out",
                out.to_str().unwrap(),
            ])
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let _ = child.kill();
        let _ = child.wait();
        assert_eq!(
            without_run_files(tree(&out))
                .iter()
                .filter(|(n, _)| !n.contains(".tmp"))
                .cloned()
                .collect::<Vec<_>>(),
            before
        );
        for (name, bytes) in tree(&out) {
            if name.ends_with(".svg") && foldchain_cli::run_files::is_run_file(&name) {
                let text = String::from_utf8(bytes).unwrap();
                assert!(text.trim_end().ends_with("</svg>"), "{name} is torn");
            }
        }
    }
    // the next run completes and clears the temporary files a killed run left
    run_keeps(&["SLLS", "--frames", "3"], &out, &before);
}

// --engine auto (the default): the local solves up to 2,000 distinct joint neighbourhoods
// (a long straight chain has a few dozen: local), the kinematic baseline beyond, named on
// stderr; --engine local is never overridden. The rule itself is unit-tested in
// `src/engine_choice.rs` (`steady_chains_have_few_neighbourhoods_and_random_ones_many`).

#[test]
fn long_straight_chains_keep_the_local_engine() {
    let d = scratch("auto-engine-straight");
    let straight = tool("fold-run")
        .args(["S*2500", "--frames", "2", "--out"])
        .arg(d.join("straight"))
        .output()
        .unwrap();
    assert_eq!(straight.status.code(), Some(0));
    assert!(!stderr(&straight).contains("kinematic"));
}

#[test]
#[ignore = "slow: folds and checks an irregular 2,501-tile chain (minutes on two cores); .ci/run runs it"]
fn irregular_long_chains_use_the_kinematic_engine_and_say_so() {
    let d = scratch("auto-engine");
    let mut x = 7u64;
    let word: String = (0..2500)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ['S', 'S', 'L', 'R'][(x >> 62) as usize]
        })
        .collect();
    let irregular = tool("fold-run")
        .args([word.as_str(), "--frames", "2", "--out"])
        .arg(d.join("irregular"))
        .output()
        .unwrap();
    assert!(matches!(irregular.status.code(), Some(0 | 1)));
    let err = stderr(&irregular);
    assert!(
        err.contains("2,501 tiles with")
            && err.contains("distinct joint neighbourhoods: the kinematic engine"),
        "{err}"
    );
}

#[test]
fn a_start_rule_with_the_local_engine_is_refused() {
    // --start-rule is the kinematic engine's; with --engine local it would be ignored
    // (and so is --speed: `--speed unit --engine local` once ran the kinematic engine
    // silently)
    let d = scratch("start-rule-local");
    for (flag, value) in [("--start-rule", "force"), ("--speed", "unit")] {
        let o = tool("fold-run")
            .args(["SS", "--engine", "local", flag, value, "--out"])
            .arg(d.join("out"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2));
        let err = stderr(&o);
        assert!(
            err.contains("--speed and --start-rule are the kinematic engine's options")
                && err.lines().count() == 1,
            "{err}"
        );
        assert!(!d.join("out").exists());
    }
}

#[test]
fn one_thread_or_two_write_the_same_timeline() {
    // the local solves' sweeps one after the other or two at once: the same events, bit for
    // bit, so the same timeline.json byte for byte
    let d = scratch("threads");
    let timeline = |threads: &str| {
        let out = d.join(threads);
        let o = tool("fold-run")
            .args(["S*300 LL S*300", "--threads", threads, "--frames", "1"])
            .args(["--json", "--out", out.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{o:?}");
        std::fs::read(out.join("timeline.json")).unwrap()
    };
    assert_eq!(timeline("1"), timeline("2"));
}
