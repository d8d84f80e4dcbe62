//! The options of a free-body run ([`FreeBodyOptions`]); why one cannot be made is a
//! [`ReferenceError`] (the free body's own options out of range, or what it does not take).

use crate::reference::free_body::tile_body::Water;
use crate::reference::{ReferenceError, ReferenceOptions};

/// Default mass of a printed tile without its magnets, g: 3.0. Estimate: the thesis' tiles
/// float in about 5 mm of water (7.3), so with their two magnets they draw less than 5 mm:
/// at most 998 kg/m^3 x 7.46 cm^2 x 5 mm = 3.7 g in all, 3.2 g without the magnets (a solid
/// printed octagon 30 mm across and 7.5 mm thick would weigh 6.7 g and sink). Range 2 to 3.2.
pub(crate) const DEFAULT_TILE_MASS: f64 = 3.0;

/// Options of a free-body run. Defaults: the reference's options (Dormand-Prince, tolerance
/// 1e-8, the model's defaults with the inertial dynamics), 3 g a tile, water at 20 C
/// (viscosity 1.0e-3 Pa s, density 998 kg/m^3) on a 0.25 mm film under each tile without
/// form drag, no momentum track.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeBodyOptions {
    /// The integrator's tolerance, the step limit, the states kept and the model (its
    /// dynamics must be inertial: the magnets' masses and drags, the restitution).
    pub reference: ReferenceOptions,
    /// Mass of a printed tile without its magnets, g.
    pub tile_mass_g: f64,
    /// The water ([`FreeBodyOptions::with_water_viscosity`] and the other `with_water_*`).
    pub(crate) water: Water,
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
    /// Another dynamic viscosity of the water, Pa s (water: 1.0e-3 at 20 C, 0.89e-3 at 25 C;
    /// 0: no film drag).
    pub fn with_water_viscosity(mut self, pa_s: f64) -> FreeBodyOptions {
        self.water.viscosity = pa_s;
        self
    }
    /// Another thickness of the sheared film under a tile, mm (0.25: a tile floating 4.75 mm
    /// deep in the thesis' 5 mm of water; range 0.1 to 1.5, a plate moving for a second in
    /// deep water shears about `sqrt(nu t)` = 1 mm).
    pub fn with_water_film(mut self, mm: f64) -> FreeBodyOptions {
        self.water.film_mm = mm;
        self
    }
    /// Another density of the water, kg/m^3.
    pub fn with_water_density(mut self, kg_m3: f64) -> FreeBodyOptions {
        self.water.density = kg_m3;
        self
    }
    /// Another form drag coefficient `C_d` of a tile's immersed edge (0: none; a blunt plate
    /// edge about 1 to 2).
    pub fn with_water_form_drag(mut self, cd: f64) -> FreeBodyOptions {
        self.water.form_drag = cd;
        self
    }
    /// Keep the momentum at every step.
    pub fn with_momentum_track(mut self) -> FreeBodyOptions {
        self.track_momentum = true;
        self
    }

    pub(crate) fn validate(&self) -> Result<(), ReferenceError> {
        let bad = |name, value, expected| {
            Err(ReferenceError::FreeBodyOption {
                name,
                value,
                expected,
            })
        };
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
