//! The options of a free-body run ([`FreeBodyOptions`]); why one cannot be made is a
//! [`ReferenceError`] (the free body's own options out of range, or what it does not take).

use crate::reference::{ReferenceError, ReferenceOptions};

/// Options of a free-body run. Defaults: the reference's options (Dormand-Prince, tolerance
/// 1e-8, the model's defaults with the inertial dynamics), no momentum track. The physical
/// parameters (the tiles' and magnets' masses, the drags, the water) are the design's
/// ([`crate::Design`]), the same every model uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeBodyOptions {
    /// The integrator's tolerance, the step limit, the states kept and the model (its
    /// dynamics must be inertial).
    pub reference: ReferenceOptions,
    /// Keep the chain's momentum at the start of every step ([`crate::reference::FreeBodyRun::momentum`]).
    pub track_momentum: bool,
}

impl Default for FreeBodyOptions {
    fn default() -> FreeBodyOptions {
        FreeBodyOptions {
            reference: ReferenceOptions::default().with_model(
                crate::model::ModelOptions::default()
                    .with_dynamics(crate::model::Dynamics::Inertial),
            ),
            track_momentum: false,
        }
    }
}

impl FreeBodyOptions {
    /// Other reference options (tolerance, steps, recording, model).
    pub fn with_reference(mut self, reference: ReferenceOptions) -> FreeBodyOptions {
        self.reference = reference;
        self
    }
    /// Keep the momentum at every step.
    pub fn with_momentum_track(mut self) -> FreeBodyOptions {
        self.track_momentum = true;
        self
    }

    pub(crate) fn validate(&self) -> Result<(), ReferenceError> {
        if self.reference.method != crate::ode::Method::Dopri5 {
            return Err(ReferenceError::FreeBodyUnsupported {
                what: "the ROS2 method",
                why: "the free-body reference steps with Dormand-Prince 5(4)",
            });
        }
        if self.reference.model.distance_cutoff.is_some() {
            return Err(ReferenceError::FreeBodyUnsupported {
                what: "a distance cutoff",
                why: "the free-body reference weighs pairs by chain index only (the pairs between its rigid groups)",
            });
        }
        Ok(())
    }
}
