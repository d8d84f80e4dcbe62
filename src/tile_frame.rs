//! A tile's frame with the sine and cosine of its heading kept: the hot loops of the force
//! evaluations (the reference's and the event engine's local solves) compose tile frames
//! joint by joint and transform points and tangents with them, and a [`crate::Pose`] would
//! call `sin_cos` on every use. The numbers are those [`crate::kinematics::poses_at_angles`]
//! composes: the same operations in the same order.

use std::f64::consts::{PI, TAU};

use kurbo::{Point, Vec2};

use crate::Pose;

/// A tile's pose with the sine and cosine of its heading.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TileFrame {
    pub(crate) x: f64,
    pub(crate) y: f64,
    pub(crate) angle: f64,
    pub(crate) sin: f64,
    pub(crate) cos: f64,
}

impl Default for TileFrame {
    /// Tile 0's frame: the origin, heading 0.
    fn default() -> TileFrame {
        TileFrame::IDENTITY
    }
}

impl TileFrame {
    /// The origin, heading 0.
    pub(crate) const IDENTITY: TileFrame = TileFrame {
        x: 0.0,
        y: 0.0,
        angle: 0.0,
        sin: 0.0,
        cos: 1.0,
    };

    /// The frame of a pose (one `sin_cos`).
    pub(crate) fn from_pose(p: &Pose) -> TileFrame {
        let (sin, cos) = p.angle.sin_cos();
        TileFrame {
            x: p.x,
            y: p.y,
            angle: p.angle,
            sin,
            cos,
        }
    }

    /// The frame as a pose.
    pub(crate) fn to_pose(self) -> Pose {
        Pose::new(self.x, self.y, self.angle)
    }

    /// A point of the tile's frame in the world (as [`crate::Pose::transform_point`]).
    pub(crate) fn point(&self, p: (f64, f64)) -> Point {
        Point::new(
            self.x + self.cos * p.0 - self.sin * p.1,
            self.y + self.sin * p.0 + self.cos * p.1,
        )
    }

    /// A vector of the tile's frame turned into the world.
    pub(crate) fn vector(&self, v: (f64, f64)) -> Vec2 {
        Vec2::new(
            self.cos * v.0 - self.sin * v.1,
            self.sin * v.0 + self.cos * v.1,
        )
    }

    /// The next tile's frame across a joint turned by `a` radians about `hinge` (the hinge
    /// of the joint's side, in this tile's frame; either for `a = 0`), tiles `2 half` wide:
    /// [`crate::kinematics::joint_transform`] then [`crate::Pose::then`], with one
    /// `sin_cos` for a turned joint and one when the heading changes.
    pub(crate) fn across_joint(&self, a: f64, hinge: Point, half: f64) -> TileFrame {
        let (s, c) = sin_cos(a);
        let (dx, dy) = (half, -hinge.y);
        let rel = (hinge.x + c * dx - s * dy, hinge.y + s * dx + c * dy);
        let p = self.point(rel);
        let angle = wrap_angle(self.angle + a);
        let (sin, cos) = if angle == self.angle {
            (self.sin, self.cos)
        } else {
            angle.sin_cos()
        };
        TileFrame {
            x: p.x,
            y: p.y,
            angle,
            sin,
            cos,
        }
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
pub(crate) fn sin_cos(a: f64) -> (f64, f64) {
    if a == 0.0 {
        (a, 1.0)
    } else {
        a.sin_cos()
    }
}
