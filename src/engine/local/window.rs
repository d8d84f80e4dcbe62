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

use crate::engine::local::trajectory::{Shapes, Track};
use crate::frame::Frame;
use crate::physics::{along_path, neighbours, torque_about, upstream, Pole};
use crate::reference::Model;
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
    poses: Vec<Frame>,
    angles: Vec<f64>,
    /// Each magnet's arc length along its path and its point there, tile frame (a magnet
    /// at rest is not placed again).
    local: Vec<(f64, (f64, f64))>,
    /// Each unknown magnet's arc length and its path's tangent there.
    tangents: Vec<(f64, (f64, f64))>,
    positions: Vec<Point>,
    /// Where each input's last look-up fell in its shape (magnets `lo..=hi`, then joints).
    hints: Vec<usize>,
}

/// One unit's window on the chain.
pub(crate) struct Window<'a> {
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
    /// Each unknown's pairs, in the order [`crate::physics`]'s neighbour sets give them:
    /// the magnet acted on and the pole acting (slots from `lo`; `None`: the RI), and
    /// whether they attract.
    pairs: Vec<Vec<(usize, Option<usize>, bool)>>,
}

impl<'a> Window<'a> {
    /// The window of unit `j` of `model` with pair cutoff `cutoff`.
    pub(crate) fn new(model: &'a Model, j: isize, cutoff: usize) -> Window<'a> {
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
        let pairs: Vec<_> = vars.iter().map(|&v| pairs(v, lo, cutoff, n)).collect();
        Window {
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

    fn value(&self, var: Var, y: &[f64], t: f64, inputs: &Inputs, hints: &mut [usize]) -> f64 {
        if let Some(i) = self.vars.iter().position(|&v| v == var) {
            return y[i];
        }
        let (track, slot) = match var {
            Var::Magnet(k) => (inputs.magnets[k], k - self.lo),
            Var::Joint(j) => (inputs.joints[j], self.hi - self.lo + 1 + j - self.lo / 2),
        };
        inputs.shapes.value_hinted(track, t, &mut hints[slot])
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
        s.hints.resize(magnets + t1 - t0, 0);
        if s.poses.len() != t1 - t0 + 1 {
            s.poses = vec![Frame::IDENTITY; t1 - t0 + 1];
            s.angles = vec![f64::NAN; t1 - t0];
            s.local = vec![(f64::NAN, (0.0, 0.0)); magnets];
            s.tangents = vec![(f64::NAN, (0.0, 0.0)); self.vars.len()];
        }
        let half = 0.5 * g.w;
        let mut changed = false;
        for tile in t0..t1 {
            let sign = m.joint_sign(tile);
            let angle = if sign != 0.0 {
                let x = self.value(Var::Joint(tile), y, t, inputs, &mut s.hints);
                sign * x.clamp(0.0, 1.0) * FRAC_PI_2
            } else {
                0.0
            };
            let slot = tile - t0;
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
            let x = self.value(Var::Magnet(k), y, t, inputs, &mut s.hints);
            let u = (x * len).clamp(0.0, len);
            let cached = &mut s.local[k - self.lo];
            if u.to_bits() != cached.0.to_bits() {
                *cached = (u, g.path(k).point_at(u));
            }
            let p = cached.1;
            s.positions.push(s.poses[k / 2 - t0].point(p));
        }
        let law = m.options().force_law;
        let ri = g.ri();
        let pole = |a: Option<usize>, s: &Scratch| -> (Point, f64) {
            match a {
                // the RI is fixed in tile 0's frame, which is the window's when it is in reach
                None => (ri.position, ri.moment),
                Some(a) => (s.positions[a], self.moments[a]),
            }
        };
        for (i, var) in self.vars.iter().enumerate() {
            out[i] = match *var {
                Var::Magnet(k) => {
                    let on = s.positions[k - self.lo];
                    let mk = self.moments[k - self.lo];
                    let mut f = Vec2::ZERO;
                    for &(_, a, attract) in &self.pairs[i] {
                        let (pa, ma) = pole(a, s);
                        f += law.force(pa, on, ma, mk, attract);
                    }
                    let len = m.path_length(k);
                    let x = y[i];
                    let u = (x * len).clamp(0.0, len);
                    let cached = &mut s.tangents[i];
                    if u.to_bits() != cached.0.to_bits() {
                        *cached = (u, g.path(k).tangent_at(u));
                    }
                    let tan = s.poses[k / 2 - t0].vector(cached.1);
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
                    for &(b, a, attract) in &self.pairs[i] {
                        let (on, mb) = (s.positions[b], self.moments[b]);
                        let (pa, ma) = pole(a, s);
                        let f = law.force(pa, on, ma, mb, attract);
                        tau += sign * torque_about(hinge, on, f);
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

/// Unknown `v`'s pairs in a window from magnet `lo` (see [`Window`]'s `pairs`): a magnet's
/// neighbours within `cutoff`, or the pairs across a joint whose torque turns it (a pole up
/// to the joint's first magnet on a magnet after it, within `cutoff` of the joint).
fn pairs(v: Var, lo: usize, cutoff: usize, n: usize) -> Vec<(usize, Option<usize>, bool)> {
    let slot = |p: Pole| match p {
        Pole::Ri => None,
        Pole::Magnet(a) => Some(a - lo),
    };
    match v {
        Var::Magnet(k) => neighbours(k, cutoff, n)
            .map(|p| (k - lo, slot(p), p.attracts(Pole::Magnet(k))))
            .collect(),
        Var::Joint(j) => {
            let last = (2 * j + 1 + cutoff).min(n - 1);
            let mut out = Vec::new();
            for b in 2 * j + 2..=last {
                for a in upstream(b, cutoff) {
                    if matches!(a, Pole::Magnet(ai) if ai > 2 * j + 1) {
                        continue;
                    }
                    out.push((b - lo, slot(a), a.attracts(Pole::Magnet(b))));
                }
            }
            out
        }
    }
}
