//! How the tools end: one place that parses the command line, prints an error (once, on one
//! line) and chooses the exit code.
//!
//! Exit codes, the same for every tool: 0 done (and the outcome is good), 1 the outcome the
//! tool judges is bad (a collision, no plan, a study below target), 2 bad input (the message
//! names the value and what was expected), [`EXIT_DISK_FULL`] an output could not be written
//! for want of space (nothing half-written is left under a real name).
//!
//! An error's message often already holds the text of its cause (`cannot read x.svg: No such
//! file`); printing the chain with `{:#}` would then say the cause twice. [`message`] leaves
//! out every cause whose text the message before it already holds.

use std::process::ExitCode;

use crate::errln;
use crate::stdout::stdout_failure;

/// The exit code of a run that could not write its output because the disk (or the user's
/// quota) is full.
pub const EXIT_DISK_FULL: u8 = 3;

/// The exit code of bad input.
pub const EXIT_BAD_INPUT: u8 = 2;

/// The error and its causes joined by `: `, each cause once, on one line.
pub fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if text.is_empty() || out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    one_line(&out)
}

/// Prints a plan's warnings on stderr, one line each (`TOOL: warning: ...`): the one place
/// that fold-plan and fold-print (which plans a drawing itself) say them.
pub fn print_plan_warnings(tool: &str, warnings: &[String]) {
    for w in warnings {
        errln!("{tool}: warning: {w}");
    }
}

/// `text` with its line breaks and runs of blanks made single spaces.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Is `e` (or one of its causes) a full disk or an exhausted quota?
pub fn is_disk_full(e: &anyhow::Error) -> bool {
    e.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(io_is_disk_full)
    })
}

/// Is this I/O error a full disk or an exhausted quota?
pub fn io_is_disk_full(e: &std::io::Error) -> bool {
    matches!(
        e.kind(),
        std::io::ErrorKind::StorageFull | std::io::ErrorKind::QuotaExceeded
    )
}

/// The exit code for an error: [`EXIT_DISK_FULL`] for a full disk, the planner's own code for
/// a shape that cannot be planned (1), [`EXIT_BAD_INPUT`] otherwise.
pub fn exit_code_of(e: &anyhow::Error) -> u8 {
    if is_disk_full(e) {
        return EXIT_DISK_FULL;
    }
    if let Some(p) = e.downcast_ref::<foldchain_planner::PlanError>() {
        return u8::try_from(p.exit_code()).unwrap_or(EXIT_BAD_INPUT);
    }
    EXIT_BAD_INPUT
}

/// Prints `tool: message` on stderr, on one line; a full disk gets what to do about it.
pub fn print_error(tool: &str, e: &anyhow::Error) {
    let mut text = message(e);
    if is_disk_full(e) && !text.contains("free some space") {
        text.push_str(" (the disk is full: free some space or write elsewhere)");
    }
    errln!("{tool}: {text}");
}

/// Parses the command line: on a mistake, clap's message on one line with a pointer to
/// `--help`, exit 2; `--help` and `--version` print and exit 0.
pub fn parse_args<A: clap::Parser>(tool: &str) -> Result<A, ExitCode> {
    parse_args_with(tool, |c| c)
}

/// [`parse_args`] with the command changed first by `edit` (a help text made at run time).
pub fn parse_args_with<A: clap::Parser>(
    tool: &str,
    edit: impl FnOnce(clap::Command) -> clap::Command,
) -> Result<A, ExitCode> {
    let parsed = edit(A::command())
        .try_get_matches()
        .and_then(|m| A::from_arg_matches(&m));
    parsed.map_err(|e| {
        if !e.use_stderr() {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        if let Some(said) = value_message(&e) {
            errln!("{tool}: {said} (see {tool} --help)");
            return ExitCode::from(EXIT_BAD_INPUT);
        }
        let text = e.to_string();
        // clap's message, its possible values and its tip, without usage and pointers
        let said: Vec<&str> = text
            .lines()
            .map(str::trim)
            .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
            .filter(|l| !l.is_empty())
            .map(|l| l.strip_prefix("error: ").unwrap_or(l))
            .collect();
        let said = if said.is_empty() {
            "bad command line".to_string()
        } else {
            one_line(
                &said
                    .join("; ")
                    .replace(":; ", ": ")
                    .replace("; tip: ", "; "),
            )
        };
        errln!("{tool}: {said} (see {tool} --help)");
        ExitCode::from(EXIT_BAD_INPUT)
    })
}

/// A bad value as `--flag VALUE: what was expected`, when clap's error is about one value.
fn value_message(e: &clap::Error) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    let text = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let arg = text(ContextKind::InvalidArg)?;
    // `--frames <N>` is named `--frames`; a positional `<CHAIN>` keeps its brackets
    let arg = match arg.split_once(' ') {
        Some((flag, _)) if flag.starts_with('-') => flag.to_string(),
        _ => arg,
    };
    let value = text(ContextKind::InvalidValue)?;
    match e.kind() {
        ErrorKind::ValueValidation => {
            let why = std::error::Error::source(e)?.to_string();
            Some(format!("{arg} {value}: {}", one_line(&why)))
        }
        ErrorKind::InvalidValue => {
            let valid = match e.get(ContextKind::ValidValue) {
                Some(ContextValue::Strings(v)) => v.join(", "),
                _ => return None,
            };
            let value = if value.is_empty() { "''".into() } else { value };
            Some(format!("{arg} {value}: expected one of {valid}"))
        }
        _ => None,
    }
}

/// Ends a tool: the outcome's exit code, or the error printed once with its exit code
/// ([`exit_code_of`]). A failure to write stdout other than a closed pipe is reported too.
pub fn finish(tool: &str, result: anyhow::Result<u8>) -> ExitCode {
    let mut code = match result {
        Ok(code) => code,
        Err(e) => {
            print_error(tool, &e);
            exit_code_of(&e)
        }
    };
    if let Some(e) = stdout_failure() {
        let full = io_is_disk_full(&e);
        let e = anyhow::Error::new(e).context("cannot write standard output");
        print_error(tool, &e);
        code = if full {
            EXIT_DISK_FULL
        } else {
            code.max(EXIT_BAD_INPUT)
        };
    }
    ExitCode::from(code)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[derive(Debug, thiserror::Error)]
    #[error("cannot read nope.svg: {source}")]
    struct Read {
        #[source]
        source: std::io::Error,
    }

    #[test]
    fn a_cause_already_said_is_not_said_again() {
        let io = std::io::Error::new(std::io::ErrorKind::NotFound, "No such file or directory");
        let e = anyhow::Error::new(Read { source: io });
        assert_eq!(
            message(&e),
            "cannot read nope.svg: No such file or directory"
        );
        let e = anyhow::anyhow!("inner").context("outer");
        assert_eq!(message(&e), "outer: inner");
        let e = anyhow::anyhow!("two\n  lines");
        assert_eq!(message(&e), "two lines");
    }

    #[test]
    fn a_full_disk_has_its_own_code() {
        let io = std::io::Error::from(std::io::ErrorKind::StorageFull);
        let e = anyhow::Error::new(io).context("cannot write out/x/step-0001.svg");
        assert!(is_disk_full(&e));
        assert_eq!(exit_code_of(&e), EXIT_DISK_FULL);
        assert_eq!(exit_code_of(&anyhow::anyhow!("bad")), EXIT_BAD_INPUT);
    }
}
