//! The frames a plan passes through, as kurbo [`Affine`] maps.
//!
//! - *physical*: the drawing seen from above, SVG user units with y up (see
//!   [`crate::shape`]);
//! - *plan*: the physical frame turned by minus the row angle, so that rows run along x;
//! - *work*: the plan frame mirrored (x by `sx`, y by `sy`, so that the rows are stacked
//!   towards +y from the chosen corner) and scaled to tile widths (w = 1). The row programme
//!   runs here. Planning by cells uses the unmirrored work frame (`sx = sy = 1`), called the
//!   *axis frame* there;
//! - *SVG*: user units with y down, where the plan's poses are given.

use kurbo::Affine;

use crate::shape::Shape;

/// One way to lay rows over the shape: the row direction and the corner they start from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Orientation {
    /// Row direction in the physical frame, radians.
    pub angle: f64,
    /// The mirror of x (+1 or -1) from the plan frame to the work frame.
    pub sx: f64,
    /// The mirror of y (+1 or -1) from the plan frame to the work frame.
    pub sy: f64,
}

impl Orientation {
    /// Rows along `angle`, not mirrored.
    pub(crate) fn along(angle: f64) -> Orientation {
        Orientation {
            angle,
            sx: 1.0,
            sy: 1.0,
        }
    }

    /// The four corners a serpentine along `angle` may start from.
    pub(crate) fn corners(angle: f64) -> [Orientation; 4] {
        [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)].map(|(sx, sy)| Orientation {
            angle,
            sx,
            sy,
        })
    }

    /// True if the work frame keeps the physical frame's handedness (no mirror, or two):
    /// a turn counter-clockwise in the work frame is then an L fold.
    pub(crate) fn keeps_handedness(&self) -> bool {
        self.sx * self.sy > 0.0
    }

    /// The physical-frame `shape` in the work frame of tiles of width `w`.
    pub(crate) fn work_shape(&self, shape: &Shape, w: f64) -> Shape {
        shape
            .rotated(-self.angle)
            .mirrored(self.sx, self.sy)
            .scaled(1.0 / w)
    }

    /// The map from the work frame to SVG user units: mirror and scale by w, turn by the
    /// row angle, flip y.
    pub(crate) fn work_to_svg(&self, w: f64) -> Affine {
        let (s, c) = self.angle.sin_cos();
        Affine::new([
            w * self.sx * c,
            -(w * self.sx * s),
            -w * self.sy * s,
            -(w * self.sy * c),
            0.0,
            0.0,
        ])
    }
}

/// The direction (SVG degrees in `[0, 180)`) along which rows of angle `row_angle` (radians,
/// physical frame) are stacked: plan +y, seen in SVG coordinates.
pub(crate) fn stacking_axis_deg(row_angle: f64) -> f64 {
    let (s, c) = row_angle.sin_cos();
    (-c).atan2(-s).to_degrees().rem_euclid(180.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Point;
    use std::f64::consts::FRAC_PI_2;

    /// The work-to-SVG map sends the work frame's +x (the row direction) to the row angle
    /// seen in SVG (y down), and undoes `work_shape` up to the y flip.
    #[test]
    fn work_to_svg_inverts_work_shape() {
        let o = Orientation {
            angle: 0.3,
            sx: -1.0,
            sy: 1.0,
        };
        let w = 2.5;
        let p = Point::new(3.0, -7.0);
        let ring = crate::shape::Ring { points: vec![p] };
        let work = o.work_shape(&Shape::from_rings(vec![ring]), w);
        let q = o.work_to_svg(w) * work.rings().next().map(|r| r.points[0]).unwrap_or(p);
        assert!(
            (q.x - p.x).abs() < 1e-12 && (q.y + p.y).abs() < 1e-12,
            "{q:?}"
        );
        assert!(!o.keeps_handedness());
        // rows along physical x are stacked along SVG y (90 degrees), and the reverse
        assert!((stacking_axis_deg(0.0) - 90.0).abs() < 1e-12);
        assert!(stacking_axis_deg(FRAC_PI_2).abs() < 1e-9);
    }
}
