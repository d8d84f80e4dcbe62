//! How the chain moves on the water while it folds, nothing anchored ([`FreeMotion`]): each
//! turning joint turns both its sides about its hinge, each side against its own inertia and
//! drag, with no net momentum ([`crate::model`]'s sides). From a run's joint angles this gives
//! the fastest a tile moves and where and when, and how far the two end tiles turn on the
//! water (the run's pictures are drawn in the frame of the first tile; these numbers are the
//! world's).
//!
//! **What it assumes.** The same as the joint's effective inertia: each side rigid in its
//! sequential shape (the folds before the joint made, the chain after it straight). A tile's
//! speed is its centre's; the fastest is looked for at each joint's fastest turn (the
//! steepest chord of its angle track, [`crate::timeline::ANGLE_TOLERANCE`]), and the velocities
//! of joints turning at once are not added. Cost: O(tiles log tiles) in all (side A's fastest
//! tile is a corner of the convex hull of its centres, kept from joint to joint).

use std::f64::consts::FRAC_PI_2;

use kurbo::Vec2;

use crate::model::Model;
use crate::timeline::{FreeMotion, RunSource};
use crate::Octagon;

impl Model {
    /// How the chain of this model moved on the water in `run` (a run of this model).
    pub fn free_motion(&self, run: &dyn RunSource) -> FreeMotion {
        let g = &self.geometry;
        let inertial = self.opts.dynamics.is_inertial();
        let mm = 1e-3;
        let angles: Vec<f64> = self.joint_sign.iter().map(|s| s * FRAC_PI_2).collect();
        let poses = crate::kinematics::poses_at_angles(&angles, g.w);
        let oct = Octagon::new(g.w);
        let mut out = FreeMotion {
            max_tile_speed_m_s: 0.0,
            fastest_tile: None,
            fastest_at_s: None,
            fastest_joint: None,
            first_tile_turn_deg: 0.0,
            last_tile_turn_deg: 0.0,
        };
        let (mut first, mut last) = (0.0, 0.0);
        // the convex hull of the tile centres before `hulled` (world frame, with their tiles)
        let (mut hull, mut hulled): (Vec<(f64, f64, usize)>, usize) = (Vec::new(), 0);
        for (j, sides) in self.sides.iter().enumerate() {
            let Some(sides) = sides else { continue };
            let track = run.joint_angle(j);
            if track.is_constant() {
                continue;
            }
            // the first tile turns with side A: the integral of side A's turn per unit angle
            // over the angle the joint travelled (Simpson's rule, 64 intervals)
            let phi_end = track.points.last().map_or(0.0, |p| p.1);
            let n = 64;
            let h = phi_end / f64::from(n);
            let mut sum = 0.0;
            for i in 0..=n {
                let wgt = if i == 0 || i == n {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                sum += wgt * sides.unit_turn(f64::from(i) * h, inertial).0;
            }
            let turn_a = sum * h / 3.0;
            first += turn_a;
            last += turn_a + phi_end;
            // the steepest chord of the track: the joint's fastest turn
            let Some((rate, phi, at)) = track
                .points
                .windows(2)
                .filter(|p| p[1].0 > p[0].0)
                .map(|p| {
                    (
                        (p[1].1 - p[0].1) / (p[1].0 - p[0].0),
                        0.5 * (p[0].1 + p[1].1),
                        track.start + 0.5 * (p[0].0 + p[1].0),
                    )
                })
                .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            else {
                continue;
            };
            let (omega_a, omega_b, v_hinge) = sides.unit_turn(phi, inertial);
            let pose = poses[j];
            let hinge = oct.hinge(self.joint_sign[j] > 0.0);
            let (hx, hy) = pose.transform_point(hinge);
            let (sn, cs) = (-pose.angle).sin_cos();
            let perp = |v: Vec2| Vec2::new(-v.y, v.x);
            let speed = |omega: f64, r: Vec2| (v_hinge + perp(r) * omega).hypot() * rate.abs();
            let mut consider = |speed: f64, tile: usize| {
                if speed > out.max_tile_speed_m_s {
                    out.max_tile_speed_m_s = speed;
                    out.fastest_tile = Some(tile);
                    out.fastest_at_s = Some(at);
                    out.fastest_joint = Some(j);
                }
            };
            // side A: the tiles up to the joint, folded, in the joint's tile frame. A tile's
            // speed is the length of an affine function of its centre, convex: its largest
            // over side A is at a corner of the convex hull of side A's centres
            hull = convex_hull(
                hull.iter()
                    .copied()
                    .chain((hulled..=j).map(|t| (poses[t].x, poses[t].y, t))),
            );
            hulled = j + 1;
            for &(px, py, t) in &hull {
                let (dx, dy) = ((px - hx) * mm, (py - hy) * mm);
                let r = Vec2::new(cs * dx - sn * dy, sn * dx + cs * dy);
                consider(speed(omega_a, r), t);
            }
            // side B: straight, turned by the joint's angle; a speed affine along it is
            // largest at one of its ends
            let (s, c) = phi.sin_cos();
            for t in [j + 1, g.tiles() - 1] {
                let r0 = Vec2::new(((t - j) as f64 * g.w - hinge.0) * mm, -hinge.1 * mm);
                let r = Vec2::new(c * r0.x - s * r0.y, s * r0.x + c * r0.y);
                consider(speed(omega_b, r), t);
            }
        }
        out.first_tile_turn_deg = first.to_degrees();
        out.last_tile_turn_deg = last.to_degrees();
        out
    }
}

/// The convex hull of `points` (x, y and a tag), counter-clockwise, without collinear
/// points (Andrew's monotone chain).
fn convex_hull(points: impl Iterator<Item = (f64, f64, usize)>) -> Vec<(f64, f64, usize)> {
    let mut p: Vec<(f64, f64, usize)> = points.collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    p.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
    if p.len() < 3 {
        return p;
    }
    let cross = |o: (f64, f64, usize), a: (f64, f64, usize), b: (f64, f64, usize)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64, usize)> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64, usize)>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::convex_hull;

    #[test]
    fn the_hull_keeps_the_corners_only() {
        // a 4 x 3 grid: its four corners, whatever the order and the repeats
        let mut pts = Vec::new();
        for x in 0..4 {
            for y in 0..3 {
                pts.push((f64::from(x), f64::from(y), (x * 3 + y) as usize));
            }
        }
        pts.push((1.0, 1.0, 99));
        let h = convex_hull(pts.into_iter().rev());
        let mut tags: Vec<usize> = h.iter().map(|p| p.2).collect();
        tags.sort_unstable();
        assert_eq!(tags, vec![0, 2, 9, 11]);
        // fewer than three points are their own hull
        assert_eq!(convex_hull([(0.0, 0.0, 0)].into_iter()).len(), 1);
    }
}
