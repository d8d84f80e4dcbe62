//! Each tile as a rigid body on the water ([`TileBodies`]): its mass and moment of inertia
//! (the printed plate, its two magnets, and on tile 0 the reaction initiator it carries),
//! and the water's drag on it, from the free-body options (the water, the tile's mass).
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

use crate::timeline::Geometry;
use crate::Octagon;

/// The water the tiles float on. Defaults: water at 20 C (viscosity 1.0e-3 Pa s, density
/// 998 kg/m^3), a sheared film of 0.25 mm under each tile, no form drag.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Water {
    /// Dynamic viscosity, Pa s (water: 1.0e-3 at 20 C, 0.89e-3 at 25 C).
    pub viscosity: f64,
    /// Thickness of the sheared film under a tile, mm (0.25: a tile floating 4.75 mm deep in
    /// the thesis' 5 mm of water; range 0.1 to 1.5, a plate moving for a second in deep
    /// water shears about `sqrt(nu t)` = 1 mm).
    pub film_mm: f64,
    /// Density, kg/m^3.
    pub density: f64,
    /// Form drag coefficient `C_d` of a tile's immersed edge (0: none; a blunt plate edge
    /// about 1 to 2).
    pub form_drag: f64,
}

impl Default for Water {
    fn default() -> Water {
        Water {
            viscosity: 1.0e-3,
            film_mm: 0.25,
            density: 998.0,
            form_drag: 0.0,
        }
    }
}

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
    /// The tiles of `geometry`, each plate `tile_mass_g` grams, its magnets of
    /// `magnet_mass_kg(tile)` each, on `water`.
    pub(crate) fn new(
        geometry: &Geometry,
        tile_mass_g: f64,
        magnet_mass_kg: impl Fn(usize) -> f64,
        water: &Water,
    ) -> TileBodies {
        let w = geometry.w * 1e-3;
        let (area, polar) = octagon_moments(w);
        let side = Octagon::new(w).side();
        let plate = tile_mass_g * 1e-3;
        let per_film = water.viscosity / (water.film_mm * 1e-3);
        let ri = geometry.ri();
        let tiles = (0..geometry.tiles())
            .map(|t| {
                let mm = magnet_mass_kg(t);
                let mut points = vec![
                    (mm, geometry.path(2 * t).rest()),
                    (mm, geometry.path(2 * t + 1).rest()),
                ];
                let total = plate + 2.0 * mm;
                if t == 0 {
                    points.push((mm, (ri.position.x, ri.position.y)));
                }
                let (mut m, mut s, mut j) = (plate, [0.0, 0.0], plate * polar / area);
                for (mass, p) in points {
                    let (x, y) = (p.0 * 1e-3, p.1 * 1e-3);
                    m += mass;
                    s[0] += mass * x;
                    s[1] += mass * y;
                    j += mass * (x * x + y * y);
                }
                let draft = total / (water.density * area);
                let k = 0.5 * water.density * water.form_drag * draft;
                TileBody {
                    m,
                    s,
                    j,
                    drag: per_film * area,
                    rotational_drag: per_film * polar,
                    form: k * w,
                    rotational_form: k * side.powi(4),
                }
            })
            .collect();
        TileBodies {
            tiles,
            form: water.form_drag > 0.0,
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
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::timeline::TileDesigns;
    use crate::Chain;

    #[test]
    fn the_thesis_tile_on_water() {
        let (area, polar) = octagon_moments(0.03);
        // area 2 (sqrt2 - 1) w^2; a disc of that area has J = A^2 / (2 pi), the octagon a
        // little more (its corners)
        assert!((area - 2.0 * (2f64.sqrt() - 1.0) * 9e-4).abs() < 1e-15);
        let disc = area * area / (2.0 * std::f64::consts::PI);
        assert!(polar > disc && polar < 1.01 * disc, "{polar} {disc}");
        let g =
            Geometry::from_designs(&Chain::parse("SS").unwrap(), &TileDesigns::default()).unwrap();
        let b = TileBodies::new(&g, 3.0, |_| 0.265e-3, &Water::default());
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
        // the magnets sit either side of the centre: tile 1's first moment is small against
        // m w, and its second moment is the plate's plus the magnets'
        assert!(b.tiles[1].s[0].abs() < 1e-3 * b.tiles[1].m * 0.03);
        assert!(b.tiles[1].j > 3e-3 * polar / area);
    }
}
