//! The chain at one moment, as a step frame draws it: the same data whichever simulation
//! made it (the event engine's timeline or a recorded state of the force-integrated
//! reference, through [`crate::timeline::RunSource::state_at`]).

use crate::{Fold, Pose};

/// Chains up to this many tiles carry their magnets' positions in a [`ChainState`] and are
/// drawn in detail (outlines, paths, magnets, hinges); longer ones are drawn lean.
pub(crate) const DETAIL_TILES: usize = 400;

/// The chain at time `time`: what a step frame draws.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainState {
    /// Time, s.
    pub time: f64,
    /// Pose of every tile (world frame, mm).
    pub poses: Vec<Pose>,
    /// World position of every magnet, mm (magnet `k` is magnet `k mod 2` of tile `k / 2`);
    /// empty for a chain drawn lean (more than [`ChainState::DETAIL_TILES`] tiles), whose frames show no
    /// magnets (it would be 32 MB per frame at a million tiles).
    pub magnets: Vec<(f64, f64)>,
    /// Whether each magnet is moving.
    pub moving: Vec<bool>,
    /// Whether each joint is turning.
    pub folding: Vec<bool>,
    /// The fold of each joint that folds at some time in the run (its hinge is drawn), `None`
    /// for the others.
    pub folds: Vec<Option<Fold>>,
}

impl ChainState {
    /// Chains up to this many tiles carry their magnets' positions and are drawn in detail
    /// (outlines, paths, magnets, hinges); longer ones are drawn lean.
    pub const DETAIL_TILES: usize = DETAIL_TILES;

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.poses.len()
    }

    /// Whether a magnet of tile `i` is moving.
    pub fn tile_moving(&self, i: usize) -> bool {
        self.moving.get(2 * i).copied().unwrap_or(false)
            || self.moving.get(2 * i + 1).copied().unwrap_or(false)
    }

    /// Whether joint `j` is turning.
    pub fn joint_folding(&self, j: usize) -> bool {
        self.folding.get(j).copied().unwrap_or(false)
    }

    /// Number of magnets moving.
    pub fn moving_count(&self) -> usize {
        self.moving.iter().filter(|&&m| m).count()
    }
}
