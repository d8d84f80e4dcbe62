//! A chain whose tiles each have their own design, as the margins see it: every magnet's
//! path, moment and bond force from its own tile's [`Design`], the joints from the tiles' mean
//! width, and the reaction initiator from tile 0.
//!
//! The engine's [`crate::timeline::Geometry`] lets tiles differ only in `s` and `e` (the
//! tiles of a built chain share their outline and magnets); a printed chain does not: each
//! tile comes out of the printer a little different and each magnet from its batch with its
//! own remanence and size. Joint `j` joins tiles of widths `w_j` and `w_{j+1}`; it is placed
//! as [`crate::kinematics::joint_transform`] places a joint of width `(w_j + w_{j+1}) / 2`,
//! which keeps the centre distance of the straight chain exact and moves the hinge by at most
//! half the width difference (a few hundredths of a millimetre for printing tolerances).

use crate::magnet_path::{MagnetPath, PathEnd, PathError};
use crate::physics::{ForceLaw, ReactionInitiator};
use crate::{Chain, Design, DesignError, Fold, JointOutcome, Tile};

/// Why a chain's margins cannot be computed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MarginError {
    /// The number of designs is neither 1 nor the number of tiles.
    #[error("{designs} tile designs for a chain of {tiles} tiles: expected 1 or {tiles}")]
    DesignCount {
        /// Designs given.
        designs: usize,
        /// Tiles in the chain.
        tiles: usize,
    },
    /// A tile's design parameter out of range.
    #[error("tile {tile}: {source}")]
    Design {
        /// The tile.
        tile: usize,
        /// What is wrong.
        #[source]
        source: DesignError,
    },
    /// A tile's curved path cannot be built.
    #[error("tile {tile}: {source}")]
    Path {
        /// The tile.
        tile: usize,
        /// What is wrong.
        #[source]
        source: PathError,
    },
    /// An empty chain.
    #[error("an empty chain has no margins")]
    Empty,
}

/// A chain with one design per tile, ready for the margins.
#[derive(Clone, Debug)]
pub(crate) struct ChainModel {
    tiles: Vec<Tile>,
    designs: Vec<Design>,
    paths: Vec<MagnetPath>,
    lengths: Vec<f64>,
    moments: Vec<f64>,
    joint_width: Vec<f64>,
    folds: Vec<Fold>,
    ri: ReactionInitiator,
    last_joint: usize,
}

impl ChainModel {
    /// The model of `chain` with `designs`: one design for every tile, or one per tile.
    /// Parameters are validated (not the inequalities: a design that breaks them has margins
    /// that say so).
    pub fn new(chain: &Chain, designs: &[Design]) -> Result<ChainModel, MarginError> {
        let n = chain.len();
        if n == 0 {
            return Err(MarginError::Empty);
        }
        if designs.len() != 1 && designs.len() != n {
            return Err(MarginError::DesignCount {
                designs: designs.len(),
                tiles: n,
            });
        }
        let design = |t: usize| designs[if designs.len() == 1 { 0 } else { t }];
        let tiles = chain.tiles().to_vec();
        let mut paths = Vec::with_capacity(2 * n);
        let mut per_tile = Vec::with_capacity(n);
        for (t, tile) in tiles.iter().enumerate() {
            let d = design(t);
            d.validate()
                .map_err(|source| MarginError::Design { tile: t, source })?;
            for (kind, end) in [(tile.first, PathEnd::First), (tile.second, PathEnd::Second)] {
                paths.push(
                    MagnetPath::new(kind, end, &d)
                        .map_err(|source| MarginError::Path { tile: t, source })?,
                );
            }
            per_tile.push(d);
        }
        let lengths = paths.iter().map(MagnetPath::length).collect();
        let moments = (0..2 * n).map(|k| per_tile[k / 2].moment()).collect();
        let joint_width = (0..n.saturating_sub(1))
            .map(|j| 0.5 * (per_tile[j].tile_width + per_tile[j + 1].tile_width))
            .collect();
        let outcomes: Vec<JointOutcome> = chain.joint_outcomes().collect();
        let folds = outcomes
            .iter()
            .map(|o| o.to_fold().unwrap_or(Fold::S))
            .collect();
        let last_joint = chain.first_inhibited().unwrap_or(n.saturating_sub(1));
        Ok(ChainModel {
            ri: ReactionInitiator::of(&per_tile[0]),
            tiles,
            designs: per_tile,
            paths,
            lengths,
            moments,
            joint_width,
            folds,
            last_joint,
        })
    }

    /// Number of magnets.
    pub fn magnets(&self) -> usize {
        2 * self.tiles.len()
    }

    /// Magnet `k`'s path, in its tile's frame.
    pub fn path(&self, k: usize) -> &MagnetPath {
        &self.paths[k]
    }

    /// Magnet `k`'s path length, mm.
    pub fn length(&self, k: usize) -> f64 {
        self.lengths[k]
    }

    /// Magnet `k`'s moment, A m^2.
    pub fn moment(&self, k: usize) -> f64 {
        self.moments[k]
    }

    /// The width joint `j` is placed with, mm (the mean of its two tiles').
    pub fn joint_width(&self, j: usize) -> f64 {
        self.joint_width[j]
    }

    /// The fold joint `j` makes (S for a straight or an inhibited joint).
    pub fn fold(&self, j: usize) -> Fold {
        self.folds[j]
    }

    /// The reaction initiator.
    pub(crate) fn ri(&self) -> ReactionInitiator {
        self.ri
    }

    /// The magnets the design means to start: every one but the chain's last, or, where a
    /// joint inhibits propagation, up to the first magnet of that joint's pair.
    pub fn starting_magnets(&self) -> std::ops::Range<usize> {
        if self.last_joint + 1 < self.tiles.len() {
            0..2 * self.last_joint + 2
        } else {
            0..self.magnets() - 1
        }
    }

    /// The joints the design means to fold, in chain order.
    pub fn folding_joints(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.folds.len().min(self.last_joint)).filter(|&j| self.folds[j] != Fold::S)
    }

    /// The bond force of tile `t`'s pair ([`ForceLaw::bonded_rest_force`]), N.
    pub fn bond_force(&self, law: ForceLaw, t: usize) -> f64 {
        law.bonded_rest_force(&self.designs[t])
    }
}
