//! The forces on one unit of the local solve: a joint's two magnets (and its angle if it
//! folds), with every magnet within the cutoff placed where its track has it. The pair law,
//! the polarity, the cutoff's neighbour sets, the drive along a path and the torque about a
//! hinge are [`crate::physics`]'s, asked exactly as the reference ([`crate::reference`])
//! asks them, but only for the unit's few unknowns: the cost of a drive does not grow with
//! the chain.
//!
//! Unit `j` (`-1 <= j < tiles`) is joint `j`'s pair: magnets `A = 2j + 1` and `B = 2j + 2`
//! where they exist (unit `-1` is magnet 0, pulled by the RI; the last unit is the chain's
//! last magnet) and the joint's fold when it folds. Positions are taken in the frame of the
//! first tile the window reaches (tile 0's, where the RI is, for the first units); drives
//! and torques do not depend on the frame.

use std::f64::consts::FRAC_PI_2;

use kurbo::{Point, Vec2};

use crate::engine::local::swing::swing_drive;
use crate::engine::local::trajectory::{Shapes, Track};
use crate::model::Model;
use crate::physics::{along_path, neighbours, torque_about, upstream, Pole};
use crate::tile_frame::TileFrame;
use crate::Octagon;

/// One unknown of a unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Var {
    /// Magnet `k`'s fraction of path travelled.
    Magnet(usize),
    /// Joint `j`'s fraction of fold made.
    Joint(usize),
}

/// Where every unknown outside the unit is: its track.
#[derive(Clone, Copy)]
pub(crate) struct Inputs<'a> {
    /// The shapes the tracks point into.
    pub(crate) shapes: &'a Shapes,
    /// Each magnet's track.
    pub(crate) magnets: &'a [Track],
    /// Each joint's track (rigid joints at rest).
    pub(crate) joints: &'a [Track],
}

/// Scratch space of a drive evaluation.
#[derive(Default)]
pub(crate) struct Scratch {
    /// Each tile's pose, and the joint angles they were built from (a pose is built again
    /// only from the first joint whose angle changed).
    poses: Vec<TileFrame>,
    angles: Vec<f64>,
    /// Each magnet's arc length along its path and its point there, tile frame (a magnet
    /// at rest is not placed again).
    local: Vec<(f64, (f64, f64))>,
    /// Each unknown magnet's path tangent where `local` has it, tile frame.
    tangents: Vec<(f64, f64)>,
    positions: Vec<Point>,
    /// Where each input's last look-up fell in its shape (magnets `lo..=hi`, then joints).
    hints: Vec<usize>,
    /// The time the inputs were last read at, and their values there (by slot, as
    /// `hints`): a Jacobian's columns read the same instant again.
    inputs_at: Option<f64>,
    inputs: Vec<f64>,
    /// Each pair's force on its downstream pole.
    forces: Vec<Vec2>,
}

/// One unit's window on the chain.
pub(crate) struct UnitForces<'a> {
    /// The chain's model (the reference's: geometry, rates, thresholds).
    pub(crate) model: &'a Model,
    /// The unit's joint (`-1`: magnet 0 alone).
    pub(crate) j: isize,
    /// The unit's unknowns: its magnets in chain order, then its joint.
    pub(crate) vars: Vec<Var>,
    /// First and last magnet within reach.
    pub(crate) lo: usize,
    /// Last magnet within reach.
    pub(crate) hi: usize,
    hinge_left: Point,
    hinge_right: Point,
    /// The moments of magnets `lo..=hi`, A m^2.
    moments: Vec<f64>,
    /// Every pair an unknown's drive reads, once: the upstream pole (slot from `lo`;
    /// `None`: the RI), the downstream magnet's slot and whether they attract. Its force
    /// is the one on the downstream magnet, the upstream one's is its opposite (as the
    /// reference sums them).
    pairs: Vec<(Option<usize>, usize, bool)>,
    /// Each unknown's terms, in the order [`crate::physics`]'s neighbour sets give them: a
    /// pair and whether the unknown's force is the pair's opposite (a magnet's), or a pair
    /// whose force turns the joint (a joint's).
    terms: Vec<Vec<(usize, bool)>>,
    /// Which unknown each slot is (magnets `lo..=hi`, then joints), if any.
    var_of_slot: Vec<Option<usize>>,
}

impl<'a> UnitForces<'a> {
    /// The window of unit `j` of `model` with pair cutoff `cutoff`.
    pub(crate) fn new(model: &'a Model, j: isize, cutoff: usize) -> UnitForces<'a> {
        let n = model.geometry.magnets();
        let vars = unit_vars(model, j);
        let (first, last) = match (
            vars.first(),
            vars.iter().rev().find(|v| matches!(v, Var::Magnet(_))),
        ) {
            (Some(Var::Magnet(a)), Some(Var::Magnet(b))) => (*a, *b),
            _ => (0, 0),
        };
        let oct = Octagon::new(model.geometry.w);
        let (lo, hi) = (first.saturating_sub(cutoff), (last + cutoff).min(n - 1));
        let mut pairs = Vec::new();
        let terms = vars
            .iter()
            .map(|&v| unit_terms(v, lo, cutoff, n, &mut pairs))
            .collect();
        let (t0, t1) = (lo / 2, hi / 2);
        let var_of_slot = (lo..=hi)
            .map(|k| vars.iter().position(|&v| v == Var::Magnet(k)))
            .chain((t0..t1).map(|jj| vars.iter().position(|&v| v == Var::Joint(jj))))
            .collect();
        UnitForces {
            model,
            j,
            lo,
            hi,
            vars,
            hinge_left: oct.hinge(true).into(),
            hinge_right: oct.hinge(false).into(),
            moments: (lo..=hi)
                .map(|k| model.geometry.design(k / 2).moment())
                .collect(),
            pairs,
            terms,
            var_of_slot,
        }
    }

    /// The reference's state index of unknown `v`.
    pub(crate) fn global(&self, v: usize) -> usize {
        match self.vars[v] {
            Var::Magnet(k) => self.model.magnet_var(k),
            // a unit's joint is there only if it folds
            Var::Joint(j) => self.model.joint_var(j).unwrap_or(usize::MAX),
        }
    }

    /// The window's tiles.
    fn tiles(&self) -> (usize, usize) {
        (self.lo / 2, self.hi / 2)
    }

    /// Every track the unit reads (magnets and joints in the window, its own excluded).
    pub(crate) fn input_tracks(&self, inputs: &Inputs) -> Vec<Track> {
        let mut out = Vec::new();
        if self.model.coupled_folds && self.vars.iter().any(|v| matches!(v, Var::Joint(_))) {
            // a coupled joint reads the whole chain (`engine::local::cluster`)
            for (k, &t) in inputs.magnets.iter().enumerate() {
                if !self.vars.contains(&Var::Magnet(k)) {
                    out.push(t);
                }
            }
            for (jj, &t) in inputs.joints.iter().enumerate() {
                if !self.vars.contains(&Var::Joint(jj)) {
                    out.push(t);
                }
            }
            return out;
        }
        for k in self.lo..=self.hi {
            if !self.vars.contains(&Var::Magnet(k)) {
                out.push(inputs.magnets[k]);
            }
        }
        let (t0, t1) = self.tiles();
        for jj in t0..t1 {
            if !self.vars.contains(&Var::Joint(jj)) {
                out.push(inputs.joints[jj]);
            }
        }
        out
    }

    /// Reads every input at `t` into `s.inputs` (by slot), unless they were read there.
    fn read_inputs(&self, t: f64, inputs: &Inputs, s: &mut Scratch) {
        if s.inputs_at.map(f64::to_bits) == Some(t.to_bits()) {
            return;
        }
        s.inputs_at = Some(t);
        let magnets = self.hi - self.lo + 1;
        for (slot, var) in self.var_of_slot.iter().enumerate() {
            if var.is_none() {
                let track = if slot < magnets {
                    inputs.magnets[self.lo + slot]
                } else {
                    inputs.joints[self.lo / 2 + slot - magnets]
                };
                s.inputs[slot] = inputs.shapes.value_hinted(track, t, &mut s.hints[slot]);
            }
        }
    }

    /// The drive of each unknown (N along a magnet's path, N m towards the fold) at time `t`
    /// with the unit's unknowns at `y`.
    pub(crate) fn drives(
        &self,
        t: f64,
        y: &[f64],
        inputs: &Inputs,
        s: &mut Scratch,
        out: &mut [f64],
    ) {
        let m = self.model;
        let g = &m.geometry;
        let (t0, t1) = self.tiles();
        let magnets = self.hi - self.lo + 1;
        if s.poses.len() != t1 - t0 + 1 {
            s.poses = vec![TileFrame::IDENTITY; t1 - t0 + 1];
            s.angles = vec![f64::NAN; t1 - t0];
            s.local = vec![(f64::NAN, (0.0, 0.0)); magnets];
            s.tangents = vec![(0.0, 0.0); self.vars.len()];
            s.hints = vec![0; self.var_of_slot.len()];
            s.inputs = vec![0.0; self.var_of_slot.len()];
            s.inputs_at = None;
        }
        self.read_inputs(t, inputs, s);
        let value = |slot: usize, s: &Scratch| match self.var_of_slot[slot] {
            Some(i) => y[i],
            None => s.inputs[slot],
        };
        let half = 0.5 * g.w;
        let mut changed = false;
        for tile in t0..t1 {
            let sign = m.joint_sign(tile);
            let slot = tile - t0;
            let angle = if sign != 0.0 {
                sign * value(magnets + slot, s).clamp(0.0, 1.0) * FRAC_PI_2
            } else {
                0.0
            };
            // the same angle after the same poses gives the same pose
            changed |= angle.to_bits() != s.angles[slot].to_bits();
            if changed {
                s.angles[slot] = angle;
                let hinge = if angle >= 0.0 {
                    self.hinge_left
                } else {
                    self.hinge_right
                };
                s.poses[slot + 1] = s.poses[slot].across_joint(angle, hinge, half);
            }
        }
        s.positions.clear();
        for k in self.lo..=self.hi {
            let len = m.path_length(k);
            let u = (value(k - self.lo, s) * len).clamp(0.0, len);
            let cached = &mut s.local[k - self.lo];
            if u.to_bits() != cached.0.to_bits() {
                let path = g.path(k);
                *cached = match self.var_of_slot[k - self.lo] {
                    Some(i) => {
                        let (p, tangent) = path.point_and_tangent_at(u);
                        s.tangents[i] = tangent;
                        (u, p)
                    }
                    None => (u, path.point_at(u)),
                };
            }
            let p = cached.1;
            s.positions.push(s.poses[k / 2 - t0].point(p));
        }
        let law = m.options().force_law;
        let ri = g.ri();
        s.forces.clear();
        for &(a, b, attract) in &self.pairs {
            let (pa, ma) = match a {
                // the RI is fixed in tile 0's frame, which is the window's when it is in reach
                None => (ri.position, ri.moment),
                Some(a) => (s.positions[a], self.moments[a]),
            };
            let f = law.force(pa, s.positions[b], ma, self.moments[b], attract);
            s.forces.push(f);
        }
        for (i, var) in self.vars.iter().enumerate() {
            let terms = &self.terms[i];
            out[i] = match *var {
                Var::Magnet(k) => {
                    let mut f = Vec2::ZERO;
                    for &(p, opposite) in terms {
                        if opposite {
                            f -= s.forces[p];
                        } else {
                            f += s.forces[p];
                        }
                    }
                    let tan = s.poses[k / 2 - t0].vector(s.tangents[i]);
                    along_path(f, tan)
                }
                Var::Joint(j) => {
                    let sign = m.joint_sign(j);
                    let h = if sign >= 0.0 {
                        self.hinge_left
                    } else {
                        self.hinge_right
                    };
                    let hinge: Point = s.poses[j - t0].point(h.into());
                    let mut tau = 0.0;
                    for &(p, _) in terms {
                        let on = s.positions[self.pairs[p].1];
                        tau += sign * torque_about(hinge, on, s.forces[p]);
                    }
                    if m.swung_faces {
                        tau += swing_drive(m, j, t, inputs);
                    }
                    tau
                }
            };
        }
    }
}

/// Unit `j`'s unknowns: its magnets in chain order, then its joint if it folds.
pub(crate) fn unit_vars(model: &Model, j: isize) -> Vec<Var> {
    let n = model.geometry.magnets();
    let mut vars = Vec::with_capacity(3);
    for k in [2 * j + 1, 2 * j + 2] {
        if k >= 0 && (k as usize) < n {
            vars.push(Var::Magnet(k as usize));
        }
    }
    if j >= 0 && (j as usize) + 1 < model.geometry.tiles() && model.joint_var(j as usize).is_some()
    {
        vars.push(Var::Joint(j as usize));
    }
    vars
}

/// Unknown `v`'s terms in a window from magnet `lo` (see [`UnitForces`]'s `terms`), its pairs
/// added to `pairs` where they are not there yet: a magnet's neighbours within `cutoff`, or
/// the pairs across a joint whose torque turns it (a pole up to the joint's first magnet on
/// a magnet after it, within `cutoff` of the joint).
fn unit_terms(
    v: Var,
    lo: usize,
    cutoff: usize,
    n: usize,
    pairs: &mut Vec<(Option<usize>, usize, bool)>,
) -> Vec<(usize, bool)> {
    let slot = |p: Pole| match p {
        Pole::Ri => None,
        Pole::Magnet(a) => Some(a - lo),
    };
    // the pair of upstream pole `a` and downstream magnet `b`, once
    let mut index = |a: Pole, b: usize| {
        let pair = (slot(a), b - lo, a.attracts(Pole::Magnet(b)));
        match pairs.iter().position(|&q| q == pair) {
            Some(i) => i,
            None => {
                pairs.push(pair);
                pairs.len() - 1
            }
        }
    };
    match v {
        Var::Magnet(k) => neighbours(k, cutoff, n)
            .map(|p| match p {
                Pole::Magnet(a) if a > k => (index(Pole::Magnet(k), a), true),
                _ => (index(p, k), false),
            })
            .collect(),
        Var::Joint(j) => {
            let last = (2 * j + 1 + cutoff).min(n - 1);
            let mut out = Vec::new();
            for b in 2 * j + 2..=last {
                for a in upstream(b, cutoff) {
                    if matches!(a, Pole::Magnet(ai) if ai > 2 * j + 1) {
                        continue;
                    }
                    out.push((index(a, b), false));
                }
            }
            out
        }
    }
}
