//! Fold words: one letter per joint, the compact form of a designed chain.
//!
//! A chain of `n` tiles has `n - 1` joints, so its word has `n - 1` letters. Tile `i` of the
//! designed chain is `(word[i-1], word[i])`, with `S` before the first joint and after the
//! last (SPEC section 2).

use std::fmt;
use std::str::FromStr;

use crate::{Chain, ChainError, Fold, Tile, MAX_TILES};

/// A fold word: the fold of every joint, from the reaction-initiator end.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub struct FoldWord {
    folds: Vec<Fold>,
}

impl FoldWord {
    /// A word from its letters.
    pub fn from_folds(folds: Vec<Fold>) -> FoldWord {
        FoldWord { folds }
    }

    /// The straight word of a chain of `tiles` tiles (`tiles - 1` letters S).
    pub fn straight(tiles: usize) -> FoldWord {
        FoldWord {
            folds: vec![Fold::S; tiles.saturating_sub(1)],
        }
    }

    /// Reads a word such as `SLLS` or `S*12 L S*12 L`: letters S, L, R in either case, each
    /// optionally followed by `*N` to repeat it; white space, `,`, `_` and `-` are ignored.
    pub fn parse(text: &str) -> Result<FoldWord, ChainError> {
        let mut folds = Vec::new();
        let mut chars = text.char_indices().peekable();
        let mut position = 0usize;
        while let Some((_, c)) = chars.next() {
            position += 1;
            if c.is_whitespace() || matches!(c, ',' | '_' | '-') {
                continue;
            }
            let fold = Fold::from_char(c).ok_or(ChainError::BadLetter {
                ch: c,
                position: position - 1,
            })?;
            let mut count = 1usize;
            if let Some(&(_, '*')) = chars.peek() {
                chars.next();
                position += 1;
                let mut digits = String::new();
                while let Some(&(_, d)) = chars.peek() {
                    if !d.is_ascii_digit() {
                        break;
                    }
                    digits.push(d);
                    chars.next();
                    position += 1;
                }
                count = parse_count(&format!("{c}*{digits}"), &digits)?;
            }
            if folds.len() + count >= MAX_TILES {
                return Err(ChainError::TooLong { max: MAX_TILES });
            }
            folds.extend(std::iter::repeat_n(fold, count));
        }
        if folds.is_empty() {
            return Err(ChainError::Empty);
        }
        Ok(FoldWord { folds })
    }

    /// The letters.
    pub fn folds(&self) -> &[Fold] {
        &self.folds
    }

    /// The number of joints (letters).
    pub fn joints(&self) -> usize {
        self.folds.len()
    }

    /// The number of tiles of the chain this word designs (one more than the joints).
    pub fn tiles(&self) -> usize {
        self.folds.len() + 1
    }

    /// The first pair of consecutive opposite folds (L then R, or R then L), if any: the
    /// thesis' designs do not use them.
    pub fn first_opposite_pair(&self) -> Option<usize> {
        self.folds.windows(2).position(|w| w[0].is_opposite(w[1]))
    }

    /// Checks that the word has no consecutive opposite folds.
    pub fn check_no_opposite_folds(&self) -> Result<(), ChainError> {
        match self.first_opposite_pair() {
            None => Ok(()),
            Some(joint) => Err(ChainError::OppositeFolds {
                joint,
                first: self.folds[joint].to_char(),
                second: self.folds[joint + 1].to_char(),
            }),
        }
    }

    /// The designed chain: tile `i` is `(word[i-1], word[i])`, with S at the two ends.
    pub fn to_chain(&self) -> Chain {
        let n = self.tiles();
        let letter = |j: isize| -> Fold {
            if j < 0 || j as usize >= self.folds.len() {
                Fold::S
            } else {
                self.folds[j as usize]
            }
        };
        let tiles = (0..n as isize)
            .map(|i| Tile::new(letter(i - 1).to_path(), letter(i).to_path()))
            .collect();
        Chain::from_tiles_unchecked(tiles)
    }

    /// The word seen in a mirror (L and R swap).
    pub fn mirrored(&self) -> FoldWord {
        FoldWord {
            folds: self.folds.iter().map(|f| f.mirrored()).collect(),
        }
    }

    /// The word with runs of four or more equal letters written `X*N`.
    pub fn to_compact_string(&self) -> String {
        let mut out = String::new();
        for (fold, run) in runs(&self.folds) {
            if run >= 4 {
                out.push_str(&format!("{fold}*{run}"));
            } else {
                for _ in 0..run {
                    out.push(fold.to_char());
                }
            }
        }
        out
    }
}

/// Runs of equal items: (item, run length).
pub(crate) fn runs<T: Copy + PartialEq>(items: &[T]) -> Vec<(T, usize)> {
    let mut out: Vec<(T, usize)> = Vec::new();
    for &x in items {
        match out.last_mut() {
            Some((y, n)) if *y == x => *n += 1,
            _ => out.push((x, 1)),
        }
    }
    out
}

/// Reads a repeat count.
pub(crate) fn parse_count(token: &str, digits: &str) -> Result<usize, ChainError> {
    let bad = || ChainError::BadCount {
        token: token.to_string(),
        count: digits.to_string(),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    match digits.parse::<usize>() {
        Ok(0) => Err(bad()),
        // a count of MAX_TILES is the longest tile run allowed (`SS*20000000`); word runs are
        // limited again by the caller, as MAX_TILES letters make one tile too many
        Ok(n) if n > MAX_TILES => Err(ChainError::TooLong { max: MAX_TILES }),
        Ok(n) => Ok(n),
        Err(_) => Err(ChainError::TooLong { max: MAX_TILES }),
    }
}

impl FromStr for FoldWord {
    type Err = ChainError;
    fn from_str(s: &str) -> Result<FoldWord, ChainError> {
        FoldWord::parse(s)
    }
}

impl fmt::Display for FoldWord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for fold in &self.folds {
            write!(f, "{}", fold.to_char())?;
        }
        Ok(())
    }
}

crate::text_serde::serde_as_text!(FoldWord);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn designed_chain_of_a_word() {
        let w = FoldWord::parse("SLLS").unwrap();
        assert_eq!(w.tiles(), 5);
        assert_eq!(w.to_chain().to_string(), "SS SL LL LS SS");
        assert_eq!(w.to_chain().to_word().unwrap(), w);
    }

    #[test]
    fn run_length_and_errors() {
        assert_eq!(FoldWord::parse("s*3 L").unwrap().to_string(), "SSSL");
        assert_eq!(FoldWord::parse("S*5").unwrap().to_compact_string(), "S*5");
        assert_eq!(FoldWord::parse(""), Err(ChainError::Empty));
        assert_eq!(FoldWord::parse("  \n"), Err(ChainError::Empty));
        assert_eq!(
            FoldWord::parse("SLX"),
            Err(ChainError::BadLetter {
                ch: 'X',
                position: 2
            })
        );
        for bad in ["S*0", "S*", "S*-3"] {
            let parsed = FoldWord::parse(bad);
            assert!(
                matches!(parsed, Err(ChainError::BadCount { .. })),
                "{bad}: {parsed:?}"
            );
        }
        for long in ["S*99999999999999999999999", "S*99999999 S*99999999"] {
            let parsed = FoldWord::parse(long);
            assert!(
                matches!(parsed, Err(ChainError::TooLong { .. })),
                "{long}: {parsed:?}"
            );
        }
    }

    #[test]
    fn opposite_folds_are_found() {
        assert_eq!(
            FoldWord::parse("SLRS").unwrap().first_opposite_pair(),
            Some(1)
        );
        assert!(FoldWord::parse("SLSR")
            .unwrap()
            .check_no_opposite_folds()
            .is_ok());
        let err = FoldWord::parse("RL")
            .unwrap()
            .check_no_opposite_folds()
            .unwrap_err();
        assert!(err.to_string().contains("joints 0 and 1"), "{err}");
    }
}
