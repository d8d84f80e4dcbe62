//! Every command quoted with its output in `README.md` and the user guide (`docs/*.md`) is run
//! here and its output compared with the quote, so that none goes stale (issue 29).
//!
//! A quote is a fenced block marked `console`: a line `$ COMMAND` is run (the first word one
//! of the seven tools, the rest split as a shell would split words in quotes), and the lines
//! after it, up to the next `$ ` line, are what it prints: stderr, then stdout (the order a
//! terminal shows for these tools, which print notes before their result). A line `...`
//! stands for any number of lines (an output that is not stable, such as a wall time). The
//! commands of one page run in order in one scratch directory holding `shapes/` and `docs/`,
//! so a later command can read what an earlier one wrote. Blocks of any other kind (plain
//! ``` blocks) are not run: they are for commands whose output is not quoted.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{root, stderr, stdout};

const TOOLS: [(&str, &str); 7] = [
    ("fold-plan", env!("CARGO_BIN_EXE_fold-plan")),
    ("fold-run", env!("CARGO_BIN_EXE_fold-run")),
    ("fold-check", env!("CARGO_BIN_EXE_fold-check")),
    ("fold-enum", env!("CARGO_BIN_EXE_fold-enum")),
    ("fold-validate", env!("CARGO_BIN_EXE_fold-validate")),
    ("fold-tolerance", env!("CARGO_BIN_EXE_fold-tolerance")),
    ("fold-print", env!("CARGO_BIN_EXE_fold-print")),
];

/// One quoted command and what it prints.
#[derive(Debug)]
struct Quote {
    line: usize,
    command: String,
    output: Vec<String>,
}

/// The `console` blocks' commands of a Markdown text.
fn quotes(text: &str) -> Vec<Quote> {
    let mut out: Vec<Quote> = Vec::new();
    let mut in_console = false;
    let mut in_other = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim_start();
        if let Some(info) = t.strip_prefix("```") {
            if in_console || in_other {
                in_console = false;
                in_other = false;
            } else if info.trim() == "console" {
                in_console = true;
            } else {
                in_other = true;
            }
            continue;
        }
        if !in_console {
            continue;
        }
        if let Some(cmd) = line.strip_prefix("$ ") {
            out.push(Quote {
                line: i + 1,
                command: cmd.to_string(),
                output: Vec::new(),
            });
        } else if let Some(q) = out.last_mut() {
            q.output.push(line.trim_end().to_string());
        } else {
            panic!("line {}: a console block must start with `$ `", i + 1);
        }
    }
    out
}

/// Splits a command into words as a shell does for plain words, "double" and 'single'
/// quotes.
fn words(cmd: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut cur = String::new();
    let mut has = false;
    let mut quote: Option<char> = None;
    for c in cmd.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => cur.push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                has = true;
            }
            (None, c) if c.is_whitespace() => {
                if has || !cur.is_empty() {
                    words.push(std::mem::take(&mut cur));
                    has = false;
                }
            }
            (None, c) => cur.push(c),
        }
    }
    assert!(quote.is_none(), "unclosed quote in {cmd}");
    if has || !cur.is_empty() {
        words.push(cur);
    }
    words
}

/// Does `actual` match `expected`, where a line `...` in `expected` stands for any lines?
fn matches(expected: &[String], actual: &[String]) -> bool {
    match expected.split_first() {
        None => actual.is_empty(),
        Some((e, rest)) if e == "..." => (0..=actual.len()).any(|k| matches(rest, &actual[k..])),
        Some((e, rest)) => actual
            .split_first()
            .is_some_and(|(a, arest)| a == e && matches(rest, arest)),
    }
}

/// Runs a page's quotes in a scratch directory; the failures, one message each.
fn check_page(page: &Path) -> (usize, Vec<String>) {
    let text = std::fs::read_to_string(page).unwrap();
    let quotes = quotes(&text);
    let name = page.file_name().unwrap().to_string_lossy().into_owned();
    let dir = std::env::temp_dir().join(format!(
        "foldchain-readme-{}-{}",
        std::process::id(),
        name.replace('.', "-")
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    for sub in ["shapes", "docs"] {
        std::os::unix::fs::symlink(root().join(sub).canonicalize().unwrap(), dir.join(sub))
            .unwrap();
    }
    let mut failures = Vec::new();
    for q in &quotes {
        let w = words(&q.command);
        let Some((_, bin)) = TOOLS.iter().find(|(t, _)| *t == w[0]) else {
            failures.push(format!(
                "{name}:{}: `{}` is not one of the seven tools",
                q.line, q.command
            ));
            continue;
        };
        let o = Command::new(bin)
            .args(&w[1..])
            .current_dir(&dir)
            .env_remove("FOLDCHAIN_PROGRESS_SECONDS")
            .output()
            .unwrap();
        let actual: Vec<String> = stderr(&o)
            .lines()
            .chain(stdout(&o).lines())
            .map(|l| l.trim_end().to_string())
            .collect();
        if o.status.code().is_none_or(|c| c > 2) || !matches(&q.output, &actual) {
            failures.push(format!(
                "{name}:{}: `{}` (exit {:?}) printed\n{}\n  but the page quotes\n{}",
                q.line,
                q.command,
                o.status.code(),
                actual.join("\n"),
                q.output.join("\n")
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    (quotes.len(), failures)
}

/// README.md and every page of the guide.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

#[test]
fn every_quoted_command_prints_what_the_page_says() {
    let mut failures = Vec::new();
    let mut total = 0;
    for page in pages() {
        let (n, f) = check_page(&page);
        total += n;
        failures.extend(f);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // the README quotes a first run at least
    assert!(total >= 4, "{total} quoted commands");
}

#[test]
fn the_readme_is_short_and_its_links_lead_somewhere() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(readme.lines().count() < 200, "{}", readme.lines().count());
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let base = page.parent().unwrap();
        // [text](target) and ![alt](target) to files in the repository
        for (i, _) in text.match_indices("](") {
            let rest = &text[i + 2..];
            let Some(end) = rest.find(')') else { continue };
            let target = rest[..end].split('#').next().unwrap();
            if target.is_empty() || target.contains("://") || target.contains(' ') {
                continue;
            }
            assert!(
                base.join(target).exists(),
                "{}: link to {target}, which is not there",
                page.display()
            );
        }
    }
}

#[test]
fn the_library_pages_example_is_the_crates_doc_test() {
    // docs/library.md quotes the crate's documentation example; the doc test runs it
    let page = std::fs::read_to_string(root().join("docs/library.md")).unwrap();
    let lib = std::fs::read_to_string(root().join("src/lib.rs")).unwrap();
    let doc: String = lib
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .map(|l| l.strip_prefix(' ').unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n");
    let start = page.find("```rust\n").expect("a rust block") + "```rust\n".len();
    let end = start + page[start..].find("```").unwrap();
    let example = page[start..end].trim_end();
    assert!(
        doc.contains(example),
        "docs/library.md's example is not src/lib.rs's doc test"
    );
}

#[test]
fn quotes_are_read_as_documented() {
    let q = quotes("text\n```console\n$ fold-check SL\nvalid\n$ fold-enum --max-tiles 2\n...\n```\n```\n$ not run\n```\n");
    assert_eq!(q.len(), 2);
    assert_eq!(q[0].output, vec!["valid"]);
    assert_eq!(
        words(r#"fold-run "S*4 L L" --s 'e/3' x"#),
        vec!["fold-run", "S*4 L L", "--s", "e/3", "x"]
    );
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert!(matches(&s(&["a", "...", "c"]), &s(&["a", "b", "b", "c"])));
    assert!(!matches(&s(&["a", "c"]), &s(&["a", "b", "c"])));
}
