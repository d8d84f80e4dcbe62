//! The chain's total dipole energy (thesis equation 8.1, figure 7.5) as a sum over units:
//! the RI with tile 0's magnets, the two magnets of each tile, and the four pairs across
//! each joint.
//!
//! Pairs two or more tiles apart are left out: they sit at least about `w` apart, against
//! `2c` (5.6 mm) for a bonded pair, so each contributes well under 1% of a bonded pair's
//! energy and changes even less. A unit's share changes only while its magnets move or its
//! joint turns, which lets a curve over time be swept unit by unit.

use kurbo::Point;

use crate::physics::{ForceLaw, Pole};

/// A group of pairs whose energy changes together.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnergyUnit {
    /// The RI with magnets 0 and 1.
    Ri,
    /// The two magnets of tile `i`.
    Tile(usize),
    /// The four pairs across joint `j` (tile `j`'s magnets with tile `j + 1`'s).
    Joint(usize),
}

impl EnergyUnit {
    /// Every unit of a chain of `tiles`: the RI, the tiles, then the joints.
    pub fn all(tiles: usize) -> impl Iterator<Item = EnergyUnit> {
        std::iter::once(EnergyUnit::Ri)
            .chain((0..tiles).map(EnergyUnit::Tile))
            .chain((0..tiles.saturating_sub(1)).map(EnergyUnit::Joint))
    }

    /// The magnets whose motion changes the unit's energy.
    pub fn magnets(self) -> Vec<usize> {
        match self {
            EnergyUnit::Ri => vec![0, 1],
            EnergyUnit::Tile(i) => vec![2 * i, 2 * i + 1],
            EnergyUnit::Joint(j) => vec![2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3],
        }
    }

    /// The unit's pairs.
    pub fn pairs(self) -> Vec<(Pole, Pole)> {
        match self {
            EnergyUnit::Ri => vec![(Pole::Ri, Pole::Magnet(0)), (Pole::Ri, Pole::Magnet(1))],
            EnergyUnit::Tile(i) => vec![(Pole::Magnet(2 * i), Pole::Magnet(2 * i + 1))],
            EnergyUnit::Joint(j) => [2 * j, 2 * j + 1]
                .into_iter()
                .flat_map(|a| {
                    [2 * j + 2, 2 * j + 3]
                        .into_iter()
                        .map(move |b| (Pole::Magnet(a), Pole::Magnet(b)))
                })
                .collect(),
        }
    }

    /// The unit's energy (J) under `law`, every magnet of moment `moment`, each pole at
    /// `position(pole)` (mm, any one frame for the unit).
    pub fn energy(self, law: ForceLaw, moment: f64, position: impl Fn(Pole) -> Point) -> f64 {
        self.pairs().into_iter().fold(0.0, |e, (a, b)| {
            e + law.energy(position(a), position(b), moment, moment, a.attracts(b))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_cover_the_near_pairs_once() {
        let tiles = 4;
        let mut pairs: Vec<(isize, isize)> = EnergyUnit::all(tiles)
            .flat_map(|u| u.pairs())
            .map(|(a, b)| (a.index(), b.index()))
            .collect();
        let n = pairs.len();
        pairs.sort_unstable();
        pairs.dedup();
        assert_eq!(pairs.len(), n);
        // RI 2, tiles 4, joints 3 x 4
        assert_eq!(n, 2 + 4 + 12);
        for u in EnergyUnit::all(tiles) {
            for (a, b) in u.pairs() {
                for p in [a, b] {
                    if let Pole::Magnet(k) = p {
                        assert!(u.magnets().contains(&k), "{u:?} {k}");
                    }
                }
            }
        }
    }

    #[test]
    fn a_bonded_pair_has_negative_energy() {
        let at = |p: Pole| Point::new(10.0 * p.index() as f64, 0.0);
        let e = EnergyUnit::Tile(0).energy(ForceLaw::default(), 0.03, at);
        assert!(e < 0.0);
        let direct =
            ForceLaw::default().energy(at(Pole::Magnet(0)), at(Pole::Magnet(1)), 0.03, 0.03, true);
        assert_eq!(e, direct);
    }
}
