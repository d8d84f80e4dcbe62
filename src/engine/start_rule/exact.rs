//! The force rule as first written, kept for the tests as the oracle of the fast search and
//! its cache: every drive rebuilds the poses of the tiles within reach, the drive is sampled
//! at every one of the rule's 64 + 16 times, and the first sign change is bisected to the
//! last bit of the clock.

use kurbo::{Point, Vec2};

use crate::engine::start_rule::{sample_times, ForceRule, ForceStart, DRIVE_TOLERANCE};
use crate::kinematics::joint_transform;
use crate::physics::{along_path, neighbours, reach, Pole};
use crate::Pose;

impl ForceRule<'_> {
    /// The force (N) along magnet `m`'s path at its rest point at time `t`, from every
    /// magnet within the cutoff of it in chain index (and the RI while within reach), each
    /// where the run has it then; the poses rebuilt from scratch.
    pub(crate) fn exact_drive(&self, m: usize, t: f64) -> f64 {
        let g = self.geometry;
        let within = reach(m, self.cutoff, g.magnets());
        let (tlo, thi) = (within.start() / 2, within.end() / 2);
        // tile poses in the frame of tile `tlo`
        let mut poses = Vec::with_capacity(thi - tlo + 1);
        let mut pose = Pose::IDENTITY;
        poses.push(pose);
        for j in tlo..thi {
            pose = pose.then(&joint_transform(self.progress.joint_angle(j, t), g.w));
            poses.push(pose);
        }
        let at = |k: usize| {
            let p = g.path(k).point_at(self.progress.travel_at(k, t));
            Point::from(poses[k / 2 - tlo].transform_point(p))
        };
        let on = Pole::Magnet(m);
        let pm = at(m);
        let tangent = Vec2::from(poses[m / 2 - tlo].transform_vector(g.path(m).tangent_at(0.0)));
        let mm = g.design(m / 2).moment();
        let ri = g.ri();
        let mut drive = 0.0;
        for source in neighbours(m, self.cutoff, g.magnets()) {
            let (p, moment) = match source {
                Pole::Magnet(k) => (at(k), g.design(k / 2).moment()),
                // the RI is fixed in tile 0's frame
                Pole::Ri => (
                    Point::from(poses[0].transform_point(ri.position.into())),
                    ri.moment,
                ),
            };
            let force = self.law.force(p, pm, moment, mm, source.attracts(on));
            drive += along_path(force, tangent);
        }
        drive
    }

    /// When magnet `m` starts, magnet `m - 1` having started at `t0`: every sample, then a
    /// bisection to the last bit.
    pub(crate) fn exact_start(&self, m: usize, t0: f64) -> ForceStart {
        let threshold = DRIVE_TOLERANCE * self.law.bonded_rest_force(self.geometry.design(0));
        let times = sample_times(&self.progress, self.cutoff, m, t0);
        let mut best = (t0, f64::NEG_INFINITY);
        let mut prev = t0;
        for (i, &t) in times.iter().enumerate() {
            let v = self.exact_drive(m, t);
            if v > threshold {
                if i == 0 {
                    return ForceStart::At(t0);
                }
                let (mut a, mut b) = (prev, t);
                for _ in 0..60 {
                    let mid = 0.5 * (a + b);
                    if mid <= a || mid >= b {
                        break;
                    }
                    if self.exact_drive(m, mid) > threshold {
                        b = mid;
                    } else {
                        a = mid;
                    }
                }
                return ForceStart::At(b);
            }
            if v > best.1 {
                best = (t, v);
            }
            prev = t;
        }
        ForceStart::Never {
            time: best.0,
            drive: best.1,
        }
    }
}
