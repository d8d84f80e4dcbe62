//! The memoised search against brute force: every word checked on its own by
//! [`check_word`] (the collision module's sequential check, no memo, no budget).

use crate::collision::{check_word, CheckOptions};
use crate::{Fold, FoldWord};

use super::CountOptions;

/// Every word of `joints` letters.
fn all_words(joints: usize) -> impl Iterator<Item = FoldWord> {
    (0..3usize.pow(joints as u32)).map(move |code| {
        let mut c = code;
        let folds: Vec<Fold> = (0..joints)
            .map(|_| {
                let f = Fold::ALL[c % 3];
                c /= 3;
                f
            })
            .collect();
        FoldWord::from_folds(folds)
    })
}

/// Valid words of `tiles` tiles by checking each, and the sum of `5^(straight joints)` over
/// them.
fn brute_force(tiles: usize, allow_opposite: bool, final_only: bool) -> (u128, u128) {
    let opts = CheckOptions::default().with_final_only(final_only);
    let (mut valid, mut weight) = (0u128, 0u128);
    for w in all_words(tiles - 1) {
        if !allow_opposite && w.first_opposite_pair().is_some() {
            continue;
        }
        if check_word(&w, &opts).is_ok() {
            valid += 1;
            let straight = w.folds().iter().filter(|&&f| f == Fold::S).count();
            weight += 5u128.pow(straight as u32);
        }
    }
    (valid, weight)
}

/// All words up to 10 tiles, with and without adjacent opposite folds, with and without the
/// sweeps: the same valid counts, and the same random-chain numerators.
#[test]
fn memoised_search_agrees_with_brute_force() {
    let max = 10;
    for final_only in [false, true] {
        for allow in [false, true] {
            let opts = CountOptions::default()
                .with_tiles(1, max)
                .with_allow_opposite(allow)
                .with_final_only(final_only)
                .with_random(true);
            let rows = opts.count_valid(&|_, _| {}).unwrap();
            assert_eq!(rows.len(), max);
            for row in rows {
                let (valid, _) = brute_force(row.tiles, allow, final_only);
                assert_eq!(
                    row.valid, valid,
                    "tiles {} allow_opposite {allow} final_only {final_only}",
                    row.tiles
                );
                // the random chain's words may hold opposite folds whatever `allow` says
                let (_, weight) = brute_force(row.tiles, true, final_only);
                let numerator = row.p_random_exact.unwrap();
                let numerator = numerator.split('/').next().unwrap();
                assert_eq!(numerator, weight.to_string(), "tiles {}", row.tiles);
            }
        }
    }
}

/// The sweeps matter: some words that end in a clean shape collide while folding, so the two
/// searches differ from 7 tiles on (LSLLSR is the first such word, found by brute force).
#[test]
fn sweeps_cut_words_with_clean_final_shapes() {
    let opts = CountOptions::default().with_tiles(6, 9);
    let swept = opts.count_valid(&|_, _| {}).unwrap();
    let shapes = opts.with_final_only(true).count_valid(&|_, _| {}).unwrap();
    assert_eq!(swept[0].valid, shapes[0].valid);
    for (a, b) in swept.iter().zip(&shapes).skip(1) {
        assert!(
            a.valid < b.valid,
            "{} tiles: {} {}",
            a.tiles,
            a.valid,
            b.valid
        );
    }
}

/// The search shares itself out over the thread pool; called from inside the pool (here from
/// two parallel tasks at once) it still finishes with the same counts.
#[test]
fn counting_from_inside_the_thread_pool() {
    use rayon::prelude::*;
    let opts = CountOptions::default().with_tiles(2, 14);
    let alone = opts.count_valid(&|_, _| {}).unwrap();
    let inside: Vec<_> = (0..2)
        .into_par_iter()
        .map(|_| opts.count_valid(&|_, _| {}).unwrap())
        .collect();
    for rows in inside {
        assert_eq!(rows, alone);
    }
}
