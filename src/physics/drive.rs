//! What a force does to the chain: its drive on a magnet along the magnet's path (the wall
//! takes the rest), and its torque about a hinge, on every joint between the two magnets of
//! the pair (the forces inside the part downstream of a joint have no net torque about it).

use std::ops::Range;

use kurbo::{Point, Vec2};

use crate::physics::Pole;

/// The drive (N) of `force` on a magnet whose path runs along the unit `tangent` there:
/// positive moves it forwards along its path.
pub fn along_path(force: Vec2, tangent: Vec2) -> f64 {
    force.dot(tangent)
}

/// The torque (N m) about `hinge` (mm) of `force` (N) acting at `at` (mm): positive turns
/// counter-clockwise (to the left).
pub fn torque_about(hinge: Point, at: Point, force: Vec2) -> f64 {
    ((at - hinge) * 1e-3).cross(force)
}

/// The joints that the force from pole `from` on magnet `on` (downstream of it) turns:
/// every joint between their tiles (joint `j` joins tiles `j` and `j + 1`; the RI sits in
/// tile 0).
pub fn joints_between(from: Pole, on: usize) -> Range<usize> {
    let first = match from {
        Pole::Ri => 0,
        Pole::Magnet(a) => a / 2,
    };
    first..on / 2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn torque_and_drive() {
        // a force along +y at 1 m along +x from the hinge turns left by 1 N m per N
        let t = torque_about(Point::ORIGIN, Point::new(1000.0, 0.0), Vec2::new(0.0, 2.0));
        assert!((t - 2.0).abs() < 1e-15);
        assert_eq!(along_path(Vec2::new(3.0, 4.0), Vec2::new(0.0, -1.0)), -4.0);
        assert_eq!(joints_between(Pole::Ri, 5), 0..2);
        assert_eq!(joints_between(Pole::Magnet(3), 7), 1..3);
        assert!(joints_between(Pole::Magnet(4), 5).is_empty());
    }
}
