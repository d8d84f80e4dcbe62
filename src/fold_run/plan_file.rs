//! Reading a chain from `fold-plan`'s JSON: only its fold word is needed.

use std::path::{Path as FsPath, PathBuf};

use crate::{Chain, ChainError, FoldWord};

#[derive(serde::Deserialize)]
struct PlanJson {
    word: String,
}

/// Why a plan file could not be read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlanFileError {
    /// The file could not be read.
    #[error("cannot read plan file {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        #[source]
        source: std::io::Error,
    },
    /// Not a plan.
    #[error("{}: not a fold-plan JSON file: {reason} (expected an object with a \"word\" field, as `fold-plan --json` writes)", path.display())]
    Json {
        /// The file.
        path: PathBuf,
        /// What serde said.
        reason: String,
    },
    /// The word is not a fold word.
    #[error("{}: bad fold word in the plan: {source}", path.display())]
    Word {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        #[source]
        source: ChainError,
    },
}

/// Reads the chain designed by a plan file's fold word.
pub fn read_plan_file(path: &FsPath) -> Result<Chain, PlanFileError> {
    let text = std::fs::read_to_string(path).map_err(|source| PlanFileError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let plan: PlanJson = serde_json::from_str(&text).map_err(|e| PlanFileError::Json {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    let word = FoldWord::parse(&plan.word).map_err(|source| PlanFileError::Word {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(word.to_chain())
}
