//! The drawings the tests walk, listed in one place so that the planner's tests and the
//! CLI's (which include this file by path) see the same set: the sample shapes
//! (`shapes/*.svg`) and the planner corpus (`planner/corpus/*/*.svg`, its tools aside).

#![allow(dead_code)] // each test file uses its part
#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::collections::BTreeSet;
use std::path::Path;

/// The stems of the SVG files in `dir` (the sample shapes: `shapes/`), sorted.
pub fn svg_stems(dir: &Path) -> Vec<String> {
    let mut stems: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "svg"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    stems.sort();
    stems
}

/// Every SVG file one folder below `corpus` (but its `tools`), as `folder/name.svg`.
pub fn corpus_files(corpus: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for dir in std::fs::read_dir(corpus).unwrap() {
        let dir = dir.unwrap().path();
        if !dir.is_dir() || dir.ends_with("tools") {
            continue;
        }
        for f in std::fs::read_dir(&dir).unwrap() {
            let f = f.unwrap().path();
            if f.extension().is_some_and(|e| e == "svg") {
                out.insert(f.strip_prefix(corpus).unwrap().display().to_string());
            }
        }
    }
    out
}
