//! The pair law the simulations use, as a value the callers pass
//! ([`crate::engine::EngineOptions::force_law`], [`crate::model::ModelOptions::force_law`]):
//! the point dipole of the thesis, or uniformly magnetised finite cylinders of the magnets'
//! real shape ([`ForceLaw::cylinder`], tabulated once per shape: [`crate::physics`]'s
//! `cylinder` module).

use kurbo::{Point, Vec2};

use crate::physics::{cylinder, dipole};
use crate::Design;

/// The force and energy between two magnets.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum ForceLaw {
    /// Point dipoles standing upright (thesis 6.11, 6.12): force `3 mu0 m_a m_b / (4 pi r^4)`
    /// along the line between the magnets.
    #[default]
    PointDipole,
    /// Uniformly magnetised cylinders standing upright side by side, `diameter_nm` and
    /// `height_nm` (nanometres, so that the law stays a small exact value): the dipole's
    /// force times a ratio of `r / D` computed from the magnets' surface charges and
    /// interpolated smoothly (0.90 at the thesis' 14.4 mm, 0.30 at 1.02 diameters; closer
    /// than one diameter, where real magnets would overlap, the ratio keeps its value at one
    /// diameter). Build it with [`ForceLaw::cylinder`].
    Cylinder {
        /// Magnet diameter, nm.
        diameter_nm: u64,
        /// Magnet height, nm.
        height_nm: u64,
    },
}

/// The names `--force-law` accepts, as [`ForceLaw::named`] reads them.
pub(crate) const FORCE_LAW_NAMES: [&str; 2] = ["dipole", "cylinder"];

impl ForceLaw {
    /// The laws' names, as [`ForceLaw::named`] reads them.
    pub const NAMES: [&'static str; 2] = FORCE_LAW_NAMES;

    /// The finite-cylinder law for the magnets of `design`.
    pub fn cylinder(design: &Design) -> ForceLaw {
        let nm = |mm: f64| (mm * 1e6).round().max(1.0) as u64;
        ForceLaw::Cylinder {
            diameter_nm: nm(design.magnet_diameter),
            height_nm: nm(design.magnet_height),
        }
    }

    /// The law called `name` ([`ForceLaw::NAMES`]: `dipole` or `cylinder`), for the magnets of
    /// `design`; `None` for another name.
    pub fn named(name: &str, design: &Design) -> Option<ForceLaw> {
        match name {
            "dipole" => Some(ForceLaw::PointDipole),
            "cylinder" => Some(ForceLaw::cylinder(design)),
            _ => None,
        }
    }

    /// The law's short name (`dipole` or `cylinder`).
    pub fn name(self) -> &'static str {
        match self {
            ForceLaw::PointDipole => "dipole",
            ForceLaw::Cylinder { .. } => "cylinder",
        }
    }

    /// The factor on the dipole's force at `r` mm (1 for the dipole).
    fn force_ratio(self, r_mm: f64) -> f64 {
        match self {
            ForceLaw::PointDipole => 1.0,
            ForceLaw::Cylinder {
                diameter_nm,
                height_nm,
            } => {
                let d = diameter_nm as f64 * 1e-6;
                cylinder::table(height_nm as f64 / diameter_nm as f64).ratio(r_mm / d)
            }
        }
    }

    /// The force (N) on the magnet at `on` from the one at `from` (both mm), moments `m_from`
    /// and `m_on` (A m^2), attracting (opposite poles) or repelling; zero for coincident
    /// points.
    pub fn force(self, from: Point, on: Point, m_from: f64, m_on: f64, attract: bool) -> Vec2 {
        let f = dipole::force(from, on, m_from, m_on, attract);
        match self {
            ForceLaw::PointDipole => f,
            ForceLaw::Cylinder { .. } => f * self.force_ratio(from.distance(on)),
        }
    }

    /// The force of [`ForceLaw::force`] by a faster form where the law has one (the point
    /// dipole's: one division and one square root), equal to a few units in the last place;
    /// the reference's inner loop.
    pub(crate) fn force_with(
        self,
        from: Point,
        on: Point,
        m_from: f64,
        m_on: f64,
        attract: bool,
    ) -> Vec2 {
        match self {
            ForceLaw::PointDipole => {
                let sign = if attract { -1.0 } else { 1.0 };
                dipole::force_with(from, on, sign * dipole::FORCE_CONSTANT * m_from * m_on)
            }
            ForceLaw::Cylinder { .. } => self.force(from, on, m_from, m_on, attract),
        }
    }

    /// The pair energy (J) of magnets at `a` and `b` (mm), moments `m_a` and `m_b` (A m^2);
    /// zero for coincident points.
    pub fn energy(self, a: Point, b: Point, m_a: f64, m_b: f64, attract: bool) -> f64 {
        let e = dipole::energy(a, b, m_a, m_b, attract);
        match self {
            ForceLaw::PointDipole => e,
            ForceLaw::Cylinder {
                diameter_nm,
                height_nm,
            } => {
                let d = diameter_nm as f64 * 1e-6;
                let t = cylinder::table(height_nm as f64 / diameter_nm as f64);
                e * t.energy_ratio(a.distance(b) / d)
            }
        }
    }

    /// The force magnitude (N) between moments `m_a` and `m_b` (A m^2) `r` metres apart.
    pub fn magnitude(self, m_a: f64, m_b: f64, r: f64) -> f64 {
        dipole::magnitude(m_a, m_b, r) * self.force_ratio(r * 1e3)
    }

    /// The bonded rest force (N): between the two magnets of a tile of `design` at rest, `b`
    /// apart (at least a magnet diameter). The scale every drive is measured against.
    pub fn bonded_rest_force(self, design: &Design) -> f64 {
        let m = design.moment();
        let b = design.b().max(design.magnet_diameter) * 1e-3;
        self.magnitude(m, m, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bonded_rest_force_of_the_thesis_design() {
        // two magnets of 0.036 A m^2 or so, b = 8.8 mm apart: tens of millinewtons
        let d = Design::thesis();
        let f = ForceLaw::PointDipole.bonded_rest_force(&d);
        let direct = ForceLaw::PointDipole
            .force(
                Point::ORIGIN,
                Point::new(d.b(), 0.0),
                d.moment(),
                d.moment(),
                true,
            )
            .hypot();
        assert!((f - direct).abs() < 1e-12 * f, "{f} {direct}");
        assert!(f > 1e-3 && f < 1.0, "{f}");
        // the cylinders' at the same distance: about 0.90 of it (magpylib: 1 / 1.1133)
        let c = ForceLaw::cylinder(&d);
        let ratio = c.bonded_rest_force(&d) / f;
        assert!((ratio - 1.0 / 1.1133).abs() < 1e-3, "{ratio}");
    }

    #[test]
    fn cylinder_force_is_minus_the_energy_gradient_and_central() {
        let d = Design::thesis();
        let law = ForceLaw::cylinder(&d);
        assert_eq!(ForceLaw::named("cylinder", &d), Some(law));
        assert_eq!(ForceLaw::named("dipole", &d), Some(ForceLaw::PointDipole));
        assert_eq!(ForceLaw::named("coulomb", &d), None);
        assert_eq!(law.name(), "cylinder");
        let m = d.moment();
        for x in [2.0, 4.6, 14.4, 40.0] {
            for attract in [true, false] {
                let h = 1e-5;
                let u = |x: f64| law.energy(Point::ORIGIN, Point::new(x, 0.0), m, m, attract);
                let du = (u(x + h) - u(x - h)) / (2.0 * h * 1e-3);
                let f = law.force(Point::ORIGIN, Point::new(x, 0.0), m, m, attract);
                assert!(
                    (f.x + du).abs() < 1e-4 * f.x.abs(),
                    "{x} {attract}: {} {du}",
                    f.x
                );
                assert_eq!(f.y, 0.0);
                assert!((f.x.abs() - law.magnitude(m, m, x * 1e-3)).abs() < 1e-12 * f.x.abs());
            }
        }
    }
}
