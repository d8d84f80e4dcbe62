//! Each tile as a rigid body on the water ([`TileBodies`]): its mass and moment of inertia
//! (the printed plate, its two magnets, and on tile 0 the reaction initiator it carries),
//! and the water's drag on it, from the design's physical parameters
//! ([`crate::physics::TileBody`]: the tile's mass, the water's viscosity, film, density and
//! form drag), the same figures every model uses.
//!
//! **Mass.** The plate is a uniform regular octagon `w` across the flats: inertia
//! `m J / A` about its centre (`A` its area, `J` its polar area moment). The magnets are
//! point masses at their rest points and the RI a point mass at its place on tile 0: in the
//! free-body equations a magnet's mass rides with its tile (its slide along its path, a few
//! millimetres, moves less than 0.3% of a tile's inertia about its centre).
//!
//! **Drag** (docs/free-body.md gives the sources and ranges). Linear film drag: the tile
//! glides on a film of water `h` thick, sheared at its speed (Couette flow): a force
//! `-mu A / h v` at the centre and a torque `-mu J / h w` about it. Optional quadratic form
//! drag of the immersed edge: `-rho C_d (w draft) |v| v / 2` at the centre, and for a turn,
//! each of the eight sides of length `a` pushing water at the normal speed `w t` (`t` along
//! the side from its middle): `-rho C_d draft a^4 |w| w / 8` summed over the sides. The
//! draft is the depth at which the tile floats with its magnets.

use crate::physics::TileBody as Plate;
use crate::timeline::Geometry;

/// One tile's mass moments about its centre in its own frame (kg, kg m, kg m^2) and its drags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TileBody {
    /// Mass, kg.
    pub(crate) m: f64,
    /// First moment about the centre, kg m (tile frame).
    pub(crate) s: [f64; 2],
    /// Second moment about the centre, kg m^2.
    pub(crate) j: f64,
    /// Linear drag of a translation, N s/m.
    pub(crate) drag: f64,
    /// Linear drag of a turn about the centre, N m s.
    pub(crate) rotational_drag: f64,
    /// Form drag factor of a translation `rho C_d w draft / 2`, kg/m.
    pub(crate) form: f64,
    /// Form drag factor of a turn, kg m^2.
    pub(crate) rotational_form: f64,
}

/// Every tile's body.
#[derive(Clone, Debug)]
pub(crate) struct TileBodies {
    pub(crate) tiles: Vec<TileBody>,
    /// Whether any tile has form drag.
    pub(crate) form: bool,
}

impl TileBodies {
    /// The tiles of `geometry`, each from its design's physical parameters, its magnets of
    /// `magnet_mass_kg(tile)` each.
    pub(crate) fn new(geometry: &Geometry, magnet_mass_kg: impl Fn(usize) -> f64) -> TileBodies {
        let ri = geometry.ri();
        let mut form = false;
        let tiles = (0..geometry.tiles())
            .map(|t| {
                let plate = Plate::of(geometry.design(t));
                form |= plate.form > 0.0;
                let mm = magnet_mass_kg(t);
                let mut points = vec![
                    (mm, geometry.path(2 * t).rest()),
                    (mm, geometry.path(2 * t + 1).rest()),
                ];
                if t == 0 {
                    points.push((mm, (ri.position.x, ri.position.y)));
                }
                let (mut m, mut s, mut j) = (plate.mass, [0.0, 0.0], plate.inertia);
                for (mass, p) in points {
                    let (x, y) = (p.0 * 1e-3, p.1 * 1e-3);
                    m += mass;
                    s[0] += mass * x;
                    s[1] += mass * y;
                    j += mass * (x * x + y * y);
                }
                TileBody {
                    m,
                    s,
                    j,
                    drag: plate.drag,
                    rotational_drag: plate.rotational_drag,
                    form: plate.form,
                    rotational_form: plate.rotational_form,
                }
            })
            .collect();
        TileBodies { tiles, form }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::timeline::TileDesigns;
    use crate::Chain;

    #[test]
    fn the_thesis_tile_on_water() {
        let g =
            Geometry::from_designs(&Chain::parse("SS").unwrap(), &TileDesigns::default()).unwrap();
        let b = TileBodies::new(&g, |_| 0.265e-3);
        // 3 g plate and two 0.265 g magnets; the RI rides on tile 0
        assert!((b.tiles[1].m - 3.53e-3).abs() < 1e-12);
        assert!((b.tiles[0].m - 3.795e-3).abs() < 1e-12);
        // a 0.25 mm film: 2.98e-3 N s/m, a plate's inertial time m / drag of about 1 s
        assert!(
            (b.tiles[1].drag - 2.982e-3).abs() < 1e-6,
            "{}",
            b.tiles[1].drag
        );
        assert_eq!(b.tiles[1].form, 0.0);
        assert!(!b.form);
        // the magnets sit either side of the centre: tile 1's first moment is small against
        // m w, and its second moment is the plate's plus the magnets'
        let plate = Plate::of(g.design(1));
        assert!(b.tiles[1].s[0].abs() < 1e-3 * b.tiles[1].m * 0.03);
        assert!(b.tiles[1].j > plate.inertia);
    }
}
