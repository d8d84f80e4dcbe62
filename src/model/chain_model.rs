//! The reference model: overdamped point-dipole dynamics of every magnet on its path and of
//! every folding joint about its hinge (SPEC (6.11), (6.12)).
//!
//! **State.** One unknown per magnet, `x_k = u_k / L_k` (the fraction of its path travelled),
//! and one per folding joint (an LL or RR pair), `psi_j = |theta_j| / (pi/2)` (the fraction of
//! its fold made). Both lie in `[0, 1]`, so one tolerance fits every unknown whatever the
//! tile size. Unknowns are interleaved tile by tile (`x_2t, x_2t+1, psi_t`), so that with the
//! chain-index cutoff the Jacobian is banded with a fixed bandwidth ([`Model::bandwidth`]).
//!
//! **Forces.** The pair law, the polarity of each pair and the chain-index cutoff are
//! [`crate::physics`]'s, as in the event engine's force start rule: by default point dipoles
//! (`F = 3 mu0 m_i m_j / (4 pi r^4)`, attracting for an odd index difference, the RI being
//! magnet `-1`), pairs at most [`ModelOptions::cutoff`] apart (default
//! [`crate::physics::DEFAULT_CUTOFF`]). [`Model::cutoff_error`] measures what the cutoff
//! leaves out on a given configuration against all pairs.
//!
//! **Motion.** A magnet slides with `gamma du/dt = F . t` (the force along its path's
//! tangent; the wall takes the rest); a joint turns with `gamma_rot dtheta/dt = tau`, the
//! torque about its hinge of every force that a magnet upstream of the joint (or the RI)
//! exerts on one downstream (internal forces of the downstream part have no net torque).
//! Each unknown has a mode: at its start, free, or at its end. A clamped unknown does not
//! move until its drive (the force along the path, or the torque towards folding) pushes it
//! away from the end by more than the static friction threshold; the driver finds those
//! moments, and the arrivals, as events (the reference's driver). Non-folding joints
//! are rigid: a straight or LR joint has no hinge that opens the way the pair pulls.

use std::f64::consts::FRAC_PI_2;

use kurbo::Point;

use crate::magnet_path::{MagnetPath, PathError};
use crate::model::mode::Mode;
use crate::model::sides::{joint_sides, Sides};
use crate::model::ModelOptions;
use crate::physics::ReactionInitiator;
use crate::physics::{magnet_drag, TileBody};
use crate::timeline::{DesignsError, Geometry, GeometryError, Parameters, TileDesigns};
use crate::{Chain, Design, Octagon, Pose};

/// A drive (N for magnets, N m for joints) smaller than this fraction of the bonded rest
/// force (or torque) counts as zero, so that exact balances (`s = 0`) do not start a magnet
/// on a rounding error: 1e-12.
pub(crate) const BALANCE_TOLERANCE: f64 = 1e-12;

/// What a model may take that the joint-angle model cannot integrate.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Allow {
    /// Form drag (the free-body reference, inertial).
    pub(crate) form_drag: bool,
}

/// What one unknown is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Unknown {
    /// Magnet `k`'s fraction of path travelled.
    Magnet(usize),
    /// Joint `j`'s fraction of fold made.
    Joint(usize),
}

/// The model of one chain.
#[derive(Clone, Debug)]
pub struct Model {
    /// The chain at rest (paths in tile frames).
    pub geometry: Geometry,
    pub(super) opts: ModelOptions,
    /// Drag of a magnet in its channel, N s/m (the design's, or the dynamics' default).
    pub(crate) drag: f64,
    /// Coulomb friction of a magnet in its channel, N.
    pub(crate) friction: f64,
    /// Mass of each magnet, kg.
    pub(crate) magnet_mass: Vec<f64>,
    /// Each joint's two sides (`None` where it does not fold).
    pub(crate) sides: Vec<Option<Sides>>,
    /// Whether the engine's local solves add to a folding joint's drive the torque that a
    /// fold turning upstream makes its face pass (the free body's held-face rule, one way:
    /// `engine::local::swing`). Off by default: an experiment (issue 27 item 2, step 3).
    pub(crate) swung_faces: bool,
    /// With [`Model::swung_faces`], the folds turning downstream too (the reaction of a
    /// later fold on an earlier one turning with it).
    pub(crate) swung_back: bool,
    /// Whether the engine's local solves turn a folding joint by the coupled joint-angle
    /// reference's equations (`engine::local::cluster`: the chain's current shape, every
    /// fold turning at once read from its track, the momentum held at zero) and take its
    /// face's release from the torque it passes. Off by default: issue 27 item 2, the
    /// cluster solve's first step.
    pub(crate) coupled_folds: bool,
    /// The unknowns, in state order.
    pub(crate) unknowns: Vec<Unknown>,
    /// State index of each magnet.
    pub(super) magnet_var: Vec<usize>,
    /// State index of each joint, `usize::MAX` for rigid joints.
    pub(super) joint_var: Vec<usize>,
    /// Fold direction of each joint: +1 left, -1 right, 0 rigid.
    pub(super) joint_sign: Vec<f64>,
    pub(super) lengths: Vec<f64>,
    pub(super) moments: Vec<f64>,
    pub(super) ri: ReactionInitiator,
    pub(super) hinge_left: Point,
    pub(super) hinge_right: Point,
    /// Bonded rest force, N (scale of the drives).
    pub force_scale: f64,
    /// Bonded rest torque about a hinge, N m.
    pub torque_scale: f64,
    /// A time scale, s: a path travelled at the bonded rest force's speed.
    pub time_scale: f64,
    bandwidth: usize,
}

/// Why a model cannot be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A design parameter out of range.
    #[error("design: {0}")]
    Design(#[from] DesignsError),
    /// A curved path that cannot be built.
    #[error(transparent)]
    Path(#[from] PathError),
    /// A physical parameter this model cannot use.
    #[error("design parameter `{name}` = {value}: not usable here: {why}")]
    Unsupported {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Why.
        why: &'static str,
    },
    /// A model option out of range.
    #[error("model option `{name}` = {value}: expected {expected}")]
    BadOption {
        /// The option.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}

impl From<GeometryError> for ModelError {
    fn from(e: GeometryError) -> ModelError {
        match e {
            GeometryError::Design(e) => ModelError::Design(e),
            GeometryError::Path(e) => ModelError::Path(e),
        }
    }
}

/// The physical parameters of a run by `model` (the name a summary gives the integrator)
/// with `opts`, a magnet drag `drag` (N s/m) and friction `friction` (N): the masses, the
/// restitution, the water and the tile's body from the design `d`. The one place both
/// simulations (a model's run, [`Model::parameters`], and the event engine's kinematic
/// baseline) make their summary's parameters.
pub(crate) fn parameters(
    d: &Design,
    opts: &ModelOptions,
    model: &'static str,
    drag: f64,
    friction: f64,
) -> Parameters {
    let tile = TileBody::of(d);
    Parameters {
        model,
        dynamics: opts.dynamics.name(),
        force_law: opts.force_law.name(),
        cutoff: opts.cutoff,
        distance_cutoff_mm: opts.distance_cutoff,
        magnet_mass_g: d.magnet_mass,
        tile_mass_g: d.tile_mass,
        tile_inertia_kg_m2: tile.inertia,
        magnet_drag_n_s_per_m: drag,
        friction_n: friction,
        restitution: d.restitution,
        water_viscosity_pa_s: d.water_viscosity,
        water_film_mm: d.water_film,
        water_density_kg_m3: d.water_density,
        form_drag_cd: d.form_drag,
        tile_drag_n_s_per_m: tile.drag,
        tile_rotational_drag_n_m_s: tile.rotational_drag,
        design: crate::timeline::design_parameters(d),
    }
}

#[cfg(test)]
impl Model {
    /// The model of the chain `word` with the thesis design at `s` (mm) and the default
    /// options: the unit tests' model.
    #[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
    pub(crate) fn thesis(word: &str, s: f64) -> Model {
        let designs = TileDesigns::global(crate::Design::thesis().with_s(s));
        Model::new(
            &Chain::parse(word).unwrap(),
            &designs,
            &ModelOptions::default(),
        )
        .unwrap()
    }
}

impl Model {
    /// The model of `chain` with `designs`.
    pub fn new(
        chain: &Chain,
        designs: &TileDesigns,
        opts: &ModelOptions,
    ) -> Result<Model, ModelError> {
        Model::build(chain, designs, opts, Allow::default())
    }

    /// The model, allowing what a particular integrator can use.
    pub(crate) fn build(
        chain: &Chain,
        designs: &TileDesigns,
        opts: &ModelOptions,
        allow: Allow,
    ) -> Result<Model, ModelError> {
        let bad = |name, value: f64, expected| ModelError::BadOption {
            name,
            value,
            expected,
        };
        if opts.cutoff == 0 {
            return Err(bad("cutoff", 0.0, "at least 1"));
        }
        if let Some(r) = opts
            .distance_cutoff
            .filter(|r| !(r.is_finite() && *r > 0.0))
        {
            return Err(bad("distance_cutoff", r, "a finite number > 0 (mm)"));
        }
        let geometry = Geometry::from_designs(chain, designs)?;
        let tiles = geometry.tiles();
        let n = geometry.magnets();
        let mut unknowns = Vec::new();
        let mut magnet_var = vec![0; n];
        let mut joint_var = vec![usize::MAX; tiles.saturating_sub(1)];
        let mut joint_sign = vec![0.0; tiles.saturating_sub(1)];
        for t in 0..tiles {
            for k in [2 * t, 2 * t + 1] {
                magnet_var[k] = unknowns.len();
                unknowns.push(Unknown::Magnet(k));
            }
            if t + 1 < tiles {
                let sign = geometry.joint_fold(t).quarter_turns() as f64;
                joint_sign[t] = sign;
                if sign != 0.0 {
                    joint_var[t] = unknowns.len();
                    unknowns.push(Unknown::Joint(t));
                }
            }
        }
        let lengths: Vec<f64> = (0..n).map(|k| geometry.path(k).length()).collect();
        let moments: Vec<f64> = (0..n).map(|k| geometry.design(k / 2).moment()).collect();
        let oct = Octagon::new(geometry.w);
        let force_scale = opts.force_law.bonded_rest_force(geometry.design(0));
        let torque_scale = force_scale * 0.5 * oct.side() * 1e-3;
        let d0 = *geometry.design(0);
        let inertial = opts.dynamics.is_inertial();
        if d0.form_drag > 0.0 && !allow.form_drag {
            return Err(ModelError::Unsupported {
                name: "form_drag",
                value: d0.form_drag,
                why: "the joint-angle model and the event engine take the water's drag as linear; only the free-body reference with inertial dynamics integrates form drag",
            });
        }
        if !inertial {
            if let Some(t) = (0..tiles).find(|&t| geometry.design(t).water_viscosity <= 0.0) {
                return Err(ModelError::Unsupported {
                    name: "water_viscosity",
                    value: geometry.design(t).water_viscosity,
                    why: "the overdamped dynamics turn a fold at its torque over the water's drag: they need water with a viscosity above 0 (the inertial dynamics take 0)",
                });
            }
        }
        let drag = magnet_drag(&d0, inertial);
        let magnet_mass: Vec<f64> = (0..n)
            .map(|k| geometry.design(k / 2).magnet_mass * 1e-3)
            .collect();
        let sides = joint_sides(&geometry, &joint_sign);
        let time_scale = drag * lengths[0] * 1e-3 / force_scale;
        let cutoff = opts.cutoff;
        // bandwidth: the widest span of state indices over a window of cutoff + 1 magnets
        let mut bandwidth = 1;
        for k in 0..n {
            let hi = (k + cutoff).min(n - 1);
            bandwidth = bandwidth.max(magnet_var[hi] - magnet_var[k] + 1);
        }
        Ok(Model {
            opts: *opts,
            drag,
            friction: d0.friction,
            magnet_mass,
            sides,
            swung_faces: false,
            swung_back: false,
            coupled_folds: false,
            unknowns,
            magnet_var,
            joint_var,
            joint_sign,
            lengths,
            moments,
            ri: geometry.ri(),
            hinge_left: oct.hinge(true).into(),
            hinge_right: oct.hinge(false).into(),
            force_scale,
            torque_scale,
            time_scale,
            bandwidth,
            geometry,
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
    pub(crate) fn drive_scale(&self, i: usize) -> f64 {
        match self.unknowns[i] {
            Unknown::Magnet(_) => self.force_scale,
            Unknown::Joint(_) => self.torque_scale,
        }
    }

    /// The static threshold a drive must exceed to move a clamped unknown.
    pub(crate) fn threshold(&self, i: usize) -> f64 {
        let balance = BALANCE_TOLERANCE * self.drive_scale(i);
        match self.unknowns[i] {
            Unknown::Magnet(_) => self.friction.max(balance),
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

    pub(super) fn path(&self, k: usize) -> &MagnetPath {
        self.geometry.path(k)
    }

    /// Magnet `k` at fraction `x` of its path: point and unit tangent, tile frame.
    pub(super) fn local(&self, k: usize, x: f64) -> ((f64, f64), (f64, f64)) {
        let p = self.path(k);
        let len = self.lengths[k];
        let u = (x * len).clamp(0.0, len);
        (p.point_at(u), p.tangent_at(u))
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

    /// The longest time a fold takes under the bonded rest torque against its drag alone,
    /// s: the slowest of the model's time scales (0 without folds).
    pub fn slowest_fold_time(&self) -> f64 {
        (0..self.joint_var.len())
            .map(|j| self.fold_time(j))
            .fold(0.0, f64::max)
    }

    /// The time joint `j`'s fold takes under the bonded rest torque against its drag alone
    /// (both sides' drag about the hinge), s; 0 for a joint that does not fold.
    pub(crate) fn fold_time(&self, j: usize) -> f64 {
        if self.sides[j].is_some() {
            self.joint_drag(j, 0.0) * FRAC_PI_2 / self.torque_scale
        } else {
            0.0
        }
    }

    /// What joint `j`'s motion depends on besides the forces (its sides' inertia and drag),
    /// as bits for a cache key; `None` for a joint that does not fold.
    pub(crate) fn joint_key(&self, j: usize) -> Option<[u64; 8]> {
        self.sides[j].map(|s| {
            let (a, b) = (s.inertia.bits(), s.drag.bits());
            [a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]
        })
    }

    /// The physical parameters this model uses, resolved, for a run by `model` (the name a
    /// summary gives the integrator).
    pub fn parameters(&self, model: &'static str) -> Parameters {
        let d = self.geometry.design(0);
        parameters(d, &self.opts, model, self.drag, self.friction)
    }

    /// The signed angle (radians) of joint `j` at fold fraction `psi`.
    pub(crate) fn joint_angle(&self, j: usize, psi: f64) -> f64 {
        self.joint_sign[j] * psi * FRAC_PI_2
    }

    /// Joint `j`'s effective drag (N m s) at fold fraction `psi`: both sides free
    /// ([`crate::model`]'s sides).
    pub(crate) fn joint_drag(&self, j: usize, psi: f64) -> f64 {
        match &self.sides[j] {
            Some(s) => s.drag.at(self.joint_angle(j, psi.clamp(0.0, 1.0))).0,
            None => f64::INFINITY,
        }
    }

    /// The rate of unknown `i` (per second) at value `y` for drive `drive` in mode `mode`.
    pub(crate) fn rate(&self, i: usize, y: f64, drive: f64, mode: Mode) -> f64 {
        if mode != Mode::Free {
            return 0.0;
        }
        match self.unknowns[i] {
            Unknown::Magnet(k) => {
                let fr = self.friction;
                let f = drive.signum() * (drive.abs() - fr).max(0.0);
                // mm/s over the path length in mm
                f / self.drag * 1e3 / self.lengths[k]
            }
            Unknown::Joint(j) => drive / self.joint_drag(j, y) / FRAC_PI_2,
        }
    }
}
