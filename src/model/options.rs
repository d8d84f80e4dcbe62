//! The options of the reference model ([`ModelOptions`]): drags, friction, which pairs
//! interact, the pair law and the dynamics.

use crate::model::Dynamics;
use crate::physics::{ForceLaw, DEFAULT_CUTOFF, DEFAULT_DRAG, DEFAULT_ROTATIONAL_DRAG};

/// Options of the reference model. Defaults: drag [`ModelOptions::DEFAULT_DRAG`] (5 N s/m), rotational drag
/// 1.125e-5 N m s (the magnet drag times the square of the thesis' magnet radius, 1.5 mm),
/// no static friction, cutoff [`ModelOptions::DEFAULT_CUTOFF`] (3), the
/// point-dipole law.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ModelOptions {
    /// Drag of a magnet in its channel, N s/m.
    pub drag: f64,
    /// Drag of a joint turning, N m s.
    pub rotational_drag: f64,
    /// Static friction threshold, N: a magnet starts (and keeps moving) only while the force
    /// along its path exceeds it; it also slows a moving magnet (Coulomb friction).
    pub static_friction: f64,
    /// Pairs at most this many apart in chain index interact (at least 1).
    pub cutoff: usize,
    /// The pair law.
    pub force_law: ForceLaw,
    /// How the chain answers the forces (default [`Dynamics::Overdamped`], which uses
    /// `drag` and `rotational_drag`; [`Dynamics::Inertial`] carries its own parameters).
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
            drag: DEFAULT_DRAG,
            rotational_drag: DEFAULT_ROTATIONAL_DRAG,
            static_friction: 0.0,
            cutoff: DEFAULT_CUTOFF,
            force_law: ForceLaw::default(),
            dynamics: Dynamics::default(),
            distance_cutoff: None,
        }
    }
}

impl ModelOptions {
    /// The default drag of a magnet in its channel, N s/m: an assumed value that makes a
    /// straight-path move of the thesis design take about a third of a second.
    pub const DEFAULT_DRAG: f64 = DEFAULT_DRAG;
    /// The default chain-index cutoff of the pair forces: each magnet feels its three nearest
    /// neighbours each way.
    pub const DEFAULT_CUTOFF: usize = DEFAULT_CUTOFF;

    /// Another magnet drag, N s/m.
    pub fn with_drag(mut self, drag: f64) -> ModelOptions {
        self.drag = drag;
        self
    }
    /// Another rotational drag, N m s.
    pub fn with_rotational_drag(mut self, drag: f64) -> ModelOptions {
        self.rotational_drag = drag;
        self
    }
    /// A static friction threshold, N.
    pub fn with_static_friction(mut self, f: f64) -> ModelOptions {
        self.static_friction = f;
        self
    }
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
