//! Standard output and standard error that a closed pipe does not crash.
//!
//! `println!` panics when stdout is a pipe whose reader has gone (`fold-run SLLS --json |
//! head -5`). The tools print through [`outln!`](crate::outln) and [`errln!`](crate::errln)
//! instead: once the reader has gone, output stops quietly and the tool finishes its work
//! and exits with its own code, as ripgrep does. Another failure to write stdout (a full disk
//! under a redirection) is kept and reported once at the end ([`stdout_failure`]).

use std::io::{ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);
static STDOUT_FAILURE: Mutex<Option<std::io::Error>> = Mutex::new(None);

/// Writes `text` and a newline to stdout; see the module documentation.
pub fn line(text: &str) {
    write(&[text.as_bytes(), b"\n"]);
}

/// Writes `text` to stdout as it is (no newline added); see the module documentation.
pub fn text(text: &str) {
    write(&[text.as_bytes()]);
}

fn write(parts: &[&[u8]]) {
    if STDOUT_CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut out = std::io::stdout().lock();
    let result = parts
        .iter()
        .try_for_each(|p| out.write_all(p))
        .and_then(|()| out.flush());
    if let Err(e) = result {
        STDOUT_CLOSED.store(true, Ordering::Relaxed);
        if e.kind() != ErrorKind::BrokenPipe {
            if let Ok(mut failure) = STDOUT_FAILURE.lock() {
                failure.get_or_insert(e);
            }
        }
    }
}

/// Writes `text` and a newline to stderr, ignoring a failure (there is nowhere left to say
/// it).
pub fn err_line(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err
        .write_all(text.as_bytes())
        .and_then(|()| err.write_all(b"\n"));
}

/// The failure to write stdout other than a closed pipe, if any (taken: reported once).
pub fn stdout_failure() -> Option<std::io::Error> {
    STDOUT_FAILURE.lock().ok().and_then(|mut f| f.take())
}

/// `println!` that a closed pipe does not crash ([`line`](crate::stdout::line)).
#[macro_export]
macro_rules! outln {
    () => {
        $crate::stdout::line("")
    };
    ($($arg:tt)*) => {
        $crate::stdout::line(&format!($($arg)*))
    };
}

/// `eprintln!` that a closed stderr does not crash ([`err_line`](crate::stdout::err_line)).
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {
        $crate::stdout::err_line(&format!($($arg)*))
    };
}
