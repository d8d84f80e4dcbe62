//! Writing output files safely.
//!
//! Every file goes to a temporary name beside its target and is renamed into place, so an
//! interrupted run never leaves a half-written file under a real name. An output directory
//! ([`OutputDir`]) is never removed, renamed or emptied: a run replaces only the files a tool
//! wrote there before (listed in the directory's [`crate::record`]), refuses a file it did not
//! write that stands under a name it writes, and removes nothing but files of its record
//! under its own names (stale step frames of an earlier, longer run) and its own temporary
//! files, so whatever else a user keeps there stays as it was.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::record::{not_ours, Record};

/// A file or directory that could not be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}", path.display())]
pub struct WriteError {
    /// The file or directory.
    pub path: PathBuf,
    /// What went wrong.
    #[source]
    pub source: std::io::Error,
}

impl WriteError {
    fn new(path: &Path, source: std::io::Error) -> WriteError {
        WriteError {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// The temporary name [`write_atomic`] writes `name` under, in the same directory.
fn temp_name(name: &str) -> String {
    format!(".{name}.tmp{}", std::process::id())
}

/// Is `file` one of [`write_atomic`]'s temporary names for a name `is_ours` accepts, from any
/// process?
pub fn is_temp_of(file: &str, is_ours: &dyn Fn(&str) -> bool) -> bool {
    let Some(rest) = file.strip_prefix('.') else {
        return false;
    };
    let Some((name, pid)) = rest.rsplit_once(".tmp") else {
        return false;
    };
    !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()) && is_ours(name)
}

/// Writes `bytes` to `path` through a temporary file in the same directory and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(temp_name(&name));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        // no fsync: the rename is what keeps a killed run from leaving a torn file under the
        // real name; syncing every frame made 100,000 frames take minutes
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(|e| WriteError::new(path, e))
}

/// Creates a directory and its parents, as an error naming it when that fails.
pub fn create_dir_all(dir: &Path) -> Result<(), WriteError> {
    std::fs::create_dir_all(dir).map_err(|e| WriteError::new(dir, e))
}

/// An output directory shared with whatever else is in it: files are added or replaced one
/// at a time, atomically, and only where no file stands or one a tool wrote (its record).
#[derive(Debug)]
pub struct OutputDir {
    dir: PathBuf,
    written: Vec<String>,
    record: Record,
}

impl OutputDir {
    /// Opens `dir` for writing, creating it (and its parents) if needed. An existing
    /// directory is used as it is; a file of that name is an error.
    pub fn create(dir: &Path) -> Result<OutputDir, WriteError> {
        if dir.exists() && !dir.is_dir() {
            return Err(WriteError::new(
                dir,
                std::io::Error::new(
                    std::io::ErrorKind::AlreadyExists,
                    "exists and is not a directory",
                ),
            ));
        }
        create_dir_all(dir)?;
        Ok(OutputDir {
            dir: dir.to_path_buf(),
            written: Vec::new(),
            record: Record::read(dir),
        })
    }

    /// Refuses, before anything is written, to replace a file under any of `names` (paths
    /// relative to the directory) that no tool wrote.
    pub fn claim<'a>(&self, names: impl IntoIterator<Item = &'a str>) -> Result<(), WriteError> {
        for name in names {
            if self.record.foreign(name) && !self.written.iter().any(|w| w == name) {
                return Err(WriteError::new(
                    &self.dir.join(name),
                    std::io::Error::new(std::io::ErrorKind::AlreadyExists, not_ours(&self.dir)),
                ));
            }
        }
        Ok(())
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// The files written so far, in order, relative to the directory.
    pub fn written(&self) -> &[String] {
        &self.written
    }

    /// Records the file `name` and writes it in the directory, atomically; a file there that
    /// no tool wrote is refused ([`OutputDir::claim`]).
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<(), WriteError> {
        self.claim([name])?;
        // the name goes into the record before the file is renamed into place: a run killed
        // between the two then leaves a listed name with no file (harmless) rather than a file
        // no record lists, which the next run would take for a user's and keep
        self.record
            .note(name)
            .map_err(|e| WriteError::new(&self.dir.join(crate::record::RECORD), e))?;
        let path = self.dir.join(name);
        write_atomic(&path, bytes)?;
        self.written.push(name.to_string());
        Ok(())
    }

    /// Writes `value` as pretty JSON and a newline into `name`, as [`OutputDir::write`].
    pub fn write_json(
        &mut self,
        name: &str,
        value: &impl serde::Serialize,
    ) -> Result<(), WriteError> {
        let mut text = serde_json::to_string_pretty(value)
            .map_err(|e| WriteError::new(&self.dir.join(name), e.into()))?;
        text.push('\n');
        self.write(name, text.as_bytes())
    }

    /// Removes the files that `stale` claims (names the tool owns, such as step frames) and
    /// the record lists but this run did not write, and the temporary files of names `ours`
    /// claims, left by an interrupted run. Nothing else is touched. Returns the names
    /// removed, sorted.
    pub fn remove_stale(
        &self,
        stale: &dyn Fn(&str) -> bool,
        ours: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<String>, WriteError> {
        self.remove_stale_in("", stale, ours)
    }

    /// [`OutputDir::remove_stale`] in the subdirectory `sub` (`stale` and `ours` see names
    /// within it; the record lists them as `sub/name`).
    pub fn remove_stale_in(
        &self,
        sub: &str,
        stale: &dyn Fn(&str) -> bool,
        ours: &dyn Fn(&str) -> bool,
    ) -> Result<Vec<String>, WriteError> {
        let dir = if sub.is_empty() {
            self.dir.clone()
        } else {
            self.dir.join(sub)
        };
        let entries = std::fs::read_dir(&dir).map_err(|e| WriteError::new(&dir, e))?;
        let mut removed = Vec::new();
        for entry in entries {
            let entry = entry.map_err(|e| WriteError::new(&dir, e))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            let full = if sub.is_empty() {
                name.clone()
            } else {
                format!("{sub}/{name}")
            };
            let ended = stale(&name) && self.record.lists(&full) && !self.written.contains(&full);
            let remove = ended || is_temp_of(&name, ours);
            if remove && entry.file_type().is_ok_and(|t| t.is_file()) {
                let path = entry.path();
                std::fs::remove_file(&path).map_err(|e| WriteError::new(&path, e))?;
                removed.push(name);
            }
        }
        removed.sort();
        Ok(removed)
    }
}

/// For the crate's unit tests: a new empty directory `foldchain-unit-{tag}-{process id}` in
/// the temporary directory (what an earlier run left there is removed first).
#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
pub(crate) fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("foldchain-unit-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn writes_and_replaces() {
        let dir = scratch("atomic");
        let p = dir.join("a.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "two");
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(leftovers.len(), 1);
        let bad = dir.join("no/such/dir/x.txt");
        let e = write_atomic(&bad, b"x").unwrap_err();
        assert!(e.to_string().contains("no/such/dir/x.txt"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_output_dir_keeps_what_it_did_not_write() {
        let dir = scratch("keep");
        std::fs::write(dir.join("keep.txt"), "mine").unwrap();
        std::fs::write(dir.join("step-0007.svg"), "old frame").unwrap();
        std::fs::write(dir.join("step-0008.svg"), "a user's, under our name").unwrap();
        std::fs::write(dir.join("step-7.svg"), "not our name").unwrap();
        std::fs::write(dir.join(".step-0001.svg.tmp42"), "torn").unwrap();
        std::fs::write(dir.join(".keep.txt.tmp42"), "a user's").unwrap();
        // an earlier run wrote step-0007.svg (its record says so), not step-0008.svg
        std::fs::write(dir.join(crate::record::RECORD), "# record\nstep-0007.svg\n").unwrap();
        let mut out = OutputDir::create(&dir).unwrap();
        out.write("step-0000.svg", b"new").unwrap();
        let e = out.write("step-0008.svg", b"new").unwrap_err();
        assert!(format!("{e:#}").contains("step-0008.svg"), "{e:#}");
        let ours = |n: &str| n.starts_with("step-") && n.len() == 13 && n.ends_with(".svg");
        let removed = out.remove_stale(&ours, &ours).unwrap();
        assert_eq!(removed, vec![".step-0001.svg.tmp42", "step-0007.svg"]);
        for (f, body) in [
            ("keep.txt", "mine"),
            ("step-0008.svg", "a user's, under our name"),
            ("step-7.svg", "not our name"),
            (".keep.txt.tmp42", "a user's"),
        ] {
            assert_eq!(std::fs::read_to_string(dir.join(f)).unwrap(), body, "{f}");
        }
        assert_eq!(out.written(), ["step-0000.svg"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A run killed between a file's rename and its line in the record left a file no
    /// record listed; the next run into the directory took it for a user's and kept it (a
    /// frame of the interrupted run mixed into the earlier one, CI of 1422951). The name is
    /// now recorded first: a write that fails once its name is recorded leaves the name
    /// listed and no file, which nothing takes for a user's.
    #[test]
    fn a_name_is_recorded_before_its_file_is_put_in_place() {
        let dir = scratch("order");
        let mut out = OutputDir::create(&dir).unwrap();
        out.write("a.txt", b"one").unwrap();
        // the temporary file cannot be made: no such subdirectory
        assert!(out.write("sub/b.txt", b"two").is_err());
        let record = crate::record::Record::read(&dir);
        assert!(record.lists("a.txt") && record.lists("sub/b.txt"));
        assert!(!record.foreign("sub/b.txt"));
        assert_eq!(out.written(), ["a.txt"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_in_the_way_is_an_error_and_is_left_alone() {
        let dir = scratch("file");
        let f = dir.join("out");
        std::fs::write(&f, "a file").unwrap();
        let e = OutputDir::create(&f).unwrap_err();
        assert!(e.source.to_string().contains("not a directory"), "{e}");
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "a file");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
