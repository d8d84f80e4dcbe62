//! The result of a free-body run ([`FreeBodyRun`]): the chain's own motion in the joint-angle
//! reference's terms (a [`ReferenceRun`]: events, folds, outcome, recorded states of every
//! magnet and joint, so that summaries, the collision check, the pictures and the viewer
//! read it as they read any run), with what only a free body has: where tile 0 went and the
//! chain's momentum.

use crate::reference::free_body::options::FreeBodyOptions;
use crate::reference::free_body::system::Momentum;
use crate::reference::ReferenceRun;
use crate::timeline::Summary;

/// The result of a free-body run.
#[derive(Debug)]
pub struct FreeBodyRun {
    /// The run in the reference's terms: the chain's shape over time is tile 0's frame's
    /// (every picture draws the chain in it), its events and outcome.
    pub run: ReferenceRun,
    /// The options used.
    pub options: FreeBodyOptions,
    /// Tile 0's pose in the world `(time s, [x m, y m, heading rad])`, at most about 4,100
    /// samples evenly thinned over the steps, the last at the end.
    pub base: Vec<(f64, [f64; 3])>,
    /// With [`FreeBodyOptions::track_momentum`]: the chain's momentum at the start of every
    /// step.
    pub momentum: Vec<Momentum>,
    /// The most rigid groups (bodies between turning joints) at once.
    pub most_groups: usize,
}

impl FreeBodyRun {
    /// The summary (as [`ReferenceRun::to_summary`]).
    pub fn to_summary(&self) -> Summary {
        self.run.to_summary()
    }

    /// When the last event happens, s.
    pub fn duration(&self) -> f64 {
        self.run.duration()
    }
}
