//! Counting the fold words that fold without self-intersection (thesis Table 5.1), and the
//! chance that a chain of random tiles folds cleanly.
//!
//! A depth-first search grows words one joint at a time ([`search`](self)). Under sequential
//! folding a prefix that collides makes every extension collide (the first tiles move the
//! same way whatever follows), so invalid prefixes are cut. Appending a tile adds these motions
//! to check: for every fold `j` of the word, the new tile rides on `j`'s straight tail as it
//! turns against tiles `0..=j`. Since that tail is straight whatever follows, the first tail
//! tile that hits anything is known when the fold is made: it is decided once per exact
//! lattice offset with the closed-form sweep test of [`crate::collision`] and kept in a
//! memo, and each word carries the resulting cap on its length (one integer), so a straight
//! extension costs O(1) and a fold one memo lookup per placed tile near its swept area.
//! Final-shape overlaps are the ends of these sweeps, so nothing else is needed. No rule about
//! letters is used: every count comes from the geometry. Mirror images (L and R swapped) fold
//! alike, so only words whose first turn is L are searched and counted twice.
//!
//! Large counts split into disjoint shards ([`CountOptions::with_shard`]) whose reports add up
//! with [`CountReport::merge`]; [`RandomEstimate::sample`] samples the random-chain probability beyond
//! exact reach.

mod first_hit;
mod lattice;
mod merge;
mod random;
mod search;

use merge::list;
pub use merge::{CountReport, Shard};
pub use random::RandomEstimate;

use crate::collision::CheckOptions;
use search::{search, Scope};

/// What to count.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub struct CountOptions {
    /// Shortest chain counted, in tiles. Default 2.
    pub min_tiles: usize,
    /// Longest chain counted, in tiles. Default 6.
    pub max_tiles: usize,
    /// Count words with adjacent opposite folds (L then R), which need LR/RL tiles. Default
    /// `false`, as in the thesis.
    pub allow_opposite: bool,
    /// Check only the final shape, not the fold sweeps. Default `false`.
    pub final_only: bool,
    /// Also compute the exact probability that a chain of tiles drawn uniformly from the nine
    /// propagates to its end and folds cleanly. Default `false`.
    pub random: bool,
    /// Count only part `k` (1-based) of `m` disjoint parts of the search. Default `None`.
    pub shard: Option<(usize, usize)>,
    /// Touching tolerance in tile widths (see [`CheckOptions::tolerance`]). Default `1e-7`.
    pub tolerance: f64,
}

impl Default for CountOptions {
    fn default() -> CountOptions {
        CountOptions {
            min_tiles: 2,
            max_tiles: 6,
            allow_opposite: false,
            final_only: false,
            random: false,
            shard: None,
            tolerance: CheckOptions::default().tolerance,
        }
    }
}

impl CountOptions {
    /// The largest chain length counted (the weights of the random-chain probability are
    /// exact integers up to this length).
    pub const MAX_TILES: usize = MAX_COUNT_TILES;

    /// Counts chains of `min` to `max` tiles.
    pub fn with_tiles(mut self, min: usize, max: usize) -> CountOptions {
        self.min_tiles = min;
        self.max_tiles = max;
        self
    }
    /// Counts words with adjacent opposite folds too.
    pub fn with_allow_opposite(mut self, allow: bool) -> CountOptions {
        self.allow_opposite = allow;
        self
    }
    /// Checks only final shapes.
    pub fn with_final_only(mut self, final_only: bool) -> CountOptions {
        self.final_only = final_only;
        self
    }
    /// Computes the random-chain probability too.
    pub fn with_random(mut self, random: bool) -> CountOptions {
        self.random = random;
        self
    }
    /// Counts only part `k` (1-based) of `m`.
    pub fn with_shard(mut self, k: usize, m: usize) -> CountOptions {
        self.shard = Some((k, m));
        self
    }
    /// Another touching tolerance, in tile widths.
    pub fn with_tolerance(mut self, tolerance: f64) -> CountOptions {
        self.tolerance = tolerance;
        self
    }
}

/// Why a count could not be made, or the reports of its shards not added up
/// ([`CountReport::merge`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CountError {
    /// Bad tile range.
    #[error("tile range {min}..={max}: expected 1 <= min <= max <= {limit}")]
    BadRange {
        /// Shortest.
        min: usize,
        /// Longest.
        max: usize,
        /// The largest length supported.
        limit: usize,
    },
    /// Bad shard.
    #[error("shard {k}/{m}: expected 1 <= k <= m")]
    BadShard {
        /// Part.
        k: usize,
        /// Parts.
        m: usize,
    },
    /// A shard written other than as `K/M`.
    #[error("shard {text:?}: expected K/M with whole numbers 1 <= K <= M, e.g. 2/8")]
    ShardText {
        /// What was given.
        text: String,
    },
    /// No shard reports to add up ([`CountReport::merge`]).
    #[error("no shard reports given")]
    NoReports,
    /// A file is not a count report.
    #[error("{file}: not a fold-enum --json report: {message}")]
    Json {
        /// The file.
        file: String,
        /// What the JSON reader said.
        message: String,
    },
    /// A report is a whole search, not a part.
    #[error(
        "{file}: not a shard (its \"shard\" is null); only the parts of one --shard run add up"
    )]
    NotAShard {
        /// The file.
        file: String,
    },
    /// A report splits the search into another number of parts.
    #[error("{file}: shard {shard} is one of {} parts, but {first} is one of {expected}", shard.m)]
    PartsDisagree {
        /// The file.
        file: String,
        /// Its part.
        shard: Shard,
        /// The first file.
        first: String,
        /// The first file's number of parts.
        expected: usize,
    },
    /// The same part twice.
    #[error("shard {shard} given twice: {first} and {second}")]
    Doubled {
        /// The part.
        shard: Shard,
        /// Where it was seen first.
        first: String,
        /// Where it was seen again.
        second: String,
    },
    /// Parts missing.
    #[error("shards missing: {} (of {m} parts)", list(missing))]
    Missing {
        /// The parts not given.
        missing: Vec<usize>,
        /// The number of parts.
        m: usize,
    },
    /// A report of another search (options, lengths, or probabilities that do not add).
    #[error("{file}: {what} differ from those of {first}")]
    Mismatch {
        /// The file.
        file: String,
        /// The first file.
        first: String,
        /// What differs.
        what: String,
    },
}

/// The largest chain length counted (the weights of the random-chain probability are exact
/// integers up to this length).
pub(crate) const MAX_COUNT_TILES: usize = 40;

/// One row of the table: chains of `tiles` tiles.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CountRow {
    /// Tiles in the chain.
    pub tiles: usize,
    /// All fold words, `3^(tiles - 1)`.
    pub candidates: u128,
    /// Words searched under the options: without adjacent opposite folds unless they are
    /// allowed.
    pub searched: u128,
    /// Words that fold without self-intersection.
    pub valid: u128,
    /// Probability that a chain of uniformly random tiles propagates to its end and folds
    /// without self-intersection (with `random`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_random: Option<f64>,
    /// The same as an exact fraction `numerator/9^(tiles-1)` (with `random`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_random_exact: Option<String>,
    /// The thesis' `(7/9)^(tiles-1)`, which ignores self-intersection (with `random`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub p_propagates: Option<f64>,
}

impl CountOptions {
    /// Counts valid fold words for every length in the options' range. `progress(done, total)`
    /// is called as parts of the search finish.
    ///
    /// ```
    /// use foldchain::count::CountOptions;
    ///
    /// // thesis Table 5.1: chains of 2, 3 and 4 tiles
    /// let rows = CountOptions::default().with_tiles(2, 4).count_valid(&|_, _| {}).unwrap();
    /// assert_eq!(rows.len(), 3);
    /// assert_eq!(rows[0].valid, 3); // two tiles: S, L and R all fold
    /// ```
    pub fn count_valid(
        &self,
        progress: &(dyn Fn(u64, u64) + Sync),
    ) -> Result<Vec<CountRow>, CountError> {
        let opts = self;
        if opts.min_tiles < 1 || opts.min_tiles > opts.max_tiles || opts.max_tiles > MAX_COUNT_TILES
        {
            return Err(CountError::BadRange {
                min: opts.min_tiles,
                max: opts.max_tiles,
                limit: MAX_COUNT_TILES,
            });
        }
        let shard = match opts.shard {
            Some((k, m)) => {
                let s = Shard::new(k, m)?;
                (s.k, s.m)
            }
            None => (1, 1),
        };
        let n = opts.max_tiles;
        let scope = Scope {
            tiles: n,
            allow_opposite: opts.allow_opposite,
            final_only: opts.final_only,
            weigh: opts.random && opts.allow_opposite,
            tolerance: opts.tolerance,
            shard,
        };
        let main = search(&scope, progress);
        // the random chain's words may have adjacent opposite folds (they stop propagation)
        let random = match (opts.random, opts.allow_opposite) {
            (false, _) => None,
            (true, true) => Some(main.weight.clone()),
            (true, false) => {
                let all = Scope {
                    allow_opposite: true,
                    weigh: true,
                    ..scope
                };
                Some(search(&all, progress).weight)
            }
        };
        let mut rows = Vec::new();
        for tiles in opts.min_tiles..=n {
            let joints = (tiles - 1) as u32;
            let candidates = 3u128.pow(joints);
            let searched = if opts.allow_opposite {
                candidates
            } else {
                words_without_opposite(tiles)
            };
            let mut row = CountRow {
                tiles,
                candidates,
                searched,
                valid: u128::from(main.valid[tiles]),
                p_random: None,
                p_random_exact: None,
                p_propagates: None,
            };
            if let Some(weight) = &random {
                let den = 9u128.pow(joints);
                row.p_random = Some(weight[tiles] as f64 / den as f64);
                row.p_random_exact = Some(format!("{}/{}", weight[tiles], den));
                row.p_propagates = Some((7.0f64 / 9.0).powi(joints as i32));
            }
            rows.push(row);
        }
        Ok(rows)
    }
}

/// Words of `tiles - 1` letters with no L next to R.
fn words_without_opposite(tiles: usize) -> u128 {
    // ending in S, ending in L (R the same by symmetry)
    let (mut s, mut l) = (1u128, 0u128);
    for _ in 0..tiles.saturating_sub(1) {
        let (ns, nl) = (s + 2 * l, s + l);
        s = ns;
        l = nl;
    }
    s + 2 * l
}

#[cfg(test)]
mod agreement;

#[cfg(test)]
mod tests {
    use super::*;

    fn none(_: u64, _: u64) {}

    /// Thesis Table 5.1.
    #[test]
    fn table_5_1() {
        let rows = CountOptions::default()
            .with_tiles(2, 6)
            .count_valid(&none)
            .unwrap();
        let got: Vec<(usize, u128, u128)> = rows
            .iter()
            .map(|r| (r.tiles, r.candidates, r.valid))
            .collect();
        assert_eq!(
            got,
            vec![(2, 3, 3), (3, 9, 7), (4, 27, 17), (5, 81, 35), (6, 243, 79)]
        );
    }

    #[test]
    fn shards_add_up() {
        // 3 parts cut at 9 joints; 100 parts cut deeper (16 words a part)
        for (m, tiles) in [(3, 12), (100, 13)] {
            let opts = CountOptions::default().with_tiles(2, tiles);
            let whole = opts.count_valid(&none).unwrap();
            let mut sum = vec![0u128; whole.len()];
            for k in 1..=m {
                let part = opts.with_shard(k, m).count_valid(&none).unwrap();
                for (s, r) in sum.iter_mut().zip(&part) {
                    *s += r.valid;
                }
            }
            assert_eq!(sum, whole.iter().map(|r| r.valid).collect::<Vec<_>>());
        }
    }

    #[test]
    fn random_probability_is_exact_and_below_propagation() {
        let rows = CountOptions::default()
            .with_tiles(2, 6)
            .with_random(true)
            .count_valid(&none)
            .unwrap();
        // two tiles: never self-intersects, so it is the propagation probability 7/9
        assert_eq!(rows[0].p_random_exact.as_deref(), Some("7/9"));
        for r in &rows {
            assert!(r.p_random.unwrap() <= r.p_propagates.unwrap() + 1e-15);
        }
        // five tiles: LLLL-like words fail, so strictly below (7/9)^4
        assert!(rows[3].p_random.unwrap() < rows[3].p_propagates.unwrap());
        // Monte Carlo agrees with the exact figure within its interval
        // (seeds 1..=10: a 95% interval may miss now and then, not often)
        let exact = rows[4].p_random.unwrap();
        let mut covered = 0;
        for seed in 1..=10 {
            let est = RandomEstimate::sample(6, 20_000, seed, &CheckOptions::default());
            covered += (est.low <= exact && exact <= est.high) as usize;
            assert!((est.p - exact).abs() < 0.02, "{est:?} vs {exact}");
        }
        assert!(
            covered >= 8,
            "{covered} of 10 intervals hold the exact value"
        );
    }

    #[test]
    fn bad_options_are_errors() {
        let d = CountOptions::default;
        for opts in [
            d().with_tiles(5, 3),
            d().with_tiles(2, 99),
            d().with_shard(0, 3),
            d().with_shard(4, 3),
        ] {
            assert!(opts.count_valid(&none).is_err(), "{opts:?}");
        }
    }

    #[test]
    fn counting_words_without_opposite_folds() {
        assert_eq!(words_without_opposite(2), 3);
        assert_eq!(words_without_opposite(3), 7);
        assert_eq!(words_without_opposite(4), 17);
        assert_eq!(words_without_opposite(5), 41);
    }
}
