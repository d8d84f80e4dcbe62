//! How the model's unknowns answer their drives under inertia
//! ([`crate::model::Dynamics::Inertial`]): per unknown its inverse effective mass, damping
//! rate and Coulomb friction ([`Coefficients`]), and the rules at the walls of its range
//! ([`InertialModel`]: the acceleration, a bounce or a rest at a wall, a release).
//!
//! **Motion.** A magnet of mass `m` on a path of length `L` (its unknown `x = u / L`):
//! `m L x'' = F . t - gamma L x' - f_c sign(x')` (the force along its path, the drag, the
//! Coulomb friction). A folding joint `j` (its unknown `psi = |theta| / (pi/2)`):
//! `I_j (pi/2) psi'' + I_j'(psi) psi'^2 (pi/2) / 2 = tau - g_j (pi/2) psi'`, with `I_j` and
//! `g_j` the effective inertia and drag of the joint's two free sides at its angle
//! ([`crate::model`]'s sides: nothing is anchored).
//!
//! **Walls.** At a wall (0 or 1) a free unknown moving outwards bounces with the
//! restitution, or stays there when the rebound would rise less than [`REST_HEIGHT`] of the
//! range against the drive pressing it on (or the restitution is 0): that is its arrival (a
//! fold's end). A clamped unknown is released, at rest, when its drive pulls it off its wall
//! by more than the static threshold and the Coulomb friction. An unknown is quiet on the
//! run's time scale when its speed and acceleration are under 1e-7 of the range.

use std::f64::consts::FRAC_PI_2;
use std::fmt;

use crate::model::chain_model::Unknown;
use crate::model::sides::Sides;
use crate::model::{Dynamics, Mode, Model};

/// A rebound that would rise less than this fraction of the range ends the bouncing.
pub(crate) const REST_HEIGHT: f64 = 1e-3;

/// A folding joint's coefficients: its sides' inertia and drag, and its sign.
#[derive(Clone, Copy, Debug)]
pub(crate) struct JointCoefficients {
    sides: Sides,
    /// +1 left, -1 right.
    sign: f64,
}

impl JointCoefficients {
    /// The effective inertia (kg m^2), its derivative by the fold fraction, and the
    /// effective drag (N m s) at fold fraction `psi`.
    fn at(&self, psi: f64) -> (f64, f64, f64) {
        let phi = self.sign * psi.clamp(0.0, 1.0) * FRAC_PI_2;
        let (inertia, slope) = self.sides.inertia.at(phi);
        let (drag, _) = self.sides.drag.at(phi);
        (inertia, slope * self.sign * FRAC_PI_2, drag)
    }
}

/// Per unknown: for a magnet, its inverse effective mass (acceleration of the unknown per
/// unit drive), its damping rate (1/s) and its Coulomb friction (in drive units); for a
/// joint, its sides ([`JointCoefficients`]), whose inertia and drag depend on the fold.
pub(crate) struct Coefficients {
    pub(crate) inv_mass: Vec<f64>,
    pub(crate) damping: Vec<f64>,
    pub(crate) coulomb: Vec<f64>,
    joints: Vec<Option<JointCoefficients>>,
}

impl Coefficients {
    /// The run's three times, s: the inertial time of the slowest unknown, a move's time at
    /// the bonded force, and a path's time at the bonded force against the drag alone (the
    /// longest is the scale the rest test is measured on, the first step comes from them).
    pub(crate) fn times(&self, model: &Model) -> (f64, f64, f64) {
        let tau = self
            .damping
            .iter()
            .filter(|d| **d > 0.0)
            .map(|d| 1.0 / d)
            .fold(0.0, f64::max);
        let inv0 = self.inv_mass.first().copied().unwrap_or(1.0);
        let move_time = (2.0 / (model.force_scale * inv0)).sqrt();
        let drag_time = self.damping.first().copied().unwrap_or(0.0) / (model.force_scale * inv0);
        (tau, move_time, drag_time)
    }

    pub(crate) fn new(model: &Model) -> Coefficients {
        let n = model.len();
        let (mut inv_mass, mut damping, mut coulomb) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut joints = vec![None; n];
        for (i, u) in model.unknowns.iter().enumerate() {
            match *u {
                Unknown::Magnet(k) => {
                    let m = model.magnet_mass[k];
                    let len = model.path_length(k) * 1e-3;
                    inv_mass[i] = 1.0 / (m * len);
                    damping[i] = model.drag / m;
                    coulomb[i] = model.friction;
                }
                Unknown::Joint(j) => {
                    if let Some(sides) = model.sides[j] {
                        let jc = JointCoefficients {
                            sides,
                            sign: model.joint_sign(j),
                        };
                        let (inertia, _, drag) = jc.at(0.0);
                        inv_mass[i] = 1.0 / (inertia * FRAC_PI_2);
                        damping[i] = drag / inertia;
                        joints[i] = Some(jc);
                    }
                }
            }
        }
        Coefficients {
            inv_mass,
            damping,
            coulomb,
            joints,
        }
    }
}

/// The inertial model's coefficients and time scale, for the local solves.
pub(crate) struct InertialModel {
    pub(crate) c: Coefficients,
    restitution: f64,
    /// The time scale of the inertial run: the longest of the inertial time,
    /// a path's time at the bonded force from rest, and its time against the drag alone.
    pub(crate) scale: f64,
    /// The shortest of the inertial time and a path's time at the bonded force (first step).
    pub(crate) first_step: f64,
    /// Per unknown, the time scale its rest test is measured on: the run's `scale`, or for a
    /// folding joint, if longer, its own slowest time (its fold under the bonded rest torque
    /// against both sides' drag, [`Model::fold_time`], and its inertial time against that
    /// drag). A fold whose sides are long turns for days at a speed that is tiny on the
    /// magnets' scale, and is not at rest.
    rest_scale: Vec<f64>,
}

impl fmt::Debug for InertialModel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("InertialModel")
            .field("restitution", &self.restitution)
            .field("scale", &self.scale)
            .finish()
    }
}

impl InertialModel {
    /// The inertial coefficients of `model`, if its dynamics are inertial.
    pub(crate) fn new(model: &Model) -> Option<InertialModel> {
        if model.options().dynamics != Dynamics::Inertial {
            return None;
        }
        let c = Coefficients::new(model);
        // the reference's scale (its inertial driver)
        let (tau, move_time, drag_time) = c.times(model);
        let scale = tau.max(move_time).max(drag_time);
        let rest_scale = model
            .unknowns
            .iter()
            .enumerate()
            .map(|(i, u)| match *u {
                Unknown::Joint(j) if c.joints[i].is_some() => {
                    let inertial = if c.damping[i] > 0.0 {
                        1.0 / c.damping[i]
                    } else {
                        0.0
                    };
                    scale.max(model.fold_time(j)).max(inertial)
                }
                _ => scale,
            })
            .collect();
        Some(InertialModel {
            restitution: model.geometry.design(0).restitution,
            scale,
            first_step: tau.min(move_time),
            rest_scale,
            c,
        })
    }

    /// The acceleration of unknown `g` (state index) at value `y` and velocity `v` under
    /// `drive`: a magnet's `(F - f_c) / (m L) - (gamma / m) v`; a joint's
    /// `(tau / (pi/2) - g psi' - I' psi'^2 / 2) / I` with its sides' inertia `I` and drag `g`
    /// at its angle ([`crate::model`]'s sides).
    pub(crate) fn acceleration(&self, g: usize, y: f64, drive: f64, v: f64) -> f64 {
        if let Some(jc) = &self.c.joints[g] {
            let (inertia, slope, drag) = jc.at(y);
            return (drive / FRAC_PI_2 - drag * v - 0.5 * slope * v * v) / inertia;
        }
        let fc = self.c.coulomb[g];
        let friction = if fc > 0.0 { fc * (v * 1e3).tanh() } else { 0.0 };
        (drive - friction) * self.c.inv_mass[g] - self.c.damping[g] * v
    }

    /// The drive under which folding joint `g` at value `y` and velocity `v` has
    /// acceleration `acc` ([`InertialModel::acceleration`] inverted; `None` for a magnet).
    pub(crate) fn joint_drive_for(&self, g: usize, y: f64, v: f64, acc: f64) -> Option<f64> {
        let jc = self.c.joints.get(g)?.as_ref()?;
        let (inertia, slope, drag) = jc.at(y);
        Some((acc * inertia + drag * v + 0.5 * slope * v * v) * FRAC_PI_2)
    }

    /// The drive a clamped unknown `g` must exceed to be released.
    pub(crate) fn threshold(&self, model: &Model, g: usize) -> f64 {
        model.threshold(g).max(self.c.coulomb[g])
    }

    /// Whether clamped unknown `g` in `mode` is pulled off its wall by `drive`.
    pub(crate) fn released(&self, model: &Model, g: usize, mode: Mode, drive: f64) -> bool {
        let th = self.threshold(model, g);
        match mode {
            Mode::AtStart => drive > th,
            Mode::AtEnd => -drive > th,
            Mode::Free => false,
        }
    }

    /// What free unknown `g` does on reaching wall `wall` (0 or 1) with velocity `v` (moving
    /// outwards) under `drive`: `None` stays there (rest), `Some(rebound)` bounces.
    pub(crate) fn bounce(&self, g: usize, wall: f64, v: f64, drive: f64) -> Option<f64> {
        let rebound = -self.restitution * v;
        // the drive pressing it on against the wall, as an acceleration
        let press = if wall == 1.0 { drive } else { -drive };
        let inv_mass = match &self.c.joints[g] {
            Some(jc) => 1.0 / (jc.at(wall).0 * FRAC_PI_2),
            None => self.c.inv_mass[g],
        };
        let a = press.max(0.0) * inv_mass;
        if self.restitution <= 0.0 || rebound * rebound < 2.0 * a * REST_HEIGHT {
            None
        } else {
            Some(rebound)
        }
    }

    /// Whether unknown `g` (state index) with velocity `v` and acceleration `a` is quiet:
    /// it would move less than 1e-7 of its range over its own time scale (the reference's
    /// and the local solves' rest test). A slow fold's joint is measured on its fold time, so
    /// a fold that creeps under its torque against the drag is not taken for a balance.
    pub(crate) fn quiet(&self, g: usize, v: f64, a: f64) -> bool {
        let t = self.rest_scale.get(g).copied().unwrap_or(self.scale);
        v.abs() * t < 1e-7 && a.abs() * t * t < 1e-7
    }
}

/// Whether a free unknown at `x` with velocity `v` has reached a wall moving outwards.
pub(crate) fn at_wall(x: f64, v: f64) -> bool {
    (x >= 1.0 && v > 0.0) || (x <= 0.0 && v < 0.0)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::model::ModelOptions;
    use crate::timeline::TileDesigns;
    use crate::{Chain, Design};

    fn inertial() -> ModelOptions {
        ModelOptions::default().with_dynamics(Dynamics::Inertial)
    }

    #[test]
    fn a_fold_creeping_against_long_sides_is_not_quiet() {
        // S*1500 LL S*1500: each fold turns two 45 m sides, for days, at a speed far under
        // 1e-7 of its range per magnet time scale; the rest test measures it on its own fold
        // time (before, the engine called that creep a balance and the run `stalled`)
        let chain = Chain::parse("S*1500 LL S*1500").unwrap();
        let designs = TileDesigns::global(Design::thesis());
        let model = Model::new(&chain, &designs, &inertial()).unwrap();
        let im = InertialModel::new(&model).unwrap();
        let g = model.joint_var(1500).unwrap();
        let fold = model.fold_time(1500);
        assert!(fold > 1e6 * im.scale, "{fold} {}", im.scale);
        // a tenth of the fold's mean speed, no acceleration: moving
        let v = 0.1 / fold;
        assert!(v * im.scale < 1e-7);
        assert!(!im.quiet(g, v, 0.0));
        // the same speed on a magnet is quiet on the magnets' scale
        assert!(im.quiet(model.magnet_var(3001), v, 0.0));
        // a joint that truly stopped is quiet
        assert!(im.quiet(g, 1e-9 / fold, 0.0));
    }

    #[test]
    fn walls_bounce_fast_arrivals_and_hold_slow_ones() {
        let chain = Chain::parse("SL").unwrap();
        let designs = TileDesigns::global(Design::thesis());
        let model = Model::new(&chain, &designs, &inertial()).unwrap();
        assert!(InertialModel::new(
            &Model::new(&chain, &designs, &ModelOptions::default()).unwrap()
        )
        .is_none());
        let im = InertialModel::new(&model).unwrap();
        let g = model.magnet_var(1);
        let push = model.force_scale;
        // the arrival speed whose rebound rises 1e-3 of the path against the bonded force
        let a = push * im.c.inv_mass[g];
        let v_rest = (2.0 * a * REST_HEIGHT).sqrt() / im.restitution;
        // a fast arrival bounces back with the restitution
        let fast = 2.0 * v_rest;
        assert_eq!(im.bounce(g, 1.0, fast, push), Some(-im.restitution * fast));
        assert_eq!(im.bounce(g, 0.0, -fast, -push), Some(im.restitution * fast));
        // a slower one pressed on by the bonded force stays
        assert_eq!(im.bounce(g, 1.0, 0.5 * v_rest, push), None);
        // the same with nothing pressing it on bounces
        assert!(im.bounce(g, 1.0, 0.5 * v_rest, -push).is_some());
        assert!(at_wall(1.0, 0.1) && at_wall(0.0, -0.1));
        assert!(!at_wall(1.0, -0.1) && !at_wall(0.5, 1.0));
        // released only by more than the threshold, towards the inside
        assert!(im.released(&model, g, Mode::AtStart, push));
        assert!(!im.released(&model, g, Mode::AtStart, -push));
        assert!(im.released(&model, g, Mode::AtEnd, -push));
        assert!(im.quiet(g, 0.0, 0.0) && !im.quiet(g, 1.0, 0.0));
    }
}
