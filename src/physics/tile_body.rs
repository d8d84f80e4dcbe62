//! A tile as a rigid body on the water ([`TileBody`]): its mass and moment of inertia, and
//! the drag of the water on it, from its design (SPEC section 3; the physical parameters of
//! [`crate::Design`]).
//!
//! **Mass.** The printed tile ([`crate::Design::tile_mass`]) as a uniform octagonal plate:
//! inertia `m J / A` about its centre, `A` the octagon's area and `J` its polar area moment.
//! Its two magnets are separate point masses (the models place them on their paths).
//!
//! **Drag.** The tile glides on a film of water `h` thick ([`crate::Design::water_film`]),
//! sheared at the tile's speed: the viscous stress `mu v / h` over its underside gives a
//! force `-mu A / h v` at the centre for a translation and a torque `-mu J / h w` about it for
//! a turn (Couette flow; `mu` the viscosity). The same plate's mass and drag are spread
//! alike, so a tile's inertial time `m / (mu A / h)` is the same translating or turning
//! (1.0 s for the thesis tile on 0.25 mm of water). Optionally, the immersed edge's form drag
//! `rho C_d (w draft) |v| v / 2` ([`crate::Design::form_drag`]), the draft being the depth at
//! which the tile and its magnets float.

use crate::{Design, Octagon};

/// A tile's mass, inertia and water drag, SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TileBody {
    /// Mass of the printed tile, magnets excluded, kg.
    pub mass: f64,
    /// Moment of inertia about its centre, magnets excluded, kg m^2.
    pub inertia: f64,
    /// Linear drag of a translation, N s/m.
    pub drag: f64,
    /// Linear drag of a turn about its centre, N m s.
    pub rotational_drag: f64,
    /// Form drag factor of a translation `rho C_d (w draft) / 2`, kg/m (0: none).
    pub form: f64,
    /// Form drag factor of a turn about the centre, kg m^2: each of the eight sides of length
    /// `a` pushing water at the normal speed `w t` (`t` along the side from its middle),
    /// `rho C_d draft a^4 / 8` summed over the sides (0: none).
    pub rotational_form: f64,
    /// The depth at which the tile floats with its magnets, m.
    pub draft: f64,
}

impl TileBody {
    /// The tile of `design`.
    pub(crate) fn of(design: &Design) -> TileBody {
        let w = design.tile_width * 1e-3;
        let (area, polar) = octagon_moments(w);
        let mass = design.tile_mass * 1e-3;
        let per_film = design.water_viscosity / (design.water_film * 1e-3);
        let total = mass + 2.0 * design.magnet_mass * 1e-3;
        let draft = total / (design.water_density * area);
        let k = 0.5 * design.water_density * design.form_drag * draft;
        TileBody {
            mass,
            inertia: mass * polar / area,
            drag: per_film * area,
            rotational_drag: per_film * polar,
            form: k * w,
            rotational_form: k * Octagon::new(w).side().powi(4),
            draft,
        }
    }
}

/// The area (m^2) and the polar area moment about the centre (m^4) of a regular octagon
/// `w` metres across the flats: triangles from the centre to each side.
pub(crate) fn octagon_moments(w: f64) -> (f64, f64) {
    let v = Octagon::new(w).vertices();
    let (mut area, mut polar) = (0.0, 0.0);
    for i in 0..8 {
        let (a, b) = (v[i], v[(i + 1) % 8]);
        let t = 0.5 * (a.0 * b.1 - a.1 * b.0);
        area += t;
        polar += t / 6.0 * (a.0 * a.0 + a.1 * a.1 + b.0 * b.0 + b.1 * b.1 + a.0 * b.0 + a.1 * b.1);
    }
    (area, polar)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_thesis_tile_on_water() {
        let t = TileBody::of(&Design::thesis());
        // area 2 (sqrt2 - 1) w^2 = 7.456 cm^2; a disc of the same area has J = A^2 / (2 pi),
        // the octagon a little more (its corners)
        let (area, polar) = octagon_moments(0.03);
        assert!((area - 2.0 * (2f64.sqrt() - 1.0) * 9e-4).abs() < 1e-15);
        let disc = area * area / (2.0 * std::f64::consts::PI);
        assert!(polar > disc && polar < 1.01 * disc, "{polar} {disc}");
        // 3 g: inertia 3e-3 J / A = 3.6e-7 kg m^2; a 0.25 mm film's drag 2.98e-3 N s/m, the
        // same inertial time both ways (1.0 s)
        assert!((t.inertia - 3.56e-7).abs() < 0.03e-7, "{}", t.inertia);
        assert!((t.drag - 2.982e-3).abs() < 1e-6, "{}", t.drag);
        let (tau, tau_rot) = (t.mass / t.drag, t.inertia / t.rotational_drag);
        assert!(
            (tau - tau_rot).abs() < 1e-12 && (tau - 1.006).abs() < 0.001,
            "{tau}"
        );
        // it floats 4.75 mm deep with its magnets (3.53 g on 7.46 cm^2), in the thesis'
        // 5 mm of water; no form drag by default
        assert!((t.draft - 4.75e-3).abs() < 0.01e-3, "{}", t.draft);
        assert_eq!(t.form, 0.0);
    }
}
