//! Joints: what happens between two neighbouring tiles (thesis Table 7.1).
//!
//! Joint `i` joins tile `i` and tile `i + 1`. Its outcome is fixed by the second path of tile
//! `i` and the first path of tile `i + 1`: two curved paths the same way fold the chain 90
//! degrees that way, two opposite curves stop propagation, anything with a straight path
//! propagates in a line.

use std::fmt;

use crate::PathKind;

/// The outcome of a joint when propagation reaches it (thesis Table 7.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum JointOutcome {
    /// Propagation continues with no fold (SS, SL, SR, LS, RS).
    Linear,
    /// A 90 degree fold to the left (LL).
    FoldLeft,
    /// A 90 degree fold to the right (RR).
    FoldRight,
    /// Propagation stops at this joint (LR, RL).
    Inhibited,
}

impl JointOutcome {
    /// The outcome of a joint between a tile whose second path is `second` and a tile whose
    /// first path is `first`.
    pub fn from_paths(second: PathKind, first: PathKind) -> JointOutcome {
        match (second, first) {
            (PathKind::L, PathKind::L) => JointOutcome::FoldLeft,
            (PathKind::R, PathKind::R) => JointOutcome::FoldRight,
            (PathKind::L, PathKind::R) | (PathKind::R, PathKind::L) => JointOutcome::Inhibited,
            _ => JointOutcome::Linear,
        }
    }

    /// The fold letter this outcome makes, or `None` when inhibited.
    pub fn to_fold(self) -> Option<Fold> {
        match self {
            JointOutcome::Linear => Some(Fold::S),
            JointOutcome::FoldLeft => Some(Fold::L),
            JointOutcome::FoldRight => Some(Fold::R),
            JointOutcome::Inhibited => None,
        }
    }
}

impl fmt::Display for JointOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            JointOutcome::Linear => "linear propagation",
            JointOutcome::FoldLeft => "90 degree fold left",
            JointOutcome::FoldRight => "90 degree fold right",
            JointOutcome::Inhibited => "propagation inhibited",
        })
    }
}

/// One letter of a fold word: what a joint of a designed chain does.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Fold {
    /// No fold: the chain continues straight.
    S,
    /// Fold 90 degrees to the left (counter-clockwise seen from above).
    L,
    /// Fold 90 degrees to the right (clockwise seen from above).
    R,
}

impl Fold {
    /// All three letters, in the order S, L, R.
    pub const ALL: [Fold; 3] = [Fold::S, Fold::L, Fold::R];

    /// The letter for a character (`S`, `L`, `R`, either case), or `None`.
    pub fn from_char(c: char) -> Option<Fold> {
        PathKind::from_char(c).map(Fold::from_path)
    }

    /// The fold's letter.
    pub fn to_char(self) -> char {
        self.to_path().to_char()
    }

    /// The path that a tile carries on each side of a joint with this fold.
    pub fn to_path(self) -> PathKind {
        match self {
            Fold::S => PathKind::S,
            Fold::L => PathKind::L,
            Fold::R => PathKind::R,
        }
    }

    /// The fold a pair of `path` paths makes.
    pub fn from_path(path: PathKind) -> Fold {
        match path {
            PathKind::S => Fold::S,
            PathKind::L => Fold::L,
            PathKind::R => Fold::R,
        }
    }

    /// The change of heading in quarter turns: +1 left, -1 right, 0 straight.
    pub fn quarter_turns(self) -> i8 {
        match self {
            Fold::S => 0,
            Fold::L => 1,
            Fold::R => -1,
        }
    }

    /// The fold seen in a mirror (L and R swap).
    pub fn mirrored(self) -> Fold {
        Fold::from_path(self.to_path().mirrored())
    }

    /// Whether two consecutive folds are opposite turns (L then R or R then L), which needs an
    /// LR or RL tile between them.
    pub fn is_opposite(self, next: Fold) -> bool {
        matches!((self, next), (Fold::L, Fold::R) | (Fold::R, Fold::L))
    }
}

impl fmt::Display for Fold {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.to_char())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Thesis Table 7.1, all nine pairs.
    #[test]
    fn table_7_1() {
        use JointOutcome::*;
        let table = [
            ("SS", Linear),
            ("SL", Linear),
            ("SR", Linear),
            ("LS", Linear),
            ("RS", Linear),
            ("LL", FoldLeft),
            ("RR", FoldRight),
            ("LR", Inhibited),
            ("RL", Inhibited),
        ];
        for (pair, outcome) in table {
            let mut c = pair.chars();
            let second = PathKind::from_char(c.next().unwrap()).unwrap();
            let first = PathKind::from_char(c.next().unwrap()).unwrap();
            assert_eq!(
                JointOutcome::from_paths(second, first),
                outcome,
                "pair {pair}"
            );
        }
    }

    #[test]
    fn folds_mirror_and_turn() {
        assert_eq!(Fold::L.mirrored(), Fold::R);
        assert_eq!(Fold::L.quarter_turns(), 1);
        assert_eq!(Fold::R.quarter_turns(), -1);
        assert!(Fold::L.is_opposite(Fold::R));
        assert!(!Fold::L.is_opposite(Fold::L));
        assert!(!Fold::S.is_opposite(Fold::R));
    }
}
