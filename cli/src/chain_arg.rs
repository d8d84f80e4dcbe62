//! Reading a chain named on a command line: inline text (a fold word, a tile list, JSON) or
//! the path of a file holding one (moved here from the library: what an argument names is
//! the command line's business; the library parses text, [`Chain::parse`]).

use std::path::{Path as FsPath, PathBuf};

use foldchain::{Chain, ChainError};

/// The largest chain file read, in bytes (256 MiB): a guard against reading a huge file whole.
pub const MAX_CHAIN_FILE_BYTES: u64 = 256 << 20;

/// Why a chain argument could not be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum InputError {
    /// The file could not be read.
    #[error("cannot read chain file {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
    /// The file is too large.
    #[error("chain file {} is {size} bytes: larger than the {max} bytes accepted", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        size: u64,
        /// The limit.
        max: u64,
    },
    /// The text is not a chain.
    #[error("{origin}: {source}")]
    Chain {
        /// Where the text came from (`chain argument` or the file's path).
        origin: String,
        /// What is wrong with it.
        #[source]
        source: ChainError,
    },
}

/// Reads a chain from a command-line argument: if it names an existing file, the file's
/// contents (lines starting with `#` are comments); otherwise the argument itself.
pub fn read_chain_arg(arg: &str) -> Result<Chain, InputError> {
    let path = FsPath::new(arg);
    if path.is_file() {
        let size = std::fs::metadata(path)
            .map_err(|source| InputError::Read {
                path: path.into(),
                source,
            })?
            .len();
        if size > MAX_CHAIN_FILE_BYTES {
            return Err(InputError::TooLarge {
                path: path.into(),
                size,
                max: MAX_CHAIN_FILE_BYTES,
            });
        }
        let bytes = std::fs::read(path).map_err(|source| InputError::Read {
            path: path.into(),
            source,
        })?;
        let text = String::from_utf8(bytes).map_err(|e| InputError::Read {
            path: path.into(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("not UTF-8 text ({e})"),
            ),
        })?;
        let body: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with('#'))
            .collect::<Vec<_>>()
            .join("\n");
        return Chain::parse(&body).map_err(|source| InputError::Chain {
            origin: path.display().to_string(),
            source,
        });
    }
    if path.is_dir() {
        return Err(InputError::Read {
            path: path.into(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "is a directory, not a chain file",
            ),
        });
    }
    Chain::parse(arg).map_err(|source| InputError::Chain {
        origin: format!("chain argument '{}'", abbreviate(arg)),
        source,
    })
}

fn abbreviate(s: &str) -> String {
    if s.chars().count() > 60 {
        format!("{}...", s.chars().take(57).collect::<String>())
    } else {
        s.to_string()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn inline_and_file() {
        assert_eq!(read_chain_arg("SLLS").unwrap().len(), 5);
        let e = read_chain_arg("SLXS").unwrap_err().to_string();
        assert!(
            e.contains("chain argument 'SLXS'") && e.contains("'X'"),
            "{e}"
        );
        let dir = crate::output::scratch("chain-arg");
        let f = dir.join("c.txt");
        std::fs::write(&f, "# a U-turn\nSS SL LL LS SS\n").unwrap();
        assert_eq!(read_chain_arg(f.to_str().unwrap()).unwrap().len(), 5);
        std::fs::write(&f, [0xff, 0xfe]).unwrap();
        let e = read_chain_arg(f.to_str().unwrap()).unwrap_err().to_string();
        assert!(e.contains("c.txt") && e.contains("UTF-8"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
