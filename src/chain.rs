//! Chains: the tiles in order from the reaction-initiator end, and their text and JSON forms.
//!
//! A chain is written three interchangeable ways: a tile list (`SS SL LL LS SS`, with
//! run-length `SS*12`), a fold word (`SLLS`, see [`FoldWord`]) and JSON (`{"tiles":[...]}`).
//! [`Chain::parse`] takes any of them.

use std::fmt;
use std::str::FromStr;

use crate::word::{parse_count, runs};
use crate::{ChainError, Fold, FoldWord, JointOutcome, Tile};

/// The largest number of tiles the parsers accept: twenty million, far beyond any chain built
/// and within what the checks and the engine handle in a minute or so and a few GiB; a guard
/// against hostile run-length counts such as `SS*99999999999`.
pub(crate) const MAX_TILES: usize = 20_000_000;

/// A chain of tiles, from the reaction-initiator end. Its JSON form is
/// `{"tiles":["SS","SL",...]}`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, serde::Deserialize)]
#[serde(try_from = "ChainJson")]
pub struct Chain {
    tiles: Vec<Tile>,
}

/// The JSON form as read: checked into a [`Chain`].
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct ChainJson {
    tiles: Vec<Tile>,
}

/// The JSON form as written, borrowing the tiles.
#[derive(serde::Serialize)]
struct ChainJsonRef<'a> {
    tiles: &'a [Tile],
}

impl serde::Serialize for Chain {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ChainJsonRef { tiles: &self.tiles }.serialize(s)
    }
}

impl TryFrom<ChainJson> for Chain {
    type Error = ChainError;
    fn try_from(j: ChainJson) -> Result<Chain, ChainError> {
        Chain::from_tiles(j.tiles)
    }
}

impl Chain {
    /// The largest number of tiles the parsers accept: twenty million, far beyond any chain
    /// built and within what the checks and the engine handle in a minute or so and a few
    /// GiB; a guard against hostile run-length counts such as `SS*99999999999`.
    pub const MAX_TILES: usize = MAX_TILES;

    /// A chain from its tiles; fails on an empty list or more than [`Chain::MAX_TILES`] tiles.
    pub fn from_tiles(tiles: Vec<Tile>) -> Result<Chain, ChainError> {
        if tiles.is_empty() {
            return Err(ChainError::Empty);
        }
        if tiles.len() > MAX_TILES {
            return Err(ChainError::TooLong { max: MAX_TILES });
        }
        Ok(Chain { tiles })
    }

    pub(crate) fn from_tiles_unchecked(tiles: Vec<Tile>) -> Chain {
        Chain { tiles }
    }

    /// Reads a chain in any of its forms: JSON (text starting with `{`, or a bare array of
    /// tiles `["SS","SL"]` starting with `[`), a tile list (items of
    /// two letters separated by white space or commas, e.g. `SS SL LS` or `SS*3`), or a fold
    /// word (`SLLS`). A prefix `tiles:` or `word:` forces the form; without one, a single item
    /// of letters is read as a fold word, so one tile alone is written `tiles:SS`, and a single
    /// item is a tile list only as a name and a count (`SS*12`; `RS*7LLS*8` is a word).
    pub fn parse(text: &str) -> Result<Chain, ChainError> {
        let t = text.trim();
        if let Some(rest) = t.strip_prefix("tiles:") {
            return Chain::parse_tile_list(rest);
        }
        if let Some(rest) = t.strip_prefix("word:") {
            return Ok(FoldWord::parse(rest)?.to_chain());
        }
        if t.starts_with('{') {
            return Chain::from_json(t);
        }
        if t.starts_with('[') {
            let tiles: Vec<Tile> =
                serde_json::from_str(t).map_err(|e| ChainError::Json(e.to_string()))?;
            return Chain::from_tiles(tiles);
        }
        let items: Vec<&str> = split_items(t).collect();
        let looks_like_tiles = items.len() > 1
            && items
                .iter()
                .all(|s| s.split('*').next().is_some_and(|p| p.chars().count() == 2))
            || items.len() == 1
                && items[0].split_once('*').is_some_and(|(name, count)| {
                    name.chars().count() == 2 && count.chars().all(|c| c.is_ascii_digit())
                });
        if looks_like_tiles {
            Chain::parse_tile_list(t)
        } else {
            Ok(FoldWord::parse(t)?.to_chain())
        }
    }

    /// Reads a tile list: items such as `SL` or `SS*12` separated by white space or commas.
    pub fn parse_tile_list(text: &str) -> Result<Chain, ChainError> {
        let mut tiles = Vec::new();
        for (index, token) in split_items(text).enumerate() {
            let (name, count) = match token.split_once('*') {
                Some((name, digits)) => (name, parse_count(token, digits)?),
                None => (token, 1),
            };
            let tile: Tile = name.parse().map_err(|_| ChainError::BadTile {
                token: token.to_string(),
                index,
            })?;
            if tiles.len() + count > MAX_TILES {
                return Err(ChainError::TooLong { max: MAX_TILES });
            }
            tiles.extend(std::iter::repeat_n(tile, count));
        }
        Chain::from_tiles(tiles)
    }

    /// Reads the JSON form `{"tiles":["SS","SL",...]}`.
    pub fn from_json(text: &str) -> Result<Chain, ChainError> {
        serde_json::from_str(text).map_err(|e| ChainError::Json(e.to_string()))
    }

    /// The JSON form `{"tiles":["SS","SL",...]}`.
    pub fn to_json(&self) -> String {
        // a list of two-letter strings always serialises; the empty string is unreachable
        serde_json::to_string(self).unwrap_or_default()
    }

    /// The tiles.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// The number of tiles.
    pub fn len(&self) -> usize {
        self.tiles.len()
    }

    /// Always false: a chain has at least one tile.
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
    }

    /// The outcome of every joint (thesis Table 7.1), from the reaction-initiator end (a
    /// user reads the same from [`Chain::first_inhibited`] and [`Chain::reached_word`]).
    pub(crate) fn joint_outcomes(&self) -> impl Iterator<Item = JointOutcome> + '_ {
        self.tiles
            .windows(2)
            .map(|w| JointOutcome::from_paths(w[0].second, w[1].first))
    }

    /// The first inhibited joint, if any: propagation stops there.
    pub fn first_inhibited(&self) -> Option<usize> {
        self.joint_outcomes()
            .position(|o| o == JointOutcome::Inhibited)
    }

    /// The fold word: the fold of every joint. Fails at the first inhibited joint.
    pub fn to_word(&self) -> Result<FoldWord, ChainError> {
        let mut folds: Vec<Fold> = Vec::with_capacity(self.tiles.len().saturating_sub(1));
        for (joint, outcome) in self.joint_outcomes().enumerate() {
            match outcome.to_fold() {
                Some(f) => folds.push(f),
                None => {
                    return Err(ChainError::Inhibited {
                        joint,
                        left: self.tiles[joint].to_string(),
                        right: self.tiles[joint + 1].to_string(),
                    })
                }
            }
        }
        Ok(FoldWord::from_folds(folds))
    }

    /// The fold word of the joints that propagation reaches: the letters up to (not
    /// including) the first inhibited joint.
    pub fn reached_word(&self) -> FoldWord {
        FoldWord::from_folds(
            self.joint_outcomes()
                .map_while(JointOutcome::to_fold)
                .collect(),
        )
    }

    /// The tile list with runs of three or more equal tiles written `XY*N`.
    pub fn to_tile_list(&self) -> String {
        let mut out = String::new();
        for (tile, run) in runs(&self.tiles) {
            if !out.is_empty() {
                out.push(' ');
            }
            if run >= 3 {
                out.push_str(&format!("{tile}*{run}"));
            } else {
                for k in 0..run {
                    if k > 0 {
                        out.push(' ');
                    }
                    out.push_str(&tile.to_string());
                }
            }
        }
        out
    }
}

fn split_items(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|s| !s.is_empty())
}

impl FromStr for Chain {
    type Err = ChainError;
    fn from_str(s: &str) -> Result<Chain, ChainError> {
        Chain::parse(s)
    }
}

/// Prints every tile, separated by spaces; [`Chain::to_tile_list`] prints run-length.
impl fmt::Display for Chain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, t) in self.tiles.iter().enumerate() {
            if i > 0 {
                f.write_str(" ")?;
            }
            write!(f, "{t}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_are_recognised() {
        let a = Chain::parse("SS SL LL LS SS").unwrap();
        let b = Chain::parse("SLLS").unwrap();
        let c = Chain::parse(r#"{"tiles":["SS","SL","LL","LS","SS"]}"#).unwrap();
        let d = Chain::parse("ss,sl,ll,ls,ss").unwrap();
        assert_eq!(a, b);
        assert_eq!(a, c);
        assert_eq!(a, d);
        assert_eq!(Chain::parse("tiles:SS").unwrap().len(), 1);
        assert_eq!(Chain::parse("SS").unwrap().len(), 3);
        assert_eq!(Chain::parse("SS*12").unwrap().len(), 12);
        assert_eq!(Chain::parse("word:SS*12").unwrap().len(), 14); // S then S*12: 13 joints

        // a word that opens with two letters and a repeat, as fold-plan writes them, is a
        // word: a single tile-list item is a name and a count only
        assert_eq!(Chain::parse("RS*7LLS*8").unwrap().len(), 19);
        assert_eq!(Chain::parse("LS*3RRS*3").unwrap().len(), 10);
    }

    #[test]
    fn json_form_round_trips() {
        let c = Chain::parse("SS SL LL LS SS").unwrap();
        assert_eq!(c.to_json(), r#"{"tiles":["SS","SL","LL","LS","SS"]}"#);
        assert_eq!(Chain::from_json(&c.to_json()).unwrap(), c);
        assert_eq!(serde_json::to_value(&c).unwrap()["tiles"][2], "LL");
        assert!(Chain::from_json(r#"{"tiles":["SS"],"extra":1}"#).is_err());
    }

    #[test]
    fn run_length_list() {
        let c = Chain::parse("SS*4 SL LS SS SS").unwrap();
        assert_eq!(c.to_tile_list(), "SS*4 SL LS SS SS");
        assert_eq!(Chain::parse(&c.to_tile_list()).unwrap(), c);
    }

    #[test]
    fn inhibited_joint_has_no_word() {
        let c = Chain::parse("SS SL RS SS").unwrap();
        assert_eq!(c.first_inhibited(), Some(1));
        let e = c.to_word().unwrap_err();
        assert!(matches!(e, ChainError::Inhibited { joint: 1, .. }));
        assert!(e.to_string().contains("joint 1"), "{e}");
        assert_eq!(c.reached_word().to_string(), "S");
    }

    #[test]
    fn bad_input_is_named() {
        let e = Chain::parse("SS SX").unwrap_err();
        assert!(e.to_string().contains("'SX'"), "{e}");
        assert_eq!(Chain::parse(""), Err(ChainError::Empty));
        assert!(Chain::parse(r#"{"tiles":[]}"#)
            .unwrap_err()
            .to_string()
            .contains("empty chain"));
        assert!(matches!(
            Chain::parse(r#"{"tiles":["SQ"]}"#),
            Err(ChainError::Json(_))
        ));
        assert!(matches!(Chain::parse("{"), Err(ChainError::Json(_))));
        assert!(matches!(Chain::parse("[["), Err(ChainError::Json(_))));
        assert_eq!(
            Chain::parse(r#"["SS", "SL"]"#),
            Chain::parse(r#"{"tiles":["SS","SL"]}"#)
        );
        assert_eq!(Chain::parse("[]"), Err(ChainError::Empty));
        assert!(matches!(
            Chain::parse("SS*0 SL"),
            Err(ChainError::BadCount { .. })
        ));
    }
}
