//! The choice between the event engine's local solves and its kinematic baseline for a chain
//! (`fold-run --engine auto`): [`AutoEngine::of`].
//!
//! The local solves cache a unit's solution by its window and its inputs, so a chain costs
//! about one solve per distinct neighbourhood of its joints (the transient after a turn dies
//! out within some ten tiles): a straight chain or a serpentine of any length has a few dozen
//! (10^6 straight tiles fold-run in about 2 s), a random fold word has about one per tile
//! (about 3 ms per tile overdamped, 13 ms inertial, on the 2-core machine). `--engine auto`
//! uses the local solves when the chain has at most [`LOCAL_ENGINE_MAX_NEIGHBOURHOODS`]
//! distinct neighbourhoods ([`distinct_neighbourhoods`]), the kinematic baseline beyond.

use std::collections::HashSet;

use crate::engine::EngineMethod;
use crate::timeline::TileDesigns;
use crate::Chain;

/// Tiles either side of a joint in its neighbourhood: 12.
pub(crate) const NEIGHBOURHOOD_RADIUS: usize = 12;

/// `--engine auto` uses the local solves up to this many distinct neighbourhoods (a
/// 2,000-tile random fold word: some 6 s of overdamped local solves, 25 s inertial).
pub(crate) const LOCAL_ENGINE_MAX_NEIGHBOURHOODS: usize = 2_000;

/// What [`AutoEngine::of`] chose, and on what grounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct AutoEngine {
    /// The engine's method chosen.
    pub method: EngineMethod,
    /// The chain's distinct joint neighbourhoods (the tiles and their designs within 12 tiles
    /// of a joint).
    pub neighbourhoods: usize,
}

impl AutoEngine {
    /// The local solves when `chain` has at most 2,000 distinct joint neighbourhoods (their
    /// cost: about one solve each), the kinematic baseline beyond: `fold-run --engine auto`.
    ///
    /// ```
    /// use foldchain::engine::{EngineMethod, TileDesigns};
    /// use foldchain::{AutoEngine, Chain};
    /// let serpentine = Chain::parse(&"S*300 LL S*300 RR ".repeat(20)).unwrap();
    /// assert_eq!(AutoEngine::of(&serpentine, &TileDesigns::default()).method, EngineMethod::Local);
    /// ```
    pub fn of(chain: &Chain, designs: &TileDesigns) -> AutoEngine {
        let neighbourhoods = distinct_neighbourhoods(chain, designs);
        AutoEngine {
            method: if neighbourhoods > LOCAL_ENGINE_MAX_NEIGHBOURHOODS {
                EngineMethod::Kinematic
            } else {
                EngineMethod::Local
            },
            neighbourhoods,
        }
    }
}

/// How many distinct neighbourhoods (the tiles and their designs within
/// [`NEIGHBOURHOOD_RADIUS`] of a joint) `chain`'s joints have, the joints within the radius of
/// either end each counted as distinct.
pub(crate) fn distinct_neighbourhoods(chain: &Chain, designs: &TileDesigns) -> usize {
    let tiles = chain.tiles();
    let n = tiles.len();
    let width = 2 * NEIGHBOURHOOD_RADIUS + 1;
    if n <= width {
        return n;
    }
    let (_, index) = designs.resolve(n);
    let code = |i: usize| -> u64 {
        let t = tiles[i];
        let d = index.get(i).copied().unwrap_or(0) as u64;
        (t.first as u64) | ((t.second as u64) << 8) | (d << 16)
    };
    // a polynomial rolling hash of each window of `width` tiles
    const B: u64 = 0x9E37_79B9_7F4A_7C15 | 1;
    let top = (1..width).fold(1u64, |p, _| p.wrapping_mul(B));
    let mut h = (0..width).fold(0u64, |h, i| h.wrapping_mul(B).wrapping_add(code(i)));
    let mut seen = HashSet::new();
    seen.insert(h);
    for i in width..n {
        h = h
            .wrapping_sub(code(i - width).wrapping_mul(top))
            .wrapping_mul(B)
            .wrapping_add(code(i));
        seen.insert(h);
    }
    seen.len() + 2 * NEIGHBOURHOOD_RADIUS
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    fn count(word: &str) -> usize {
        distinct_neighbourhoods(&Chain::parse(word).unwrap(), &TileDesigns::default())
    }

    #[test]
    fn steady_chains_have_few_neighbourhoods_and_random_ones_many() {
        let straight = count("S*100000");
        assert!(straight <= 2 * NEIGHBOURHOOD_RADIUS + 1, "{straight}");
        let row = "S*315 LL S*315 RR ";
        let serpentine = count(&row.repeat(150));
        assert!(serpentine < 10 * width(), "{serpentine}");
        // a fold word of no repeating pattern: about one a tile
        let mut rng = crate::rng::SplitMix64::new(12345);
        let random: String = (0..3000)
            .map(|_| ['S', 'S', 'L', 'R'][(rng.next_u64() >> 62) as usize])
            .collect();
        let r = count(&random);
        assert!(r > 2_900 && r <= 3_001, "{r}");
        assert_eq!(count("SLLS"), 5);
    }

    fn width() -> usize {
        2 * NEIGHBOURHOOD_RADIUS + 1
    }
}
