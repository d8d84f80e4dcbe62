//! `fold-print` end to end on real files: the parts, plates, assembly sheet and parts.json
//! of a chain and of the key shape; plates whose tiles are the bill of materials; bad input
//! named with exit 2; a user's files in the output directory left alone.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Output;

use foldchain::{BillOfMaterials, Chain};
use foldchain_print::read_3mf;

mod common;
use common::{absent, root, stderr, stdout, text, tool};

/// Runs tool `name` with `args` from the workspace root.
fn in_root(name: &str, args: &[&str]) -> Output {
    tool(name).args(args).current_dir(root()).output().unwrap()
}

fn print(args: &[&str]) -> Output {
    in_root("fold-print", args)
}

/// fold-plan's plan of the key drawing at `tiles` tiles, as JSON, after asserting exit 0.
fn key_plan(tiles: &str) -> Output {
    let o = in_root(
        "fold-plan",
        &["shapes/key.svg", "--tiles", tiles, "--json", "--quiet"],
    );
    ok(&o);
    o
}

fn ok(o: &Output) {
    assert_eq!(
        o.status.code(),
        Some(0),
        "stdout {}\nstderr {}",
        stdout(o),
        stderr(o)
    );
}

/// The tiles on every plate, counted per object name (the part's label), and every plate's
/// meshes checked closed.
fn plate_counts(dir: &Path) -> BTreeMap<String, usize> {
    let mut counts = BTreeMap::new();
    let mut k = 1;
    while let Ok(bytes) = std::fs::read(dir.join(format!("plates/plate-{k}.3mf"))) {
        let model = read_3mf(&bytes).unwrap();
        for (name, mesh) in &model.objects {
            assert!(mesh.topology().is_sound(), "plate {k} {name}");
        }
        for it in &model.items {
            *counts
                .entry(model.objects[it.object].0.clone())
                .or_insert(0) += 1;
            // inside the default 250 x 210 mm bed
            assert!(
                it.x >= 15.0 && it.x <= 235.0 && it.y >= 15.0 && it.y <= 195.0,
                "{it:?}"
            );
        }
        k += 1;
    }
    assert!(k > 1, "no plates in {}", dir.display());
    counts
}

fn bom_by_name(chain: &Chain) -> BTreeMap<String, usize> {
    BillOfMaterials::from_chain(chain)
        .parts
        .iter()
        .map(|(p, n)| (p.to_string(), *n))
        .collect()
}

#[test]
fn a_u_turn_prints_its_parts_plates_sheet_and_report() {
    let dir = absent("u");
    std::fs::create_dir_all(dir.join("plates")).unwrap();
    // a user's files, one in plates/ under a name the tool does not own
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join("plates/my-plate.3mf"), "mine too").unwrap();
    let o = print(&["SLLS", "--out", dir.to_str().unwrap()]);
    ok(&o);
    let chain = Chain::parse("SLLS").unwrap();
    assert_eq!(plate_counts(&dir), bom_by_name(&chain));
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("parts.json")).unwrap()).unwrap();
    assert_eq!(report["tiles"], 5);
    assert_eq!(report["magnets"]["count"], 10);
    assert!(report["estimate_basis"].as_str().unwrap().contains("mm3/s"));
    for part in report["parts"].as_array().unwrap() {
        let file = dir.join(part["file"].as_str().unwrap());
        let model = read_3mf(&std::fs::read(&file).unwrap()).unwrap();
        assert!(model.objects[0].1.topology().is_sound());
        assert!(dir.join(part["picture"].as_str().unwrap()).is_file());
    }
    let sheet = text(&dir.join("assembly.svg"));
    assert!(usvg::Tree::from_str(&sheet, &usvg::Options::default()).is_ok());
    assert_eq!(sheet.matches(">#").count(), 5);
    assert!(sheet.contains("RI S"));
    assert_eq!(text(&dir.join("notes.txt")), "mine");
    assert_eq!(text(&dir.join("plates/my-plate.3mf")), "mine too");
    // a second run with a smaller bed needs more plates; a third with the default bed
    // removes the plates it no longer writes, and only those
    ok(&print(&[
        "SLLS",
        "--bed",
        "70,40",
        "--spacing",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]));
    assert!(dir.join("plates/plate-3.3mf").is_file());
    ok(&print(&["SLLS", "--out", dir.to_str().unwrap()]));
    assert!(!dir.join("plates/plate-2.3mf").exists());
    assert!(dir.join("plates/my-plate.3mf").is_file());
    // STL: one mesh per part and plate, still closed after 32-bit rounding
    let stl_dir = absent("u-stl");
    ok(&print(&[
        "SLLS",
        "--format",
        "stl",
        "--printer",
        "resin",
        "--out",
        stl_dir.to_str().unwrap(),
    ]));
    let mesh =
        foldchain_print::from_stl(&std::fs::read(stl_dir.join("parts/RR.stl")).unwrap()).unwrap();
    assert!(mesh.topology().is_sound());
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&stl_dir);
}

#[test]
fn the_key_prints_its_plans_bill_of_materials() {
    let dir = absent("key");
    let o = print(&[
        "shapes/key.svg",
        "--tiles",
        "171",
        "--out",
        dir.to_str().unwrap(),
    ]);
    ok(&o);
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("parts.json")).unwrap()).unwrap();
    let chain = foldchain::Chain::parse(report["tile_list"].as_str().unwrap()).unwrap();
    let n = report["tiles"].as_u64().unwrap() as usize;
    assert_eq!(chain.len(), n);
    // the plan of fold-plan itself: the same chain
    let plan = key_plan("171");
    let plan: serde_json::Value = serde_json::from_slice(&plan.stdout).unwrap();
    assert_eq!(plan["tile_list"], report["tile_list"]);
    assert!((150..=190).contains(&n), "{n}");
    assert_eq!(plate_counts(&dir), bom_by_name(&chain));
    let sheet = text(&dir.join("assembly.svg"));
    assert_eq!(sheet.matches(">#").count(), n);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_is_named_with_exit_2_and_writes_nothing() {
    let dir = absent("bad");
    let out = dir.to_str().unwrap();
    for (args, says) in [
        (vec!["SL", "--bed", "250", "--out", out], "--bed"),
        (vec!["SL", "--bed", "0,10", "--out", out], "--bed"),
        (
            vec!["SL", "--clearance", "-0.1", "--out", out],
            "--clearance",
        ),
        (vec!["SL", "--spacing", "1e9", "--out", out], "--spacing"),
        (vec!["SL", "--floor", "9", "--out", out], "floor"),
        (vec!["SL", "--bed", "20,20", "--out", out], "does not fit"),
        (vec!["nope.txt", "--out", out], "no such file"),
        (
            vec!["SL", "--tiles", "9", "--out", out],
            "only to a SHAPE.svg",
        ),
        (vec!["--out", out], "no chain"),
    ] {
        let o = print(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(err.starts_with("fold-print: "), "{err}");
        assert!(!dir.join("parts.json").exists(), "{args:?} wrote files");
    }
    // a design whose wall leaves less than the printable minimum
    std::fs::create_dir_all(&dir).unwrap();
    let design = dir.join("thin.json");
    std::fs::write(&design, r#"{"wall": 0.2}"#).unwrap();
    let o = print(&["SLLS", "--design", design.to_str().unwrap(), "--out", out]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("mm thick"), "{err}");
    assert!(!dir.join("parts.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A plan's warnings (a part left empty, a count off the request) are said by fold-print as
/// fold-plan says them, on stderr (also with `--json`) and in parts.json: for a drawing it
/// plans itself, the same warnings as fold-plan's plan of it; for a plan file, its own.
#[test]
fn a_plans_warnings_are_printed_as_fold_plan_prints_them() {
    let plan = key_plan("300");
    let plan_err = String::from_utf8_lossy(&plan.stderr).into_owned();
    let mut json: serde_json::Value = serde_json::from_slice(&plan.stdout).unwrap();
    let warnings: Vec<String> = json["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap().to_string())
        .collect();
    let dir = absent("warnings");
    let out = dir.to_str().unwrap();
    for extra in [&[][..], &["--json"][..]] {
        let mut args = vec!["shapes/key.svg", "--tiles", "300", "--out", out, "--quiet"];
        args.extend_from_slice(extra);
        let o = print(&args);
        ok(&o);
        let err = String::from_utf8_lossy(&o.stderr);
        for w in &warnings {
            assert!(
                plan_err.contains(&format!("fold-plan: warning: {w}")),
                "{plan_err}"
            );
            assert!(err.contains(&format!("fold-print: warning: {w}")), "{err}");
        }
        let report: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("parts.json")).unwrap()).unwrap();
        let listed = report
            .get("plan_warnings")
            .and_then(|w| w.as_array())
            .map_or(0, Vec::len);
        assert_eq!(listed, warnings.len(), "{report}");
    }
    // a plan file with a warning of its own
    let said = "the plan has 9 tiles, 10.0% fewer than the 10 asked (tolerance 3.0%)";
    json["warnings"] = serde_json::json!([said]);
    std::fs::create_dir_all(&dir).unwrap();
    let plan_file = dir.join("warned-plan.json");
    std::fs::write(&plan_file, json.to_string()).unwrap();
    let out2 = dir.join("out");
    let o = print(&[
        "--plan",
        plan_file.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
        "--quiet",
    ]);
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains(&format!("fold-print: warning: {said}")),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
