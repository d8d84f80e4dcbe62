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
//! not in the thesis: the default, [`crate::physics::DEFAULT_DRAG`], is an assumed value that
//! makes a straight-path move of the thesis design take about a third of a second; every time
//! scales linearly with it. The closed form is the point-dipole law's (`1/r^4`): another
//! [`ForceLaw`] needs its own.
//!
//! **Unit speed.** Every magnet moves at 1 mm per second: the timeline is then the thesis'
//! transition diagram (figure 6.3), time in seconds equal to distance in millimetres.
//!
//! **The motion table.** A magnet's motion depends on its path, its partner's path and the
//! fold between them only, so a run keeps one [`Motion`] per distinct triple
//! ([`MotionTable`]).

use std::f64::consts::FRAC_PI_2;

use rustc_hash::FxHashMap;

use crate::physics::ForceLaw;
use crate::timeline::{Geometry, SpeedLaw};
use crate::{Design, Fold};

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
            SpeedLaw::Overdamped { drag } | SpeedLaw::Inertial { drag } => {
                let m = design.moment();
                // K, N m^4: the point-dipole force at 1 m
                let k = ForceLaw::PointDipole.magnitude(m, m, 1.0);
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

/// Every magnet's motion, one [`Motion`] per distinct (path, partner's path, fold).
#[derive(Debug)]
pub(crate) struct MotionTable {
    motions: Vec<Motion>,
    motion_of: Vec<u32>,
}

impl MotionTable {
    /// The motions of every magnet of `geometry` under `law`.
    pub(crate) fn new(geometry: &Geometry, law: SpeedLaw) -> MotionTable {
        let n = geometry.magnets();
        let tiles = geometry.tiles();
        let mut motions: Vec<Motion> = Vec::new();
        // The end gap depends on the two paths of the pair and the fold between them only.
        let mut index: FxHashMap<(u32, u32, Fold), u32> = FxHashMap::default();
        let mut motion_of = Vec::with_capacity(n);
        for k in 0..n {
            let other = if k == 0 {
                u32::MAX
            } else if k % 2 == 1 {
                if k + 1 < n {
                    geometry.path_id(k + 1)
                } else {
                    u32::MAX - 1
                }
            } else {
                geometry.path_id(k - 1)
            };
            let j = if k % 2 == 1 {
                k / 2
            } else {
                (k / 2).wrapping_sub(1)
            };
            let fold = if k == 0 || j + 1 >= tiles {
                Fold::S
            } else {
                geometry.joint_fold(j)
            };
            let key = (geometry.path_id(k), other, fold);
            let id = *index.entry(key).or_insert_with(|| {
                motions.push(Motion::new(
                    geometry.path(k).length(),
                    end_gap(geometry, k),
                    geometry.design(k / 2),
                    law,
                ));
                (motions.len() - 1) as u32
            });
            motion_of.push(id);
        }
        MotionTable { motions, motion_of }
    }

    /// Magnet `k`'s motion.
    pub(crate) fn of(&self, k: usize) -> &Motion {
        &self.motions[self.motion_of[k] as usize]
    }
}

/// The distance between the final points of magnet `k` and the one it heads for, in the
/// final shape (a folding pair measured after its fold: `2c`, as a straight pair).
fn end_gap(g: &Geometry, k: usize) -> f64 {
    if k == 0 {
        return g.end_in(0, 0).distance(g.ri().position);
    }
    let (a, b) = if k % 2 == 1 { (k, k + 1) } else { (k - 1, k) };
    if b >= g.magnets() {
        return 0.0;
    }
    let j = a / 2;
    let pa = kurbo::Point::from(g.path(a).end_point());
    let angle = g.joint_fold(j).quarter_turns() as f64 * FRAC_PI_2;
    let pb = crate::kinematics::joint_transform(angle, g.w).transform_point(g.path(b).end_point());
    pa.distance(pb.into())
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
        let f = ForceLaw::default().magnitude(d.moment(), d.moment(), r);
        assert!(
            (v * 1e-3 - f / crate::physics::DEFAULT_DRAG).abs() / v < 1e-5,
            "{v}"
        );
    }
}
