//! Error messages as the tools print them: the error and its causes, each said once.
//!
//! An error's message often already holds the text of its cause (`cannot read x.svg: No such
//! file`); printing the chain with `{:#}` would then say the cause twice. [`message`] leaves
//! out every cause whose text the message before it already holds.

/// The error and its causes joined by `: `, each cause once.
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
    out
}

/// Prints `tool: message` on stderr.
pub fn print_error(tool: &str, e: &anyhow::Error) {
    eprintln!("{tool}: {}", message(e));
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
    }
}
