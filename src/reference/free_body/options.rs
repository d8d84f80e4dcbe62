//! The options of a free-body run ([`FreeBodyOptions`]) and why one cannot be made
//! ([`FreeBodyError`]).

use crate::reference::free_body::tile_body::Water;
use crate::reference::{ReferenceError, ReferenceOptions};

/// Default mass of a printed tile without its magnets, g: 3.0. Estimate: the thesis' tiles
/// float in about 5 mm of water (7.3), so with their two magnets they draw less than 5 mm:
/// at most 998 kg/m^3 x 7.46 cm^2 x 5 mm = 3.7 g in all, 3.2 g without the magnets (a solid
/// printed octagon 30 mm across and 7.5 mm thick would weigh 6.7 g and sink). Range 2 to 3.2.
pub(crate) const DEFAULT_TILE_MASS: f64 = 3.0;

/// Options of a free-body run. Defaults: the reference's options (Dormand-Prince, tolerance
/// 1e-8, the model's defaults with the inertial dynamics), 3 g a tile, water at
/// 20 C on a 0.25 mm film without form drag ([`Water`]), no momentum track.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeBodyOptions {
    /// The integrator's tolerance, the step limit, the states kept and the model (its
    /// dynamics must be inertial: the magnets' masses and drags, the restitution).
    pub reference: ReferenceOptions,
    /// Mass of a printed tile without its magnets, g.
    pub tile_mass_g: f64,
    /// The water.
    pub water: Water,
    /// Keep the chain's momentum at the start of every step ([`crate::reference::FreeBodyRun::momentum`]).
    pub track_momentum: bool,
}

impl Default for FreeBodyOptions {
    fn default() -> FreeBodyOptions {
        FreeBodyOptions {
            reference: ReferenceOptions::default().with_model(
                crate::model::ModelOptions::default().with_dynamics(
                    crate::model::Dynamics::Inertial(crate::physics::Inertia::default()),
                ),
            ),
            tile_mass_g: DEFAULT_TILE_MASS,
            water: Water::default(),
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
    /// Another tile mass, g.
    pub fn with_tile_mass(mut self, grams: f64) -> FreeBodyOptions {
        self.tile_mass_g = grams;
        self
    }
    /// Other water.
    pub fn with_water(mut self, water: Water) -> FreeBodyOptions {
        self.water = water;
        self
    }
    /// Keep the momentum at every step.
    pub fn with_momentum_track(mut self) -> FreeBodyOptions {
        self.track_momentum = true;
        self
    }

    pub(crate) fn validate(&self) -> Result<(), FreeBodyError> {
        let bad = |name, value, expected| {
            Err(FreeBodyError::BadOption {
                name,
                value,
                expected,
            })
        };
        if self.reference.method != crate::ode::Method::Dopri5 {
            return Err(FreeBodyError::Unsupported {
                what: "the ROS2 method",
                why: "the free-body reference steps with Dormand-Prince 5(4)",
            });
        }
        if self.reference.model.distance_cutoff.is_some() {
            return Err(FreeBodyError::Unsupported {
                what: "a distance cutoff",
                why: "the free-body reference weighs pairs by chain index only (the pairs between its rigid groups)",
            });
        }
        if !(self.tile_mass_g.is_finite() && self.tile_mass_g > 0.0) {
            return bad("tile_mass", self.tile_mass_g, "a mass > 0 g");
        }
        let w = &self.water;
        for (name, v) in [
            ("water_viscosity", w.viscosity),
            ("water_film", w.film_mm),
            ("water_density", w.density),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return bad(name, v, "a finite number >= 0");
            }
        }
        if !(w.film_mm > 0.0 && w.density > 0.0) {
            return bad(
                "water_film",
                w.film_mm,
                "a film > 0 mm on water of density > 0",
            );
        }
        if !(w.form_drag.is_finite() && w.form_drag >= 0.0) {
            return bad("form_drag", w.form_drag, "a coefficient >= 0");
        }
        Ok(())
    }
}

/// Why a free-body run could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FreeBodyError {
    /// The reference's options or the model refused the input.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
    /// An option out of range.
    #[error("free-body option `{name}` = {value}: expected {expected}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// Something the free-body reference does not do.
    #[error("the free-body reference does not take {what}: {why}")]
    Unsupported {
        /// What was asked for.
        what: &'static str,
        /// Why not.
        why: &'static str,
    },
}
