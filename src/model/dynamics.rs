//! Which dynamics the reference integrates: overdamped (first order, the stiff limit) or
//! inertial (second order, [`Inertia`]). A choice of its own, so that the model
//! ([`crate::model::Model`]) and the inertial driver both name it without importing
//! each other.

use crate::physics::Inertia;

/// How the chain answers the forces.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[non_exhaustive]
pub enum Dynamics {
    /// First order: every velocity proportional to its drive (drag
    /// [`crate::model::ModelOptions::drag`] and
    /// [`crate::model::ModelOptions::rotational_drag`]); the limit of negligible mass,
    /// and the stiff case. The default.
    #[default]
    Overdamped,
    /// Second order, with mass, drag, friction and bouncing walls ([`Inertia`]).
    Inertial(Inertia),
}

impl Dynamics {
    /// The short name: `overdamped` or `inertial`.
    pub fn name(self) -> &'static str {
        match self {
            Dynamics::Overdamped => "overdamped",
            Dynamics::Inertial(_) => "inertial",
        }
    }
}
