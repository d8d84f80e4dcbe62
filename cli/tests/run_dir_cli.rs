//! `fold-run --out DIR` replaces DIR's run as a whole (issue 29): a new run over an earlier
//! one keeps a user's files and leaves nothing beside DIR; a second writer is refused while
//! one holds DIR; Ctrl-C leaves one whole run; a full disk exits 3 and leaves DIR as it was.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::Command;

use foldchain_cli::run_dir::StagedDir;
use foldchain_cli::run_files::owns_run_entry;

fn fold_run() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fold-run"))
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("foldchain-rundir-cli-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn frames(dir: &Path) -> usize {
    names(dir).iter().filter(|n| n.starts_with("step-")).count()
}

#[test]
fn a_run_replaces_the_earlier_one_whole_and_keeps_a_users_files() {
    let base = scratch("replace");
    let dir = base.join("out");
    let run = |frames: &str| {
        let o = fold_run()
            .args(["SLLS", "--frames", frames, "--out", dir.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
    };
    run("9");
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::create_dir(dir.join("engine")).unwrap();
    std::fs::write(dir.join("engine/sketch.txt"), "mine too").unwrap();
    run("3");
    assert_eq!(frames(&dir), 3);
    assert_eq!(
        std::fs::read_to_string(dir.join("notes.txt")).unwrap(),
        "mine"
    );
    // a folder of the user's that shares a name with --compare's is not the tool's
    assert_eq!(
        std::fs::read_to_string(dir.join("engine/sketch.txt")).unwrap(),
        "mine too"
    );
    assert_eq!(names(&base), ["out"], "nothing left beside DIR");
    std::fs::remove_dir_all(&base).unwrap();
}

#[test]
fn a_second_writer_is_refused_at_once() {
    let base = scratch("lock");
    let dir = base.join("out");
    // this test holds DIR as a running fold-run would
    let held = StagedDir::open(&dir, owns_run_entry).unwrap();
    let o = fold_run()
        .args(["S*20", "--out", dir.to_str().unwrap()])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(e.contains("another run is writing into it"), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    drop(held);
    assert!(names(&dir).is_empty());
    std::fs::remove_dir_all(&base).unwrap();
}

#[test]
fn an_interrupt_leaves_one_whole_run() {
    let base = scratch("int");
    let dir = base.join("out");
    let o = fold_run()
        .args(["S*60", "--frames", "5", "--out", dir.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success());
    let earlier = names(&dir);
    let mut child = fold_run()
        .args(["S*60", "--frames", "400", "--out", dir.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let status = child.wait().unwrap();
    let now = names(&dir);
    if status.success() {
        // it finished before the signal
        assert_eq!(frames(&dir), 400);
    } else {
        assert_eq!(status.code(), Some(130));
        assert_eq!(now, earlier);
    }
    assert_eq!(
        names(&base),
        ["out"],
        "Ctrl-C removed the staging directory"
    );
    std::fs::remove_dir_all(&base).unwrap();
}

/// In a mount namespace of its own (root, `unshare`): a 1 MB tmpfs. Skipped where that is
/// not allowed.
#[test]
fn a_full_disk_exits_3_and_leaves_the_earlier_run() {
    let base = scratch("full");
    let mnt = base.join("mnt");
    std::fs::create_dir_all(&mnt).unwrap();
    let bin = env!("CARGO_BIN_EXE_fold-run");
    let script = format!(
        "mount -t tmpfs -o size=1m tmpfs {m} || exit 77
         {bin} SLLS --frames 4 --out {m}/run > /dev/null || exit 78
         echo mine > {m}/run/notes.txt
         {bin} 'S*400' --frames 300 --out {m}/run > /dev/null 2> {b}/err.txt
         echo $? > {b}/code.txt
         ls -a {m} > {b}/beside.txt
         ls {m}/run > {b}/left.txt",
        m = mnt.display(),
        b = base.display()
    );
    let status = Command::new("unshare")
        .args(["-m", "sh", "-c", &script])
        .status();
    match status.map(|s| s.code()) {
        Ok(Some(0)) => {}
        other => {
            eprintln!("note: no private tmpfs here ({other:?}); the full-disk test is skipped");
            return;
        }
    }
    let read = |f: &str| std::fs::read_to_string(base.join(f)).unwrap();
    assert_eq!(read("code.txt").trim(), "3", "{}", read("err.txt"));
    let err = read("err.txt");
    assert!(
        err.contains("No space left") && err.contains("free some space"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let left: Vec<String> = read("left.txt")
        .lines()
        .map(|s| s.trim().to_string())
        .collect();
    assert!(left.contains(&"notes.txt".to_string()), "{left:?}");
    assert_eq!(
        left.iter().filter(|n| n.starts_with("step-")).count(),
        4,
        "the earlier run, whole: {left:?}"
    );
    assert!(
        !read("beside.txt").contains("fold-staging"),
        "{}",
        read("beside.txt")
    );
    std::fs::remove_dir_all(&base).unwrap();
}
