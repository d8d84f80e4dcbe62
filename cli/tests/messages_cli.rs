//! What the tools say, and refuse, on the command line (issue 14): each tool's own help with
//! its exit codes, errors said once, missing files not read as fold words, outputs that
//! would overwrite an input refused before any work, options that would be ignored refused,
//! progress when stderr is not a terminal, and the run's own report.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::process::Output;

mod common;
use common::{
    assert_exit, assert_exit_saying, assert_mentions, plan_sample, run, scratch, shape, stderr,
    tool,
};

/// Asserts exit code 2 and a message holding every one of `words`.
fn bad(o: &Output, words: &[&str]) {
    assert_exit_saying(o, 2, words);
}

#[test]
fn every_tool_has_its_own_help_with_exit_codes() {
    let mut abouts = Vec::new();
    for t in [
        "fold-plan",
        "fold-run",
        "fold-check",
        "fold-enum",
        "fold-validate",
    ] {
        let o = run(t, &["--help"]);
        assert_eq!(o.status.code(), Some(0), "{t}");
        let h = String::from_utf8(o.stdout).unwrap();
        assert!(
            h.contains("Exit codes:") && h.contains("Examples:"),
            "{t}: {h}"
        );
        assert!(h.contains(t), "{t} help names its tool: {h}");
        abouts.push(h.lines().next().unwrap().to_string());
    }
    abouts.sort();
    abouts.dedup();
    assert_eq!(abouts.len(), 5, "each tool describes itself: {abouts:?}");
    let h = String::from_utf8(run("fold-validate", &["--help"]).stdout).unwrap();
    for scene in [
        "3-tile SL",
        "20-tile s=0.3",
        "107-tile square",
        "SLLS rot x1e7",
    ] {
        assert!(h.contains(scene), "fold-validate --help lists {scene}");
    }
}

#[test]
fn an_error_is_said_once() {
    let d = scratch("once");
    let missing = d.join("nope.svg");
    let o = run("fold-plan", &[missing.to_str().unwrap()]);
    bad(&o, &["nope.svg"]);
    assert_eq!(
        stderr(&o).matches("No such file").count(),
        1,
        "{}",
        stderr(&o)
    );
    assert_eq!(stderr(&o).lines().count(), 1);
}

#[test]
fn a_missing_file_is_not_read_as_a_fold_word() {
    let o = run("fold-check", &["nope.txt"]);
    bad(&o, &["nope.txt", "no such file, and not a fold word"]);
    let o = run("fold-check", &[shape("square.svg").to_str().unwrap()]);
    bad(&o, &["square.svg", "fold-plan", "fold-run"]);
    let o = run("fold-run", &["missing/chain.json"]);
    bad(&o, &["missing/chain.json", "no such file"]);
}

#[test]
fn an_output_over_an_input_is_refused_before_any_work() {
    let d = scratch("over");
    let sq = d.join("sq.svg");
    std::fs::copy(shape("square.svg"), &sq).unwrap();
    let before = std::fs::read(&sq).unwrap();
    for flag in ["--preview", "--out"] {
        let o = run(
            "fold-plan",
            &[sq.to_str().unwrap(), flag, sq.to_str().unwrap()],
        );
        bad(&o, &[flag, "refusing to overwrite"]);
        // the same file through another spelling of its path
        let other = d.join(".").join("sq.svg");
        let o = run(
            "fold-plan",
            &[sq.to_str().unwrap(), flag, other.to_str().unwrap()],
        );
        bad(&o, &[flag]);
    }
    assert_eq!(std::fs::read(&sq).unwrap(), before);
    // fold-run: a design file kept in the output directory under one of the run's names
    let design = d.join("summary.json");
    std::fs::write(&design, r#"{"s": 0.3}"#).unwrap();
    let o = run(
        "fold-run",
        &[
            "SLLS",
            "--design",
            design.to_str().unwrap(),
            "--out",
            d.to_str().unwrap(),
        ],
    );
    bad(&o, &["--out", "would overwrite the input file"]);
    assert_eq!(std::fs::read_to_string(&design).unwrap(), r#"{"s": 0.3}"#);
}

#[test]
fn options_that_would_be_ignored_are_refused() {
    bad(
        &run("fold-enum", &["--max-tiles", "5", "--samples", "10"]),
        &["--samples", "--random"],
    );
    bad(
        &run("fold-validate", &["--case", "SLLS control"]),
        &["--stiff"],
    );
    bad(
        &run(
            "fold-validate",
            &["--quick", "--reference-tolerance", "1e-8"],
        ),
        &["--quick", "--reference-tolerance"],
    );
    bad(
        &run("fold-run", &["SLLS", "--tiles", "40"]),
        &["--tiles", "SHAPE.svg"],
    );
}

#[test]
fn bad_numbers_get_our_messages() {
    bad(
        &run("fold-run", &["SLLS", "--tiles", "-5"]),
        &["-5", "whole number"],
    );
    bad(
        &run(
            "fold-plan",
            &[shape("square.svg").to_str().unwrap(), "--tiles", "-5"],
        ),
        &["-5", "whole number"],
    );
    let o = run("fold-enum", &["--max-tiles", "1"]);
    bad(&o, &["--max-tiles 1", "from 2 to"]);
    assert!(!stderr(&o).contains("min"), "{}", stderr(&o));
    bad(
        &run("fold-run", &["SLLS", "--frames", "100001"]),
        &["--frames 100001", "from 1 to 100,000"],
    );
    // 1e-3 is a number of millimetres, not the design parameter e
    let d = scratch("s");
    let o = run(
        "fold-run",
        &["SS", "--s", "1e-3", "--out", d.to_str().unwrap(), "--json"],
    );
    assert_ne!(o.status.code(), Some(2), "{}", stderr(&o));
    let a = run(
        "fold-run",
        &[
            "SS",
            "--s",
            "0.001",
            "--out",
            d.join("b").to_str().unwrap(),
            "--json",
        ],
    );
    let v = |o: &Output| -> serde_json::Value { serde_json::from_slice(&o.stdout).unwrap() };
    assert_eq!(v(&o)["duration_s"], v(&a)["duration_s"]);
}

#[test]
fn the_validation_output_is_checked_before_the_work() {
    let d = scratch("vout");
    let f = d.join("afile.txt");
    std::fs::write(&f, "x").unwrap();
    let t0 = std::time::Instant::now();
    let o = run("fold-validate", &["--out", f.to_str().unwrap()]);
    bad(&o, &["afile.txt", "not a directory"]);
    // the full validation takes minutes; a refusal before it, well under that
    assert!(t0.elapsed().as_secs() < 20);
    assert_eq!(std::fs::read_to_string(&f).unwrap(), "x");
}

#[test]
fn a_plan_whose_word_and_tile_list_disagree_is_refused() {
    let d = scratch("plan");
    let p = d.join("p.json");
    let o = plan_sample("square.svg", 30, &["--out", p.to_str().unwrap()]);
    assert_exit(&o, 0);
    let mut plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
    plan["tile_list"] = "SS SS SS".into();
    std::fs::write(&p, plan.to_string()).unwrap();
    bad(
        &run(
            "fold-run",
            &[
                "--plan",
                p.to_str().unwrap(),
                "--out",
                d.join("o").to_str().unwrap(),
            ],
        ),
        &["p.json", "disagree"],
    );
    assert!(!d.join("o").exists());
}

#[test]
fn a_run_reports_its_folder_its_simulated_time_and_odd_designs() {
    let d = scratch("report");
    // an inline JSON chain gets a plain folder name
    let o = tool("fold-run")
        .current_dir(&d)
        .args([r#"{"tiles":["SS","SL","LS"]}"#])
        .output()
        .unwrap();
    assert_exit(&o, 0);
    let names: Vec<String> = std::fs::read_dir(d.join("out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["SL"]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("s of simulated time"), "{text}");
    // --json names the output directory
    let out = d.join("j");
    let o = run(
        "fold-run",
        &["SLLS", "--json", "--out", out.to_str().unwrap()],
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["out_dir"], out.to_str().unwrap());
    // an absurd remanence is refused with its range
    let design = d.join("absurd.json");
    std::fs::write(&design, r#"{"s": 0.3, "remanence": 1e300}"#).unwrap();
    let a = d.join("a");
    let run_design = || {
        let args = [
            "SLLS",
            "--design",
            design.to_str().unwrap(),
            "--out",
            a.to_str().unwrap(),
        ];
        run("fold-run", &args)
    };
    let o = run_design();
    bad(&o, &["absurd.json", "`remanence` = 1e300 T", "up to 2 T"]);
    // 10 um tiles with weak magnets in grease take years of simulated time: say so (their
    // water drag scales with them, so the channel's drag and the magnets make it slow)
    std::fs::write(
        &design,
        r#"{"tile_width": 0.01, "d": 0.005, "e": 0.0015, "s": 0.0001, "magnet_diameter": 0.001, "magnet_height": 0.0015, "wall": 0.0002, "remanence": 0.01, "magnet_drag": 10000}"#,
    )
    .unwrap();
    let o = run_design();
    assert_mentions(&stderr(&o), &["warning", "simulated time"]);
}

#[test]
fn a_long_count_is_never_silent_off_a_terminal() {
    // 24 tiles: about 0.3 s of counting, six progress intervals (22 tiles took 0.07-0.12 s
    // once the fold check's memo went into blocks, too near the interval to print for sure)
    let o = tool("fold-enum")
        .env("FOLDCHAIN_PROGRESS_SECONDS", "0.05")
        .args(["--max-tiles", "24"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0));
    let e = stderr(&o);
    let line = e
        .lines()
        .find(|l| l.contains("counting:"))
        .unwrap_or_else(|| panic!("no progress line: {e}"));
    assert_mentions(line, &["parts", "/s", "left"]);
    let o = tool("fold-enum")
        .env("FOLDCHAIN_PROGRESS_SECONDS", "0.05")
        .args(["--max-tiles", "24", "--quiet"])
        .output()
        .unwrap();
    assert!(!stderr(&o).contains("counting:"), "{}", stderr(&o));
    // a run that would take days says so first
    let mut child = tool("fold-enum")
        .args(["--max-tiles", "40"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    {
        use std::io::BufRead;
        let mut r = std::io::BufReader::new(child.stderr.take().unwrap());
        r.read_line(&mut first).unwrap();
    }
    let _ = child.kill();
    let _ = child.wait();
    assert_mentions(&first, &["valid words", "roughly"]);
}

#[test]
fn long_runs_and_studies_are_never_silent_off_a_terminal() {
    // issue 29: a 300,000-tile fold-run and fold-tolerance "S*999" print progress within 5 s
    // when stderr is not a terminal (the first line after 2 s, a thread of its own, so one
    // long library call is heard from too); here the interval is shortened to keep the
    // cases small. --quiet silences both.
    let d = scratch("progress");
    for quiet in [false, true] {
        let mut run = tool("fold-run");
        run.env("FOLDCHAIN_PROGRESS_SECONDS", "0.02")
            .args(["S*3000 LL S*3000", "--frames", "2", "--out"])
            .arg(d.join(format!("run-{quiet}")));
        let mut study = tool("fold-tolerance");
        study
            .env("FOLDCHAIN_PROGRESS_SECONDS", "0.02")
            .args(["S*99", "--samples", "400"]);
        if quiet {
            run.arg("--quiet");
            study.arg("--quiet");
        }
        let (r, t) = (run.output().unwrap(), study.output().unwrap());
        assert_exit(&r, 0);
        assert_exit(&t, 0);
        let (re, te) = (stderr(&r), stderr(&t));
        assert_eq!(re.contains("fold-run: event engine"), !quiet, "{re}");
        assert_eq!(te.contains("fold-tolerance: samples:"), !quiet, "{te}");
    }
}
