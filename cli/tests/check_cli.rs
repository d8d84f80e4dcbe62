//! `fold-check` and `fold-enum` run as a user would: real binaries, real files.

use std::process::Output;

use foldchain::collision::{check_word, CheckOptions};
use foldchain::{Fold, FoldWord};

mod common;
use common::{absent, assert_exit, assert_mentions, run, shape, stderr, stdout};

fn check(args: &[&str]) -> Output {
    run("fold-check", args)
}

fn fold_enum(args: &[&str]) -> Output {
    run("fold-enum", args)
}

#[test]
fn valid_ring_and_colliding_five() {
    let o = check(&["LLL"]);
    assert_exit(&o, 0);
    assert_eq!(stdout(&o).trim(), "valid");
    let o = check(&["LLLL"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("tiles 0 and 4"), "{}", stdout(&o));
}

#[test]
fn sweeps_reject_what_the_final_shape_allows() {
    let o = check(&["LSLLSR"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("while joint 3 folds"), "{}", stdout(&o));
    let o = check(&["--final-only", "LSLLSR"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
fn inhibited_tile_list_exits_1() {
    let o = check(&["SS SL RS SS"]);
    assert_exit(&o, 1);
    assert_mentions(&stdout(&o), &["inhibited", "joint 1"]);
}

#[test]
fn chain_from_a_file_and_json() {
    let dir = absent("cli");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("u-turn.txt");
    std::fs::write(&f, "# a tight U-turn\nSS*4 SL LL LS SS*4\n").unwrap();
    let o = check(&["--json", f.to_str().unwrap()]);
    assert_exit(&o, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["tiles"], 11);
    assert_eq!(v["result"]["verdict"], "valid");
    // a bare JSON array of tiles is a chain too
    let o = check(&[r#"["SS", "SL", "LL", "LS", "SS"]"#]);
    assert_exit(&o, 0);
    // a plan fold-plan wrote is read for its tiles; a damaged one is reported as a plan
    let plan = dir.join("plan.json");
    let o = run(
        "fold-plan",
        &[
            shape("disc.svg").to_str().unwrap(),
            "--tiles",
            "60",
            "--quiet",
            "--out",
            plan.to_str().unwrap(),
        ],
    );
    assert_exit(&o, 0);
    assert_exit(&check(&[plan.to_str().unwrap()]), 0);
    let text = std::fs::read_to_string(&plan).unwrap();
    std::fs::write(&plan, &text[..text.len() / 2]).unwrap();
    let o = check(&[plan.to_str().unwrap()]);
    assert_exit(&o, 2);
    assert_mentions(&stderr(&o), &["plan.json", "not a fold-plan JSON file"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_exits_2_with_a_clear_message() {
    for (arg, needle) in [
        ("SLXS", "'X'"),
        ("", "empty chain"),
        ("SS S? LS", "S?"),
        ("SS*0", "repeat count"),
    ] {
        let o = check(&[arg]);
        assert_eq!(o.status.code(), Some(2), "{arg:?}: {}", stdout(&o));
        assert!(stderr(&o).contains(needle), "{arg:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
    }
    let dir = absent("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("binary.txt");
    std::fs::write(&f, [0u8, 159, 146, 150]).unwrap();
    let o = check(&[f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("binary.txt"), "{}", stderr(&o));
    let o = check(&[dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("directory"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn table_5_1_from_fold_enum() {
    let o = fold_enum(&["--max-tiles", "6", "--json"]);
    assert_exit(&o, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let rows: Vec<(u64, u64, u64)> = v["rows"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            (
                r["tiles"].as_u64().unwrap(),
                r["candidates"].as_u64().unwrap(),
                r["valid"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        rows,
        vec![(2, 3, 3), (3, 9, 7), (4, 27, 17), (5, 81, 35), (6, 243, 79)]
    );
    // the text table says the same
    let o = fold_enum(&["--max-tiles", "6"]);
    let text = stdout(&o);
    assert!(
        text.lines()
            .any(|l| l.split_whitespace().collect::<Vec<_>>() == ["6", "243", "99", "79"]),
        "{text}"
    );
}

/// The valid count of `fold-enum --json` for one length: the exit code must be 0 and the row
/// must hold a number.
fn valid_count(args: &[&str]) -> u64 {
    let o = fold_enum(args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("fold-enum prints JSON");
    v["rows"][0]["valid"]
        .as_u64()
        .unwrap_or_else(|| panic!("{args:?}: no valid count in {v}"))
}

/// Every fold word of `joints` letters (3^joints of them).
fn all_words(joints: u32) -> Vec<FoldWord> {
    (0..3usize.pow(joints))
        .map(|mut code| {
            let folds = (0..joints)
                .map(|_| {
                    let f = Fold::ALL[code % 3];
                    code /= 3;
                    f
                })
                .collect();
            FoldWord::from_folds(folds)
        })
        .collect()
}

#[test]
fn final_only_counts_more_from_seven_tiles() {
    let seven = ["--min-tiles", "7", "--max-tiles", "7", "--json"];
    let sweep = valid_count(&seven);
    let fin = valid_count(&[&seven[..], &["--final-only"]].concat());
    // the same counts word by word: every 6-letter word checked on its own, with and without
    // the sweeps (the library's check, not fold-enum's search); words with adjacent opposite
    // folds (L then R) need LR/RL tiles and are left out unless --allow-lr
    let words: Vec<FoldWord> = all_words(6)
        .into_iter()
        .filter(|w| {
            w.folds()
                .windows(2)
                .all(|p| p[0].quarter_turns() * p[1].quarter_turns() >= 0)
        })
        .collect();
    let count = |opts: CheckOptions| {
        words
            .iter()
            .filter(|w| check_word(w, &opts).is_ok())
            .count() as u64
    };
    assert_eq!(sweep, count(CheckOptions::default()));
    assert_eq!(fin, count(CheckOptions::default().with_final_only(true)));
    assert!(fin > sweep, "final-only {fin}, with sweeps {sweep}");
}

#[test]
fn shards_add_up_from_the_command_line() {
    let thirteen = ["--max-tiles", "13", "--min-tiles", "13", "--json"];
    let whole = valid_count(&thirteen);
    let parts: Vec<u64> = (1..=4)
        .map(|k| valid_count(&[&thirteen[..], &["--shard", &format!("{k}/4")]].concat()))
        .collect();
    assert!(parts.iter().all(|&p| p < whole), "{parts:?} of {whole}");
    assert_eq!(parts.iter().sum::<u64>(), whole);
}

/// The chance that a chain of `tiles` uniformly random tiles propagates to its end and folds
/// cleanly, as a fraction of `9^(tiles-1)`: at each joint the second path of one tile and the
/// first of the next are independent uniform letters, so a joint folds L with weight 1 (L, L),
/// R with weight 1 (R, R), is inhibited with weight 2 (L, R or R, L) and propagates straight
/// with weight 5; the word must then fold without collision.
fn random_chain_numerator(tiles: u32) -> u64 {
    all_words(tiles - 1)
        .iter()
        .filter(|w| check_word(w, &CheckOptions::default()).is_ok())
        .map(|w| {
            w.folds()
                .iter()
                .map(|f| if f.quarter_turns() == 0 { 5 } else { 1 })
                .product::<u64>()
        })
        .sum()
}

#[test]
fn merge_adds_up_shard_files_and_refuses_a_missing_or_doubled_one() {
    let dir = absent("merge");
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for k in 1..=3 {
        let o = fold_enum(&["--max-tiles", "14", "--json", "--shard", &format!("{k}/3")]);
        assert_exit(&o, 0);
        let f = dir.join(format!("part-{k}.json"));
        std::fs::write(&f, &o.stdout).unwrap();
        files.push(f.display().to_string());
    }
    let whole: serde_json::Value =
        serde_json::from_str(&stdout(&fold_enum(&["--max-tiles", "14", "--json"]))).unwrap();
    let mut args = vec!["--merge"];
    args.extend(files.iter().map(String::as_str));
    args.push("--json");
    let o = fold_enum(&args);
    assert_exit(&o, 0);
    let merged: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(merged["rows"], whole["rows"]);
    // part 2 missing
    let o = fold_enum(&["--merge", &files[0], &files[2]]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("shards missing: 2 (of 3 parts)"),
        "{}",
        stderr(&o)
    );
    // part 3 twice
    let o = fold_enum(&["--merge", &files[0], &files[1], &files[2], &files[2]]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("shard 3/3 given twice"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn random_chains_column() {
    let o = fold_enum(&[
        "--max-tiles",
        "5",
        "--random",
        "--json",
        "--random-exact-max",
        "4",
        "--samples",
        "20000",
    ]);
    assert_exit(&o, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let rows = v["rows"].as_array().unwrap();
    for (row, tiles) in rows.iter().zip(2u32..=4) {
        let exact = format!("{}/{}", random_chain_numerator(tiles), 9u64.pow(tiles - 1));
        assert_eq!(row["p_random_exact"], exact.as_str(), "{tiles} tiles");
    }
    assert_eq!(rows[0]["p_random_exact"], "7/9");
    // five tiles: sampled; the exact value lies within five standard errors of the estimate
    // (the sampling is seeded, so this is not flaky: a failure means a wrong estimate)
    let exact5 = random_chain_numerator(5) as f64 / 9f64.powi(4);
    let p5 = rows[3]["p_random"].as_f64().unwrap();
    let standard_error = (exact5 * (1.0 - exact5) / 20_000.0).sqrt();
    assert!(
        (p5 - exact5).abs() < 5.0 * standard_error,
        "sampled {p5}, exact {exact5}, standard error {standard_error}"
    );
    // and computed exactly, five tiles give exactly that fraction
    let o = fold_enum(&["--min-tiles", "5", "--max-tiles", "5", "--random", "--json"]);
    assert_exit(&o, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let row = &v["rows"][0];
    let exact = format!("{}/6561", random_chain_numerator(5));
    assert_eq!(row["p_random_exact"], exact.as_str());
    assert_eq!(row["p_random"].as_f64(), Some(exact5));
}

#[test]
fn fold_enum_bad_options_exit_2() {
    for args in [
        vec!["--max-tiles", "3", "--min-tiles", "5"],
        vec!["--max-tiles", "99"],
        vec!["--max-tiles", "5", "--shard", "0/3"],
        vec!["--max-tiles", "5", "--shard", "x"],
        vec!["--max-tiles", "five"],
    ] {
        let o = fold_enum(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            !stderr(&o).is_empty() && !stderr(&o).contains("panicked"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
}
