//! `fold-plan` on the command line: the tile list and summary it prints, the files it writes,
//! and its exit codes for unplannable shapes (1) and bad files (2).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use foldchain::collision::{check_word, CheckOptions};
use foldchain_planner::Plan;

mod common;
use common::{absent, assert_exit_saying, assert_mentions, plan_sample, run, stderr};

/// Word and tile list agree and the chain folds without collision (sequential sweeps).
fn assert_sound(p: &Plan) {
    let word = p.fold_word().unwrap();
    assert_eq!(word.tiles(), p.tiles);
    assert_eq!(word.to_chain().to_tile_list(), p.tile_list);
    assert_eq!(p.poses.len(), p.tiles);
    check_word(&word, &CheckOptions::default()).unwrap();
}

const TWO_DISCS: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100"><circle cx="30" cy="50" r="25"/><circle cx="270" cy="50" r="25"/></svg>"#;

#[test]
fn cli_prints_tile_list_and_summary_and_writes_files() {
    let dir = absent("cli");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("plan.json");
    let pv = dir.join("preview.svg");
    let o = plan_sample(
        "key.svg",
        171,
        &[
            "--out",
            out.to_str().unwrap(),
            "--preview",
            pv.to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2);
    assert!(lines[0].starts_with("SS"), "{}", lines[0]);
    assert_mentions(lines[1], &["tiles", "covered"]);
    let p = Plan::from_json(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_sound(&p);
    assert!(std::fs::read_to_string(&pv).unwrap().contains("<polygon"));
    let o = plan_sample("disc.svg", 50, &["--json"]);
    assert!(o.status.success());
    let p = Plan::from_json(std::str::from_utf8(&o.stdout).unwrap()).unwrap();
    assert_sound(&p);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_files_exit_2_naming_the_file() {
    let dir = absent("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        ("broken.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"><rect", "not a readable SVG"),
        ("empty.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><rect width=\"5\" height=\"5\" fill=\"none\" stroke=\"red\"/></svg>", "no filled area"),
        ("bow.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"60\" height=\"60\"><polygon id=\"tie\" points=\"0,0 50,50 50,0 0,50\"/></svg>", "self-intersecting"),
    ];
    for (name, body, what) in cases {
        let f = dir.join(name);
        std::fs::write(&f, body).unwrap();
        let out = dir.join(format!("{name}.json"));
        let o = run(
            "fold-plan",
            &[f.to_str().unwrap(), "--out", out.to_str().unwrap()],
        );
        assert_eq!(o.status.code(), Some(2), "{name}");
        let err = stderr(&o);
        assert!(err.contains(name) && err.contains(what), "{name}: {err}");
        assert!(!out.exists(), "no output for bad input");
    }
    let o = run("fold-plan", &[dir.join("missing.svg").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("missing.svg"));
    // two discs far apart: one chain cannot fill both (tests/plan_cells.rs says why)
    let two = dir.join("two.svg");
    std::fs::write(&two, r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100"><circle cx="30" cy="50" r="25"/><circle cx="270" cy="50" r="25"/></svg>"#).unwrap();
    let o = run("fold-plan", &[two.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "unplannable shape exits 1");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_exits_1_naming_why() {
    let dir = absent("cells");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("two.svg");
    std::fs::write(&f, TWO_DISCS).unwrap();
    let out = dir.join("plan.json");
    let o = run(
        "fold-plan",
        &[f.to_str().unwrap(), "--out", out.to_str().unwrap()],
    );
    assert_exit_saying(&o, 1, &["separate parts", "cannot plan"]);
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
