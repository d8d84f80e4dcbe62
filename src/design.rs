//! Tile design parameters and the path-length inequalities (thesis chapter 6).
//!
//! Along one tile of length `2d`: `c` is the distance from the tile edge to a magnet's final
//! position, `a = s + e` the path length (`s` inside the centre half of the tile, `e` outside
//! it) and `b` the distance between a tile's two magnets at rest, so `2c + 2a + b = 2d`.
//! [`Design::report`] evaluates inequalities (6.1) to (6.10) with their two sides and margins;
//! [`Design::check`] turns the first failure into an error naming it.

use std::f64::consts::PI;

/// Permeability of free space, H/m (the thesis' value, 4 pi 1e-7).
pub(crate) const MU0: f64 = 4.0 * PI * 1e-7;

/// Default wall thickness of a curved path's final point, mm ([`Design::wall`]).
pub(crate) const DEFAULT_WALL: f64 = 0.8;

/// Density of sintered NdFeB, g/cm^3 (manufacturers quote 7.4 to 7.6).
pub(crate) const NDFEB_DENSITY: f64 = 7.5;

/// Default magnet mass, g: a 3 mm x 5 mm cylinder of NdFeB at [`NDFEB_DENSITY`] (0.2651 g).
pub(crate) const DEFAULT_MAGNET_MASS: f64 = 0.265;

/// Tile and magnet design. Lengths in millimetres, mass in grams, remanence in tesla.
///
/// Defaults are the thesis design (SPEC section 4): 30 mm tiles (`d` = 15 mm), `s` = 0.3 mm,
/// path length `a` = 5 mm (so `e` = 4.7 mm), `c = d/2 - e`, 3 mm x 5 mm NdFeB magnets with a
/// remanence of 1.3 T (grade N42, a typical value; the thesis gives no grade), a 0.8 mm wall
/// between a curved path's final point and the tile's diagonal face.
///
/// **Physical parameters.** The design also carries everything the dynamics need, each used
/// by every model that runs (the event engine, the joint-angle and free-body references) or
/// refused where a model cannot use it: the masses of a magnet and of a tile, the drag and
/// friction of a magnet in its channel, the restitution at a wall, and the water the tiles
/// float on (viscosity, the sheared film under a tile, density, form drag). The thesis
/// measures none of the dynamics: every default is an estimate, with its reasoning in the
/// field's documentation and in `docs/physics.md`. The thesis' 0.625 g per magnet does not
/// fit a 3 mm x 5 mm NdFeB cylinder, which weighs 0.265 g at the alloy's density of about
/// 7.5 g/cm^3 ([`Design::cylinder_mass`]): the default is the cylinder's mass, the magnet the
/// model's forces are computed for.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Design {
    /// Across-flats tile width `w`, mm. Default 30.
    pub tile_width: f64,
    /// Half the tile length along the chain, `d`, mm. Default 15 (= w/2).
    pub d: f64,
    /// How far inside the centre half of the tile the magnets rest, `s`, mm. Default 0.3.
    pub s: f64,
    /// Path length outside the centre half, `e`, mm. Default 4.7.
    pub e: f64,
    /// Distance from the tile edge to a magnet's final position, `c`, mm; `None` for the
    /// thesis' layout `c = d/2 - e`. Default `None`.
    pub c: Option<f64>,
    /// Magnet diameter, mm. Default 3.
    pub magnet_diameter: f64,
    /// Magnet height, mm. Default 5.
    pub magnet_height: f64,
    /// Magnet remanence, T. Default 1.3.
    pub remanence: f64,
    /// Magnet mass, g. Default 0.265: a 3 mm x 5 mm NdFeB cylinder (the thesis quotes 0.625 g,
    /// which does not fit that size; see the type's documentation).
    pub magnet_mass: f64,
    /// Wall thickness between a curved path's final point and the tile's diagonal face
    /// that closes the fold, mm. Default 0.8: a wall that FDM printing (two 0.4 mm
    /// perimeters) and resin printing (about 0.5 mm minimum) both make reliably. The magnet
    /// centre ends `r + wall` from the face ([`Design::fold_clearance`]), unless `c` is given,
    /// which then sets that distance as before (the thesis' layout `c` = 2.8 mm amounts to a
    /// 1.3 mm wall).
    pub wall: f64,
    /// Mass of a printed tile without its magnets, g. Default 3.0. Estimate: the thesis'
    /// tiles float in about 5 mm of water (7.3), so with their two magnets they draw less
    /// than 5 mm: at most 998 kg/m^3 x 7.46 cm^2 x 5 mm = 3.7 g in all, 3.2 g without the
    /// magnets (a solid 30 mm octagon 7.5 mm thick of printed resin would weigh 6.7 g and
    /// sink: the tiles are hollow, their channels water-filled). Range 2 to 3.2 g.
    pub tile_mass: f64,
    /// Drag of a magnet sliding in its channel, N s/m; `None` (default): the dynamics'
    /// estimate, 0.05 N s/m inertial (water and silicone oil round a 3 mm magnet and in a
    /// 1-10 um film under its base: range 1e-3 to 1) or 5 N s/m overdamped (the earlier
    /// assumption that makes every move slow: the overdamped model is the stiff limit).
    pub magnet_drag: Option<f64>,
    /// Coulomb (sliding) friction of a magnet in its channel, N. Default 0 (lubricated;
    /// range 0 to 1 mN). A magnet at rest starts only when the force along its path exceeds
    /// it.
    pub friction: f64,
    /// Coefficient of restitution of a magnet at its path's end or a fold at its walls.
    /// Default 0.3 (a plated magnet on a printed wall, damped by the liquid; range 0 to 0.6;
    /// the thesis saw magnets bounce, 7.3.1).
    pub restitution: f64,
    /// Dynamic viscosity of the water, Pa s. Default 1.0e-3 (water at 20 C; 0.89e-3 at 25 C).
    /// 0 (no water drag) is taken by the inertial models only, as an idealisation; design
    /// files and command lines are held to 1e-5 (air) or more.
    pub water_viscosity: f64,
    /// Thickness of the sheared water under a tile, mm. Default 0.25. Estimate: a tile
    /// (with [`Design::tile_mass`] and its magnets) floats about 4.75 mm deep in the thesis'
    /// container of about 5 mm of water (7.3: "if too much water is used there can be
    /// difficulties with water resistance"), so its underside glides over the floor on a
    /// film of about 0.25 mm, sheared linearly (Couette flow). The depth is "approximately
    /// 5mm": range 0.1 to 1.5 mm (a plate moving for about a second in deep water shears a
    /// layer `sqrt(nu t)` = 1 mm). A tile's linear drag is `mu A / h` translating and
    /// `mu J / h` turning about its centre (`A`, `J` its area and polar area moment).
    pub water_film: f64,
    /// Form drag coefficient of a tile's immersed edge, `C_d` in `F = rho C_d A |v| v / 2`
    /// (`A` the tile's width times its draft): 0 (default) leaves it out; about 1 to 2 for a
    /// blunt plate edge. Only the free-body reference (inertial) integrates it; the other
    /// models refuse a value above 0.
    pub form_drag: f64,
    /// Density of the water, kg/m^3 (form drag; a tile's draft). Default 998.
    pub water_density: f64,
}

impl Default for Design {
    fn default() -> Design {
        Design {
            tile_width: 30.0,
            d: 15.0,
            s: 0.3,
            e: 4.7,
            c: None,
            magnet_diameter: 3.0,
            magnet_height: 5.0,
            remanence: 1.3,
            magnet_mass: DEFAULT_MAGNET_MASS,
            wall: DEFAULT_WALL,
            tile_mass: 3.0,
            magnet_drag: None,
            friction: 0.0,
            restitution: 0.3,
            water_viscosity: 1.0e-3,
            water_film: 0.25,
            form_drag: 0.0,
            water_density: 998.0,
        }
    }
}

/// Why a design was rejected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DesignError {
    /// A parameter that is not a finite number in its allowed range.
    #[error("design parameter `{name}` = {}{}{unit}: expected {expected}", short(*value), if unit.is_empty() { "" } else { " " })]
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// Its unit (`mm`, `T`, `g`).
        unit: &'static str,
        /// What was expected: the range, and why.
        expected: String,
    },
    /// An inequality of thesis chapter 6 that does not hold.
    #[error(
        "inequality ({id}) {statement} fails: {lhs_name} = {lhs:.6} mm, {rhs_name} = {rhs:.6} mm"
    )]
    Inequality {
        /// The thesis' equation number, e.g. `6.9`.
        id: &'static str,
        /// The inequality as written, e.g. `s < e/3`.
        statement: &'static str,
        /// Name of the left side.
        lhs_name: &'static str,
        /// Value of the left side.
        lhs: f64,
        /// Name of the right side.
        rhs_name: &'static str,
        /// Value of the right side.
        rhs: f64,
    },
}

/// How one inequality stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Standing {
    /// It holds with room to spare.
    Holds,
    /// It holds only with equality, at the edge of its range (e.g. (6.1) at `s = 0`: the
    /// chain is marginally stable and any disturbance cascades). A warning, not an error.
    Marginal,
    /// It fails.
    Fails,
}

/// One inequality evaluated for a design.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct InequalityCheck {
    /// The thesis' equation number.
    pub id: &'static str,
    /// The inequality as written.
    pub statement: &'static str,
    /// Left side, name and value (mm).
    pub lhs_name: &'static str,
    /// Left side value, mm.
    pub lhs: f64,
    /// Right side, name.
    pub rhs_name: &'static str,
    /// Right side value, mm.
    pub rhs: f64,
    /// `(rhs - lhs) / max(|lhs|, |rhs|)`: positive when the inequality holds with room.
    pub relative_margin: f64,
    /// Whether it holds.
    pub standing: Standing,
}

/// The physical range of one design field that a design file or a command line may give
/// ([`Design::check_ranges`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FieldRange {
    /// The field's name in the design JSON.
    pub name: &'static str,
    /// The smallest value.
    pub min: f64,
    /// The largest value (times the tile width when `relative_to_width`).
    pub max: f64,
    /// Whether `max` is a multiple of the tile width.
    pub relative_to_width: bool,
    /// The unit.
    pub unit: &'static str,
    /// Why this range.
    pub why: &'static str,
}

/// The physical ranges of the design fields held to a fixed range; the lengths inside a tile
/// (`d`, `s`, `e`, `c`, `magnet_diameter`) are bounded by the tile's own size
/// ([`Design::validate`]).
pub(crate) const RANGES: [FieldRange; 13] = [
    FieldRange {
        name: "tile_width",
        min: 0.01,
        max: 1000.0,
        relative_to_width: false,
        unit: "mm",
        why: "from micrometre-scale tiles (thesis 8.2.1) to a metre",
    },
    FieldRange {
        name: "magnet_height",
        min: 0.0,
        max: 1.0,
        relative_to_width: true,
        unit: "mm",
        why: "a magnet standing in the tile",
    },
    FieldRange {
        name: "remanence",
        min: 0.01,
        max: 2.0,
        relative_to_width: false,
        unit: "T",
        why: "sintered NdFeB is 1.1-1.5 T, ferrites about 0.4 T",
    },
    FieldRange {
        name: "magnet_mass",
        min: 0.0,
        max: 1000.0,
        relative_to_width: false,
        unit: "g",
        why: "a magnet lighter than a kilogram",
    },
    FieldRange {
        name: "wall",
        min: 0.0,
        max: 0.25,
        relative_to_width: true,
        unit: "mm",
        why: "a wall inside the tile's corner",
    },
    FieldRange {
        name: "tile_mass",
        min: 0.0,
        max: 100_000.0,
        relative_to_width: false,
        unit: "g",
        why: "a tile lighter than 100 kg",
    },
    FieldRange {
        name: "magnet_drag",
        min: 0.0,
        max: 1e4,
        relative_to_width: false,
        unit: "N s/m",
        why: "from a free magnet in water (3e-5) to one stuck in grease",
    },
    FieldRange {
        name: "friction",
        min: 0.0,
        max: 10.0,
        relative_to_width: false,
        unit: "N",
        why: "below the pull of any magnet the model knows",
    },
    FieldRange {
        name: "restitution",
        min: 0.0,
        max: 0.99,
        relative_to_width: false,
        unit: "",
        why: "a bounce loses energy",
    },
    FieldRange {
        name: "water_viscosity",
        min: 1e-5,
        max: 100.0,
        relative_to_width: false,
        unit: "Pa s",
        why: "from air (1.8e-5) to honey (about 10)",
    },
    FieldRange {
        name: "water_film",
        min: 1e-3,
        max: 1000.0,
        relative_to_width: false,
        unit: "mm",
        why: "from a micrometre film to a metre of water",
    },
    FieldRange {
        name: "form_drag",
        min: 0.0,
        max: 10.0,
        relative_to_width: false,
        unit: "",
        why: "a plate broadside has about 2",
    },
    FieldRange {
        name: "water_density",
        min: 1.0,
        max: 20_000.0,
        relative_to_width: false,
        unit: "kg/m^3",
        why: "from air to mercury",
    },
];

/// The widest values [`Design::validate`] takes for any field, in the field's unit (zero
/// aside, where a field may be zero): far beyond any tile or magnet, so that no product of
/// them overflows or vanishes (the smallest, 1e-15, leaves room for the library's stress
/// cases such as `s = 1e-12 d`; a fourth power of it, 1e-60, is still far from underflow).
pub(crate) const NUMERIC_RANGE: (f64, f64) = (1e-15, 1e9);

/// A parameter out of its range: `name`, its `value` in `unit`, and what was expected.
fn bad(
    name: &'static str,
    value: f64,
    unit: &'static str,
    expected: String,
) -> Result<(), DesignError> {
    Err(DesignError::BadParameter {
        name,
        value,
        unit,
        expected,
    })
}

fn short(v: f64) -> String {
    crate::short_number(v)
}

/// Relative tolerance under which two sides count as equal (so `s = e/3` given as a fraction
/// of `e` is recognised as the edge despite rounding): 1e-12.
pub(crate) const EQUALITY_TOLERANCE: f64 = 1e-12;

impl Design {
    /// The thesis design.
    pub fn thesis() -> Design {
        Design::default()
    }

    /// The drag of a magnet in its channel, N s/m: `magnet_drag` when the design sets it,
    /// else the dynamics' default (0.05 when `inertial`, else 5; `physics.md` gives the
    /// estimates behind both).
    ///
    /// ```
    /// use foldchain::Design;
    /// assert_eq!(Design::thesis().channel_drag(false), 5.0);
    /// assert_eq!(Design::thesis().channel_drag(true), 0.05);
    /// ```
    pub fn channel_drag(&self, inertial: bool) -> f64 {
        crate::physics::magnet_drag(self, inertial)
    }

    /// The same design with another `s`, mm.
    pub fn with_s(mut self, s: f64) -> Design {
        self.s = s;
        self
    }

    /// The same design with another `e`, mm.
    pub fn with_e(mut self, e: f64) -> Design {
        self.e = e;
        self
    }

    /// The same design with another tile width, mm (and `d` = half of it).
    pub fn with_tile_width(mut self, w: f64) -> Design {
        self.tile_width = w;
        self.d = 0.5 * w;
        self
    }

    /// The path length `a = s + e`, mm.
    pub fn a(&self) -> f64 {
        self.s + self.e
    }

    /// The distance from the tile edge to a magnet's final position, mm.
    pub fn c(&self) -> f64 {
        self.c.unwrap_or(0.5 * self.d - self.e)
    }

    /// The distance from a curved path's final point (the magnet centre) to the diagonal
    /// face of the tile that closes the fold, mm: `c` when it is given, else the magnet
    /// radius plus [`Design::wall`] (2.3 mm for the thesis design). The two magnets of a
    /// folded pair end twice this apart.
    pub fn fold_clearance(&self) -> f64 {
        self.c.unwrap_or(0.5 * self.magnet_diameter + self.wall)
    }

    /// The mass of one magnet as a cylinder of NdFeB (7.5 g/cm^3), g: 0.265 g for the
    /// thesis' 3 mm x 5 mm magnets.
    pub fn cylinder_mass(&self) -> f64 {
        self.magnet_volume_m3() * 1e6 * NDFEB_DENSITY
    }

    /// The rest distance between a tile's two magnets, `b = 2d - 2c - 2a`, mm
    /// (`d - 2s` in the thesis' layout).
    pub fn b(&self) -> f64 {
        2.0 * self.d - 2.0 * self.c() - 2.0 * self.a()
    }

    /// The rest distance between neighbouring magnets of two tiles, `2c + 2a`, mm
    /// (`d + 2s` in the thesis' layout).
    pub fn inter_tile_rest_distance(&self) -> f64 {
        2.0 * self.c() + 2.0 * self.a()
    }

    /// The magnet volume, m^3.
    pub fn magnet_volume_m3(&self) -> f64 {
        let r = 0.5 * self.magnet_diameter * 1e-3;
        PI * r * r * self.magnet_height * 1e-3
    }

    /// The magnetic moment of one magnet, A m^2: `Br V / mu0`.
    pub fn moment(&self) -> f64 {
        self.remanence * self.magnet_volume_m3() / MU0
    }

    /// Checks that every parameter is a finite number of the right sign, that the lengths
    /// make a tile that can be built (the path inside the tile's half, the tile's two magnets
    /// at rest at least a magnet diameter apart), and that no value is so large or small
    /// that the arithmetic overflows (1e-15 to 1e9 in the field's unit). A design file or command line is
    /// held to the narrower physical ranges of [`Design::check_ranges`] as well.
    pub fn validate(&self) -> Result<(), DesignError> {
        self.check_signs()?;
        if let Some(g) = self.magnet_drag.filter(|g| *g <= 0.0) {
            return bad("magnet_drag", g, "N s/m", "a finite number > 0".into());
        }
        if self.restitution >= 1.0 {
            return bad(
                "restitution",
                self.restitution,
                "",
                "a number from 0 up to, not including, 1 (a bounce loses energy)".into(),
            );
        }
        self.check_geometry()?;
        let (lo, hi) = NUMERIC_RANGE;
        for (name, value, unit) in self
            .positive_fields()
            .into_iter()
            .chain(self.non_negative_fields())
        {
            if value > hi || (value > 0.0 && value < lo) {
                return bad(
                    name,
                    value,
                    unit,
                    format!("a number from {} to {} {unit}", short(lo), short(hi)),
                );
            }
        }
        Ok(())
    }

    /// Every field a finite number of the right sign, field by field, so that a NaN or a
    /// negative value is what is named.
    fn check_signs(&self) -> Result<(), DesignError> {
        for (name, value, unit) in self.positive_fields() {
            if !value.is_finite() || value <= 0.0 {
                return Err(DesignError::BadParameter {
                    name,
                    value,
                    unit,
                    expected: "a finite number > 0".into(),
                });
            }
        }
        for (name, value, unit) in self.non_negative_fields() {
            if !value.is_finite() || value < 0.0 {
                return Err(DesignError::BadParameter {
                    name,
                    value,
                    unit,
                    expected: "a finite number >= 0".into(),
                });
            }
        }
        Ok(())
    }

    /// The lengths make a tile that can be built.
    fn check_geometry(&self) -> Result<(), DesignError> {
        if 2.0 * self.d > self.tile_width * (1.0 + EQUALITY_TOLERANCE) {
            return bad(
                "d",
                self.d,
                "mm",
                format!(
                    "at most half the tile width, {} mm (the magnets' track lies inside the tile)",
                    short(0.5 * self.tile_width)
                ),
            );
        }
        if self.magnet_diameter >= self.tile_width {
            return bad(
                "magnet_diameter",
                self.magnet_diameter,
                "mm",
                format!("less than the tile width, {} mm", short(self.tile_width)),
            );
        }
        if self.e >= self.d {
            return bad(
                "e",
                self.e,
                "mm",
                format!(
                    "less than d = {} mm (the path's outer part lies in the tile's half)",
                    short(self.d)
                ),
            );
        }
        if let Some(c) = self.c {
            if c >= self.d {
                return bad("c", c, "mm", format!("less than d = {} mm", short(self.d)));
            }
        }
        // magnets that meet across a joint end 2c apart: at least a diameter, or they overlap
        let r = 0.5 * self.magnet_diameter;
        if self.c() < r * (1.0 - EQUALITY_TOLERANCE) {
            return match self.c {
                Some(c) => bad(
                    "c",
                    c,
                    "mm",
                    format!(
                        "at least the magnet radius, {} mm (magnets meeting at a joint end 2c apart and would overlap)",
                        short(r)
                    ),
                ),
                None => bad(
                    "e",
                    self.e,
                    "mm",
                    format!(
                        "at most d/2 - r = {} mm, so that c = d/2 - e keeps the magnets meeting at a joint a diameter apart (thesis (6.10): e < d/2)",
                        short(0.5 * self.d - r)
                    ),
                ),
            };
        }
        // the rest distance of the tile's two magnets at s = 0; s moves each one s inwards
        let b0 = 2.0 * self.d - 2.0 * self.c() - 2.0 * self.e;
        if b0 < self.magnet_diameter {
            let (name, value) = match self.c {
                Some(c) => ("c", c),
                None => ("e", self.e),
            };
            return bad(
                name,
                value,
                "mm",
                format!(
                    "smaller: the tile's two magnets would rest {} mm apart, less than their diameter {} mm",
                    short(b0),
                    short(self.magnet_diameter)
                ),
            );
        }
        let s_max = self.s_max();
        if self.s > s_max * (1.0 + EQUALITY_TOLERANCE) {
            return bad(
                "s",
                self.s,
                "mm",
                format!(
                    "0 to {} mm (at most e, and the tile's two magnets at rest at least a diameter apart; the thesis' inequality (6.9) wants s < e/3 = {} mm)",
                    short(s_max),
                    short(self.e / 3.0)
                ),
            );
        }
        Ok(())
    }

    /// The physical parameters of the dynamics this design sets to other than their
    /// defaults (masses, drags, friction, restitution, the water), by field name: a static
    /// study (margins, the tolerance study) uses none of them and refuses them.
    pub fn dynamic_fields_set(&self) -> Vec<&'static str> {
        let d = Design::default();
        [
            ("magnet_mass", self.magnet_mass != d.magnet_mass),
            ("tile_mass", self.tile_mass != d.tile_mass),
            ("magnet_drag", self.magnet_drag != d.magnet_drag),
            ("friction", self.friction != d.friction),
            ("restitution", self.restitution != d.restitution),
            ("water_viscosity", self.water_viscosity != d.water_viscosity),
            ("water_film", self.water_film != d.water_film),
            ("form_drag", self.form_drag != d.form_drag),
            ("water_density", self.water_density != d.water_density),
        ]
        .into_iter()
        .filter_map(|(name, set)| set.then_some(name))
        .collect()
    }

    /// The largest `s` a tile of this design can be built with, mm: at most `e`, and the
    /// tile's two magnets at rest at least a magnet diameter apart.
    pub fn s_max(&self) -> f64 {
        let b0 = 2.0 * self.d - 2.0 * self.c() - 2.0 * self.e;
        self.e.min(0.5 * (b0 - self.magnet_diameter)).max(0.0)
    }

    /// Checks [`Design::validate`] and the physical ranges a design file or a command line
    /// is held to (the ranges a tile can have: see the message of each field): values outside them are almost certainly a typing error
    /// (a tile 30 m wide, a magnet of 100 T), and far outside them the models have not been
    /// tried. The library's own studies (moments scaled by 10^6, micrometre tiles) use
    /// [`Design::validate`] alone.
    pub fn check_ranges(&self) -> Result<(), DesignError> {
        self.check_signs()?;
        for range in RANGES {
            let value = match range.name {
                "tile_width" => self.tile_width,
                "magnet_height" => self.magnet_height,
                "remanence" => self.remanence,
                "magnet_mass" => self.magnet_mass,
                "wall" => self.wall,
                "tile_mass" => self.tile_mass,
                "magnet_drag" => match self.magnet_drag {
                    Some(v) => v,
                    None => continue,
                },
                "friction" => self.friction,
                "restitution" => self.restitution,
                "water_viscosity" => self.water_viscosity,
                "water_film" => self.water_film,
                "form_drag" => self.form_drag,
                "water_density" => self.water_density,
                _ => continue,
            };
            let max = if range.relative_to_width {
                range.max * self.tile_width
            } else {
                range.max
            };
            if value < range.min || value > max {
                let lower = if range.min == 0.0 {
                    "more than 0".to_string()
                } else {
                    format!("from {} {}", short(range.min), range.unit)
                };
                let upper = if range.relative_to_width {
                    format!("{} mm, {} x the tile width", short(max), short(range.max))
                } else {
                    format!("{} {}", short(max), range.unit)
                };
                return Err(DesignError::BadParameter {
                    name: range.name,
                    value,
                    unit: range.unit,
                    expected: format!("{lower} up to {upper} ({})", range.why),
                });
            }
        }
        self.validate()
    }

    fn positive_fields(&self) -> [(&'static str, f64, &'static str); 10] {
        [
            ("tile_width", self.tile_width, "mm"),
            ("d", self.d, "mm"),
            ("e", self.e, "mm"),
            ("magnet_diameter", self.magnet_diameter, "mm"),
            ("magnet_height", self.magnet_height, "mm"),
            ("remanence", self.remanence, "T"),
            ("magnet_mass", self.magnet_mass, "g"),
            ("tile_mass", self.tile_mass, "g"),
            ("water_film", self.water_film, "mm"),
            ("water_density", self.water_density, "kg/m^3"),
        ]
    }

    fn non_negative_fields(&self) -> Vec<(&'static str, f64, &'static str)> {
        let mut v = vec![("s", self.s, "mm")];
        if let Some(c) = self.c {
            v.push(("c", c, "mm"));
        }
        v.push(("wall", self.wall, "mm"));
        if let Some(g) = self.magnet_drag {
            v.push(("magnet_drag", g, "N s/m"));
        }
        // 0 (no water drag) is an idealisation the library takes (momentum studies); a design
        // file or command line is held to the physical range ([`Design::check_ranges`])
        v.push(("water_viscosity", self.water_viscosity, "Pa s"));
        v.push(("friction", self.friction, "N"));
        v.push(("restitution", self.restitution, ""));
        v.push(("form_drag", self.form_drag, ""));
        v
    }

    /// Every inequality (6.1) to (6.10), evaluated. Parameters are not validated here.
    pub fn report(&self) -> Vec<InequalityCheck> {
        let (a, b, c, d, s, e) = (self.a(), self.b(), self.c(), self.d, self.s, self.e);
        // The reduced forms (6.6), (6.9), (6.10) come first so that a failure is named by
        // the parameter rule it breaks; (6.3) and (6.4) reduce to (6.9) in the thesis layout.
        let strict = Kind::Strict;
        vec![
            evaluate("6.6", "0 <= s", ("0", 0.0), ("s", s), Kind::NonStrict),
            evaluate("6.9", "s < e/3", ("s", s), ("e/3", e / 3.0), strict),
            evaluate(
                "6.10",
                "e < d/2 (thesis 6.7, restated as 6.10)",
                ("e", e),
                ("d/2", 0.5 * d),
                strict,
            ),
            evaluate(
                "6.8",
                "4s <= s + e (each magnet can travel the 4s that starts the next)",
                ("4s", 4.0 * s),
                ("s+e", s + e),
                Kind::NonStrict,
            ),
            evaluate(
                "6.1",
                "b < 2c + 2a (at rest the chain does not actuate by itself)",
                ("b", b),
                ("2c+2a", 2.0 * c + 2.0 * a),
                Kind::StrictWarnOnEquality,
            ),
            evaluate(
                "6.2",
                "c + a < b (the RI can start M1)",
                ("c+a", c + a),
                ("b", b),
                strict,
            ),
            evaluate(
                "6.3",
                "2c + 2a < a + b (M2 turns to M3 once M1 has moved)",
                ("2c+2a", 2.0 * c + 2.0 * a),
                ("a+b", a + b),
                strict,
            ),
            evaluate(
                "6.4",
                "2c + a < b (M3 starts)",
                ("2c+a", 2.0 * c + a),
                ("b", b),
                strict,
            ),
            evaluate(
                "6.5",
                "2c + a < b (left half of 2c + a < b < 2c + 2a)",
                ("2c+a", 2.0 * c + a),
                ("b", b),
                strict,
            ),
            evaluate(
                "6.5",
                "b < 2c + 2a (right half of 2c + a < b < 2c + 2a)",
                ("b", b),
                ("2c+2a", 2.0 * c + 2.0 * a),
                Kind::StrictWarnOnEquality,
            ),
        ]
    }

    /// Validates the parameters and every inequality; the first failure is the error.
    /// Marginal inequalities (equality where the thesis allows it as a limit, e.g. `s = 0`)
    /// pass: see [`Design::warnings`].
    pub fn check(&self) -> Result<Vec<InequalityCheck>, DesignError> {
        self.validate()?;
        let report = self.report();
        if let Some(f) = report.iter().find(|r| r.standing == Standing::Fails) {
            return Err(DesignError::Inequality {
                id: f.id,
                statement: f.statement,
                lhs_name: f.lhs_name,
                lhs: f.lhs,
                rhs_name: f.rhs_name,
                rhs: f.rhs,
            });
        }
        Ok(report)
    }

    /// The inequalities that hold only with equality (warnings).
    pub fn warnings(&self) -> Vec<InequalityCheck> {
        self.report()
            .into_iter()
            .filter(|r| r.standing == Standing::Marginal)
            .collect()
    }

    /// The change that `s` makes to the two rest forces against `s = 0`, as fractions:
    /// `(partner, neighbour)`. The partner in the same tile sits `d - 2s` away instead of `d`
    /// (stronger by `(d/(d-2s))^4 - 1`, +17.73% for the thesis design); the neighbour in the
    /// next tile `d + 2s` away (weaker by `1 - (d/(d+2s))^4`, -14.52%). The thesis quotes these
    /// two figures with the labels inter- and intra-tile the other way round.
    pub fn rest_force_change(&self) -> (f64, f64) {
        let d = self.d;
        let f = |r: f64| r.powi(-4);
        (
            f(self.b()) / f(d) - 1.0,
            f(self.inter_tile_rest_distance()) / f(d) - 1.0,
        )
    }
}

/// How an inequality treats equality.
#[derive(Clone, Copy)]
enum Kind {
    /// `<=`: equality holds.
    NonStrict,
    /// `<`: equality fails.
    Strict,
    /// `<`, but equality is the thesis' limiting case: a warning.
    StrictWarnOnEquality,
}

fn evaluate(
    id: &'static str,
    statement: &'static str,
    (lhs_name, lhs): (&'static str, f64),
    (rhs_name, rhs): (&'static str, f64),
    kind: Kind,
) -> InequalityCheck {
    let scale = lhs.abs().max(rhs.abs());
    let relative_margin = if scale > 0.0 {
        (rhs - lhs) / scale
    } else {
        0.0
    };
    let equal = (rhs - lhs).abs() <= EQUALITY_TOLERANCE * scale.max(f64::MIN_POSITIVE);
    let standing = if equal {
        match kind {
            Kind::NonStrict => Standing::Holds,
            Kind::Strict => Standing::Fails,
            Kind::StrictWarnOnEquality => Standing::Marginal,
        }
    } else if lhs < rhs {
        Standing::Holds
    } else {
        Standing::Fails
    };
    InequalityCheck {
        id,
        statement,
        lhs_name,
        lhs,
        rhs_name,
        rhs,
        relative_margin,
        standing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thesis_design_passes() {
        let d = Design::thesis();
        let report = d.check().unwrap();
        assert!(
            report.iter().all(|r| r.standing == Standing::Holds),
            "{report:#?}"
        );
        assert!((d.b() - 14.4).abs() < 1e-12);
        assert!((d.c() - 2.8).abs() < 1e-12);
        assert!((2.0 * d.c() + 2.0 * d.a() + d.b() - 2.0 * d.d).abs() < 1e-12);
    }

    #[test]
    fn s_at_or_above_e_over_3_fails_6_9() {
        let e = 4.7;
        for s in [e / 3.0, e / 3.0 + 0.01, 1.6] {
            let err = Design::thesis().with_s(s).check().unwrap_err();
            match &err {
                DesignError::Inequality { id, .. } => assert_eq!(*id, "6.9", "s = {s}: {err}"),
                other => panic!("s = {s}: {other}"),
            }
            assert!(err.to_string().contains("(6.9)"), "{err}");
        }
        assert!(Design::thesis().with_s(e / 3.0 - 0.01).check().is_ok());
    }

    #[test]
    fn e_at_or_above_d_over_2_fails() {
        for e in [7.5, 8.0] {
            let err = Design::thesis().with_e(e).check().unwrap_err();
            let msg = err.to_string();
            assert!(msg.contains("(6.10)"), "{msg}");
        }
        // named as (6.10) in the report in any case
        let r = Design::thesis().with_e(8.0).report();
        assert!(r
            .iter()
            .any(|c| c.id == "6.10" && c.standing == Standing::Fails));
    }

    #[test]
    fn s_zero_is_a_warning() {
        let d = Design::thesis().with_s(0.0);
        assert!(d.check().is_ok());
        let w = d.warnings();
        assert!(w.iter().any(|c| c.id == "6.1"), "{w:#?}");
    }

    #[test]
    fn bad_parameters_are_named() {
        let e = Design::thesis().with_s(-0.1).check().unwrap_err();
        assert!(e.to_string().contains("`s` = -0.1"), "{e}");
        let e = Design::thesis().with_e(f64::NAN).check().unwrap_err();
        assert!(e.to_string().contains("`e` = NaN"), "{e}");
        let e = Design {
            remanence: -1.0,
            ..Design::thesis()
        }
        .check()
        .unwrap_err();
        assert!(e.to_string().contains("remanence"), "{e}");
    }

    #[test]
    fn fold_clearance_from_the_wall_or_c() {
        let d = Design::thesis();
        assert!((d.fold_clearance() - 2.3).abs() < 1e-12);
        let thin = Design { wall: 0.5, ..d };
        assert!((thin.fold_clearance() - 2.0).abs() < 1e-12);
        // an explicit c keeps its old meaning
        let old = Design { c: Some(2.8), ..d };
        assert!((old.fold_clearance() - 2.8).abs() < 1e-12);
        let e = Design { wall: -0.1, ..d }.check().unwrap_err();
        assert!(e.to_string().contains("`wall` = -0.1"), "{e}");
        // 3 mm x 5 mm NdFeB: about 0.265 g, well under the thesis' 0.625 g
        assert!(
            (d.cylinder_mass() - 0.265).abs() < 0.001,
            "{}",
            d.cylinder_mass()
        );
    }

    #[test]
    fn force_change_matches_thesis_figures() {
        let (partner, neighbour) = Design::thesis().rest_force_change();
        // the thesis truncates to 17.73% and 14.52%
        assert!((partner - 0.1773).abs() < 1e-4, "{partner}");
        assert!((neighbour + 0.1452).abs() < 1e-4, "{neighbour}");
        // and the ratio is about 7:5
        let ratio = (1.0 + partner) / (1.0 + neighbour);
        assert!((ratio - 1.4).abs() < 0.03, "{ratio}");
    }
}
