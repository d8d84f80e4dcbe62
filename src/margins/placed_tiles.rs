//! The few tiles around a magnet or a joint, placed for one state of the chain: where each
//! magnet sits on its path and at what angle each joint stands. The drive on a magnet and the
//! torque about a hinge are then sums of [`crate::physics`] pair forces over the poles within
//! the cutoff, as the engine's force rule and the reference integrator sum them.

use kurbo::{Point, Vec2};

use crate::kinematics::joint_transform;
use crate::margins::ChainModel;
use crate::octagon::Octagon;
use crate::physics::{along_path, neighbours, torque_about, ForceLaw, Pole};
use crate::Pose;

/// One state of the chain, as the margins pose it: each magnet's travel along its path (mm)
/// and each joint's angle (radians, positive = left).
pub(crate) trait State {
    /// Magnet `k`'s travel, mm.
    fn travel(&self, k: usize) -> f64;
    /// Joint `j`'s angle, radians.
    fn angle(&self, j: usize) -> f64;
}

/// Magnets `lo..=hi` placed in the frame of tile `lo / 2`, reused between evaluations.
pub(crate) struct PlacedTiles {
    lo: usize,
    hi: usize,
    poses: Vec<Pose>,
    points: Vec<Point>,
}

impl PlacedTiles {
    /// A window over magnets `lo..=hi`.
    pub(crate) fn new(lo: usize, hi: usize) -> PlacedTiles {
        PlacedTiles {
            lo,
            hi,
            poses: Vec::with_capacity(hi / 2 - lo / 2 + 1),
            points: Vec::with_capacity(hi - lo + 1),
        }
    }

    /// Places the window's tiles and magnets for `state`.
    pub(crate) fn place(&mut self, model: &ChainModel, state: &impl State) {
        let (tlo, thi) = (self.lo / 2, self.hi / 2);
        self.poses.clear();
        let mut pose = Pose::IDENTITY;
        self.poses.push(pose);
        for j in tlo..thi {
            pose = pose.then(&joint_transform(state.angle(j), model.joint_width(j)));
            self.poses.push(pose);
        }
        self.points.clear();
        for k in self.lo..=self.hi {
            let p = model.path(k).point_at(state.travel(k));
            self.points
                .push(Point::from(self.poses[k / 2 - tlo].transform_point(p)));
        }
    }

    fn point(&self, k: usize) -> Point {
        self.points[k - self.lo]
    }

    fn pose(&self, tile: usize) -> &Pose {
        &self.poses[tile - self.lo / 2]
    }

    /// The pole's position and moment, as placed.
    fn source(&self, model: &ChainModel, pole: Pole) -> (Point, f64) {
        match pole {
            Pole::Magnet(k) => (self.point(k), model.moment(k)),
            Pole::Ri => {
                let ri = model.ri();
                (
                    Point::from(self.pose(0).transform_point(ri.position.into())),
                    ri.moment,
                )
            }
        }
    }

    /// The drive (N) along magnet `m`'s path at travel `u`, from every pole within `cutoff`.
    /// The window must hold them.
    pub(crate) fn drive(
        &self,
        model: &ChainModel,
        law: ForceLaw,
        cutoff: usize,
        m: usize,
        u: f64,
    ) -> f64 {
        self.drive_from(model, law, cutoff, m, u, true)
    }

    /// [`PlacedTiles::drive`], the reaction initiator left out unless `with_ri`.
    pub(crate) fn drive_from(
        &self,
        model: &ChainModel,
        law: ForceLaw,
        cutoff: usize,
        m: usize,
        u: f64,
        with_ri: bool,
    ) -> f64 {
        let on = Pole::Magnet(m);
        let pm = self.point(m);
        let tangent = Vec2::from(
            self.pose(m / 2)
                .transform_vector(model.path(m).tangent_at(u)),
        );
        let mm = model.moment(m);
        neighbours(m, cutoff, model.magnets())
            .filter(|p| with_ri || *p != Pole::Ri)
            .map(|source| {
                let (p, moment) = self.source(model, source);
                along_path(law.force(p, pm, moment, mm, source.attracts(on)), tangent)
            })
            .sum()
    }

    /// The torque (N m) about joint `j`'s hinge on the part of the chain after it, in the
    /// direction `sign` (+1 left, -1 right), from every pair within `cutoff` that straddles
    /// the joint. The window must hold magnets `2j + 2 - cutoff ..= 2j + 1 + cutoff`.
    pub(crate) fn torque(
        &self,
        model: &ChainModel,
        law: ForceLaw,
        cutoff: usize,
        j: usize,
        sign: f64,
    ) -> f64 {
        let octagon = Octagon::new(model.joint_width(j));
        let hinge = Point::from(self.pose(j).transform_point(octagon.hinge(sign > 0.0)));
        let first_after = 2 * j + 2;
        let last = (2 * j + 1 + cutoff).min(model.magnets() - 1);
        let mut torque = 0.0;
        for b in first_after..=last {
            let on = Pole::Magnet(b);
            let pb = self.point(b);
            let mb = model.moment(b);
            for source in neighbours(b, cutoff, model.magnets()) {
                if source.index() >= first_after as isize {
                    continue;
                }
                let (p, moment) = self.source(model, source);
                let f = law.force(p, pb, moment, mb, source.attracts(on));
                torque += torque_about(hinge, pb, f);
            }
        }
        sign * torque
    }

    /// The lever (mm) of magnet `k` about joint `j`'s hinge, as placed.
    pub(crate) fn lever(&self, model: &ChainModel, j: usize, k: usize, left: bool) -> f64 {
        let octagon = Octagon::new(model.joint_width(j));
        let hinge = Point::from(self.pose(j).transform_point(octagon.hinge(left)));
        hinge.distance(self.point(k))
    }
}
