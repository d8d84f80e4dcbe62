//! Floating-point rigid poses in the plane, for tiles at arbitrary fold angles.

use parry2d_f64::math::{Pose as ParryPose, Vector};

/// A rigid motion of the plane: rotation by `angle` (radians, counter-clockwise) then
/// translation by `(x, y)`.
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Pose {
    /// Translation x.
    pub x: f64,
    /// Translation y.
    pub y: f64,
    /// Rotation, radians counter-clockwise.
    pub angle: f64,
}

/// An angle brought into `[-pi, pi)`, so that composing many turns keeps the angle's
/// magnitude, and with it the rounding of its sine and cosine, bounded.
pub(crate) fn wrap_angle(a: f64) -> f64 {
    if (-std::f64::consts::PI..std::f64::consts::PI).contains(&a) {
        a
    } else {
        (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
    }
}

impl Pose {
    /// The identity.
    pub const IDENTITY: Pose = Pose {
        x: 0.0,
        y: 0.0,
        angle: 0.0,
    };

    /// A pose from translation and angle.
    pub const fn new(x: f64, y: f64, angle: f64) -> Pose {
        Pose { x, y, angle }
    }

    /// A point given in this pose's frame, placed in the world.
    pub fn transform_point(&self, p: (f64, f64)) -> (f64, f64) {
        let (s, c) = self.angle.sin_cos();
        (self.x + c * p.0 - s * p.1, self.y + s * p.0 + c * p.1)
    }

    /// A vector given in this pose's frame, turned into the world.
    pub fn transform_vector(&self, v: (f64, f64)) -> (f64, f64) {
        let (s, c) = self.angle.sin_cos();
        (c * v.0 - s * v.1, s * v.0 + c * v.1)
    }

    /// `self` then `other` in `self`'s frame: the pose of a frame given relative to this one.
    pub fn then(&self, other: &Pose) -> Pose {
        let (x, y) = self.transform_point((other.x, other.y));
        Pose::new(x, y, wrap_angle(self.angle + other.angle))
    }

    /// Rotation by `angle` about the point `centre`, applied after this pose.
    pub fn rotated_about(&self, centre: (f64, f64), angle: f64) -> Pose {
        let (s, c) = angle.sin_cos();
        let (dx, dy) = (self.x - centre.0, self.y - centre.1);
        Pose::new(
            centre.0 + c * dx - s * dy,
            centre.1 + s * dx + c * dy,
            self.angle + angle,
        )
    }

    /// The heading in degrees, in `[0, 360)`.
    pub fn heading_degrees(&self) -> f64 {
        let d = self.angle.to_degrees().rem_euclid(360.0);
        if d >= 360.0 - 1e-9 {
            0.0
        } else {
            d
        }
    }

    /// The pose as parry2d's type.
    pub fn to_parry(&self) -> ParryPose {
        ParryPose::new(Vector::new(self.x, self.y), self.angle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_and_rotation() {
        let a = Pose::new(1.0, 0.0, std::f64::consts::FRAC_PI_2);
        let b = Pose::new(1.0, 0.0, 0.0);
        let c = a.then(&b);
        assert!((c.x - 1.0).abs() < 1e-15 && (c.y - 1.0).abs() < 1e-15);
        let r = Pose::new(2.0, 0.0, 0.0).rotated_about((1.0, 0.0), std::f64::consts::PI);
        assert!((r.x - 0.0).abs() < 1e-15 && r.y.abs() < 1e-15);
        assert!(
            (Pose::new(0.0, 0.0, -std::f64::consts::FRAC_PI_2).heading_degrees() - 270.0).abs()
                < 1e-12
        );
    }
}
