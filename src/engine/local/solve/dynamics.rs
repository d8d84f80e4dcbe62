//! How a unit's unknowns answer their drives: the overdamped model's rates (first order,
//! [`crate::reference::Model::rate`]) or the inertial model's accelerations (second order,
//! [`crate::reference::Dynamics::Inertial`]), with the inertial model's walls.
//!
//! **Inertial.** Each unknown carries a position and a velocity; its acceleration is
//! `(drive - friction) / (m L) - (gamma / m) v` with the coefficients of the reference's
//! inertial driver ([`crate::reference::inertial::Coefficients`], by the unknown's state
//! index), so a unit's motion is the reference's equation for those unknowns. At a wall (0
//! or 1) a free unknown moving outwards bounces with the restitution, or stays there when
//! the rebound would rise less than [`REST_HEIGHT`] of the range against the drive pressing
//! it on (or the restitution is 0): that is its arrival (a fold's end). A clamped unknown
//! is released, at rest, when its drive pulls it off its wall by more than the static
//! threshold and the Coulomb friction. The unit has settled when every free unknown is
//! quiet on the reference's time scale (speed and acceleration under 1e-7 of the range).

use std::fmt;

use crate::reference::inertial::{Coefficients, REST_HEIGHT};
use crate::reference::{Dynamics, Mode, Model};

/// The inertial model's coefficients and time scale, for the local solves.
pub(crate) struct InertialModel {
    c: Coefficients,
    restitution: f64,
    /// The reference's time scale of the inertial run: the longest of the inertial time,
    /// a path's time at the bonded force from rest, and its time against the drag alone.
    pub(crate) scale: f64,
    /// The shortest of the inertial time and a path's time at the bonded force (first step).
    pub(crate) first_step: f64,
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
        let Dynamics::Inertial(inertia) = model.options().dynamics else {
            return None;
        };
        let c = Coefficients::new(model, &inertia);
        // the reference's scale (its inertial driver)
        let (tau, move_time, drag_time) = c.times(model);
        Some(InertialModel {
            restitution: inertia.restitution,
            scale: tau.max(move_time).max(drag_time),
            first_step: tau.min(move_time),
            c,
        })
    }

    /// The acceleration of unknown `g` (state index) at velocity `v` under `drive`.
    pub(crate) fn acceleration(&self, g: usize, drive: f64, v: f64) -> f64 {
        let fc = self.c.coulomb[g];
        let friction = if fc > 0.0 { fc * (v * 1e3).tanh() } else { 0.0 };
        (drive - friction) * self.c.inv_mass[g] - self.c.damping[g] * v
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
        let a = press.max(0.0) * self.c.inv_mass[g];
        if self.restitution <= 0.0 || rebound * rebound < 2.0 * a * REST_HEIGHT {
            None
        } else {
            Some(rebound)
        }
    }

    /// Whether an unknown with velocity `v` and acceleration `a` is quiet (the reference's
    /// rest test).
    pub(crate) fn quiet(&self, v: f64, a: f64) -> bool {
        v.abs() * self.scale < 1e-7 && a.abs() * self.scale * self.scale < 1e-7
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
    use crate::engine::{run, EngineOptions};
    use crate::physics::Inertia;
    use crate::reference::{run_reference, ModelOptions, ReferenceOptions};
    use crate::timeline::{EventKind, TileDesigns};
    use crate::{Chain, Design};

    fn inertial() -> ModelOptions {
        ModelOptions::default().with_dynamics(Dynamics::Inertial(Inertia::default()))
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
        assert!(im.quiet(0.0, 0.0) && !im.quiet(1.0, 0.0));
    }

    #[test]
    fn inertial_engine_events_are_the_inertial_references() {
        // a serpentine repeats its U-turns: a cached unit must not stand for a joint that
        // swings a different tail (its inertia grows with the tiles it swings)
        let serpentine = "S*8 L L S*8 R R S*8 L L S*8 R R S*8";
        for (word, s, most) in [
            ("SL", 0.3, 1.0),
            ("LL", 0.3, 1.0),
            ("SSLS", 0.05, 1.0),
            (serpentine, 0.3, 5.0),
        ] {
            let chain = Chain::parse(word).unwrap();
            let designs = TileDesigns::global(Design::thesis().with_s(s));
            let r = run_reference(
                &chain,
                &designs,
                &ReferenceOptions::default().with_model(inertial()),
            )
            .unwrap();
            let e = run(
                &chain,
                &designs,
                &EngineOptions::default().with_model(inertial()),
            )
            .unwrap();
            assert_eq!(e.outcome.name(), r.outcome.name(), "{word}");
            let d = r.duration();
            // seconds at most (the overdamped runs take ten times longer or more)
            assert!(d < most, "{word}: {d}");
            let motion = |k: EventKind| k != EventKind::RiContact;
            let (a, b): (Vec<_>, Vec<_>) = (
                r.events.iter().filter(|x| motion(x.kind)).collect(),
                e.events.iter().filter(|x| motion(x.kind)).collect(),
            );
            assert_eq!(a.len(), b.len(), "{word}");
            // the n-th event of a kind and index against the n-th (a magnet pulled off its
            // end arrives twice)
            let nth = |list: &[&crate::timeline::Event], x: &crate::timeline::Event| {
                list.iter()
                    .filter(|y| y.kind == x.kind && y.index == x.index && y.time < x.time)
                    .count()
            };
            for x in &a {
                let n = nth(&a, x);
                let y = b
                    .iter()
                    .filter(|y| y.kind == x.kind && y.index == x.index)
                    .nth(n)
                    .unwrap_or_else(|| panic!("{word}: {x:?} missing"));
                // the reference locates its starts within its steps as the engine does
                // (measured: within 2.8e-5 of the run; 5e-3 when it noted them at the end
                // of the step, up to a step late)
                assert!(
                    (x.time - y.time).abs() <= 1e-4 * d,
                    "{word}: {x:?} vs {y:?}"
                );
            }
        }
    }
}
