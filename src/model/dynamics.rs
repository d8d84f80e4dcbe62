//! Which dynamics the models integrate: overdamped (first order, the stiff limit) or
//! inertial (second order). The physical parameters of both are the design's
//! ([`crate::Design`]: masses, drags, restitution, the water).

/// How the chain answers the forces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Dynamics {
    /// First order: every velocity proportional to its drive, against the drags alone; the
    /// limit of negligible mass, and the stiff case. The default.
    #[default]
    Overdamped,
    /// Second order, with the masses, drags, friction and bouncing walls of the design.
    Inertial,
}

impl Dynamics {
    /// The short name: `overdamped` or `inertial`.
    pub fn name(self) -> &'static str {
        match self {
            Dynamics::Overdamped => "overdamped",
            Dynamics::Inertial => "inertial",
        }
    }

    /// Whether the dynamics carry masses.
    pub fn is_inertial(self) -> bool {
        self == Dynamics::Inertial
    }
}
