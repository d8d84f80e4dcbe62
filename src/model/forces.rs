//! The drives of the reference model at one state ([`Model::forces_with_cutoff`]): tile
//! frames from the joint angles, magnet positions and tangents, the pair forces of
//! [`crate::physics`] within the cutoff (and the distance cutoff), the drive of every magnet
//! along its path and the torque on every folding joint.
//!
//! **Cost.** One evaluation allocates nothing once its [`Forces`] has grown to the chain
//! (every buffer is kept and reused), and takes one `sin_cos` per tile whose heading differs
//! from the tile before it and one per turned joint (a straight run shares its heading): the
//! frames are the same numbers [`crate::kinematics::poses_at_angles`] composes (the same
//! operations in the same order), kept with their sine and cosine.

use std::f64::consts::FRAC_PI_2;

use kurbo::{Point, Vec2};

use crate::model::{Mode, Model, Unknown};
use crate::physics::{along_path, joints_between, pairs_within, torque_about, Pole};
use crate::tile_frame::TileFrame;

/// Everything the forces give at one state, with the scratch of one evaluation.
#[derive(Clone, Debug, Default)]
pub(crate) struct Forces {
    /// World positions of the magnets, mm (after [`Model::forces_moving`], only those near
    /// a free unknown are current).
    pub(crate) positions: Vec<Point>,
    /// Drive of each unknown (force along the path, N, or torque towards folding, N m).
    pub(crate) drive: Vec<f64>,
    frames: Vec<TileFrame>,
    tangents: Vec<Vec2>,
    force: Vec<Vec2>,
    hinges: Vec<Point>,
    points: Vec<Point>,
    /// The state and modes of the last full evaluation by [`Model::forces_moving`] (empty
    /// modes: none since the last [`Model::forces_with_cutoff`]).
    base_y: Vec<f64>,
    base_modes: Vec<Mode>,
    /// The epoch of the last full evaluation by [`Model::forces_free`] (0: none since the
    /// last [`Model::forces_with_cutoff`]), and the full evaluations into this scratch.
    base_epoch: u64,
    evaluations: u64,
    /// Spans of magnets whose drives the free unknowns change.
    spans: Vec<(usize, usize)>,
}

impl Forces {
    /// How many full evaluations went into this scratch: the drives a caller kept are the
    /// same as these but where [`Model::changed`] says, as long as this count is the same.
    pub(crate) fn evaluations(&self) -> u64 {
        self.evaluations
    }
}

impl Model {
    /// Magnet `k` at fraction `x` of its path (point and unit tangent, tile frame), the
    /// path continued along its end tangents beyond `[0, 1]`: the forces stay smooth
    /// through a magnet's arrival, so a step that overshoots it keeps its order and the
    /// arrival is found on the step's dense output (the driver never keeps a state
    /// beyond the range).
    pub(crate) fn local_continued(&self, k: usize, x: f64) -> ((f64, f64), (f64, f64)) {
        let p = self.path(k);
        let len = self.lengths[k];
        let u = x * len;
        let beyond = if u < 0.0 {
            u
        } else if u > len {
            u - len
        } else {
            return (p.point_at(u), p.tangent_at(u));
        };
        let end = u.clamp(0.0, len);
        let (q, t) = (p.point_at(end), p.tangent_at(end));
        ((q.0 + t.0 * beyond, q.1 + t.1 * beyond), t)
    }

    /// Drives of every unknown at state `y` with `modes`, as [`Model::forces_with_cutoff`]
    /// with the model's cutoff, computed again only where a free unknown reaches: a
    /// clamped unknown's drive depends on the magnets within the cutoff of it and the joints
    /// between them (relative positions, which a move elsewhere leaves alone), so between
    /// two full evaluations at the same modes and clamped values only the drives of the
    /// magnets within the cutoff of a free magnet, or on a pair across a free joint, and of
    /// the joints such pairs cross change. The others keep their values from the last full
    /// evaluation (exactly the same numbers but for the rounding of world coordinates).
    /// A full evaluation when the modes or a clamped value changed, or with a distance
    /// cutoff (its pairs are not local in chain index).
    pub(crate) fn forces_moving(&self, y: &[f64], modes: &[Mode], out: &mut Forces) {
        let current = self.opts.distance_cutoff.is_none()
            && !out.base_modes.is_empty()
            && out.base_modes.as_slice() == modes
            && out.base_y.len() == y.len()
            && (0..y.len()).all(|i| modes[i] == Mode::Free || y[i] == out.base_y[i]);
        if !current {
            self.forces_with_cutoff(y, self.opts.cutoff, out);
            out.base_y.clear();
            out.base_y.extend_from_slice(y);
            out.base_modes.clear();
            out.base_modes.extend_from_slice(modes);
            return;
        }
        let free = (0..modes.len()).filter(|&i| modes[i] == Mode::Free);
        self.drives_near(y, free, out);
    }

    /// Drives at state `y` as [`Model::forces_moving`], for a caller that keeps the free
    /// unknowns `free` (in order) and counts the changes of modes in `epoch` (from 1), and
    /// changes a clamped value only with the modes: a full evaluation when `epoch` is not
    /// that of the last full one into `out` (or with a distance cutoff), else the drives
    /// near the free unknowns only, so that the cost is O(what moves) and not O(n).
    /// Whether it was a full evaluation ([`Forces::evaluations`] counts them; after one that
    /// was not, [`Model::changed`] gives the unknowns whose drives it computed again).
    pub(crate) fn forces_free(
        &self,
        y: &[f64],
        free: &[usize],
        epoch: u64,
        out: &mut Forces,
    ) -> bool {
        if self.opts.distance_cutoff.is_some() || epoch == 0 || out.base_epoch != epoch {
            self.forces_with_cutoff(y, self.opts.cutoff, out);
            out.base_epoch = epoch;
            return true;
        }
        self.drives_near(y, free.iter().copied(), out);
        false
    }

    /// The unknowns (state indices, in ranges in order) whose drives the last evaluation
    /// into `out` computed again, when it was not a full one: the magnets within the cutoff
    /// of a free unknown's reach and the joints between them.
    pub(crate) fn changed<'a>(
        &'a self,
        out: &'a Forces,
    ) -> impl Iterator<Item = std::ops::Range<usize>> + 'a {
        out.spans
            .iter()
            .map(|&(lo, hi)| self.magnet_var[lo]..self.magnet_var[hi] + 1)
    }

    /// The drives near the free unknowns `free` (state indices, in order) at state `y`, the
    /// others kept from the last full evaluation into `out` ([`Model::forces_moving`]).
    fn drives_near(&self, y: &[f64], free: impl Iterator<Item = usize> + Clone, out: &mut Forces) {
        let n = self.geometry.magnets();
        let c = self.opts.cutoff;
        // the spans of magnets whose drives change, merged
        let mut spans = std::mem::take(&mut out.spans);
        spans.clear();
        for i in free.clone() {
            let (lo, hi) = match self.unknowns[i] {
                Unknown::Magnet(k) => (k.saturating_sub(c), k + c),
                Unknown::Joint(j) => ((2 * j + 2).saturating_sub(c), 2 * j + 1 + c),
            };
            let hi = hi.min(n - 1);
            match spans.last_mut() {
                Some(last) if lo <= last.1 + 1 => last.1 = last.1.max(hi),
                _ => spans.push((lo, hi)),
            }
        }
        let Some(&(_, reach)) = spans.last() else {
            out.spans = spans;
            return;
        };
        // positions from `c` before a span to `c` after it; frames from the first free
        // joint (those before it are the full evaluation's) up to the last tile needed
        let last_tile = ((reach + c).min(n - 1)) / 2;
        let mut frames = std::mem::take(&mut out.frames);
        let first_free_joint = free.clone().find_map(|i| match self.unknowns[i] {
            Unknown::Joint(j) => Some(j),
            Unknown::Magnet(_) => None,
        });
        if let Some(j0) = first_free_joint.filter(|&j0| j0 < last_tile) {
            self.frames_from(y, j0, last_tile, &mut frames);
        }
        for &(lo, hi) in &spans {
            for k in lo.saturating_sub(c)..=(hi + c).min(n - 1) {
                let (p, t) = self.local_continued(k, y[self.magnet_var[k]]);
                let frame = &frames[k / 2];
                out.positions[k] = frame.point(p);
                out.tangents[k] = frame.vector(t);
            }
        }
        let law = self.opts.force_law;
        let pair = |a: Option<usize>, b: usize, positions: &[Point]| {
            let (pa, ma) = match a {
                None => (self.ri.position, self.ri.moment),
                Some(a) => (positions[a], self.moments[a]),
            };
            let attract = a.map_or(b % 2 == 0, |a| b.abs_diff(a) % 2 == 1);
            law.force_with(pa, positions[b], ma, self.moments[b], attract)
        };
        for &(lo, hi) in &spans {
            for k in lo..=hi {
                let mut f = Vec2::ZERO;
                if k < c {
                    f += pair(None, k, &out.positions);
                }
                for a in k.saturating_sub(c)..=(k + c).min(n - 1) {
                    if a != k {
                        f += pair(Some(a), k, &out.positions);
                    }
                }
                out.drive[self.magnet_var[k]] = along_path(f, out.tangents[k]);
            }
            // joints crossed by a pair that changed: torques of every pair across them
            let joints = lo / 2..(hi / 2).min(self.joint_var.len());
            for (j, frame) in joints.clone().zip(&frames[joints]) {
                let v = self.joint_var[j];
                if v == usize::MAX {
                    continue;
                }
                let sign = self.joint_sign[j];
                let h = if sign >= 0.0 {
                    self.hinge_left
                } else {
                    self.hinge_right
                };
                let hinge = frame.point((h.x, h.y));
                let mut torque = 0.0;
                for b in 2 * j + 2..=(2 * j + 1 + c).min(n - 1) {
                    let on = out.positions[b];
                    if b < c {
                        torque += torque_about(hinge, on, pair(None, b, &out.positions));
                    }
                    for a in b.saturating_sub(c)..=2 * j + 1 {
                        torque += torque_about(hinge, on, pair(Some(a), b, &out.positions));
                    }
                }
                out.drive[v] = sign * torque;
            }
        }
        out.frames = frames;
        out.spans = spans;
    }

    /// The tile frames at state `y` into `frames` (the poses of
    /// [`crate::kinematics::poses_at_angles`] at [`Model::joint_angles`] for `y` in
    /// `[0, 1]`).
    fn frames(&self, y: &[f64], frames: &mut Vec<TileFrame>) {
        frames.clear();
        frames.resize(self.geometry.tiles(), TileFrame::default());
        frames[0].cos = 1.0;
        self.frames_from(y, 0, self.joint_var.len(), frames);
    }

    /// The frames of tiles `first + 1..=last` from the frame of tile `first` (already in
    /// `frames`, which holds every tile), as [`Model::frames`].
    fn frames_from(&self, y: &[f64], first: usize, last: usize, frames: &mut [TileFrame]) {
        let mut f = frames[first];
        let half = 0.5 * self.geometry.w;
        for j in first..last {
            let v = self.joint_var[j];
            // the fold continued beyond [0, 1] as the path is (local_continued)
            let a = if v == usize::MAX {
                0.0
            } else {
                self.joint_sign[j] * y[v] * FRAC_PI_2
            };
            // the next tile relative to this one: a turn by `a` about the joint's hinge
            // (kinematics::joint_transform, whose hinge is the same for `a` of the joint's
            // sign and either for a = 0)
            let h = if self.joint_sign[j] >= 0.0 {
                self.hinge_left
            } else {
                self.hinge_right
            };
            f = f.across_joint(a, h, half);
            frames[j + 1] = f;
        }
    }

    /// Drives of every unknown at state `y` (see [`Forces`]), with pairs up to `cutoff`
    /// apart in chain index.
    pub(crate) fn forces_with_cutoff(&self, y: &[f64], cutoff: usize, out: &mut Forces) {
        out.base_modes.clear();
        out.base_epoch = 0;
        out.evaluations += 1;
        let n = self.geometry.magnets();
        let mut frames = std::mem::take(&mut out.frames);
        self.frames(y, &mut frames);
        out.positions.clear();
        out.tangents.clear();
        for k in 0..n {
            let (p, t) = self.local_continued(k, y[self.magnet_var[k]]);
            let frame = &frames[k / 2];
            out.positions.push(frame.point(p));
            out.tangents.push(frame.vector(t));
        }
        out.force.clear();
        out.force.resize(n, Vec2::ZERO);
        out.drive.clear();
        out.drive.resize(self.len(), 0.0);
        out.hinges.clear();
        for (frame, &sign) in frames.iter().zip(&self.joint_sign) {
            let h = if sign >= 0.0 {
                self.hinge_left
            } else {
                self.hinge_right
            };
            out.hinges.push(frame.point((h.x, h.y)));
        }
        out.frames = frames;
        let law = self.opts.force_law;
        for b in 0..n {
            let on = out.positions[b];
            let mb = self.moments[b];
            // the RI first (magnet -1, fixed in tile 0's frame, which is the world frame),
            // then the magnets within the cutoff upstream (physics::upstream's order)
            let ri = (b < cutoff).then_some((None, self.ri.position, self.ri.moment));
            let first = b.saturating_sub(cutoff);
            let magnets = (first..b).map(|a| (Some(a), out.positions[a], self.moments[a]));
            for (a, pa, ma) in ri.into_iter().chain(magnets) {
                // an odd index difference attracts (the RI's index is -1)
                let attract = a.map_or(b % 2 == 0, |a| (b - a) % 2 == 1);
                let f = law.force_with(pa, on, ma, mb, attract);
                out.force[b] += f;
                if let Some(a) = a {
                    out.force[a] -= f;
                }
                // torque on every folding joint between the two (b downstream)
                let from = a.map_or(0, |a| a / 2);
                for j in from..b / 2 {
                    let v = self.joint_var[j];
                    if v != usize::MAX {
                        out.drive[v] += self.joint_sign[j] * torque_about(out.hinges[j], on, f);
                    }
                }
            }
        }
        // pairs near in space but beyond the chain-index cutoff (the RI is point n)
        let far = match self.opts.distance_cutoff {
            Some(r) if cutoff < n => {
                out.points.clear();
                out.points.extend_from_slice(&out.positions);
                out.points.push(self.ri.position);
                pairs_within(&out.points, r)
            }
            _ => Vec::new(),
        };
        for (a, b) in far {
            // the RI is magnet -1: its pair with b is beyond the cutoff when b >= cutoff
            let (from, on) = if b == n {
                (Pole::Ri, a)
            } else {
                (Pole::Magnet(a), b)
            };
            if (on as isize) - from.index() <= cutoff as isize {
                continue;
            }
            let (pa, ma) = match from {
                Pole::Ri => (self.ri.position, self.ri.moment),
                Pole::Magnet(a) => (out.positions[a], self.moments[a]),
            };
            let pb = out.positions[on];
            let attract = from.attracts(Pole::Magnet(on));
            let f = law.force(pa, pb, ma, self.moments[on], attract);
            out.force[on] += f;
            if let Pole::Magnet(a) = from {
                out.force[a] -= f;
            }
            for j in joints_between(from, on) {
                let v = self.joint_var[j];
                if v != usize::MAX {
                    out.drive[v] += self.joint_sign[j] * torque_about(out.hinges[j], pb, f);
                }
            }
        }
        for k in 0..n {
            out.drive[self.magnet_var[k]] = along_path(out.force[k], out.tangents[k]);
        }
    }
}

/// The model's drives and rates on a `Forces` scratch.
impl Model {
    /// Drives at state `y` with the model's cutoff.
    pub(crate) fn forces(&self, y: &[f64], out: &mut Forces) {
        self.forces_with_cutoff(y, self.opts.cutoff, out);
    }

    /// The right-hand side `dy/dt` at `y` with `modes`; also leaves the drives in `work`.
    pub(crate) fn rhs(&self, y: &[f64], modes: &[Mode], work: &mut Forces, dy: &mut [f64]) {
        self.forces_moving(y, modes, work);
        for i in 0..self.len() {
            dy[i] = self.rate(i, y[i], work.drive[i], modes[i]);
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

    #[test]
    fn frames_are_the_kinematic_poses() {
        // every joint kind, half folded, a fold past a half turn of heading: the cached
        // frames are the poses of kinematics::poses_at_angles, bit for bit
        let m = Model::thesis("SLLSRRSLLLLSRS", 0.3);
        let y: Vec<f64> = (0..m.len()).map(|i| (i as f64 * 0.37).fract()).collect();
        let mut frames = Vec::new();
        m.frames(&y, &mut frames);
        let poses = m.poses(&y);
        assert_eq!(frames.len(), poses.len());
        for (f, p) in frames.iter().zip(&poses) {
            assert_eq!((f.x, f.y, f.angle), (p.x, p.y, p.angle));
            assert_eq!((f.sin, f.cos), p.angle.sin_cos());
        }
        assert!(poses.iter().any(|p| p.angle.abs() > 2.0));
    }

    #[test]
    fn drives_near_the_free_unknowns_only_are_the_full_drives() {
        // a base state, then the free unknowns moved (magnets and joints, one near the RI):
        // the drives computed again near them, the others kept, are the full evaluation's
        let m = Model::thesis("SLLSRRSSLS", 0.3);
        let n = m.len();
        let mut modes = vec![Mode::AtStart; n];
        let mut y: Vec<f64> = vec![0.0; n];
        for (i, u) in m.unknowns.iter().enumerate() {
            // tiles 0 to 3 arrived, the first fold closed; then a few free ones
            let done = match *u {
                Unknown::Magnet(k) => k < 8,
                Unknown::Joint(j) => j < 2,
            };
            if done {
                modes[i] = Mode::AtEnd;
                y[i] = 1.0;
            }
        }
        let free = [
            m.magnet_var(0),
            m.magnet_var(9),
            m.joint_var(5).unwrap(),
            m.magnet_var(14),
        ];
        for &i in &free {
            modes[i] = Mode::Free;
            y[i] = 0.3;
        }
        let mut moving = Forces::default();
        m.forces_moving(&y, &modes, &mut moving);
        // the same through the packed drivers' entry: a full evaluation at a new epoch
        let mut sorted = free.to_vec();
        sorted.sort_unstable();
        let mut packed = Forces::default();
        assert!(m.forces_free(&y, &sorted, 1, &mut packed));
        let base = packed.drive.clone();
        for (step, &i) in free.iter().enumerate() {
            y[i] = 0.9 - 0.2 * step as f64;
        }
        m.forces_moving(&y, &modes, &mut moving);
        assert!(!moving.base_modes.is_empty());
        // the same epoch: near the free unknowns only, the very numbers of forces_moving,
        // and the drives it did not compute again are the base's
        assert!(!m.forces_free(&y, &sorted, 1, &mut packed));
        assert_eq!(packed.drive, moving.drive);
        assert_eq!(packed.evaluations(), 1);
        let mut near = vec![false; n];
        for r in m.changed(&packed) {
            near[r].iter_mut().for_each(|b| *b = true);
        }
        assert!(near.iter().any(|&b| !b));
        for i in 0..n {
            assert!(near[i] || packed.drive[i] == base[i], "{i}");
        }
        let mut full = Forces::default();
        m.forces_with_cutoff(&y, m.options().cutoff, &mut full);
        let mut changed = 0;
        for i in 0..n {
            let scale = m.drive_scale(i);
            assert!(
                (moving.drive[i] - full.drive[i]).abs() < 1e-12 * scale,
                "{i}: {} {}",
                moving.drive[i],
                full.drive[i]
            );
            changed += usize::from(moving.drive[i] != 0.0);
        }
        assert!(changed > n / 2, "{changed}");
        // a clamped value changed: a full evaluation again
        y[0] = 0.5;
        modes[0] = Mode::AtStart;
        m.forces_moving(&y, &modes, &mut moving);
        m.forces_with_cutoff(&y, m.options().cutoff, &mut full);
        assert_eq!(moving.drive, full.drive);
        // a new epoch (the modes changed): a full evaluation again
        assert!(m.forces_free(&y, &sorted, 2, &mut packed));
        assert_eq!(packed.drive, full.drive);
        assert_eq!(packed.evaluations(), 2);
    }

    /// The thesis model of `word` at s = 0.3 mm and its forces with every unknown at 0.
    fn at_start(word: &str) -> (Model, Forces) {
        let m = Model::thesis(word, 0.3);
        let mut f = Forces::default();
        m.forces(&vec![0.0; m.len()], &mut f);
        (m, f)
    }

    #[test]
    fn rest_state_holds_but_magnet_0_is_pulled_by_the_ri() {
        let (m, f) = at_start("SSSS");
        assert!(f.drive[m.magnet_var(0)] > 0.0);
        for k in 1..m.geometry.magnets() {
            assert!(f.drive[m.magnet_var(k)] < 0.0, "{k}: {}", f.drive[k]);
        }
    }

    #[test]
    fn straight_joint_held_by_the_face_and_banded() {
        let (m, f) = at_start("SLLS");
        for j in [1, 2] {
            let v = m.joint_var(j).unwrap();
            assert!(f.drive[v] < 0.0, "joint {j}: {}", f.drive[v]);
        }
        assert!(m.joint_var(0).is_none());
        assert!(m.bandwidth() <= 7, "{}", m.bandwidth());
    }

    #[test]
    fn cutoff_error_is_small_at_rest() {
        let m = Model::thesis("S*19", 0.3);
        let e = m.cutoff_error(&vec![0.0; m.len()]);
        assert!(e < 0.01, "{e}");
    }
}
