//! Generators shared by the property tests: fold letters, run lengths and fold words.

use foldchain::{Fold, FoldWord};
use proptest::prelude::*;

/// Any fold letter.
pub fn fold() -> impl Strategy<Value = Fold> {
    (0usize..3).prop_map(|i| Fold::ALL[i])
}

/// Run lengths: mostly short, sometimes long, so that run-length forms (`SS*40`, `S*40`) and
/// runs of exactly the thresholds (3 tiles, 4 letters) all occur.
pub fn run_length() -> impl Strategy<Value = usize> {
    prop_oneof![
        6 => 1usize..=5,
        2 => 1usize..=60,
        1 => 100usize..=200,
    ]
}

/// Fold words of 1 to `max` letters made of runs of random letters.
pub fn word(max: usize) -> impl Strategy<Value = FoldWord> {
    prop::collection::vec((fold(), run_length()), 1..(max / 8).max(2)).prop_map(move |runs| {
        let mut folds: Vec<Fold> = runs
            .into_iter()
            .flat_map(|(f, n)| std::iter::repeat_n(f, n))
            .collect();
        folds.truncate(max);
        FoldWord::from_folds(folds)
    })
}
