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

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use kurbo::{Point, Vec2};

use crate::physics::{along_path, joints_between, pairs_within, torque_about, upstream, Pole};
use crate::reference::dynamics::Model;

/// Everything the forces give at one state, with the scratch of one evaluation.
#[derive(Clone, Debug, Default)]
pub(crate) struct Forces {
    /// World positions of the magnets, mm.
    pub(crate) positions: Vec<Point>,
    /// Drive of each unknown (force along the path, N, or torque towards folding, N m).
    pub(crate) drive: Vec<f64>,
    frames: Vec<Frame>,
    tangents: Vec<Vec2>,
    force: Vec<Vec2>,
    hinges: Vec<Point>,
    points: Vec<Point>,
}

/// A tile's pose with the sine and cosine of its heading.
#[derive(Clone, Copy, Debug, Default)]
struct Frame {
    x: f64,
    y: f64,
    angle: f64,
    sin: f64,
    cos: f64,
}

impl Frame {
    /// A point of the tile's frame in the world (as [`crate::Pose::transform_point`]).
    fn point(&self, p: (f64, f64)) -> Point {
        Point::new(
            self.x + self.cos * p.0 - self.sin * p.1,
            self.y + self.sin * p.0 + self.cos * p.1,
        )
    }

    /// A vector of the tile's frame turned into the world.
    fn vector(&self, v: (f64, f64)) -> Vec2 {
        Vec2::new(
            self.cos * v.0 - self.sin * v.1,
            self.sin * v.0 + self.cos * v.1,
        )
    }
}

/// An angle brought into `[-pi, pi)` (as [`crate::Pose::then`] keeps headings).
fn wrap_angle(a: f64) -> f64 {
    if (-PI..PI).contains(&a) {
        a
    } else {
        (a + PI).rem_euclid(TAU) - PI
    }
}

/// `(sin, cos)` of `a`, without the call for a zero angle.
fn sin_cos(a: f64) -> (f64, f64) {
    if a == 0.0 {
        (a, 1.0)
    } else {
        a.sin_cos()
    }
}

impl Model {
    /// Magnet `k` at fraction `x` of its path (point and unit tangent, tile frame), the
    /// path continued along its end tangents beyond `[0, 1]`: the forces stay smooth
    /// through a magnet's arrival, so a step that overshoots it keeps its order and the
    /// arrival is found on the step's dense output (the driver never keeps a state
    /// beyond the range).
    fn local_continued(&self, k: usize, x: f64) -> ((f64, f64), (f64, f64)) {
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

    /// The tile frames at state `y` into `frames` (the poses of
    /// [`crate::kinematics::poses_at_angles`] at [`Model::joint_angles`] for `y` in
    /// `[0, 1]`).
    fn frames(&self, y: &[f64], frames: &mut Vec<Frame>) {
        frames.clear();
        let mut f = Frame {
            cos: 1.0,
            ..Frame::default()
        };
        frames.push(f);
        let half = 0.5 * self.geometry.w;
        for (j, &v) in self.joint_var.iter().enumerate() {
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
            let (s, c) = sin_cos(a);
            let (dx, dy) = (half, -h.y);
            let rel = (h.x + c * dx - s * dy, h.y + s * dx + c * dy);
            let p = f.point(rel);
            let angle = wrap_angle(f.angle + a);
            let (sin, cos) = if angle == f.angle {
                (f.sin, f.cos)
            } else {
                angle.sin_cos()
            };
            f = Frame {
                x: p.x,
                y: p.y,
                angle,
                sin,
                cos,
            };
            frames.push(f);
        }
    }

    /// Drives of every unknown at state `y` (see [`Forces`]), with pairs up to `cutoff`
    /// apart in chain index.
    pub(crate) fn forces_with_cutoff(&self, y: &[f64], cutoff: usize, out: &mut Forces) {
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
            for a in upstream(b, cutoff) {
                // the RI is fixed in tile 0's frame, which is the world frame
                let (pa, ma) = match a {
                    Pole::Ri => (self.ri.position, self.ri.moment),
                    Pole::Magnet(a) => (out.positions[a], self.moments[a]),
                };
                let f = law.force(pa, on, ma, self.moments[b], a.attracts(Pole::Magnet(b)));
                out.force[b] += f;
                if let Pole::Magnet(a) = a {
                    out.force[a] -= f;
                }
                // torque on every folding joint between the two (b downstream)
                for j in joints_between(a, b) {
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

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::reference::ModelOptions;
    use crate::timeline::TileDesigns;
    use crate::{Chain, Design};

    #[test]
    fn frames_are_the_kinematic_poses() {
        // every joint kind, half folded, a fold past a half turn of heading: the cached
        // frames are the poses of kinematics::poses_at_angles, bit for bit
        let m = Model::new(
            &Chain::parse("SLLSRRSLLLLSRS").unwrap(),
            &TileDesigns::global(Design::thesis().with_s(0.3)),
            &ModelOptions::default(),
        )
        .unwrap();
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
}
