//! The reference model: overdamped point-dipole dynamics of every magnet on its path and of
//! every folding joint about its hinge (SPEC (6.11), (6.12)).
//!
//! **State.** One unknown per magnet, `x_k = u_k / L_k` (the fraction of its path travelled),
//! and one per folding joint (an LL or RR pair), `psi_j = |theta_j| / (pi/2)` (the fraction of
//! its fold made). Both lie in `[0, 1]`, so one tolerance fits every unknown whatever the
//! tile size. Unknowns are interleaved tile by tile (`x_2t, x_2t+1, psi_t`), so that with the
//! chain-index cutoff the Jacobian is banded with a fixed bandwidth ([`Model::bandwidth`]).
//!
//! **Forces.** Moments stand upright and alternate along the chain (the RI is magnet `-1`),
//! so the pair force is central: `F = 3 mu0 m_i m_j / (4 pi r^4)`, attracting for an odd
//! index difference and repelling for an even one. Only pairs at most
//! [`ModelOptions::cutoff`] apart in chain index interact (default 3: partner,
//! neighbour, the same-pole magnets one tile away and the next opposite pole). The first
//! pair left out is 4 apart, two tiles (about `2w`) away in a straight run: `(b / 2w)^4`
//! = 0.33% of the bonded rest force on the thesis design, and the left-out terms alternate
//! in sign. [`Model::cutoff_error`] measures it on a given configuration against all pairs.
//!
//! **Motion.** A magnet slides with `gamma du/dt = F . t` (the force along its path's
//! tangent; the wall takes the rest); a joint turns with `gamma_rot dtheta/dt = tau`, the
//! torque about its hinge of every force that a magnet upstream of the joint (or the RI)
//! exerts on one downstream (internal forces of the downstream part have no net torque).
//! Each unknown has a mode: at its start, free, or at its end. A clamped unknown does not
//! move until its drive (the force along the path, or the torque towards folding) pushes it
//! away from the end by more than the static friction threshold; the driver finds those
//! moments, and the arrivals, as events ([`crate::reference::events`]). Non-folding joints
//! are rigid: a straight or LR joint has no hinge that opens the way the pair pulls.

use std::f64::consts::FRAC_PI_2;

use crate::design::MU0;
use crate::engine::{Geometry, TileDesigns, DEFAULT_DRAG};
use crate::magnet_path::MagnetPath;
use crate::{Chain, Octagon, PathKind, Pose};

/// Default chain-index cutoff of the pair forces (see the module documentation).
pub const DEFAULT_CUTOFF: usize = 3;

/// Default rotational drag of a joint, N m s: the magnet drag [`DEFAULT_DRAG`] times the
/// square of the thesis' magnet radius (1.5 mm), 1.125e-5. The thesis gives no value; with
/// it a fold of the thesis design takes about as long as the magnets' move, as in the event
/// engine's fold law. Fold times scale with it.
pub const DEFAULT_ROTATIONAL_DRAG: f64 = DEFAULT_DRAG * 1.5e-3 * 1.5e-3;

/// A drive (N for magnets, N m for joints) smaller than this fraction of the bonded rest
/// force (or torque) counts as zero, so that exact balances (`s = 0`) do not start a magnet
/// on a rounding error: 1e-12.
pub const BALANCE_TOLERANCE: f64 = 1e-12;

/// Options of the reference model. Defaults: drag [`DEFAULT_DRAG`], rotational drag
/// [`DEFAULT_ROTATIONAL_DRAG`], no static friction, cutoff [`DEFAULT_CUTOFF`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelOptions {
    /// Drag of a magnet in its channel, N s/m.
    pub drag: f64,
    /// Drag of a joint turning, N m s.
    pub rotational_drag: f64,
    /// Static friction threshold, N: a magnet starts (and keeps moving) only while the force
    /// along its path exceeds it; it also slows a moving magnet (Coulomb friction).
    pub static_friction: f64,
    /// Pairs at most this many apart in chain index interact (at least 1).
    pub cutoff: usize,
}

impl Default for ModelOptions {
    fn default() -> ModelOptions {
        ModelOptions {
            drag: DEFAULT_DRAG,
            rotational_drag: DEFAULT_ROTATIONAL_DRAG,
            static_friction: 0.0,
            cutoff: DEFAULT_CUTOFF,
        }
    }
}

impl ModelOptions {
    /// Another magnet drag, N s/m.
    pub fn with_drag(mut self, drag: f64) -> ModelOptions {
        self.drag = drag;
        self
    }
    /// Another rotational drag, N m s.
    pub fn with_rotational_drag(mut self, drag: f64) -> ModelOptions {
        self.rotational_drag = drag;
        self
    }
    /// A static friction threshold, N.
    pub fn with_static_friction(mut self, f: f64) -> ModelOptions {
        self.static_friction = f;
        self
    }
    /// Another chain-index cutoff.
    pub fn with_cutoff(mut self, cutoff: usize) -> ModelOptions {
        self.cutoff = cutoff;
        self
    }
}

/// What one unknown is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unknown {
    /// Magnet `k`'s fraction of path travelled.
    Magnet(usize),
    /// Joint `j`'s fraction of fold made.
    Joint(usize),
}

/// Where an unknown is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Held at 0 (magnet at rest, joint straight).
    AtStart,
    /// Moving freely inside `(0, 1)`.
    Free,
    /// Held at 1 (magnet arrived, joint closed by its walls).
    AtEnd,
}

/// The model of one chain.
#[derive(Debug)]
pub struct Model {
    /// The engine's geometry (paths in tile frames).
    pub geometry: Geometry,
    opts: ModelOptions,
    /// The unknowns, in state order.
    pub unknowns: Vec<Unknown>,
    /// State index of each magnet.
    magnet_var: Vec<usize>,
    /// State index of each joint, `usize::MAX` for rigid joints.
    joint_var: Vec<usize>,
    /// Fold direction of each joint: +1 left, -1 right, 0 rigid.
    joint_sign: Vec<f64>,
    lengths: Vec<f64>,
    kinks: Vec<f64>,
    moments: Vec<f64>,
    ri_moment: f64,
    hinge_left: (f64, f64),
    hinge_right: (f64, f64),
    /// Bonded rest force, N (scale of the drives).
    pub force_scale: f64,
    /// Bonded rest torque about a hinge, N m.
    pub torque_scale: f64,
    /// A time scale, s: a path travelled at the bonded rest force's speed.
    pub time_scale: f64,
    bandwidth: usize,
}

/// Everything the forces give at one state.
#[derive(Clone, Debug, Default)]
pub struct Forces {
    /// World positions of the magnets, mm.
    pub positions: Vec<(f64, f64)>,
    /// Drive of each unknown (force along the path, N, or torque towards folding, N m).
    pub drive: Vec<f64>,
}

/// Why a model cannot be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// Bad design.
    #[error(transparent)]
    Engine(#[from] crate::engine::EngineError),
    /// A model option out of range.
    #[error("reference option `{name}` = {value}: expected {expected}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}

fn fold_sign(a: PathKind, b: PathKind) -> f64 {
    match (a, b) {
        (PathKind::L, PathKind::L) => 1.0,
        (PathKind::R, PathKind::R) => -1.0,
        _ => 0.0,
    }
}

impl Model {
    /// The model of `chain` with `designs`.
    pub fn new(
        chain: &Chain,
        designs: &TileDesigns,
        opts: &ModelOptions,
    ) -> Result<Model, ModelError> {
        let bad = |name, value: f64, expected| ModelError::BadOption {
            name,
            value,
            expected,
        };
        for (name, v) in [
            ("drag", opts.drag),
            ("rotational_drag", opts.rotational_drag),
        ] {
            if !v.is_finite() || v <= 0.0 {
                return Err(bad(name, v, "a finite number > 0"));
            }
        }
        if !opts.static_friction.is_finite() || opts.static_friction < 0.0 {
            return Err(bad(
                "static_friction",
                opts.static_friction,
                "a finite number >= 0",
            ));
        }
        if opts.cutoff == 0 {
            return Err(bad("cutoff", 0.0, "at least 1"));
        }
        designs
            .validate("design")
            .map_err(crate::engine::EngineError::from)?;
        let (list, per_tile) = designs.resolve(chain.len());
        let geometry =
            Geometry::new(chain, list, per_tile).map_err(crate::engine::EngineError::from)?;
        let tiles = chain.tiles();
        let n = geometry.magnets();
        let mut unknowns = Vec::new();
        let mut magnet_var = vec![0; n];
        let mut joint_var = vec![usize::MAX; tiles.len().saturating_sub(1)];
        let mut joint_sign = vec![0.0; tiles.len().saturating_sub(1)];
        for t in 0..tiles.len() {
            for k in [2 * t, 2 * t + 1] {
                magnet_var[k] = unknowns.len();
                unknowns.push(Unknown::Magnet(k));
            }
            if t + 1 < tiles.len() {
                let sign = fold_sign(tiles[t].second, tiles[t + 1].first);
                joint_sign[t] = sign;
                if sign != 0.0 {
                    joint_var[t] = unknowns.len();
                    unknowns.push(Unknown::Joint(t));
                }
            }
        }
        let lengths: Vec<f64> = (0..n).map(|k| geometry.path(k).length()).collect();
        let kinks: Vec<f64> = (0..n)
            .map(|k| {
                if geometry.path(k).is_curved() {
                    geometry.design(k / 2).s
                } else {
                    f64::INFINITY
                }
            })
            .collect();
        let moments: Vec<f64> = (0..n).map(|k| geometry.design(k / 2).moment()).collect();
        let d0 = *geometry.design(0);
        let oct = Octagon::new(geometry.w);
        let b = d0.b().max(d0.magnet_diameter) * 1e-3;
        let force_scale =
            3.0 * MU0 / (4.0 * std::f64::consts::PI) * moments[0] * moments[0] / b.powi(4);
        let torque_scale = force_scale * 0.5 * oct.side() * 1e-3;
        let time_scale = opts.drag * lengths[0] * 1e-3 / force_scale;
        let cutoff = opts.cutoff;
        // bandwidth: the widest span of state indices over a window of cutoff + 1 magnets
        let mut bandwidth = 1;
        for k in 0..n {
            let hi = (k + cutoff).min(n - 1);
            bandwidth = bandwidth.max(magnet_var[hi] - magnet_var[k] + 1);
        }
        Ok(Model {
            geometry,
            opts: *opts,
            unknowns,
            magnet_var,
            joint_var,
            joint_sign,
            lengths,
            kinks,
            ri_moment: moments[0],
            moments,
            hinge_left: oct.hinge(true),
            hinge_right: oct.hinge(false),
            force_scale,
            torque_scale,
            time_scale,
            bandwidth,
        })
    }

    /// Number of unknowns.
    pub fn len(&self) -> usize {
        self.unknowns.len()
    }

    /// Whether there are no unknowns.
    pub fn is_empty(&self) -> bool {
        self.unknowns.is_empty()
    }

    /// The options.
    pub fn options(&self) -> &ModelOptions {
        &self.opts
    }

    /// Half-bandwidth of the Jacobian: unknowns farther apart in state order never interact.
    pub fn bandwidth(&self) -> usize {
        self.bandwidth
    }

    /// State index of magnet `k`.
    pub fn magnet_var(&self, k: usize) -> usize {
        self.magnet_var[k]
    }

    /// State index of joint `j`, if it folds.
    pub fn joint_var(&self, j: usize) -> Option<usize> {
        let v = self.joint_var[j];
        (v != usize::MAX).then_some(v)
    }

    /// Fold direction of joint `j`: +1 left, -1 right, 0 rigid.
    pub fn joint_sign(&self, j: usize) -> f64 {
        self.joint_sign[j]
    }

    /// Magnet `k`'s path length, mm.
    pub fn path_length(&self, k: usize) -> f64 {
        self.lengths[k]
    }

    /// The scale a drive of unknown `i` is measured against.
    pub fn drive_scale(&self, i: usize) -> f64 {
        match self.unknowns[i] {
            Unknown::Magnet(_) => self.force_scale,
            Unknown::Joint(_) => self.torque_scale,
        }
    }

    /// The static threshold a drive must exceed to move a clamped unknown.
    pub fn threshold(&self, i: usize) -> f64 {
        let balance = BALANCE_TOLERANCE * self.drive_scale(i);
        match self.unknowns[i] {
            Unknown::Magnet(_) => self.opts.static_friction.max(balance),
            Unknown::Joint(_) => balance,
        }
    }

    /// The signed joint angles (radians, positive = left) of state `y`.
    pub fn joint_angles(&self, y: &[f64]) -> Vec<f64> {
        (0..self.joint_var.len())
            .map(|j| match self.joint_var(j) {
                Some(v) => self.joint_sign[j] * y[v].clamp(0.0, 1.0) * FRAC_PI_2,
                None => 0.0,
            })
            .collect()
    }

    /// Tile poses (world frame, mm) of state `y`.
    pub fn poses(&self, y: &[f64]) -> Vec<Pose> {
        crate::kinematics::poses_at_angles(&self.joint_angles(y), self.geometry.w)
    }

    fn path(&self, k: usize) -> &MagnetPath {
        self.geometry.path(k)
    }

    /// Magnet `k` at fraction `x` of its path: point and unit tangent, tile frame.
    fn local(&self, k: usize, x: f64) -> ((f64, f64), (f64, f64)) {
        let p = self.path(k);
        let len = self.lengths[k];
        let u = (x * len).clamp(0.0, len);
        let point = p.point_at(u);
        let kink = self.kinks[k];
        let (a, b) = if u < kink {
            // straight part: the direction away from the tile centre, exactly
            let sx = if k % 2 == 0 { -1.0 } else { 1.0 };
            return (point, (sx, 0.0));
        } else {
            // a chord symmetric about u is parallel to an arc's tangent at u; kept on the arc
            let h = 1e-6 * len;
            let lo = (u - h).max(kink.min(len));
            let hi = (u + h).min(len);
            if hi > lo {
                (lo, hi)
            } else {
                (lo - h, lo)
            }
        };
        let (pa, pb) = (p.point_at(a), p.point_at(b));
        let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
        let norm = (dx * dx + dy * dy).sqrt();
        if norm > 0.0 {
            (point, (dx / norm, dy / norm))
        } else {
            (point, (if k % 2 == 0 { -1.0 } else { 1.0 }, 0.0))
        }
    }

    /// World positions of the magnets (mm) at state `y`.
    pub fn positions(&self, y: &[f64]) -> Vec<(f64, f64)> {
        let poses = self.poses(y);
        (0..self.geometry.magnets())
            .map(|k| {
                let (p, _) = self.local(k, y[self.magnet_var[k]]);
                poses[k / 2].transform_point(p)
            })
            .collect()
    }

    /// Force (N) on magnet at `q` from one at `p`, moments `mp`, `mq`, attracting or not.
    fn pair(p: (f64, f64), q: (f64, f64), mp: f64, mq: f64, attract: bool) -> (f64, f64) {
        let (dx, dy) = ((q.0 - p.0) * 1e-3, (q.1 - p.1) * 1e-3);
        let r2 = dx * dx + dy * dy;
        if r2 <= 0.0 {
            return (0.0, 0.0);
        }
        let r = r2.sqrt();
        let mag = 3.0 * MU0 / (4.0 * std::f64::consts::PI) * mp * mq / (r2 * r2);
        let sign = if attract { -1.0 } else { 1.0 };
        (sign * mag * dx / r, sign * mag * dy / r)
    }

    /// Drives of every unknown at state `y` (see [`Forces`]), with pairs up to `cutoff`
    /// apart in chain index.
    pub fn forces_with_cutoff(&self, y: &[f64], cutoff: usize, out: &mut Forces) {
        let n = self.geometry.magnets();
        let poses = self.poses(y);
        out.positions.clear();
        let mut tangents = Vec::with_capacity(n);
        for k in 0..n {
            let (p, t) = self.local(k, y[self.magnet_var[k]]);
            let pose = &poses[k / 2];
            out.positions.push(pose.transform_point(p));
            tangents.push(pose.transform_vector(t));
        }
        let mut force = vec![(0.0, 0.0); n];
        out.drive.clear();
        out.drive.resize(self.len(), 0.0);
        let hinges: Vec<(f64, f64)> = (0..self.joint_var.len())
            .map(|j| {
                let h = if self.joint_sign[j] >= 0.0 {
                    self.hinge_left
                } else {
                    self.hinge_right
                };
                poses[j].transform_point(h)
            })
            .collect();
        let ri = self.geometry.ri_position();
        // a = -1 is the RI (fixed in tile 0's frame, which is the world frame)
        for b in 0..n {
            let lo = b.saturating_sub(cutoff);
            let first: isize = if b < cutoff { -1 } else { lo as isize };
            for a in first..b as isize {
                let (pa, ma) = if a < 0 {
                    (ri, self.ri_moment)
                } else {
                    (out.positions[a as usize], self.moments[a as usize])
                };
                let attract = (b as isize - a) % 2 == 1;
                let f = Model::pair(pa, out.positions[b], ma, self.moments[b], attract);
                force[b].0 += f.0;
                force[b].1 += f.1;
                if a >= 0 {
                    force[a as usize].0 -= f.0;
                    force[a as usize].1 -= f.1;
                }
                // torque on every folding joint between the two (b downstream)
                let ta = if a < 0 { 0 } else { a as usize / 2 };
                for (j, &h) in hinges.iter().enumerate().take(b / 2).skip(ta) {
                    let v = self.joint_var[j];
                    if v == usize::MAX {
                        continue;
                    }
                    let r = (
                        (out.positions[b].0 - h.0) * 1e-3,
                        (out.positions[b].1 - h.1) * 1e-3,
                    );
                    let tau = r.0 * f.1 - r.1 * f.0;
                    out.drive[v] += self.joint_sign[j] * tau;
                }
            }
        }
        for k in 0..n {
            let (f, t) = (force[k], tangents[k]);
            out.drive[self.magnet_var[k]] = f.0 * t.0 + f.1 * t.1;
        }
    }

    /// Drives at state `y` with the model's cutoff.
    pub fn forces(&self, y: &[f64], out: &mut Forces) {
        self.forces_with_cutoff(y, self.opts.cutoff, out);
    }

    /// The rate of unknown `i` (per second) for drive `drive` in mode `mode`.
    pub fn rate(&self, i: usize, drive: f64, mode: Mode) -> f64 {
        if mode != Mode::Free {
            return 0.0;
        }
        match self.unknowns[i] {
            Unknown::Magnet(k) => {
                let fr = self.opts.static_friction;
                let f = drive.signum() * (drive.abs() - fr).max(0.0);
                // mm/s over the path length in mm
                f / self.opts.drag * 1e3 / self.lengths[k]
            }
            Unknown::Joint(_) => drive / self.opts.rotational_drag / FRAC_PI_2,
        }
    }

    /// The right-hand side `dy/dt` at `y` with `modes`; also leaves the drives in `work`.
    pub fn rhs(&self, y: &[f64], modes: &[Mode], work: &mut Forces, dy: &mut [f64]) {
        self.forces(y, work);
        for i in 0..self.len() {
            dy[i] = self.rate(i, work.drive[i], modes[i]);
        }
    }

    /// The largest change the cutoff makes to any magnet's drive at state `y`, as a
    /// fraction of the bonded rest force (all pairs against pairs up to the cutoff).
    pub fn cutoff_error(&self, y: &[f64]) -> f64 {
        let (mut a, mut b) = (Forces::default(), Forces::default());
        self.forces(y, &mut a);
        self.forces_with_cutoff(y, self.geometry.magnets() + 1, &mut b);
        let mut worst: f64 = 0.0;
        for (i, u) in self.unknowns.iter().enumerate() {
            if let Unknown::Magnet(_) = u {
                worst = worst.max((a.drive[i] - b.drive[i]).abs() / self.force_scale);
            }
        }
        worst
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::Design;

    fn model(word: &str, s: f64) -> Model {
        Model::new(
            &Chain::parse(word).unwrap(),
            &TileDesigns::global(Design::thesis().with_s(s)),
            &ModelOptions::default(),
        )
        .unwrap()
    }

    #[test]
    fn rest_state_holds_but_magnet_0_is_pulled_by_the_ri() {
        let m = model("SSSS", 0.3);
        let y = vec![0.0; m.len()];
        let mut f = Forces::default();
        m.forces(&y, &mut f);
        assert!(f.drive[m.magnet_var(0)] > 0.0);
        for k in 1..m.geometry.magnets() {
            assert!(f.drive[m.magnet_var(k)] < 0.0, "{k}: {}", f.drive[k]);
        }
    }

    #[test]
    fn straight_joint_held_by_the_face_and_banded() {
        let m = model("SLLS", 0.3);
        let y = vec![0.0; m.len()];
        let mut f = Forces::default();
        m.forces(&y, &mut f);
        for j in [1, 2] {
            let v = m.joint_var(j).unwrap();
            assert!(f.drive[v] < 0.0, "joint {j}: {}", f.drive[v]);
        }
        assert!(m.joint_var(0).is_none());
        assert!(m.bandwidth() <= 7, "{}", m.bandwidth());
    }

    #[test]
    fn cutoff_error_is_small_at_rest() {
        let m = model("S*19", 0.3);
        let e = m.cutoff_error(&vec![0.0; m.len()]);
        assert!(e < 0.01, "{e}");
    }
}
