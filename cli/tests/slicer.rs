//! A real slicer takes what `fold-print` writes: PrusaSlicer's command line slices a tile
//! of the thesis design and a plate written by the binary (and, in the slow test `.ci/run`
//! runs, every tile type: nine 3MF files), each to G-code, with exit 0 and no error in its
//! output.
//!
//! Without `prusa-slicer` on PATH this test prints a note and passes, except under
//! `CI=true`, where it fails (`.ci/run` installs Debian's `prusa-slicer`).

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::Command;

use foldchain::{Design, Tile};
use foldchain_print::{to_3mf, Item, Object, PartOptions, TilePart};

mod common;
use common::{absent, run, stderr, stdout};

/// The slicer, or `None` (with a note) when there is none outside CI.
fn slicer() -> Option<PathBuf> {
    common::on_path(&["prusa-slicer"], "prusa-slicer", "slicer")
}

/// Slices `model` to G-code next to it and returns the G-code; fails the test on a non-zero
/// exit, a missing or empty G-code file or an error in the slicer's output.
fn slice(exe: &Path, model: &Path, extra: &[&str]) -> String {
    let gcode = model.with_extension("gcode");
    let o = Command::new(exe)
        .arg("--export-gcode")
        .args(extra)
        .arg("--output")
        .arg(&gcode)
        .arg(model)
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    let log = format!("{}{}", stdout(&o), stderr(&o));
    assert!(
        o.status.success(),
        "{}: prusa-slicer exit {:?}\n{log}",
        model.display(),
        o.status.code()
    );
    let errors: Vec<&str> = log
        .lines()
        .filter(|l| l.to_ascii_lowercase().contains("error"))
        .collect();
    assert!(errors.is_empty(), "{}: {errors:?}", model.display());
    let text = std::fs::read_to_string(&gcode).unwrap();
    assert!(text.lines().filter(|l| l.starts_with("G1 ")).count() > 100);
    text
}

/// A G-code comment's value (`; key = value`).
fn comment<'a>(gcode: &'a str, key: &str) -> &'a str {
    gcode
        .lines()
        .find_map(|l| l.strip_prefix(&format!("; {key} = ")))
        .unwrap_or("?")
}

/// Slices a tile of each of `tiles` (its own 3MF, in the bed's middle) into `dir`.
fn slice_tiles(exe: &Path, dir: &Path, tiles: &[Tile]) {
    let opts = PartOptions::default();
    for &tile in tiles {
        let part = TilePart::new(tile, &Design::thesis(), &opts).unwrap();
        let file = dir.join(format!("{tile}.3mf"));
        let bytes = to_3mf(
            &file.display().to_string(),
            &tile.to_string(),
            &[Object {
                name: tile.to_string(),
                mesh: &part.mesh,
            }],
            &[Item {
                object: 0,
                angle: 0.0,
                x: 125.0,
                y: 105.0,
            }],
        )
        .unwrap();
        std::fs::write(&file, bytes).unwrap();
        let g = slice(exe, &file, &[]);
        println!(
            "{tile}: mesh {:.0} mm3; PrusaSlicer: {} cm3 of filament, {}",
            part.volume(),
            comment(&g, "filament used [cm3]"),
            comment(&g, "estimated printing time (normal mode)")
        );
    }
}

/// The scratch directory `name`, emptied.
fn fresh(name: &str) -> PathBuf {
    let dir = absent(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn prusaslicer_slices_a_tile_and_a_plate() {
    let Some(exe) = slicer() else { return };
    let dir = fresh("slicer");
    // RR, a tile of two curved channels, then a plate the binary writes (a tight U-turn:
    // five tiles of four parts)
    slice_tiles(&exe, &dir, &["RR".parse().unwrap()]);
    let out = dir.join("u");
    let o = run("fold-print", &["SLLS", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let g = slice(
        &exe,
        &out.join("plates/plate-1.3mf"),
        &["--bed-shape", "0x0,250x0,250x210,0x210"],
    );
    println!(
        "plate-1 of SLLS: PrusaSlicer: {} cm3 of filament, {}",
        comment(&g, "filament used [cm3]"),
        comment(&g, "estimated printing time (normal mode)")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "slow: slices every tile type with PrusaSlicer (a minute on two cores); .ci/run runs it"]
fn prusaslicer_slices_every_tile_type() {
    let Some(exe) = slicer() else { return };
    let dir = fresh("slicer-every-tile");
    slice_tiles(&exe, &dir, &Tile::ALL);
    let _ = std::fs::remove_dir_all(&dir);
}
