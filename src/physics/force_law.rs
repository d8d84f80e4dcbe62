//! The pair law the simulations use, as a value the callers pass
//! ([`crate::engine::EngineOptions::force_law`], [`crate::reference::ModelOptions::force_law`]):
//! today the point dipole of the thesis; a finite-cylinder law is a new variant here.

use kurbo::{Point, Vec2};

use crate::physics::dipole;
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
}

impl ForceLaw {
    /// The force (N) on the magnet at `on` from the one at `from` (both mm), moments `m_from`
    /// and `m_on` (A m^2), attracting (opposite poles) or repelling; zero for coincident
    /// points.
    pub fn force(self, from: Point, on: Point, m_from: f64, m_on: f64, attract: bool) -> Vec2 {
        match self {
            ForceLaw::PointDipole => dipole::force(from, on, m_from, m_on, attract),
        }
    }

    /// The pair energy (J) of magnets at `a` and `b` (mm), moments `m_a` and `m_b` (A m^2);
    /// zero for coincident points.
    pub fn energy(self, a: Point, b: Point, m_a: f64, m_b: f64, attract: bool) -> f64 {
        match self {
            ForceLaw::PointDipole => dipole::energy(a, b, m_a, m_b, attract),
        }
    }

    /// The force magnitude (N) between moments `m_a` and `m_b` (A m^2) `r` metres apart.
    pub fn magnitude(self, m_a: f64, m_b: f64, r: f64) -> f64 {
        match self {
            ForceLaw::PointDipole => dipole::magnitude(m_a, m_b, r),
        }
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
    }
}
