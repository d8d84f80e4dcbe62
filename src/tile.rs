//! Tiles: an ordered pair of paths, and the physical part each one is.
//!
//! A tile's first path faces the reaction-initiator end of the chain, its second path the far
//! end. A tile turned round by 180 degrees swaps its paths and mirrors them, so the nine
//! ordered pairs are six physical parts.

use std::fmt;
use std::str::FromStr;

use crate::{ChainError, PathKind};

/// A tile: the path towards the reaction initiator, then the path away from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Tile {
    /// The path nearer the reaction-initiator end.
    pub first: PathKind,
    /// The path nearer the far end of the chain.
    pub second: PathKind,
}

/// A physical tile part: the tiles that are one part turned round.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Part {
    /// Two straight paths (SS).
    SS,
    /// One straight and one curved path: the SL and RS tiles.
    RS,
    /// One curved and one straight path: the LS and SR tiles.
    SR,
    /// Two paths curved the same way: the LL and RR tiles.
    RR,
    /// The LR tile (turned round it is itself), for diagonal runs.
    LR,
    /// The RL tile (turned round it is itself), for diagonal runs.
    RL,
}

impl Part {
    /// The part's name, as the thesis writes it.
    pub fn name(self) -> &'static str {
        match self {
            Part::SS => "SS",
            Part::RS => "RS",
            Part::SR => "SR",
            Part::RR => "RR",
            Part::LR => "LR",
            Part::RL => "RL",
        }
    }
}

impl fmt::Display for Part {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Tile {
    /// A tile from its two paths.
    pub const fn new(first: PathKind, second: PathKind) -> Tile {
        Tile { first, second }
    }

    /// All nine tiles: SS SL SR LS LL LR RS RL RR.
    pub const ALL: [Tile; 9] = [
        Tile::new(PathKind::S, PathKind::S),
        Tile::new(PathKind::S, PathKind::L),
        Tile::new(PathKind::S, PathKind::R),
        Tile::new(PathKind::L, PathKind::S),
        Tile::new(PathKind::L, PathKind::L),
        Tile::new(PathKind::L, PathKind::R),
        Tile::new(PathKind::R, PathKind::S),
        Tile::new(PathKind::R, PathKind::L),
        Tile::new(PathKind::R, PathKind::R),
    ];

    /// The straight tile SS.
    pub const STRAIGHT: Tile = Tile::new(PathKind::S, PathKind::S);

    /// The same part turned round by 180 degrees: paths swapped and mirrored.
    pub fn turned(self) -> Tile {
        Tile::new(self.second.mirrored(), self.first.mirrored())
    }

    /// The physical part this tile is.
    pub fn part(self) -> Part {
        use PathKind::*;
        match (self.first, self.second) {
            (S, S) => Part::SS,
            (S, L) | (R, S) => Part::RS,
            (L, S) | (S, R) => Part::SR,
            (L, L) | (R, R) => Part::RR,
            (L, R) => Part::LR,
            (R, L) => Part::RL,
        }
    }
}

impl FromStr for Tile {
    type Err = ChainError;

    /// A tile from its name, two of the letters S, L, R (`SL`); anything else is
    /// [`ChainError::NotATile`].
    fn from_str(s: &str) -> Result<Tile, ChainError> {
        let mut chars = s.chars();
        match (chars.next(), chars.next(), chars.next()) {
            (Some(a), Some(b), None) => match (PathKind::from_char(a), PathKind::from_char(b)) {
                (Some(first), Some(second)) => Ok(Tile::new(first, second)),
                _ => Err(ChainError::NotATile(s.to_string())),
            },
            _ => Err(ChainError::NotATile(s.to_string())),
        }
    }
}

impl fmt::Display for Tile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}{}", self.first, self.second)
    }
}

crate::text_serde::serde_as_text!(Tile);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nine_tiles_six_parts() {
        let parts: std::collections::BTreeSet<Part> = Tile::ALL.iter().map(|t| t.part()).collect();
        assert_eq!(parts.len(), 6);
        for t in Tile::ALL {
            assert_eq!(t.turned().part(), t.part(), "{t} turned is {}", t.turned());
            assert_eq!(t.turned().turned(), t);
            assert_eq!(t.to_string().parse::<Tile>().unwrap(), t);
        }
        assert_eq!("SL".parse::<Tile>().unwrap().turned().to_string(), "RS");
        assert_eq!("LS".parse::<Tile>().unwrap().turned().to_string(), "SR");
        assert!("S".parse::<Tile>().is_err());
        assert!("SSS".parse::<Tile>().is_err());
        assert!("SX".parse::<Tile>().is_err());
    }
}
