//! The record of the files the tools wrote into an output directory, kept in the directory
//! itself ([`RECORD`], one path relative to the directory a line). A tool replaces or removes
//! a file under one of its own names only when the record lists it, so a user's
//! `summary.json` or `assembly.svg` dropped into an output directory (or a directory an
//! older version wrote, before the record) is refused by name, never overwritten.
//!
//! The record only grows: a name is appended the first time a file is written under it. A
//! line torn by a killed run names no file, so at worst a file of ours is refused once more.

use std::collections::HashSet;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The record's file name in an output directory.
pub const RECORD: &str = ".foldchain-files";

/// The first line of a new record.
const HEADER: &str = "# files foldchain's tools wrote into this directory (one a line); they replace or remove only these\n";

/// The names a directory's record lists, and the record opened for appending once a new name
/// is written.
#[derive(Debug)]
pub struct Record {
    dir: PathBuf,
    names: HashSet<String>,
    file: Option<File>,
}

impl Record {
    /// The record of `dir`: empty when `dir` has none (a new directory, or one no tool wrote).
    pub fn read(dir: &Path) -> Record {
        let names = std::fs::read_to_string(dir.join(RECORD))
            .map(|text| {
                text.lines()
                    .filter(|l| !l.is_empty() && !l.starts_with('#'))
                    .map(str::to_string)
                    .collect()
            })
            .unwrap_or_default();
        Record {
            dir: dir.to_path_buf(),
            names,
            file: None,
        }
    }

    /// Does the record list `name` (a path relative to the directory, `/` between parts)?
    pub fn lists(&self, name: &str) -> bool {
        self.names.contains(name)
    }

    /// Is there something at `name` in the directory that the record does not list: a file a
    /// tool must not replace?
    pub fn foreign(&self, name: &str) -> bool {
        !self.lists(name) && std::fs::symlink_metadata(self.dir.join(name)).is_ok()
    }

    /// Adds `name` to the record (appended to the file the first time).
    pub fn note(&mut self, name: &str) -> std::io::Result<()> {
        if self.names.contains(name) {
            return Ok(());
        }
        if self.file.is_none() {
            let path = self.dir.join(RECORD);
            let new = std::fs::symlink_metadata(&path).is_err();
            let mut f = std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(&path)?;
            if new {
                f.write_all(HEADER.as_bytes())?;
            }
            self.file = Some(f);
        }
        if let Some(f) = self.file.as_mut() {
            f.write_all(format!("{name}\n").as_bytes())?;
        }
        self.names.insert(name.to_string());
        Ok(())
    }
}

/// Did a tool write the entry at `path`: a file its directory's record lists, or a directory
/// whose own record lists every file in it?
pub fn wrote(path: &Path) -> bool {
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    if meta.is_dir() {
        let record = Record::read(path);
        return std::fs::read_dir(path).is_ok_and(|entries| {
            entries.flatten().all(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                name == RECORD || record.lists(&name)
            })
        });
    }
    match (path.parent(), path.file_name()) {
        (Some(dir), Some(name)) => {
            let dir = if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                dir
            };
            Record::read(dir).lists(&name.to_string_lossy())
        }
        _ => false,
    }
}

/// The first file in `dir/sub` (`sub` empty: `dir` itself) under a name `ours` claims (given
/// as `sub/name`) that `dir`'s record does not list: a file a run into `dir` would replace
/// but no tool wrote. `None` when there is none, or no such directory.
pub fn first_foreign(dir: &Path, sub: &str, ours: &dyn Fn(&str) -> bool) -> Option<PathBuf> {
    let record = Record::read(dir);
    let at = if sub.is_empty() {
        dir.to_path_buf()
    } else {
        dir.join(sub)
    };
    let mut names: Vec<String> = std::fs::read_dir(&at)
        .ok()?
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| !t.is_dir()))
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .map(|n| {
            if sub.is_empty() {
                n
            } else {
                format!("{sub}/{n}")
            }
        })
        .filter(|n| ours(n) && !record.lists(n))
        .collect();
    names.sort();
    names.first().map(|n| dir.join(n))
}

/// Why a file in `dir` that no tool wrote is not replaced, and what to do.
pub fn not_ours(dir: &Path) -> String {
    format!(
        "it exists and no foldchain tool wrote it (it is not listed in {}); refusing to replace it: move it away or choose another output directory",
        dir.join(RECORD).display()
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn a_record_lists_what_was_noted_and_only_that() {
        let dir = crate::output::scratch("record");
        std::fs::write(dir.join("mine.txt"), "a user's").unwrap();
        std::fs::write(dir.join("ours.txt"), "the tool's").unwrap();
        let mut r = Record::read(&dir);
        assert!(r.foreign("mine.txt") && r.foreign("ours.txt"));
        assert!(!r.foreign("absent.txt"));
        r.note("ours.txt").unwrap();
        r.note("ours.txt").unwrap();
        drop(r);
        let r = Record::read(&dir);
        assert!(r.lists("ours.txt") && !r.foreign("ours.txt"));
        assert!(r.foreign("mine.txt"));
        assert!(wrote(&dir.join("ours.txt")) && !wrote(&dir.join("mine.txt")));
        let text = std::fs::read_to_string(dir.join(RECORD)).unwrap();
        assert_eq!(text.matches("ours.txt").count(), 1, "{text}");
        assert!(!wrote(&dir), "a directory holding a user's file");
        std::fs::remove_file(dir.join("mine.txt")).unwrap();
        assert!(wrote(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
