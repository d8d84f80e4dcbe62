//! The channel a magnet slides in, as a plane region: every point within `r` of the
//! magnet's path ([`MagnetPath`], the same curve the engine drives the magnet along), where
//! `r` is half the magnet's diameter plus half the clearance.
//!
//! The region is the union of exact pieces, so that its walls are the path's true offsets:
//! a rectangle along a straight part, quadrilaterals between the path's offset points
//! `p(u) +- r n(u)` along an arc (each vertex on the offset curve; chords within the arc
//! tolerance of it), and discs at the rest point, at the end of a straight part and at the
//! final point (the path turns where its straight part meets its arc).

use foldchain::magnet_path::MagnetPath;

use crate::region::{self, ccw, disc, segments_for_angle, Contour, Pt, Region};

/// One magnet's channel in a tile's frame.
#[derive(Clone, Debug)]
pub struct Channel {
    /// The path the magnet's centre follows.
    pub path: MagnetPath,
    /// Half the channel's width, mm: magnet radius plus half the clearance.
    pub radius: f64,
    /// The region the channel takes out of the tile.
    pub region: Region,
}

impl Channel {
    /// The channel of `path` for a magnet of `diameter` with `clearance`, walls within
    /// `tol` of their curves.
    pub fn new(path: MagnetPath, diameter: f64, clearance: f64, tol: f64) -> Channel {
        let radius = 0.5 * (diameter + clearance);
        let region = region::cleaned(region::union(&pieces(&path, radius, tol)), region::MIN_EDGE);
        Channel {
            path,
            radius,
            region,
        }
    }
}

/// The path's point and unit normal (left of its direction) at arc length `u`.
fn point_normal(path: &MagnetPath, u: f64) -> (Pt, Pt) {
    let ((x, y), (tx, ty)) = path.point_and_tangent_at(u);
    ([x, y], [-ty, tx])
}

fn offset(p: Pt, n: Pt, r: f64) -> Pt {
    [p[0] + r * n[0], p[1] + r * n[1]]
}

/// The pieces whose union is the channel, each counter-clockwise.
fn pieces(path: &MagnetPath, r: f64, tol: f64) -> Vec<Contour> {
    let len = path.length();
    let s = path.straight_length().min(len);
    let mut out = Vec::new();
    let rest = path.rest();
    out.push(disc([rest.0, rest.1], r, tol));
    if s > 0.0 {
        let (p0, n0) = point_normal(path, 0.0);
        let (p1, _) = point_normal(path, s);
        out.push(ccw(vec![
            offset(p0, n0, -r),
            offset(p1, n0, -r),
            offset(p1, n0, r),
            offset(p0, n0, r),
        ]));
        out.push(disc(p1, r, tol));
    }
    if len > s {
        // the arc's turn from its tangents at both ends; its radius from length and turn
        let t0 = path.point_and_tangent_at(s).1;
        let t1 = path.point_and_tangent_at(len).1;
        let turn = (t0.0 * t1.1 - t0.1 * t1.0)
            .atan2(t0.0 * t1.0 + t0.1 * t1.1)
            .abs();
        let radius = if turn > 0.0 {
            (len - s) / turn
        } else {
            f64::INFINITY
        };
        let n = if radius.is_finite() {
            segments_for_angle(turn, radius + r, tol)
        } else {
            1
        };
        let us: Vec<f64> = (0..=n)
            .map(|i| s + (len - s) * i as f64 / n as f64)
            .collect();
        for w in us.windows(2) {
            let (pa, na) = point_normal(path, w[0]);
            let (pb, nb) = point_normal(path, w[1]);
            out.push(ccw(vec![
                offset(pa, na, -r),
                offset(pb, nb, -r),
                offset(pb, nb, r),
                offset(pa, na, r),
            ]));
        }
    }
    let end = path.end_point();
    out.push(disc([end.0, end.1], r, tol));
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::magnet_path::PathEnd;
    use foldchain::{Design, PathKind};

    #[test]
    fn a_straight_channel_is_a_capsule() {
        let d = Design::thesis();
        let p = MagnetPath::new(PathKind::S, PathEnd::First, &d).unwrap();
        let c = Channel::new(p, 3.0, 0.2, 0.001);
        assert_eq!(c.region.len(), 1);
        let r = 1.6;
        let capsule = std::f64::consts::PI * r * r + 2.0 * r * d.a();
        let a = region::area(&c.region);
        assert!((a - capsule).abs() < 0.01, "{a} vs {capsule}");
    }
}
