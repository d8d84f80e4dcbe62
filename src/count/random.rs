//! The chance that a chain of random tiles folds cleanly, estimated by sampling: for lengths
//! beyond the exact search's reach ([`super::CountOptions::count_valid`] with `random` gives it exactly).
//!
//! Each joint's two paths are drawn independently and uniformly from S, L and R (the nine
//! tiles); a chain propagates through a joint unless its paths are opposite folds, and the
//! part reached is checked with [`check_word`].

use rayon::prelude::*;

use crate::collision::{check_word, CheckOptions};
use crate::rng::{mix64, SplitMix64};
use crate::{Fold, FoldWord};

/// Estimate of the random-chain probability by sampling, with its 95% (Wilson) interval.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RandomEstimate {
    /// Tiles in the chain.
    pub tiles: usize,
    /// Chains sampled.
    pub samples: u64,
    /// Chains that propagated to the end and folded cleanly.
    pub successes: u64,
    /// The estimate.
    pub p: f64,
    /// Lower end of the 95% interval.
    pub low: f64,
    /// Upper end of the 95% interval.
    pub high: f64,
}

impl RandomEstimate {
    /// Samples `samples` chains of `tiles` tiles drawn uniformly from the nine tiles, folds
    /// the part that propagation reaches and counts those that reach the end and fold
    /// cleanly, with a 95% Wilson interval. Deterministic for a given `seed` (and independent
    /// across lengths for one seed).
    ///
    /// ```
    /// use foldchain::collision::CheckOptions;
    /// use foldchain::count::RandomEstimate;
    ///
    /// let est = RandomEstimate::sample(6, 2000, 1, &CheckOptions::default());
    /// assert!(est.low <= est.p && est.p <= est.high);
    /// ```
    pub fn sample(tiles: usize, samples: u64, seed: u64, opts: &CheckOptions) -> RandomEstimate {
        estimate_random(tiles, samples, seed, opts)
    }
}

/// Samples `samples` chains of `tiles` tiles drawn uniformly from the nine tiles, folds the
/// part that propagation reaches and counts those that reach the end and fold cleanly.
/// Deterministic for a given `seed` (and independent across lengths for one seed).
pub(crate) fn estimate_random(
    tiles: usize,
    samples: u64,
    seed: u64,
    opts: &CheckOptions,
) -> RandomEstimate {
    let chunks = 64u64;
    let per = samples.div_ceil(chunks);
    let successes: u64 = (0..chunks)
        .into_par_iter()
        .map(|c| {
            // independent streams: each chunk starts at a hashed point of the 2^64 cycle (a
            // plain `seed ^ c` start would make the chunks shifted copies of one stream)
            let mut rng = SplitMix64::new(mix64(
                seed.wrapping_mul(0xD1B5_4A32_D192_ED03)
                    ^ (tiles as u64).wrapping_mul(0x8CB9_2BA7_2F3D_8DD7)
                    ^ c,
            ));
            let count = per.min(samples.saturating_sub(c * per));
            let mut ok = 0u64;
            for _ in 0..count {
                // each joint independently: the second path of one tile and the first of the
                // next are independent uniform letters
                let mut folds = Vec::with_capacity(tiles.saturating_sub(1));
                let mut inhibited = false;
                for _ in 1..tiles {
                    let a = rng.below(3);
                    let b = rng.below(3);
                    let f = match (a, b) {
                        (1, 1) => Fold::L,
                        (2, 2) => Fold::R,
                        (1, 2) | (2, 1) => {
                            inhibited = true;
                            break;
                        }
                        _ => Fold::S,
                    };
                    folds.push(f);
                }
                if !inhibited && check_word(&FoldWord::from_folds(folds), opts).is_ok() {
                    ok += 1;
                }
            }
            ok
        })
        .sum();
    let (p, low, high) = wilson(successes, samples);
    RandomEstimate {
        tiles,
        samples,
        successes,
        p,
        low,
        high,
    }
}

/// The Wilson score interval at 95%.
fn wilson(k: u64, n: u64) -> (f64, f64, f64) {
    if n == 0 {
        return (f64::NAN, 0.0, 1.0);
    }
    let z = 1.959_963_984_540_054;
    let (k, n) = (k as f64, n as f64);
    let p = k / n;
    let den = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / den;
    let half = z * ((p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt()) / den;
    (p, (centre - half).max(0.0), (centre + half).min(1.0))
}
