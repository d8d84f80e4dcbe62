//! `fold-check` and `fold-enum` run as a user would: real binaries, real files.

use std::process::{Command, Output};

fn run(bin: &str, args: &[&str]) -> Output {
    Command::new(bin).args(args).output().expect("binary runs")
}

fn check(args: &[&str]) -> Output {
    run(env!("CARGO_BIN_EXE_fold-check"), args)
}

fn fold_enum(args: &[&str]) -> Output {
    run(env!("CARGO_BIN_EXE_fold-enum"), args)
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn valid_ring_and_colliding_five() {
    let o = check(&["LLL"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
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
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stdout(&o).contains("inhibited") && stdout(&o).contains("joint 1"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn chain_from_a_file_and_json() {
    let dir = std::env::temp_dir().join(format!("foldchain-check-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("u-turn.txt");
    std::fs::write(&f, "# a tight U-turn\nSS*4 SL LL LS SS*4\n").unwrap();
    let o = check(&["--json", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(v["tiles"], 11);
    assert_eq!(v["result"]["verdict"], "valid");
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
    let dir = std::env::temp_dir().join(format!("foldchain-check-bad-{}", std::process::id()));
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
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
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

#[test]
fn final_only_counts_more_from_seven_tiles() {
    let sweep = fold_enum(&["--min-tiles", "7", "--max-tiles", "7", "--json"]);
    let fin = fold_enum(&[
        "--min-tiles",
        "7",
        "--max-tiles",
        "7",
        "--json",
        "--final-only",
    ]);
    let a: serde_json::Value = serde_json::from_str(&stdout(&sweep)).unwrap();
    let b: serde_json::Value = serde_json::from_str(&stdout(&fin)).unwrap();
    assert!(
        b["rows"][0]["valid"].as_u64() > a["rows"][0]["valid"].as_u64(),
        "{a} {b}"
    );
}

#[test]
fn shards_add_up_from_the_command_line() {
    let whole: serde_json::Value = serde_json::from_str(&stdout(&fold_enum(&[
        "--max-tiles",
        "13",
        "--min-tiles",
        "13",
        "--json",
    ])))
    .unwrap();
    let mut sum = 0;
    for k in 1..=4 {
        let shard = format!("{k}/4");
        let part: serde_json::Value = serde_json::from_str(&stdout(&fold_enum(&[
            "--max-tiles",
            "13",
            "--min-tiles",
            "13",
            "--json",
            "--shard",
            &shard,
        ])))
        .unwrap();
        sum += part["rows"][0]["valid"].as_u64().unwrap();
    }
    assert_eq!(Some(sum), whole["rows"][0]["valid"].as_u64());
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
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows[0]["p_random_exact"], "7/9");
    // five tiles: sampled, close to the exact value the library computes
    let p5 = rows[3]["p_random"].as_f64().unwrap();
    assert!((0.3..0.4).contains(&p5), "{p5}");
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
