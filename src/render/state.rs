//! The chain at one moment, as a frame draws it: the same data whichever simulation made it
//! (the event engine's timeline, [`ChainState::from_timeline`], or a recorded state of the
//! force-integrated reference, [`crate::reference`]).

use crate::engine::{joint_angles_at, Timeline};
use crate::kinematics::poses_at_angles;
use crate::render::DETAIL_TILES;
use crate::{Fold, Pose};

/// The chain at time `time`: what [`crate::render::frame_svg`] draws.
#[derive(Clone, Debug, PartialEq)]
pub struct ChainState {
    /// Time, s.
    pub time: f64,
    /// Pose of every tile (world frame, mm).
    pub poses: Vec<Pose>,
    /// World position of every magnet, mm (magnet `k` is magnet `k mod 2` of tile `k / 2`);
    /// empty for a chain drawn lean (more than [`DETAIL_TILES`] tiles), whose frames show no
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
    /// The event engine's chain at time `t`.
    pub fn from_timeline(tl: &Timeline, t: f64) -> ChainState {
        let poses = poses_at_angles(&joint_angles_at(tl, t), tl.geometry.w);
        let magnets = if tl.tiles() <= DETAIL_TILES {
            (0..tl.geometry.magnets())
                .map(|k| poses[k / 2].transform_point(tl.local_position(k, t)))
                .collect()
        } else {
            Vec::new()
        };
        let moving = (0..tl.geometry.magnets())
            .map(|k| tl.is_moving(k, t))
            .collect();
        let joints = tl.tiles().saturating_sub(1);
        let folding = (0..joints)
            .map(|j| tl.fold_at(j).is_some_and(|f| t >= f.start && t < f.end))
            .collect();
        let folds = (0..joints).map(|j| tl.fold_at(j).map(|f| f.fold)).collect();
        ChainState {
            time: t,
            poses,
            magnets,
            moving,
            folding,
            folds,
        }
    }

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
