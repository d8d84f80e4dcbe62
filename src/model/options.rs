//! The options of the model ([`ModelOptions`]): which pairs interact, the pair law and the
//! dynamics. The physical parameters (masses, drags, friction, restitution, the water) are
//! the design's ([`crate::Design`]), so that one file states them for every model.

use crate::model::Dynamics;
use crate::physics::{ForceLaw, DEFAULT_CUTOFF};

/// Options of the model. Defaults: cutoff [`ModelOptions::DEFAULT_CUTOFF`] (3), the point-dipole law,
/// overdamped dynamics, no distance cutoff.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ModelOptions {
    /// Pairs at most this many apart in chain index interact (at least 1).
    pub cutoff: usize,
    /// The pair law.
    pub force_law: ForceLaw,
    /// How the chain answers the forces (default [`Dynamics::Overdamped`]).
    pub dynamics: Dynamics,
    /// Pairs nearer than this (mm) interact too, however far apart in chain index (found on
    /// a grid); `None` (the default) for the chain-index
    /// cutoff alone. Such pairs lie outside the Jacobian's band, which ROS2 then only
    /// approximates. 90 mm (three tile widths) keeps every pair whose force exceeds 0.07% of
    /// the bonded rest force ((14.4 / 90)^4).
    pub distance_cutoff: Option<f64>,
}

impl Default for ModelOptions {
    fn default() -> ModelOptions {
        ModelOptions {
            cutoff: DEFAULT_CUTOFF,
            force_law: ForceLaw::default(),
            dynamics: Dynamics::default(),
            distance_cutoff: None,
        }
    }
}

impl ModelOptions {
    /// The default chain-index cutoff of the pair forces: each magnet feels its three nearest
    /// neighbours each way.
    pub const DEFAULT_CUTOFF: usize = DEFAULT_CUTOFF;

    /// Another chain-index cutoff.
    pub fn with_cutoff(mut self, cutoff: usize) -> ModelOptions {
        self.cutoff = cutoff;
        self
    }
    /// Another pair law.
    pub fn with_force_law(mut self, force_law: ForceLaw) -> ModelOptions {
        self.force_law = force_law;
        self
    }
    /// Other dynamics.
    pub fn with_dynamics(mut self, dynamics: Dynamics) -> ModelOptions {
        self.dynamics = dynamics;
        self
    }

    /// A distance cutoff, mm (pairs nearer than it interact whatever their chain index;
    /// `None`: the chain-index cutoff alone).
    pub fn with_distance_cutoff(mut self, mm: Option<f64>) -> ModelOptions {
        self.distance_cutoff = mm;
        self
    }
}
