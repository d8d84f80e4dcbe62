//! Errors of the chain formats and conversions, a tile's name included.

/// Why a chain could not be read or converted.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ChainError {
    /// The input held no tiles or letters.
    #[error(
        "empty chain: expected at least one tile (e.g. `SS SL LS`) or fold letter (e.g. `SLLS`)"
    )]
    Empty,
    /// A character that is not a fold letter.
    #[error(
        "unexpected character '{ch}' at position {position} of a fold word: expected S, L or R"
    )]
    BadLetter {
        /// The character found.
        ch: char,
        /// Its position (0-based, in characters).
        position: usize,
    },
    /// A token of a tile list that is not a tile.
    #[error("bad tile '{token}' (item {index} of the tile list): expected two of the letters S, L, R, optionally followed by *N (e.g. SS*12)")]
    BadTile {
        /// The token found.
        token: String,
        /// Its index in the list (0-based).
        index: usize,
    },
    /// A run-length count that is not a positive whole number.
    #[error("bad repeat count '{count}' in '{token}': expected a whole number from 1 up")]
    BadCount {
        /// The token holding the count.
        token: String,
        /// The count as written.
        count: String,
    },
    /// The chain would hold more tiles than the tool accepts.
    #[error("chain too long: more than {max} tiles")]
    TooLong {
        /// The largest number of tiles accepted.
        max: usize,
    },
    /// A joint whose paths curve opposite ways: propagation stops there, so the chain has no
    /// fold word past it.
    #[error("joint {joint} (between tile {joint} `{left}` and tile {} `{right}`) pairs opposite curves: propagation is inhibited there", joint + 1)]
    Inhibited {
        /// The joint index (0 = the joint nearest the reaction initiator).
        joint: usize,
        /// The tile before the joint.
        left: String,
        /// The tile after the joint.
        right: String,
    },
    /// Consecutive opposite folds (L then R) where the chain's rules do not allow them.
    #[error("joints {joint} and {} fold opposite ways ({first}{second}): adjacent opposite folds need an LR/RL tile, which this design does not allow", joint + 1)]
    OppositeFolds {
        /// The first of the two joints.
        joint: usize,
        /// Its fold.
        first: char,
        /// The next joint's fold.
        second: char,
    },
    /// JSON that is not a chain.
    #[error("bad chain JSON: {0}")]
    Json(String),
    /// A tile name that is not two of the letters S, L, R (`"SX".parse::<Tile>()`).
    #[error("'{0}' is not a tile: expected two of the letters S, L, R (e.g. SL)")]
    NotATile(String),
}
