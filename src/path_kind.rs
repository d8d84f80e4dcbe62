//! Magnet paths: the walled channel a magnet slides in, one of three kinds.
//!
//! A path is straight (`S`) or curved towards the left (`L`) or right (`R`), the letter naming
//! the fold direction it contributes to, seen travelling down the chain away from the reaction
//! initiator (SPEC section 2).

use std::fmt;

/// The kind of path a magnet slides in.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum PathKind {
    /// Straight path: contributes no fold.
    S,
    /// Curved path contributing to a fold to the left.
    L,
    /// Curved path contributing to a fold to the right.
    R,
}

impl PathKind {
    /// All three paths, in the order S, L, R.
    pub const ALL: [PathKind; 3] = [PathKind::S, PathKind::L, PathKind::R];

    /// The path for a letter (`S`, `L` or `R`, either case), or `None`.
    pub fn from_char(c: char) -> Option<PathKind> {
        match c.to_ascii_uppercase() {
            'S' => Some(PathKind::S),
            'L' => Some(PathKind::L),
            'R' => Some(PathKind::R),
            _ => None,
        }
    }

    /// The path's letter.
    pub fn to_char(self) -> char {
        match self {
            PathKind::S => 'S',
            PathKind::L => 'L',
            PathKind::R => 'R',
        }
    }

    /// The path seen in a mirror (L and R swap).
    pub fn mirrored(self) -> PathKind {
        match self {
            PathKind::S => PathKind::S,
            PathKind::L => PathKind::R,
            PathKind::R => PathKind::L,
        }
    }
}

impl fmt::Display for PathKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.to_char())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn letters_round_trip() {
        for p in PathKind::ALL {
            assert_eq!(PathKind::from_char(p.to_char()), Some(p));
            assert_eq!(p.mirrored().mirrored(), p);
        }
        assert_eq!(PathKind::from_char('x'), None);
        assert_eq!(PathKind::from_char('l'), Some(PathKind::L));
    }
}
