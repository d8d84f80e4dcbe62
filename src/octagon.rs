//! The tile outline: a regular octagon of across-flats width `w`, and its hinges.
//!
//! In a tile's own frame the chain runs along +x through the centre, the faces shared with the
//! neighbours are the flats at x = +-w/2, and the hinge of a fold is the end vertex of the
//! shared face on the fold side (SPEC section 3).

use parry2d_f64::math::Vector;
use parry2d_f64::shape::ConvexPolygon;

use crate::exact::{ExactPoint, Surd};
use crate::{Fold, Pose};

/// Half the side of the unit-width octagon, `(sqrt2 - 1) / 2`, in half widths: `-1 + 2/sqrt2`.
const HALF_SIDE: Surd = Surd::new(-1, 2);
/// Half the width, in half widths.
const HALF_WIDTH: Surd = Surd::new(1, 0);

/// A regular octagon tile outline of across-flats width `width`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Octagon {
    /// Across-flats width (same unit as every other length).
    pub width: f64,
}

impl Octagon {
    /// An octagon of across-flats width `width`.
    pub fn new(width: f64) -> Octagon {
        Octagon { width }
    }

    /// The side length: `w (sqrt2 - 1)`.
    pub fn side(&self) -> f64 {
        self.width * (std::f64::consts::SQRT_2 - 1.0)
    }

    /// Distance from centre to a vertex: `w/2 * sqrt(4 - 2 sqrt2)`.
    pub fn circumradius(&self) -> f64 {
        0.5 * self.width * (4.0 - 2.0 * std::f64::consts::SQRT_2).sqrt()
    }

    /// The eight vertices in the tile frame, exactly, counter-clockwise from `(w/2, -side/2)`.
    pub fn exact_vertices() -> [ExactPoint; 8] {
        let (w, h) = (HALF_WIDTH, HALF_SIDE);
        [
            ExactPoint::new(w, -h),
            ExactPoint::new(w, h),
            ExactPoint::new(h, w),
            ExactPoint::new(-h, w),
            ExactPoint::new(-w, h),
            ExactPoint::new(-w, -h),
            ExactPoint::new(-h, -w),
            ExactPoint::new(h, -w),
        ]
    }

    /// The eight vertices in the tile frame, counter-clockwise.
    pub fn vertices(&self) -> [(f64, f64); 8] {
        Octagon::exact_vertices().map(|p| p.to_f64(self.width))
    }

    /// The vertices of the octagon moved inwards by `delta` on every face (an octagon of width
    /// `w - 2 delta`): used to tell touching from overlapping.
    pub fn inset_vertices(&self, delta: f64) -> [(f64, f64); 8] {
        Octagon::new(self.width - 2.0 * delta).vertices()
    }

    /// The vertices placed at a pose.
    pub fn vertices_at(&self, pose: &Pose) -> [(f64, f64); 8] {
        self.vertices().map(|p| pose.transform_point(p))
    }

    /// The hinge of a fold in the tile frame, exactly: the end of the face shared with the
    /// next tile on the fold side. `None` for a straight joint.
    pub fn exact_hinge(fold: Fold) -> Option<ExactPoint> {
        match fold {
            Fold::S => None,
            Fold::L => Some(ExactPoint::new(HALF_WIDTH, HALF_SIDE)),
            Fold::R => Some(ExactPoint::new(HALF_WIDTH, -HALF_SIDE)),
        }
    }

    /// The hinge of a fold to the left (`left = true`) or right, in the tile frame.
    pub fn hinge(&self, left: bool) -> (f64, f64) {
        let h = 0.5 * self.side();
        (0.5 * self.width, if left { h } else { -h })
    }

    /// The outline as a parry2d convex polygon, optionally inset by `delta`.
    pub fn to_parry(&self, delta: f64) -> Option<ConvexPolygon> {
        let pts = self
            .inset_vertices(delta)
            .iter()
            .map(|&(x, y)| Vector::new(x, y))
            .collect();
        ConvexPolygon::from_convex_polyline(pts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_octagon() {
        let o = Octagon::new(30.0);
        let v = o.vertices();
        for i in 0..8 {
            let (a, b) = (v[i], v[(i + 1) % 8]);
            let len = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
            assert!((len - o.side()).abs() < 1e-12, "side {i}: {len}");
            let r = (a.0 * a.0 + a.1 * a.1).sqrt();
            assert!((r - o.circumradius()).abs() < 1e-12);
        }
        let p = o.to_parry(0.0).unwrap();
        assert_eq!(p.points().len(), 8);
        let (hx, hy) = Octagon::exact_hinge(Fold::L).unwrap().to_f64(30.0);
        assert!((o.hinge(true).0 - hx).abs() < 1e-12 && (o.hinge(true).1 - hy).abs() < 1e-12);
    }
}
