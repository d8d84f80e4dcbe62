//! Exact coordinates: numbers of the form (a + b/sqrt2) * w/2 with integer a and b.
//!
//! Tile centres of a folded chain are integer combinations of w and w/sqrt2 and hinge and
//! outline vertices are half of that, so every final pose is held exactly in integers and
//! turned into `f64` only for output: no drift at any chain length.

use std::cmp::Ordering;
use std::ops::{Add, Neg, Sub};

/// The number `(a + b / sqrt2) * w / 2`, for a tile width `w` given when converting.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct Surd {
    /// Rational part, in half tile widths.
    pub a: i64,
    /// Coefficient of 1/sqrt2, in half tile widths.
    pub b: i64,
}

impl Surd {
    /// Zero.
    pub const ZERO: Surd = Surd { a: 0, b: 0 };

    /// `(a + b/sqrt2) * w/2`.
    pub const fn new(a: i64, b: i64) -> Surd {
        Surd { a, b }
    }

    /// The value in units of `w`, as `f64`.
    pub fn to_f64(self, w: f64) -> f64 {
        (self.a as f64 + self.b as f64 * std::f64::consts::FRAC_1_SQRT_2) * 0.5 * w
    }

    /// The absolute value, decided exactly.
    pub fn abs(self) -> Surd {
        if self.signum() == Ordering::Less {
            -self
        } else {
            self
        }
    }

    /// The sign of the value, decided exactly.
    pub fn signum(self) -> Ordering {
        // sign(a + b/sqrt2) = sign(a*sqrt2 + b); compare 2a^2 with b^2 when the signs differ.
        let (a, b) = (self.a as i128, self.b as i128);
        let sa = a.cmp(&0);
        let sb = b.cmp(&0);
        if sa == sb || sb == Ordering::Equal {
            return sa;
        }
        if sa == Ordering::Equal {
            return sb;
        }
        match (2 * a * a).cmp(&(b * b)) {
            Ordering::Greater => sa,
            Ordering::Less => sb,
            Ordering::Equal => Ordering::Equal, // impossible for integers unless both zero
        }
    }
}

impl Add for Surd {
    type Output = Surd;
    fn add(self, o: Surd) -> Surd {
        Surd::new(self.a + o.a, self.b + o.b)
    }
}

impl Sub for Surd {
    type Output = Surd;
    fn sub(self, o: Surd) -> Surd {
        Surd::new(self.a - o.a, self.b - o.b)
    }
}

impl Neg for Surd {
    type Output = Surd;
    fn neg(self) -> Surd {
        Surd::new(-self.a, -self.b)
    }
}

impl PartialOrd for Surd {
    fn partial_cmp(&self, other: &Surd) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Surd {
    fn cmp(&self, other: &Surd) -> Ordering {
        (*self - *other).signum()
    }
}

/// A heading: a whole number of quarter turns counter-clockwise from +x, in `0..4`.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct QuarterTurns(u8);

impl QuarterTurns {
    /// Heading from a whole number of quarter turns (any integer, taken modulo 4).
    pub fn new(q: i64) -> QuarterTurns {
        QuarterTurns(q.rem_euclid(4) as u8)
    }

    /// The number of quarter turns, in `0..4`.
    pub fn get(self) -> u8 {
        self.0
    }

    /// The heading turned by `q` more quarter turns.
    pub fn turned(self, q: i64) -> QuarterTurns {
        QuarterTurns::new(self.0 as i64 + q)
    }

    /// The angle in radians, in `[0, 2 pi)`.
    pub fn to_radians(self) -> f64 {
        self.0 as f64 * std::f64::consts::FRAC_PI_2
    }

    /// The angle in degrees: 0, 90, 180 or 270.
    pub fn to_degrees(self) -> f64 {
        self.0 as f64 * 90.0
    }

    /// The unit vector of the heading, exactly: `(1, 0)`, `(0, 1)`, `(-1, 0)` or `(0, -1)`.
    pub fn unit_vector(self) -> kurbo::Vec2 {
        match self.0 {
            0 => kurbo::Vec2::new(1.0, 0.0),
            1 => kurbo::Vec2::new(0.0, 1.0),
            2 => kurbo::Vec2::new(-1.0, 0.0),
            _ => kurbo::Vec2::new(0.0, -1.0),
        }
    }
}

/// A point with exact coordinates.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct ExactPoint {
    /// x coordinate.
    pub x: Surd,
    /// y coordinate.
    pub y: Surd,
}

impl ExactPoint {
    /// The origin.
    pub const ORIGIN: ExactPoint = ExactPoint {
        x: Surd::ZERO,
        y: Surd::ZERO,
    };

    /// A point from its coordinates.
    pub const fn new(x: Surd, y: Surd) -> ExactPoint {
        ExactPoint { x, y }
    }

    /// The vector turned counter-clockwise by a heading (exact: quarter turns only swap and
    /// negate coordinates).
    pub fn rotated(self, h: QuarterTurns) -> ExactPoint {
        let ExactPoint { x, y } = self;
        match h.get() {
            0 => ExactPoint::new(x, y),
            1 => ExactPoint::new(-y, x),
            2 => ExactPoint::new(-x, -y),
            _ => ExactPoint::new(y, -x),
        }
    }

    /// `(x, y)` in `f64` for a tile width `w`.
    pub fn to_f64(self, w: f64) -> (f64, f64) {
        (self.x.to_f64(w), self.y.to_f64(w))
    }
}

impl Add for ExactPoint {
    type Output = ExactPoint;
    fn add(self, o: ExactPoint) -> ExactPoint {
        ExactPoint::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for ExactPoint {
    type Output = ExactPoint;
    fn sub(self, o: ExactPoint) -> ExactPoint {
        ExactPoint::new(self.x - o.x, self.y - o.y)
    }
}

/// An exact tile pose: centre and heading.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize,
)]
pub struct ExactPose {
    /// The tile centre.
    pub centre: ExactPoint,
    /// The direction the chain runs through the tile, away from the reaction initiator.
    pub heading: QuarterTurns,
}

impl ExactPose {
    /// The pose in `f64` for a tile width `w`.
    pub fn to_pose(self, w: f64) -> crate::Pose {
        let (x, y) = self.centre.to_f64(w);
        crate::Pose::new(x, y, self.heading.to_radians())
    }

    /// A point given in the tile's own frame, placed in the world.
    pub fn transform(self, local: ExactPoint) -> ExactPoint {
        self.centre + local.rotated(self.heading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_sign() {
        assert_eq!(Surd::new(1, -1).signum(), Ordering::Greater); // 1 - 0.707
        assert_eq!(Surd::new(1, -2).signum(), Ordering::Less); // 1 - 1.414
        assert_eq!(Surd::new(-3, 5).signum(), Ordering::Greater); // -3 + 3.54
        assert_eq!(Surd::new(0, 0).signum(), Ordering::Equal);
        assert!(Surd::new(0, 2) > Surd::new(1, 0));
        assert_eq!(Surd::new(1, -2).abs(), Surd::new(-1, 2));
        assert_eq!(Surd::new(1, -1).abs(), Surd::new(1, -1));
    }

    #[test]
    fn quarter_turns_wrap() {
        assert_eq!(QuarterTurns::new(-1).get(), 3);
        assert_eq!(QuarterTurns::new(5).get(), 1);
        let p = ExactPoint::new(Surd::new(1, 0), Surd::new(0, 1));
        assert_eq!(p.rotated(QuarterTurns::new(4)), p);
        assert_eq!(
            p.rotated(QuarterTurns::new(1))
                .rotated(QuarterTurns::new(3)),
            p
        );
    }

    #[test]
    fn unit_vector_turns_with_the_heading() {
        // the unit vector of heading q is (1, 0) turned by q quarter turns, as rotated() says
        let one = ExactPoint::new(Surd::new(2, 0), Surd::ZERO);
        for q in 0..4 {
            let h = QuarterTurns::new(q);
            let (x, y) = one.rotated(h).to_f64(1.0);
            assert_eq!(h.unit_vector(), kurbo::Vec2::new(x, y), "heading {q}");
        }
    }
}
