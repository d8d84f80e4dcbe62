//! The free-body equations at one state ([`FreeBody`]): the rigid groups' poses and
//! velocities from the base (tile 0) and the turning joints, the magnets' pair forces
//! ([`crate::physics`]'s law, polarity and chain-index cutoff, as [`Model`] weighs them), the
//! water's drag, and the groups' accelerations by the articulated-body recursion
//! (Featherstone 2008, ch. 7 and 9.3, floating base), O(groups) once the forces are known.
//!
//! **State** (SI units): `[X, Y, phi, VX, VY, w]` of tile 0 in the world (its centre, m; its
//! heading, rad; their rates), then per model unknown (magnet or folding joint, the model's
//! order) its value and its rate: a magnet's fraction of path, a joint's fraction of fold.
//!
//! **Forces.** The pair forces are internal: only the pairs between two groups (a few per
//! turning joint) move the groups, and only those near a magnet drive it along its path. A
//! magnet slides relative to its tile by the model's inertial law (`m L x'' = F . t -
//! gamma L x'`, [`InertialModel`]); the channel passes the pair force on to the tile (the
//! magnet's own mass rides with its tile, [`crate::reference::free_body`]). The RI rides
//! on tile 0. With no water drag, linear and angular momentum are conserved exactly by the
//! equations (the pair forces are central and come in equal and opposite pairs).
//!
//! **A held joint** carries a torque about its hinge ([`FreeBody::held_drives`]): what the
//! part of the chain after it needs to follow the group it belongs to. A joint held straight
//! by its face lets go when that torque would have to pull the part back from folding, a
//! closed one when it would have to hold it closed: the free-body counterpart of the model's
//! joint drive (the torque of the pairs across the joint), to which it reduces when the
//! chain is still.

use std::f64::consts::FRAC_PI_2;

use kurbo::{Point, Vec2};

use crate::model::{InertialModel, Mode, Model, Unknown};
use crate::ode::System;
use crate::physics::ReactionInitiator;
use crate::reference::free_body::groups::{Groups, Moments};
use crate::reference::free_body::spatial::{
    add, axpy, cross_force, cross_motion, dot, inertia, minus_outer, mul, shift_force_back,
    shift_inertia_back, shift_motion, solve, Mat3, Vec3,
};
use crate::reference::free_body::tile_body::TileBodies;
use crate::tile_frame::TileFrame;

/// Entries of the base in the state.
pub(crate) const BASE: usize = 6;

/// What stays the same over a run.
#[derive(Debug)]
pub(crate) struct Setup {
    pub(crate) model: Model,
    pub(crate) im: InertialModel,
    pub(crate) bodies: TileBodies,
    pub(crate) moments: Vec<f64>,
    pub(crate) ri: ReactionInitiator,
    /// Left and right hinge in a tile's frame, mm.
    pub(crate) hinges: [Point; 2],
    pub(crate) cutoff: usize,
    /// The folding joints.
    pub(crate) folding: Vec<usize>,
    /// Coefficient of restitution of a fold meeting its walls.
    pub(crate) restitution: f64,
    /// The coupled joint-angle reference ([`crate::reference::ReferenceOptions::coupled`]):
    /// the base's pose is not integrated and its velocity is not a state but what keeps the
    /// chain's momentum zero ([`FreeBody::evaluate`]).
    pub(crate) zero_momentum: bool,
}

impl Setup {
    /// State index of model unknown `i`'s value (its rate follows it).
    pub(crate) fn at(i: usize) -> usize {
        BASE + 2 * i
    }

    /// The hinge of joint `j` in its first tile's frame, mm.
    pub(crate) fn hinge(&self, j: usize) -> Point {
        self.hinges[usize::from(self.model.joint_sign(j) < 0.0)]
    }

    /// The model unknowns' values in state `z`.
    pub(crate) fn values(&self, z: &[f64]) -> Vec<f64> {
        (0..self.model.len()).map(|i| z[Self::at(i)]).collect()
    }

    /// The model unknowns' rates in state `z`.
    pub(crate) fn rates(&self, z: &[f64]) -> Vec<f64> {
        (0..self.model.len()).map(|i| z[Self::at(i) + 1]).collect()
    }
}

/// Scratch of one evaluation.
#[derive(Debug, Default)]
pub(crate) struct Work {
    /// Group frames in tile 0's frame, mm, and their reference points (first tile centres), m.
    pub(crate) frames: Vec<TileFrame>,
    pub(crate) origin: Vec<[f64; 2]>,
    /// Per group: velocity, velocity-product acceleration, inertia (tile 0's axes, about its
    /// reference point), external force, articulated inertia and bias, joint axis (of the
    /// joint before it), `U`, `D`, `u`, acceleration, force across the joint before it.
    pub(crate) v: Vec<Vec3>,
    c: Vec<Vec3>,
    pub(crate) inertia: Vec<Mat3>,
    fext: Vec<Vec3>,
    ia: Vec<Mat3>,
    pa: Vec<Vec3>,
    pub(crate) axis: Vec<Vec3>,
    uvec: Vec<Vec3>,
    dd: Vec<f64>,
    uu: Vec<f64>,
    pub(crate) a: Vec<Vec3>,
    pub(crate) ftrans: Vec<Vec3>,
    /// Per group: the turn rate's acceleration of the joint before it, rad/s^2.
    pub(crate) qdd: Vec<f64>,
    /// The base's acceleration in the world: `[w', VX', VY']`.
    pub(crate) base_acc: [f64; 3],
    /// Drives of the free magnets (N), by model unknown.
    pub(crate) drive: Vec<f64>,
    /// Magnet positions (mm) and tangents in tile 0's frame, computed when first asked for
    /// in an evaluation (`stamp == epoch`).
    pos: Vec<Point>,
    tan: Vec<Vec2>,
    stamp: Vec<u32>,
    epoch: u32,
    /// The whole state being evaluated: the stepper's packed states are scattered into it
    /// (the held unknowns' entries stay as they were set when the modes last changed).
    pub(crate) full: Vec<f64>,
}

/// The free-body system at one set of modes and groups.
pub(crate) struct FreeBody<'a> {
    pub(crate) setup: &'a Setup,
    pub(crate) groups: &'a Groups,
    pub(crate) modes: &'a [Mode],
    /// The free unknowns, in order: the stepper's state is the base then their values and
    /// rates.
    pub(crate) packed: &'a [usize],
}

/// A frame `b` given in frame `a`, in `a`'s parent.
fn compose(a: &TileFrame, b: &TileFrame) -> TileFrame {
    let p = a.point((b.x, b.y));
    TileFrame {
        x: p.x,
        y: p.y,
        angle: a.angle + b.angle,
        sin: a.sin * b.cos + a.cos * b.sin,
        cos: a.cos * b.cos - a.sin * b.sin,
    }
}

fn mm(p: Point) -> [f64; 2] {
    [p.x * 1e-3, p.y * 1e-3]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The wrench at `o` (m) of force `f` (N) acting at `p` (mm).
fn wrench(p: Point, f: Vec2, o: [f64; 2]) -> Vec3 {
    let r = sub(mm(p), o);
    [r[0] * f.y - r[1] * f.x, f.x, f.y]
}

/// Group inertia (or drag) of moments `m` in tile 0's axes, the group turned by `(sin, cos)`.
fn spatial(m: &Moments, sin: f64, cos: f64) -> Mat3 {
    inertia(m.m, m.turned_s(sin, cos), m.j)
}

impl FreeBody<'_> {
    fn model(&self) -> &Model {
        &self.setup.model
    }

    /// Magnet `k`'s position (mm) and tangent in tile 0's frame.
    fn magnet(&self, k: usize, w: &mut Work) -> (Point, Vec2) {
        if w.stamp[k] != w.epoch {
            let t = k / 2;
            let g = self.groups.of_tile[t];
            let f = compose(&w.frames[g], &self.groups.rel[t]);
            let (p, tg) = self
                .model()
                .local_continued(k, w.full[Setup::at(self.model().magnet_var(k))]);
            w.pos[k] = f.point(p);
            w.tan[k] = f.vector(tg);
            w.stamp[k] = w.epoch;
        }
        (w.pos[k], w.tan[k])
    }

    /// The force on magnet `b` from magnet `a` (`None`: the RI), N, and `b`'s position.
    fn pair(&self, a: Option<usize>, b: usize, w: &mut Work) -> (Vec2, Point, Point) {
        let (pb, _) = self.magnet(b, w);
        let (pa, ma, attract) = match a {
            None => (self.setup.ri.position, self.setup.ri.moment, b % 2 == 0),
            Some(a) => (
                self.magnet(a, w).0,
                self.setup.moments[a],
                b.abs_diff(a) % 2 == 1,
            ),
        };
        let law = self.model().options().force_law;
        (
            law.force_with(pa, pb, ma, self.setup.moments[b], attract),
            pa,
            pb,
        )
    }

    /// The force on magnet `k` of every pole within the cutoff, N.
    pub(crate) fn magnet_force(&self, k: usize, w: &mut Work) -> Vec2 {
        let n = self.model().geometry.magnets();
        let c = self.setup.cutoff;
        let mut f = Vec2::ZERO;
        if k < c {
            f += self.pair(None, k, w).0;
        }
        for a in k.saturating_sub(c)..=(k + c).min(n - 1) {
            if a != k {
                f += self.pair(Some(a), k, w).0;
            }
        }
        f
    }

    /// Magnet `k`'s drive along its path, N.
    pub(crate) fn magnet_drive(&self, k: usize, w: &mut Work) -> f64 {
        let f = self.magnet_force(k, w);
        let (_, t) = self.magnet(k, w);
        f.dot(t)
    }

    /// Evaluates the whole state `z`: frames, velocities, forces, accelerations (into `w`).
    pub(crate) fn evaluate(&self, z: &[f64], w: &mut Work) {
        w.full.clear();
        w.full.extend_from_slice(z);
        self.evaluate_full(w);
    }

    /// Evaluates the state in `w.full`.
    fn evaluate_full(&self, w: &mut Work) {
        self.clear_work(w);
        if self.setup.zero_momentum {
            // the base's velocity that gives the chain no momentum at the joints' rates
            // (`w.full[2]`, the base's heading, stays 0: tile 0's axes are the world's)
            w.full[3..BASE].fill(0.0);
            self.frames_and_velocities(w);
            self.inertias_and_drags(w);
            let (h, composite) = self.base_momentum(w);
            let v0 = solve(&composite, [-h[0], -h[1], -h[2]]).unwrap_or([0.0; 3]);
            w.full[3] = v0[1];
            w.full[4] = v0[2];
            w.full[5] = v0[0];
        }
        let (sp, cp) = self.frames_and_velocities(w);
        self.inertias_and_drags(w);
        self.pair_wrenches(w);
        let model = self.model();
        // the free magnets' drives
        for (p, &i) in self.packed.iter().enumerate() {
            if let Unknown::Magnet(k) = model.unknowns[i] {
                w.drive[p] = self.magnet_drive(k, w);
            }
        }
        self.articulated(w, |_| 0.0, true);
        let a0 = w.a[0];
        let v0 = w.v[0];
        // the classical acceleration of tile 0's centre: the spatial one plus w x v
        let ax = a0[1] - v0[0] * v0[2];
        let ay = a0[2] + v0[0] * v0[1];
        w.base_acc = [a0[0], cp * ax - sp * ay, sp * ax + cp * ay];
    }

    /// Sizes `w`'s buffers for the groups and magnets and clears them, and starts a new epoch
    /// of the magnets' cached positions.
    fn clear_work(&self, w: &mut Work) {
        let ng = self.groups.len();
        let n = self.model().geometry.magnets();
        if w.stamp.len() != n {
            w.stamp = vec![0; n];
            w.pos = vec![Point::ORIGIN; n];
            w.tan = vec![Vec2::ZERO; n];
            w.epoch = 0;
        }
        w.epoch = w.epoch.wrapping_add(1);
        if w.epoch == 0 {
            w.stamp.fill(0);
            w.epoch = 1;
        }
        for buf in [
            &mut w.v,
            &mut w.c,
            &mut w.fext,
            &mut w.pa,
            &mut w.axis,
            &mut w.uvec,
            &mut w.a,
            &mut w.ftrans,
        ] {
            buf.clear();
            buf.resize(ng, [0.0; 3]);
        }
        for buf in [&mut w.inertia, &mut w.ia] {
            buf.clear();
            buf.resize(ng, [[0.0; 3]; 3]);
        }
        for buf in [&mut w.dd, &mut w.uu, &mut w.qdd] {
            buf.clear();
            buf.resize(ng, 0.0);
        }
        w.drive.clear();
        w.drive.resize(self.packed.len(), 0.0);
    }

    /// Each group's frame, joint axis and velocity, outwards from the base; the base's
    /// heading's sine and cosine.
    fn frames_and_velocities(&self, w: &mut Work) -> (f64, f64) {
        let model = self.model();
        let groups = self.groups;
        let ng = groups.len();
        let half = 0.5 * model.geometry.w;
        w.frames.clear();
        w.origin.clear();
        // the base's velocity in tile 0's axes
        let (sp, cp) = w.full[2].sin_cos();
        let (vx, vy) = (w.full[3], w.full[4]);
        w.v[0] = [w.full[5], cp * vx + sp * vy, -sp * vx + cp * vy];
        w.frames.push(TileFrame::IDENTITY);
        w.origin.push([0.0, 0.0]);
        // frames, joint axes and velocities outwards
        for g in 1..ng {
            let j = groups.last[g - 1];
            let v = model.joint_var(j).unwrap_or(0);
            let sign = model.joint_sign(j);
            let theta = sign * w.full[Setup::at(v)] * FRAC_PI_2;
            let theta_dot = sign * w.full[Setup::at(v) + 1] * FRAC_PI_2;
            let before = compose(&w.frames[g - 1], &groups.rel[j]);
            let hinge = self.setup.hinge(j);
            let f = before.across_joint(theta, hinge, half);
            let h = mm(before.point((hinge.x, hinge.y)));
            let o = [f.x * 1e-3, f.y * 1e-3];
            w.frames.push(f);
            w.origin.push(o);
            let r = sub(o, h);
            let axis = [1.0, -r[1], r[0]];
            w.axis[g] = axis;
            let vj = [theta_dot, axis[1] * theta_dot, axis[2] * theta_dot];
            let shifted = shift_motion(w.v[g - 1], sub(o, w.origin[g - 1]));
            w.v[g] = axpy(shifted, 1.0, vj);
            w.c[g] = cross_motion(w.v[g], vj);
        }
        (sp, cp)
    }

    /// Each group's spatial inertia, and the water's drags as its external force.
    fn inertias_and_drags(&self, w: &mut Work) {
        let model = self.model();
        let groups = self.groups;
        let ng = groups.len();
        // inertias and drags
        for g in 0..ng {
            let (s, co) = (w.frames[g].sin, w.frames[g].cos);
            w.inertia[g] = spatial(&groups.mass[g], s, co);
            let drag = spatial(&groups.drag[g], s, co);
            let fd = mul(&drag, w.v[g]);
            w.fext[g] = [-fd[0], -fd[1], -fd[2]];
        }
        if self.setup.bodies.form {
            for t in 0..model.geometry.tiles() {
                let g = groups.of_tile[t];
                let f = compose(&w.frames[g], &groups.rel[t]);
                let r = sub([f.x * 1e-3, f.y * 1e-3], w.origin[g]);
                let vt = shift_motion(w.v[g], r);
                let b = &self.setup.bodies.tiles[t];
                let speed = vt[1].hypot(vt[2]);
                let drag = [
                    -b.rotational_form * vt[0].abs() * vt[0],
                    -b.form * speed * vt[1],
                    -b.form * speed * vt[2],
                ];
                w.fext[g] = axpy(w.fext[g], 1.0, shift_force_back(drag, r));
            }
        }
    }

    /// The pair forces between groups (and with the RI) as wrenches on the groups.
    fn pair_wrenches(&self, w: &mut Work) {
        let groups = self.groups;
        let ng = groups.len();
        let n = self.model().geometry.magnets();
        let c = self.setup.cutoff;
        // the pairs between groups: each counted at the boundary after the group of its
        // upstream magnet
        for g in 1..ng {
            let j = groups.last[g - 1];
            let a0 = 2 * groups.first[g - 1];
            for b in 2 * j + 2..=(2 * j + 1 + c).min(n - 1) {
                for a in b.saturating_sub(c).max(a0)..=2 * j + 1 {
                    let (f, pa, pb) = self.pair(Some(a), b, w);
                    let gb = groups.of_tile[b / 2];
                    let ga = groups.of_tile[a / 2];
                    w.fext[gb] = axpy(w.fext[gb], 1.0, wrench(pb, f, w.origin[gb]));
                    w.fext[ga] = axpy(w.fext[ga], -1.0, wrench(pa, f, w.origin[ga]));
                }
            }
        }
        for b in 0..c.min(n) {
            let gb = groups.of_tile[b / 2];
            if gb != 0 {
                let (f, pa, pb) = self.pair(None, b, w);
                w.fext[gb] = axpy(w.fext[gb], 1.0, wrench(pb, f, w.origin[gb]));
                w.fext[0] = axpy(w.fext[0], -1.0, wrench(pa, f, w.origin[0]));
            }
        }
    }

    /// The articulated-body recursion on the evaluated frames and inertias: accelerations
    /// `w.a` and joint accelerations `w.qdd` under joint torques `tau(g)` (on the joint
    /// before group `g`) and, when `loaded`, the velocities and external forces of `w`
    /// (else none: the response to the torques alone, from rest).
    pub(crate) fn articulated(&self, w: &mut Work, tau: impl Fn(usize) -> f64, loaded: bool) {
        let ng = self.groups.len();
        for g in 0..ng {
            w.ia[g] = w.inertia[g];
            w.pa[g] = if loaded {
                let p = cross_force(w.v[g], mul(&w.inertia[g], w.v[g]));
                axpy(p, -1.0, w.fext[g])
            } else {
                [0.0; 3]
            };
        }
        for g in (1..ng).rev() {
            let s = w.axis[g];
            let u = mul(&w.ia[g], s);
            let d = dot(s, u);
            let uu = tau(g) - dot(s, w.pa[g]);
            let ia = minus_outer(&w.ia[g], u, d);
            let mut pa = axpy(w.pa[g], uu / d, u);
            if loaded {
                pa = axpy(pa, 1.0, mul(&ia, w.c[g]));
            }
            w.uvec[g] = u;
            w.dd[g] = d;
            w.uu[g] = uu;
            let r = sub(w.origin[g], w.origin[g - 1]);
            w.ia[g - 1] = add(&w.ia[g - 1], &shift_inertia_back(&ia, r));
            w.pa[g - 1] = axpy(w.pa[g - 1], 1.0, shift_force_back(pa, r));
        }
        let p0 = w.pa[0];
        w.a[0] = solve(&w.ia[0], [-p0[0], -p0[1], -p0[2]]).unwrap_or([f64::NAN; 3]);
        w.ftrans[0] = [0.0; 3];
        for g in 1..ng {
            let r = sub(w.origin[g], w.origin[g - 1]);
            let mut a = shift_motion(w.a[g - 1], r);
            if loaded {
                a = axpy(a, 1.0, w.c[g]);
            }
            let qdd = (w.uu[g] - dot(w.uvec[g], a)) / w.dd[g];
            a = axpy(a, qdd, w.axis[g]);
            w.a[g] = a;
            w.qdd[g] = qdd;
            // the force through the joint on everything after it
            w.ftrans[g] = axpy(mul(&w.ia[g], a), 1.0, w.pa[g]);
        }
    }

    /// The rates of the packed state into `out` (after an evaluation into `w`).
    fn rates(&self, w: &Work, out: &mut [f64]) {
        let model = self.model();
        let z = &w.full;
        if self.setup.zero_momentum {
            // the base's velocity follows the joints' rates: nothing of it is stepped
            out[..BASE].fill(0.0);
        } else {
            out[0] = z[3];
            out[1] = z[4];
            out[2] = z[5];
            out[3] = w.base_acc[1];
            out[4] = w.base_acc[2];
            out[5] = w.base_acc[0];
        }
        for (p, &i) in self.packed.iter().enumerate() {
            let v = z[Setup::at(i) + 1];
            out[BASE + 2 * p] = v;
            out[BASE + 2 * p + 1] = match model.unknowns[i] {
                // (a magnet's acceleration does not depend on its place on its path)
                Unknown::Magnet(_) => self.setup.im.acceleration(i, 0.0, w.drive[p], v),
                Unknown::Joint(j) => {
                    let g = self.groups.of_tile[j + 1];
                    model.joint_sign(j) * w.qdd[g] / FRAC_PI_2
                }
            };
        }
    }

    /// The drive of every held folding joint (model unknown index, N m towards folding) at
    /// the state last evaluated into `w`: minus the torque about its hinge that the joint
    /// passes to the part after it, the part's rate of angular momentum about the hinge
    /// less the torques of the water and of the pairs acting on it from outside it.
    pub(crate) fn held_drives(&self, w: &mut Work, out: &mut Vec<(usize, f64)>) {
        out.clear();
        let model = self.model();
        let groups = self.groups;
        let n = model.geometry.magnets();
        let c = self.setup.cutoff;
        for &j in &self.setup.folding {
            let Some(v) = model.joint_var(j) else {
                continue;
            };
            if self.modes[v] == Mode::Free {
                continue;
            }
            let g = groups.of_tile[j];
            let (s, co) = (w.frames[g].sin, w.frames[g].cos);
            let o = w.origin[g];
            let mi = spatial(&groups.suffix_mass[j + 1], s, co);
            let di = spatial(&groups.suffix_drag[j + 1], s, co);
            let (a, vel) = (w.a[g], w.v[g]);
            let mut need = axpy(mul(&mi, a), 1.0, cross_force(vel, mul(&mi, vel)));
            need = axpy(need, 1.0, mul(&di, vel));
            let last = groups.last[g];
            if self.setup.bodies.form {
                for t in j + 1..=last {
                    let f = compose(&w.frames[g], &groups.rel[t]);
                    let r = sub([f.x * 1e-3, f.y * 1e-3], o);
                    let vt = shift_motion(vel, r);
                    let b = &self.setup.bodies.tiles[t];
                    let speed = vt[1].hypot(vt[2]);
                    let drag = [
                        b.rotational_form * vt[0].abs() * vt[0],
                        b.form * speed * vt[1],
                        b.form * speed * vt[2],
                    ];
                    need = axpy(need, 1.0, shift_force_back(drag, r));
                }
            }
            // the pairs acting on the part (magnets lo..=hi) from outside it
            let (lo, hi) = (2 * j + 2, 2 * last + 1);
            for m in lo..=(lo + c - 1).min(hi) {
                for p in m.saturating_sub(c)..lo {
                    let (f, _, pm) = self.pair(Some(p), m, w);
                    need = axpy(need, -1.0, wrench(pm, f, o));
                }
                if m < c {
                    let (f, _, pm) = self.pair(None, m, w);
                    need = axpy(need, -1.0, wrench(pm, f, o));
                }
            }
            for m in (hi + 1).saturating_sub(c).max(lo)..=hi {
                for p in hi + 1..=(m + c).min(n - 1) {
                    let (f, _, pm) = self.pair(Some(p), m, w);
                    need = axpy(need, -1.0, wrench(pm, f, o));
                }
            }
            if g + 1 < groups.len() {
                let r = sub(w.origin[g + 1], o);
                need = axpy(need, 1.0, shift_force_back(w.ftrans[g + 1], r));
            }
            // the torque about the hinge
            let before = compose(&w.frames[g], &groups.rel[j]);
            let h = mm(before.point({
                let p = self.setup.hinge(j);
                (p.x, p.y)
            }));
            let r = sub(o, h);
            let torque = dot([1.0, -r[1], r[0]], need);
            out.push((v, -model.joint_sign(j) * torque));
        }
    }

    /// The chain's momentum about tile 0's centre in tile 0's axes (`[angular, x, y]`) and
    /// its composite inertia there (every joint held), after [`FreeBody::evaluate`].
    pub(crate) fn base_momentum(&self, w: &Work) -> (Vec3, Mat3) {
        let mut h = [0.0; 3];
        let mut composite = [[0.0; 3]; 3];
        for g in 0..self.groups.len() {
            let hg = mul(&w.inertia[g], w.v[g]);
            h = axpy(h, 1.0, shift_force_back(hg, w.origin[g]));
            composite = add(&composite, &shift_inertia_back(&w.inertia[g], w.origin[g]));
        }
        (h, composite)
    }

    /// The chain's momentum at state `z` (after [`FreeBody::evaluate`] into `w`) at `time`.
    pub(crate) fn momentum(&self, time: f64, z: &[f64], w: &Work) -> Momentum {
        let (sp, cp) = z[2].sin_cos();
        let world = |h: Vec3| {
            let p = [cp * h[1] - sp * h[2], sp * h[1] + cp * h[2]];
            (p, h[0] + z[0] * p[1] - z[1] * p[0])
        };
        let (mut linear_scale, mut angular_scale) = (0.0, 0.0);
        for g in 0..self.groups.len() {
            let hg = shift_force_back(mul(&w.inertia[g], w.v[g]), w.origin[g]);
            let (p, l) = world(hg);
            linear_scale += p[0].hypot(p[1]);
            angular_scale += l.abs();
        }
        let (linear, angular) = world(self.base_momentum(w).0);
        Momentum {
            time,
            linear,
            angular,
            linear_scale,
            angular_scale,
        }
    }
}

/// The chain's momentum at one moment (world frame, SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Momentum {
    /// Time, s.
    pub time: f64,
    /// Linear momentum, kg m/s.
    pub linear: [f64; 2],
    /// Angular momentum about the world origin, kg m^2/s.
    pub angular: f64,
    /// The sum of the magnitudes of the rigid groups' linear momenta: what the total's
    /// error is measured against.
    pub linear_scale: f64,
    /// The same of their angular momenta about the world origin.
    pub angular_scale: f64,
}

impl System for FreeBody<'_> {
    type Work = Work;

    fn bandwidth(&self) -> usize {
        0
    }

    fn counts(&self, i: usize) -> bool {
        // the base's pose feeds nothing back; its velocities do (the water's drag)
        i >= 3
    }

    /// `z` is the packed state: the base, then the free unknowns' values and rates.
    fn rhs(&self, z: &[f64], work: &mut Work, out: &mut [f64]) {
        work.full[..BASE].copy_from_slice(&z[..BASE]);
        for (p, &i) in self.packed.iter().enumerate() {
            let at = Setup::at(i);
            work.full[at] = z[BASE + 2 * p];
            work.full[at + 1] = z[BASE + 2 * p + 1];
        }
        self.evaluate_full(work);
        self.rates(work, out);
    }
}
