//! How fast a magnet slides along its path: the speed law, in closed form both ways (time to
//! reach a point, point reached at a time), so the engine never integrates.
//!
//! **Overdamped (default).** A magnet in its oil-filled channel moves at the speed where drag
//! balances the pull of the magnet it is heading for: `gamma du/dt = K / r^4`, with
//! `K = 3 mu0 m^2 / (4 pi)` (thesis 6.12) and `r` the distance still to close. The partner is
//! taken at its own final point, so `r = rho - u` with `rho` = the magnet's path length plus
//! the distance between the two path ends (the reaction initiator for the first magnet).
//! Then `r^5` falls linearly: `t(u) = gamma (rho^5 - (rho - u)^5) / (5K)` and
//! `u(t) = rho - (rho^5 - 5K t / gamma)^(1/5)`, in seconds. The drag coefficient `gamma` is
//! not in the thesis: the default, [`DEFAULT_DRAG`], is an assumed value that makes a
//! straight-path move of the thesis design take about a third of a second; every time scales
//! linearly with it.
//!
//! **Unit speed.** Every magnet moves at 1 mm per second: the timeline is then the thesis'
//! transition diagram (figure 6.3), time in seconds equal to distance in millimetres.

use crate::design::MU0;
use crate::Design;

/// Default drag coefficient, N s/m (an assumption: see the module documentation).
pub const DEFAULT_DRAG: f64 = 5.0;

/// The speed law.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpeedLaw {
    /// Overdamped motion under the pair's `1/r^4` attraction, drag coefficient in N s/m.
    Overdamped {
        /// Drag coefficient, N s/m.
        drag: f64,
    },
    /// 1 mm per second: the transition diagram's timeline.
    Unit,
}

impl Default for SpeedLaw {
    fn default() -> SpeedLaw {
        SpeedLaw::Overdamped { drag: DEFAULT_DRAG }
    }
}

/// The motion of one magnet along its path, from the moment it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion {
    /// Path length, mm.
    pub length: f64,
    /// `rho` (mm): path length plus the distance between the two path ends.
    pub rho: f64,
    /// Seconds per mm^5 (`gamma / 5K`, in mm units), or `None` at unit speed.
    tau: Option<f64>,
}

impl Motion {
    /// The motion over a path of `length` mm towards a partner whose final point lies
    /// `end_gap` mm from this path's end, for magnets of `design` under `law`.
    pub fn new(length: f64, end_gap: f64, design: &Design, law: SpeedLaw) -> Motion {
        let tau = match law {
            SpeedLaw::Unit => None,
            SpeedLaw::Overdamped { drag } => {
                let m = design.moment();
                let k = 3.0 * MU0 / (4.0 * std::f64::consts::PI) * m * m; // N m^4
                                                                          // gamma (rho^5 - r^5) / 5K with lengths in metres = 1e-15 * (same in mm)
                Some(drag * 1e-15 / (5.0 * k))
            }
        };
        Motion {
            length,
            rho: length + end_gap.max(0.0),
            tau,
        }
    }

    /// Seconds to travel `u` mm (clamped to the path).
    pub fn time_to(&self, u: f64) -> f64 {
        let u = u.clamp(0.0, self.length);
        match self.tau {
            None => u,
            Some(tau) => {
                let r = self.rho - u;
                tau * (self.rho.powi(5) - r.powi(5))
            }
        }
    }

    /// Seconds to travel the whole path.
    pub fn duration(&self) -> f64 {
        self.time_to(self.length)
    }

    /// The arc length travelled `t` seconds after starting (clamped to the path).
    pub fn distance_at(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let u = match self.tau {
            None => t,
            Some(tau) => {
                let r5 = self.rho.powi(5) - t / tau;
                if r5 <= 0.0 {
                    self.length
                } else {
                    self.rho - r5.powf(0.2)
                }
            }
        };
        u.clamp(0.0, self.length)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn closed_forms_invert_each_other() {
        let d = Design::thesis();
        for law in [SpeedLaw::Unit, SpeedLaw::default()] {
            let m = Motion::new(5.0, 5.6, &d, law);
            for i in 0..=50 {
                let u = 5.0 * i as f64 / 50.0;
                let t = m.time_to(u);
                assert!((m.distance_at(t) - u).abs() < 1e-9, "{law:?} {u}");
            }
            assert_eq!(m.distance_at(m.duration() * 2.0), 5.0);
        }
        // overdamped: speeds up as the gap closes; a third of a second or so per move
        let m = Motion::new(5.0, 5.6, &d, SpeedLaw::default());
        let first = m.time_to(1.0);
        let last = m.duration() - m.time_to(4.0);
        assert!(last < first / 5.0, "{first} {last}");
        assert!(m.duration() > 0.1 && m.duration() < 1.0, "{}", m.duration());
    }

    #[test]
    fn matches_the_force_law() {
        // the speed at any point is F(r) / gamma
        let d = Design::thesis();
        let m = Motion::new(5.0, 5.6, &d, SpeedLaw::default());
        let u = 2.0;
        let h = 1e-6;
        let v = 2.0 * h / (m.time_to(u + h) - m.time_to(u - h)); // mm/s
        let r = (m.rho - u) * 1e-3;
        let f = crate::dipole::pair_force(d.moment(), r);
        assert!((v * 1e-3 - f / DEFAULT_DRAG).abs() / v < 1e-5, "{v}");
    }
}
