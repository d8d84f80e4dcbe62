//! The name of a run: its output directory under `out/` and its pictures' titles, made from
//! the chain as given (a short plain text, its fold word or its length) or from a file's stem.

use std::path::Path;

use foldchain::Chain;

/// The name of a run given inline: the text itself when it is short and plain, else a name
/// made from its fold word or its length.
pub fn inline_name(arg: &str, chain: &Chain) -> String {
    let t = arg.trim();
    let plain = t
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || matches!(c, ' ' | '*' | '-' | '_'));
    if plain && t.len() <= 40 {
        return sanitize(t);
    }
    match chain.to_word() {
        Ok(w) if w.to_string().len() <= 40 => sanitize(&w.to_string()),
        _ => format!("chain-{}-tiles", chain.len()),
    }
}

/// `name` with anything but ASCII letters, digits, `-` and `_` replaced by `_`, at most 40
/// characters; `run` when empty.
pub fn sanitize(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .take(40)
        .collect();
    if s.is_empty() {
        "run".into()
    } else {
        s
    }
}

/// A file's name without its extension, as a run's name (`run` when it has none).
pub fn stem(p: &Path) -> String {
    p.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into())
}
