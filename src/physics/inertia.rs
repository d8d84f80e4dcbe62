//! The inertial model's parameters ([`Inertia`]): magnet mass and drag, Coulomb friction,
//! the tiles' rotational inertia and drag per swung tile, and the restitution of a magnet
//! or a fold meeting its wall. Every default is an estimate, with its reasoning and range,
//! since the thesis measures none of them (docs/physics.md, "Physical parameters").
//!
//! With them a magnet of the thesis design has an inertial time `m / gamma` of about 5 ms,
//! short against a move (tens of ms): its motion is inertial but well damped, and it bounces
//! at its path's end as the thesis saw (7.3.1). The overdamped model
//! ([`crate::model::Dynamics::Overdamped`]) is the limit `m -> 0` at a drag large
//! enough to make every move slow.

/// Default magnet drag in the inertial model, N s/m: 0.05. Estimate: water pushed round a
/// 3 mm magnet and sheared in a thin film under its 7 mm^2 base (Stokes-like drag of a 3 mm
/// body in water, `6 pi eta r` = 3e-5 N s/m, is the floor; a 1-10 um film of water under the
/// base gives `eta A / h` = 7e-4 to 7e-3 N s/m, of silicone oil up to 1 N s/m): range 1e-3 to
/// 1 N s/m. The overdamped model's 5 N s/m ([`crate::physics::DEFAULT_DRAG`]) lies above it.
pub(crate) const DEFAULT_INERTIAL_DRAG: f64 = 0.05;

/// Default rotational inertia of one tile about a hinge, kg m^2: 1.5e-6 (a 30 mm octagon of
/// printed plastic about 5 mm thick, about 5 g with its magnets, its centre about 15 mm from
/// the hinge).
pub(crate) const DEFAULT_TILE_INERTIA: f64 = 1.5e-6;

/// Default rotational drag of one swung tile, N m s: 3e-7 (a tile turning on water: the drag
/// of its wetted underside and edges at a lever of about 15 mm).
pub(crate) const DEFAULT_TILE_ROTATIONAL_DRAG: f64 = 3e-7;

/// Default coefficient of restitution of a magnet (or fold) meeting its end: 0.3 (a plated
/// magnet on a printed plastic wall, damped by the liquid; range 0 to 0.6).
pub(crate) const DEFAULT_RESTITUTION: f64 = 0.3;

/// The inertial model's parameters. Defaults: the design's magnet as an NdFeB cylinder
/// ([`crate::Design::cylinder_mass`], 0.265 g for the thesis magnets; the thesis' 0.625 g is
/// the design's `magnet_mass`, used when `magnet_mass_g` is set to it), drag
/// 0.05 N s/m, no Coulomb friction, 1.5e-6 kg m^2 and 3e-7 N m s per swung
/// tile, restitution 0.3 (the constants in `physics/inertia.rs` say where each comes from).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Inertia {
    /// Mass of a magnet, g; `None` for the NdFeB cylinder of the design's magnet size.
    pub magnet_mass_g: Option<f64>,
    /// Drag of a magnet in its channel, N s/m.
    pub drag: f64,
    /// Coulomb (sliding) friction of a magnet, N: it opposes motion, and a magnet at rest
    /// starts only when the force along its path exceeds it.
    pub coulomb: f64,
    /// Rotational inertia per swung tile, kg m^2. A joint's inertia is this times the
    /// number of tiles downstream of it (the part it swings): a lower bound, since the far
    /// tiles of a long tail swing on a longer lever.
    pub tile_inertia: f64,
    /// Rotational drag per swung tile, N m s (a joint's drag grows with its tail likewise).
    pub tile_rotational_drag: f64,
    /// Coefficient of restitution at a path's end or a fold's wall, in [0, 1).
    pub restitution: f64,
}

impl Default for Inertia {
    fn default() -> Inertia {
        Inertia {
            magnet_mass_g: None,
            drag: DEFAULT_INERTIAL_DRAG,
            coulomb: 0.0,
            tile_inertia: DEFAULT_TILE_INERTIA,
            tile_rotational_drag: DEFAULT_TILE_ROTATIONAL_DRAG,
            restitution: DEFAULT_RESTITUTION,
        }
    }
}

impl Inertia {
    /// Another restitution of the walls (0: dead stop, 1: elastic).
    pub fn with_restitution(mut self, restitution: f64) -> Inertia {
        self.restitution = restitution;
        self
    }

    /// The mass of a magnet of `design`, kg.
    pub fn magnet_mass_kg(&self, design: &crate::Design) -> f64 {
        self.magnet_mass_g.unwrap_or_else(|| design.cylinder_mass()) * 1e-3
    }

    /// The same with another magnet drag, N s/m.
    pub fn with_drag(mut self, drag: f64) -> Inertia {
        self.drag = drag;
        self
    }

    /// The same with a magnet mass, g.
    pub fn with_magnet_mass(mut self, grams: f64) -> Inertia {
        self.magnet_mass_g = Some(grams);
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inertial_time_is_milliseconds() {
        let d = crate::Design::thesis();
        let i = Inertia::default();
        let tau = i.magnet_mass_kg(&d) / i.drag;
        assert!(tau > 2e-3 && tau < 2e-2, "{tau}");
        assert_eq!(
            Inertia::default()
                .with_magnet_mass(0.625)
                .magnet_mass_kg(&d),
            0.625e-3
        );
    }
}
