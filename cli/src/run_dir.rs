//! An output directory replaced as a whole: a run writes into a staging directory beside
//! `DIR` and swaps it into place at the end, so that after any interruption (Ctrl-C, `kill
//! -9`, a full disk, an error) `DIR` holds either the whole earlier run or the whole new one,
//! never a mixture. A lock on `DIR` refuses a second writer while one is at work.
//!
//! How, as rsync's `--delay-updates` or a compiler's output directory, but in one step:
//! 1. `DIR` is created if needed and locked (`flock` on the directory, not blocking: a second
//!    writer is refused at once with [`RunDirError::Locked`]).
//! 2. The run writes into `.NAME.fold-staging.PID` beside `DIR` (same file system), locked
//!    too.
//! 3. [`StagedDir::commit`] carries over whatever in `DIR` the tool does not own (a user's
//!    notes: regular files as hard links, the same file under two names; anything else
//!    moved), then exchanges the two directories in one `renameat2(RENAME_EXCHANGE)`, moves
//!    back anything a user added in between, and removes the old run.
//! 4. A staging directory left by a killed run is found by the next run into `DIR` (its lock
//!    is free), whatever in it is not the tool's is put back into `DIR`, and it is removed.
//!    Ctrl-C removes the staging directory at once ([`install_interrupt_cleanup`]).
//!
//! A user's files in `DIR` are never rewritten, and never lost: at every moment each is in
//! `DIR` or, for the instant between being moved and the exchange, in the staging directory
//! the next run puts it back from.

use std::ffi::OsString;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Why a run's output directory could not be prepared or put in place.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RunDirError {
    /// Another process is writing into the directory.
    #[error("{}: another run is writing into it (its lock is held); wait for it to finish or choose another --out", dir.display())]
    Locked {
        /// The directory.
        dir: PathBuf,
    },
    /// The path cannot be replaced as a whole.
    #[error("{}: {reason}", dir.display())]
    Unusable {
        /// The directory.
        dir: PathBuf,
        /// Why, and what to do.
        reason: String,
    },
    /// A file system operation failed.
    #[error("{}: cannot {action}: {source}; {} is left as it was", path.display(), dir.display())]
    Io {
        /// The output directory.
        dir: PathBuf,
        /// The file or directory the operation was on.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
}

/// A run's staging directory beside its output directory; see the module documentation.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    staging: PathBuf,
    owns: fn(&Path) -> bool,
    _target_lock: File,
    _staging_lock: File,
    committed: bool,
}

/// The staging directory of a run in progress, removed by Ctrl-C
/// ([`install_interrupt_cleanup`]); `None` when there is none or it is being committed.
static STAGING: Mutex<Option<PathBuf>> = Mutex::new(None);

/// Removes the staging directory of the run in progress when the process gets SIGINT (or
/// SIGTERM), then exits with 130. Commit holds the same lock, so an interrupt during the
/// exchange waits for it: `DIR` then holds the new run.
pub fn install_interrupt_cleanup() {
    let _ = ctrlc::set_handler(|| {
        if let Ok(mut staging) = STAGING.lock() {
            if let Some(dir) = staging.take() {
                // renamed first, so that the writer's next file fails instead of landing
                // in a directory being removed; a file it had open when the rename came
                // may still appear, hence the retries
                let mut trash = dir.clone().into_os_string();
                trash.push(".interrupted");
                let trash = PathBuf::from(trash);
                let gone = if std::fs::rename(&dir, &trash).is_ok() {
                    trash
                } else {
                    dir
                };
                for _ in 0..20 {
                    if std::fs::remove_dir_all(&gone).is_ok() || !gone.exists() {
                        break;
                    }
                    std::thread::sleep(std::time::Duration::from_millis(10));
                }
            }
        }
        std::process::exit(130);
    });
}

/// The suffix of staging directories: `.NAME.fold-staging.PID`.
const STAGING_TAG: &str = ".fold-staging.";

impl StagedDir {
    /// Prepares to replace `dir` as a whole: creates it if needed, locks it, clears what a
    /// killed run left beside it and makes a fresh staging directory. `owns` says which
    /// entries of `dir` are the tool's (replaced); every other entry is carried over.
    pub fn open(dir: &Path, owns: fn(&Path) -> bool) -> Result<StagedDir, RunDirError> {
        let target = resolve(dir)?;
        let parent = target
            .parent()
            .map(Path::to_path_buf)
            .ok_or_else(|| unusable(dir, "has no parent directory to stage the run in"))?;
        let name = target
            .file_name()
            .map(|n| n.to_os_string())
            .ok_or_else(|| unusable(dir, "names no directory"))?;
        if let Ok(cwd) = std::env::current_dir().and_then(|c| c.canonicalize()) {
            if cwd.starts_with(&target) {
                return Err(unusable(
                    dir,
                    "holds the current directory; the run replaces DIR as a whole, so give it a directory of its own (e.g. out/NAME)",
                ));
            }
        }
        let io = |path: &Path, action: &'static str| {
            let (dir, path) = (dir.to_path_buf(), path.to_path_buf());
            move |source| RunDirError::Io {
                dir,
                path,
                action,
                source,
            }
        };
        std::fs::create_dir_all(&parent).map_err(io(&parent, "create the directory"))?;
        match std::fs::create_dir(&target) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(io(&target, "create the directory")(e)),
        }
        let target_lock = lock_current(&target, dir)?;
        clear_stale(&parent, &name, &target, owns);
        let staging = parent.join(staging_name(&name, std::process::id()));
        if staging.exists() {
            // our own pid's, left by an earlier process that had it: stale (its lock was free)
            let _ = std::fs::remove_dir_all(&staging);
        }
        std::fs::create_dir(&staging).map_err(io(&staging, "create the staging directory"))?;
        let staging_lock = match try_lock(&staging) {
            Ok(Some(f)) => f,
            Ok(None) => return Err(RunDirError::Locked { dir: dir.into() }),
            Err(e) => return Err(io(&staging, "lock the staging directory")(e)),
        };
        if let Ok(mut s) = STAGING.lock() {
            *s = Some(staging.clone());
        }
        Ok(StagedDir {
            target,
            staging,
            owns,
            _target_lock: target_lock,
            _staging_lock: staging_lock,
            committed: false,
        })
    }

    /// Where the run writes: the staging directory.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The output directory the run goes to (with links resolved).
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Puts the staging directory in place of the output directory, in one exchange; see
    /// the module documentation.
    pub fn commit(mut self) -> Result<(), RunDirError> {
        // Ctrl-C waits while the directories change places
        let mut registered = STAGING.lock().ok();
        let io = |path: &Path, action: &'static str| {
            let (dir, path) = (self.target.clone(), path.to_path_buf());
            move |source| RunDirError::Io {
                dir,
                path,
                action,
                source,
            }
        };
        if let Ok(meta) = std::fs::metadata(&self.target) {
            let _ = std::fs::set_permissions(&self.staging, meta.permissions());
        }
        let entries =
            std::fs::read_dir(&self.target).map_err(io(&self.target, "read the directory"))?;
        for entry in entries {
            let entry = entry.map_err(io(&self.target, "read the directory"))?;
            let from = entry.path();
            if (self.owns)(&from) {
                continue;
            }
            let to = self.staging.join(entry.file_name());
            if to.exists() {
                return Err(unusable(
                    &self.target,
                    &format!(
                        "holds {} that the run also writes; move it away first",
                        entry.file_name().to_string_lossy()
                    ),
                ));
            }
            carry(&from, &to).map_err(io(&from, "keep the file in the new run"))?;
        }
        exchange(&self.staging, &self.target)
            .map_err(io(&self.target, "put the new run in place"))?;
        self.committed = true;
        // the staging name now holds the earlier run: keep whatever a user added meanwhile
        let old = self.staging.clone();
        if let Ok(entries) = std::fs::read_dir(&old) {
            for entry in entries.flatten() {
                let to = self.target.join(entry.file_name());
                if !(self.owns)(&entry.path()) && !to.exists() {
                    let _ = std::fs::rename(entry.path(), to);
                }
            }
        }
        let _ = std::fs::remove_dir_all(&old);
        if let Some(s) = registered.as_mut() {
            **s = None;
        }
        Ok(())
    }
}

impl Drop for StagedDir {
    /// An uncommitted run (an error, a full disk) leaves `DIR` as it was and removes its
    /// staging directory.
    fn drop(&mut self) {
        if !self.committed {
            if let Ok(mut s) = STAGING.lock() {
                *s = None;
            }
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

fn unusable(dir: &Path, reason: &str) -> RunDirError {
    RunDirError::Unusable {
        dir: dir.to_path_buf(),
        reason: reason.to_string(),
    }
}

fn staging_name(name: &OsString, pid: u32) -> OsString {
    let mut s = OsString::from(".");
    s.push(name);
    s.push(format!("{STAGING_TAG}{pid}"));
    s
}

/// `dir` with its parent's links resolved; a link to a directory is followed, so the
/// directory it points to is the one replaced.
fn resolve(dir: &Path) -> Result<PathBuf, RunDirError> {
    if let Ok(meta) = std::fs::metadata(dir) {
        if !meta.is_dir() {
            return Err(unusable(dir, "exists and is not a directory"));
        }
        return dir.canonicalize().map_err(|source| RunDirError::Io {
            dir: dir.into(),
            path: dir.into(),
            action: "resolve the path",
            source,
        });
    }
    let name = dir
        .file_name()
        .filter(|n| *n != "..")
        .ok_or_else(|| unusable(dir, "names no directory"))?;
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent).map_err(|source| RunDirError::Io {
        dir: dir.into(),
        path: parent.clone(),
        action: "create the directory",
        source,
    })?;
    let parent = parent.canonicalize().map_err(|source| RunDirError::Io {
        dir: dir.into(),
        path: parent.clone(),
        action: "resolve the path",
        source,
    })?;
    Ok(parent.join(name))
}

/// Locks the directory now at `target`: retried when the path was swapped for another
/// directory between opening and locking (a run committing at that moment).
fn lock_current(target: &Path, shown: &Path) -> Result<File, RunDirError> {
    for _ in 0..20 {
        let lock = try_lock(target).map_err(|source| RunDirError::Io {
            dir: shown.into(),
            path: target.into(),
            action: "lock the directory",
            source,
        })?;
        let Some(file) = lock else {
            return Err(RunDirError::Locked { dir: shown.into() });
        };
        if same_directory(&file, target) {
            return Ok(file);
        }
    }
    Err(RunDirError::Locked { dir: shown.into() })
}

/// Removes the staging directories a killed run left beside `target` (their lock is free),
/// after putting back into `target` whatever in them is not the tool's.
fn clear_stale(parent: &Path, name: &OsString, target: &Path, owns: fn(&Path) -> bool) {
    let mut prefix = OsString::from(".");
    prefix.push(name);
    prefix.push(STAGING_TAG);
    let prefix = prefix.to_string_lossy().into_owned();
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name().to_string_lossy().into_owned();
        // `.NAME.fold-staging.PID`, or with `.interrupted` when Ctrl-C could not finish
        let pid = file_name
            .strip_prefix(&prefix)
            .map(|p| p.strip_suffix(".interrupted").unwrap_or(p));
        if !pid.is_some_and(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit())) {
            continue;
        }
        let stale = entry.path();
        // a live run holds its lock (only one can hold the target's, and we do: this is a
        // run's leftover after its commit, or a killed run's)
        let Ok(Some(_lock)) = try_lock(&stale) else {
            continue;
        };
        if let Ok(inner) = std::fs::read_dir(&stale) {
            for e in inner.flatten() {
                let to = target.join(e.file_name());
                if !owns(&e.path()) && !to.exists() {
                    let _ = std::fs::rename(e.path(), to);
                }
            }
        }
        let _ = std::fs::remove_dir_all(&stale);
    }
}

/// Puts `from` (in the old directory) under `to` (in the new one): a regular file as a hard
/// link (the same file, now in both), anything else moved.
fn carry(from: &Path, to: &Path) -> std::io::Result<()> {
    let meta = std::fs::symlink_metadata(from)?;
    if meta.file_type().is_file() && std::fs::hard_link(from, to).is_ok() {
        return Ok(());
    }
    std::fs::rename(from, to)
}

#[cfg(unix)]
fn try_lock(path: &Path) -> std::io::Result<Option<File>> {
    use rustix::fs::{flock, FlockOperation};
    let file = File::open(path)?;
    match flock(&file, FlockOperation::NonBlockingLockExclusive) {
        Ok(()) => Ok(Some(file)),
        Err(e) if e == rustix::io::Errno::WOULDBLOCK => Ok(None),
        Err(e) => Err(e.into()),
    }
}

#[cfg(not(unix))]
fn try_lock(path: &Path) -> std::io::Result<Option<File>> {
    // no advisory lock here: a second writer is not refused
    File::open(path).map(Some)
}

#[cfg(unix)]
fn same_directory(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_directory(_file: &File, _path: &Path) -> bool {
    true
}

/// Exchanges the directories `a` and `b` in one step where the system can
/// (`renameat2(RENAME_EXCHANGE)` on Linux), else in two renames (`b` is then missing for an
/// instant).
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    #[cfg(any(target_os = "linux", target_os = "android"))]
    {
        use rustix::fs::{renameat_with, RenameFlags, CWD};
        match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
            Ok(()) => return Ok(()),
            Err(e) if e == rustix::io::Errno::INVAL || e == rustix::io::Errno::NOSYS => {}
            Err(e) => return Err(e.into()),
        }
    }
    let aside = a.with_extension("old");
    std::fs::rename(b, &aside)?;
    std::fs::rename(a, b)?;
    std::fs::rename(&aside, a)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::output::scratch;

    fn ours(p: &Path) -> bool {
        p.file_name()
            .is_some_and(|n| n.to_string_lossy().starts_with("run-"))
    }

    /// A scratch directory for test `tag` and an empty `out` directory in it.
    fn base_and_out(tag: &str) -> (PathBuf, PathBuf) {
        let base = scratch(tag);
        let dir = base.join("out");
        std::fs::create_dir_all(&dir).unwrap();
        (base, dir)
    }

    /// The text of file `path`.
    fn text(path: &Path) -> String {
        std::fs::read_to_string(path).unwrap()
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_run_replaces_the_earlier_one_and_keeps_the_users_files() {
        let (base, dir) = base_and_out("replace");
        std::fs::create_dir_all(dir.join("notes")).unwrap();
        std::fs::write(dir.join("run-a.txt"), "old").unwrap();
        std::fs::write(dir.join("run-old-only.txt"), "old").unwrap();
        std::fs::write(dir.join("mine.txt"), "user").unwrap();
        std::fs::write(dir.join("notes/n.txt"), "user").unwrap();
        let staged = StagedDir::open(&dir, ours).unwrap();
        // nothing in DIR changes while the run writes
        std::fs::write(staged.path().join("run-a.txt"), "new").unwrap();
        std::fs::write(staged.path().join("run-b.txt"), "new").unwrap();
        assert_eq!(text(&dir.join("run-a.txt")), "old");
        // a second writer is refused while the first holds the lock
        let second = StagedDir::open(&dir, ours).unwrap_err();
        assert!(matches!(second, RunDirError::Locked { .. }), "{second}");
        staged.commit().unwrap();
        assert_eq!(names(&dir), ["mine.txt", "notes", "run-a.txt", "run-b.txt"]);
        assert_eq!(text(&dir.join("run-a.txt")), "new");
        assert_eq!(text(&dir.join("mine.txt")), "user");
        assert_eq!(text(&dir.join("notes/n.txt")), "user");
        // nothing is left beside DIR, and the lock is free again
        assert_eq!(names(&base), ["out"]);
        drop(StagedDir::open(&dir, ours).unwrap());
        assert_eq!(names(&base), ["out"]);
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn an_abandoned_run_leaves_the_directory_as_it_was() {
        let (base, dir) = base_and_out("abandon");
        std::fs::write(dir.join("run-a.txt"), "old").unwrap();
        let staged = StagedDir::open(&dir, ours).unwrap();
        std::fs::write(staged.path().join("run-a.txt"), "half").unwrap();
        drop(staged);
        assert_eq!(names(&dir), ["run-a.txt"]);
        assert_eq!(text(&dir.join("run-a.txt")), "old");
        assert_eq!(names(&base), ["out"]);
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn a_killed_runs_staging_is_cleared_and_a_moved_user_file_put_back() {
        let (base, dir) = base_and_out("killed");
        // what a run killed between moving a user's folder and the exchange leaves
        let stale = base.join(".out.fold-staging.999999");
        std::fs::create_dir_all(stale.join("notes")).unwrap();
        std::fs::write(stale.join("run-a.txt"), "half").unwrap();
        std::fs::write(stale.join("notes/n.txt"), "user").unwrap();
        let staged = StagedDir::open(&dir, ours).unwrap();
        assert_eq!(names(&dir), ["notes"]);
        assert!(!stale.exists());
        staged.commit().unwrap();
        assert_eq!(names(&dir), ["notes"]);
        std::fs::remove_dir_all(&base).unwrap();
    }

    #[test]
    fn a_file_or_the_current_directory_is_refused() {
        let base = scratch("refuse");
        let f = base.join("afile");
        std::fs::write(&f, "x").unwrap();
        let e = StagedDir::open(&f, ours).unwrap_err();
        assert!(e.to_string().contains("not a directory"), "{e}");
        assert_eq!(text(&f), "x");
        std::fs::remove_dir_all(&base).unwrap();
    }
}
