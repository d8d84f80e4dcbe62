//! The chain's magnets as poles: chain index, polarity and the chain-index cutoff.
//!
//! Magnet `k` is magnet `k mod 2` of tile `k / 2`; the reaction initiator is magnet `-1`
//! ([`Pole::Ri`]). Moments stand upright and alternate along the chain, so two poles attract
//! when their indices differ by an odd number and repel when by an even one.
//!
//! Only pairs at most `cutoff` apart in chain index interact. The default, [`DEFAULT_CUTOFF`]
//! = 3, keeps the partner, the neighbour, the same-pole magnet one tile away and the next
//! opposite pole. The first pair left out is 4 apart, two tiles (about `2w`) away in a
//! straight run: `(b / 2w)^4` = 0.33% of the bonded rest force on the thesis design, and
//! the left-out terms alternate in sign ([`crate::model::Model::cutoff_error`] measures
//! it on a configuration).

use std::ops::RangeInclusive;

/// Default chain-index cutoff of the pair forces (see the module documentation).
pub(crate) const DEFAULT_CUTOFF: usize = 3;

/// A magnet of the chain by chain index, or the reaction initiator (magnet `-1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pole {
    /// The reaction initiator, fixed in tile 0's frame.
    Ri,
    /// Magnet `k`.
    Magnet(usize),
}

impl Pole {
    /// The chain index (`-1` for the RI).
    pub fn index(self) -> isize {
        match self {
            Pole::Ri => -1,
            Pole::Magnet(k) => k as isize,
        }
    }

    /// Whether the two poles attract (an odd index difference).
    pub fn attracts(self, other: Pole) -> bool {
        (self.index() - other.index()).rem_euclid(2) == 1
    }
}

/// The magnets within `cutoff` of magnet `m` (itself included), in a chain of `magnets`.
pub fn reach(m: usize, cutoff: usize, magnets: usize) -> RangeInclusive<usize> {
    m.saturating_sub(cutoff)..=(m.saturating_add(cutoff)).min(magnets - 1)
}

/// Every pole within `cutoff` of magnet `m` in a chain of `magnets`: the magnets in chain
/// order, then the RI when it is within reach.
pub fn neighbours(m: usize, cutoff: usize, magnets: usize) -> impl Iterator<Item = Pole> {
    reach(m, cutoff, magnets)
        .filter(move |&k| k != m)
        .map(Pole::Magnet)
        .chain((m < cutoff).then_some(Pole::Ri))
}

/// The poles before magnet `b` within `cutoff`, the RI first: with `b` running over the
/// chain, every interacting pair `(a, b)` once.
pub fn upstream(b: usize, cutoff: usize) -> impl Iterator<Item = Pole> {
    (b < cutoff)
        .then_some(Pole::Ri)
        .into_iter()
        .chain((b.saturating_sub(cutoff)..b).map(Pole::Magnet))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polarity_alternates_from_the_ri() {
        assert!(Pole::Ri.attracts(Pole::Magnet(0)));
        assert!(!Pole::Ri.attracts(Pole::Magnet(1)));
        assert!(Pole::Magnet(3).attracts(Pole::Magnet(4)));
        assert!(Pole::Magnet(4).attracts(Pole::Magnet(3)));
        assert!(!Pole::Magnet(2).attracts(Pole::Magnet(6)));
    }

    #[test]
    fn upstream_pairs_are_the_neighbour_pairs_once() {
        // every pair (a, b), a < b, met from b's side is met from a's side too, and none
        // twice: the two views of the cutoff agree
        let (n, cutoff) = (11, 3);
        let mut from_upstream = Vec::new();
        for b in 0..n {
            for a in upstream(b, cutoff) {
                from_upstream.push((a.index(), b as isize));
            }
        }
        let mut from_neighbours = Vec::new();
        for m in 0..n {
            for p in neighbours(m, cutoff, n) {
                if p.index() < m as isize {
                    from_neighbours.push((p.index(), m as isize));
                }
            }
        }
        from_upstream.sort_unstable();
        from_neighbours.sort_unstable();
        assert_eq!(from_upstream, from_neighbours);
        // the RI reaches magnets 0..cutoff
        let ri: Vec<isize> = from_upstream
            .iter()
            .filter(|p| p.0 == -1)
            .map(|p| p.1)
            .collect();
        assert_eq!(ri, vec![0, 1, 2]);
        assert!(from_upstream.iter().all(|p| p.1 - p.0 <= cutoff as isize));
        assert_eq!(reach(9, 3, n), 6..=10);
        assert_eq!(reach(1, usize::MAX, n), 0..=10);
    }
}
