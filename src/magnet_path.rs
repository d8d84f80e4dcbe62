//! The walled channel a magnet slides in, as a real parametric curve in the tile's frame
//! (SPEC section 4): a straight path, or `s` straight towards the next magnet followed by a
//! circular arc to a final point past the hinge.
//!
//! In a tile's frame the chain runs along +x through the centre. The tile's first path (the
//! one facing the reaction initiator) lies on the -x side, its second path on the +x side;
//! both start at the rest point `(-+b/2, 0)` and move away from the tile centre.
//!
//! **Curved paths.** The final point `F` lies `r` (the magnet radius, 1.5 mm) past the hinge
//! laterally, `y_F = side/2 + r` on the fold side, and as near the shared face as the walls
//! allow: the magnet rests against a wall of thickness [`Design::wall`] in front of the
//! diagonal face that closes the fold, its centre `k = r + wall` from the face
//! ([`Design::fold_clearance`]; `c` instead when a design gives it), so
//! `x_F = w/2 - r - k sqrt2`. After the fold the two magnets of the pair sit `2k` apart
//! (4.6 mm for the thesis design with its 0.8 mm wall). The thesis' layout `c` = 2.8 mm (a
//! 1.3 mm wall) leaves the last fold of a chain stalled short of its end: see docs/physics.md,
//! "The end-of-chain stall". The arc runs from `Q` (the rest point moved
//! `s` towards the next magnet) to `F` and is tangent at `F` to the tile's cross axis (the
//! thesis' "horizontal" line through the final point: its figures draw the chain vertically):
//! the two paths of a folding pair then end parallel, the angle between them closing
//! monotonically to zero as the thesis requires. (An arc tangent to the chain axis at `F`
//! would have to start backwards from `Q` with the thesis' dimensions.)

use std::f64::consts::SQRT_2;

use crate::{Design, PathKind};

/// Which end of its tile a path lies at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PathEnd {
    /// The first path, on the -x side (towards the reaction initiator).
    First,
    /// The second path, on the +x side.
    Second,
}

/// A magnet path in its tile's frame, parametrised by arc length `u` in `[0, length]`, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagnetPath {
    /// The path kind.
    pub kind: PathKind,
    /// Which end of the tile it lies at.
    pub end: PathEnd,
    /// Rest point x (mm, tile frame), always on the axis.
    rest_x: f64,
    /// Length of the straight part (the whole path when straight), mm.
    straight: f64,
    /// Arc centre and radius (tile frame, mm), and the arc's start angle (radians, negative).
    arc: Option<Arc>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Arc {
    cx: f64,
    cy: f64,
    radius: f64,
    start: f64,
}

/// Why a curved path cannot be built for a design.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PathError {
    /// The final point of a curved path does not lie beyond the end of its straight part.
    #[error("curved path cannot be built: its final point x = {x_final:.4} mm (w/2 - r - k sqrt2, k = r + wall or c) does not lie beyond the end of its straight part at x = {x_straight:.4} mm (b/2 + s); use a thinner wall, a smaller c or s, or wider tiles")]
    Degenerate {
        /// Final point x.
        x_final: f64,
        /// End of the straight part.
        x_straight: f64,
    },
}

impl MagnetPath {
    /// The path of kind `kind` at end `end` of a tile built to `design`.
    pub fn new(kind: PathKind, end: PathEnd, design: &Design) -> Result<MagnetPath, PathError> {
        let sign = match end {
            PathEnd::First => -1.0,
            PathEnd::Second => 1.0,
        };
        let rest_x = sign * 0.5 * design.b();
        let lateral = match kind {
            PathKind::S => {
                return Ok(MagnetPath {
                    kind,
                    end,
                    rest_x,
                    straight: design.a(),
                    arc: None,
                })
            }
            PathKind::L => 1.0,
            PathKind::R => -1.0,
        };
        let w = design.tile_width;
        let r = 0.5 * design.magnet_diameter;
        let half_side = 0.5 * w * (SQRT_2 - 1.0);
        let y_f = half_side + r;
        let x_f = 0.5 * w - r - design.fold_clearance() * SQRT_2;
        let x_q = 0.5 * design.b() + design.s;
        let dx = x_f - x_q;
        if dx.is_nan() || dx <= 0.0 {
            return Err(PathError::Degenerate {
                x_final: x_f,
                x_straight: x_q,
            });
        }
        // Circle through Q = (x_q, 0) and F = (x_f, y_f), centre on the line y = y_f (so its
        // tangent at F is the cross axis): centre (x_f - R, y_f), R = (dx^2 + y_f^2) / 2dx.
        let radius = (dx * dx + y_f * y_f) / (2.0 * dx);
        let start = (-y_f).atan2(radius - dx);
        Ok(MagnetPath {
            kind,
            end,
            rest_x,
            straight: design.s,
            arc: Some(Arc {
                cx: sign * (x_f - radius),
                cy: lateral * y_f,
                radius,
                start,
            }),
        })
    }

    /// The arc length of the whole path, mm.
    pub fn length(&self) -> f64 {
        self.straight + self.arc.map_or(0.0, |a| a.radius * -a.start)
    }

    /// The point at arc length `u` (clamped to the path), tile frame, mm.
    pub fn point_at(&self, u: f64) -> (f64, f64) {
        let u = u.clamp(0.0, self.length());
        let sign = self.sign();
        if u <= self.straight {
            return (self.rest_x + sign * u, 0.0);
        }
        match self.arc {
            None => (self.rest_x + sign * self.straight, 0.0),
            Some(a) => {
                let phi = a.start + (u - self.straight) / a.radius;
                let lateral = a.cy.signum();
                (
                    a.cx + sign * a.radius * phi.cos(),
                    a.cy + lateral * a.radius * phi.sin(),
                )
            }
        }
    }

    /// The rest point, tile frame.
    pub fn rest(&self) -> (f64, f64) {
        (self.rest_x, 0.0)
    }

    /// The final point, tile frame.
    pub fn end_point(&self) -> (f64, f64) {
        self.point_at(self.length())
    }

    /// The length of the straight part that leaves the rest point, mm: `s` on a curved
    /// path, the whole path when straight.
    pub fn straight_length(&self) -> f64 {
        self.straight
    }

    /// Whether the path is curved.
    pub fn is_curved(&self) -> bool {
        self.arc.is_some()
    }

    /// The unit tangent (tile frame) along which a magnet at arc length `u` moves forwards.
    /// On the straight part it is the direction away from the tile centre, exactly; on the
    /// arc, the chord over `[u - h, u + h]` (`h` = 1e-6 of the length) kept on the arc, which
    /// is parallel to the arc's tangent at `u` (within `h` of the arc's ends, at the chord's
    /// middle). Taken as the difference of the chord's two points, it carries their rounding
    /// (about 1e-10); [`MagnetPath::point_and_tangent_at`] gives the same direction without it.
    pub fn tangent_at(&self, u: f64) -> (f64, f64) {
        let along = (self.sign(), 0.0);
        if self.arc.is_none() || u < self.straight {
            return along;
        }
        let (a, b) = self.chord_ends(u);
        let (pa, pb) = (self.point_at(a), self.point_at(b));
        let d = (pb.0 - pa.0, pb.1 - pa.1);
        let norm = d.0.hypot(d.1);
        if norm > 0.0 {
            (d.0 / norm, d.1 / norm)
        } else {
            along
        }
    }

    /// [`MagnetPath::point_at`] and the direction of [`MagnetPath::tangent_at`] together:
    /// one sine and cosine away from the arc's ends, the chord's direction taken as the arc's
    /// tangent at its middle (the same within about 1e-10, without the rounding of two nearby
    /// points). The event engine's drives use it; the reference keeps `tangent_at`.
    pub fn point_and_tangent_at(&self, u: f64) -> ((f64, f64), (f64, f64)) {
        let along = (self.sign(), 0.0);
        let Some(a) = self.arc.filter(|_| u >= self.straight) else {
            return (self.point_at(u), along);
        };
        let len = self.length();
        let (c0, c1) = self.chord_ends(u);
        if c0.min(len) >= c1.min(len) {
            // no chord on the path
            return (self.point_at(u), along);
        }
        let uc = u.clamp(0.0, len);
        let phi = |u: f64| a.start + (u - self.straight) / a.radius;
        let lateral = a.cy.signum();
        let (sin_u, cos_u) = phi(uc).sin_cos();
        // the arc's tangent at the chord's middle: `u` itself away from the arc's ends
        let h = 1e-6 * len;
        let (sin, cos) = if c0 == u - h && c1 == u + h {
            (sin_u, cos_u)
        } else {
            phi(0.5 * (c0 + c1)).sin_cos()
        };
        let point = if uc > self.straight {
            (
                a.cx + self.sign() * a.radius * cos_u,
                a.cy + lateral * a.radius * sin_u,
            )
        } else {
            self.point_at(u)
        };
        (point, (-self.sign() * sin, lateral * cos))
    }

    /// The ends of the chord [`MagnetPath::tangent_at`] takes at `u` on the arc: `u - h` and
    /// `u + h` (`h` = 1e-6 of the length), kept on the arc.
    fn chord_ends(&self, u: f64) -> (f64, f64) {
        let len = self.length();
        let h = 1e-6 * len;
        let lo = (u - h).max(self.straight.min(len));
        let hi = (u + h).min(len);
        if hi > lo {
            (lo, hi)
        } else {
            (lo - h, lo)
        }
    }

    /// Points along the path for drawing, at most `max_step` mm apart.
    pub fn polyline(&self, max_step: f64) -> Vec<(f64, f64)> {
        let len = self.length();
        let n = ((len / max_step.max(1e-6)).ceil() as usize).clamp(1, 512);
        let mut pts = vec![self.rest()];
        if !self.is_curved() {
            pts.push(self.end_point());
            return pts;
        }
        {
            pts.push(self.point_at(self.straight));
        }
        for i in 1..=n {
            let u = len * i as f64 / n as f64;
            if u > self.straight {
                pts.push(self.point_at(u));
            }
        }
        pts
    }

    fn sign(&self) -> f64 {
        match self.end {
            PathEnd::First => -1.0,
            PathEnd::Second => 1.0,
        }
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use kurbo::Point;

    fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
        Point::from(a).distance(Point::from(b))
    }

    #[test]
    fn straight_path_runs_a_to_c_from_the_edge() {
        let d = Design::thesis();
        let p = MagnetPath::new(PathKind::S, PathEnd::Second, &d).unwrap();
        assert!((p.length() - d.a()).abs() < 1e-12);
        assert!((p.end_point().0 - (d.d - d.c())).abs() < 1e-12);
        let q = MagnetPath::new(PathKind::S, PathEnd::First, &d).unwrap();
        assert!((q.end_point().0 + (d.d - d.c())).abs() < 1e-12);
    }

    #[test]
    fn curved_path_is_continuous_and_ends_past_the_hinge() {
        let d = Design::thesis();
        for kind in [PathKind::L, PathKind::R] {
            for end in [PathEnd::First, PathEnd::Second] {
                let p = MagnetPath::new(kind, end, &d).unwrap();
                let n = 2000;
                let step = p.length() / n as f64;
                for i in 0..n {
                    let a = p.point_at(i as f64 * step);
                    let b = p.point_at((i + 1) as f64 * step);
                    // arc length parametrisation: chords never longer than the step
                    assert!(dist(a, b) <= step * (1.0 + 1e-9), "{kind:?} {end:?} {i}");
                    // the straight part meets the arc at an angle: chords there are shorter
                    assert!(dist(a, b) >= step * 0.8, "{kind:?} {end:?} {i}");
                }
                let (x, y) = p.end_point();
                let lateral = if kind == PathKind::L { 1.0 } else { -1.0 };
                let half_side = 15.0 * (SQRT_2 - 1.0);
                assert!((y * lateral - (half_side + 1.5)).abs() < 1e-9, "{y}");
                assert!((x.abs() - (15.0 - 1.5 - 2.3 * SQRT_2)).abs() < 1e-9, "{x}");
                // the magnet's edge touches the 0.8 mm wall in front of the diagonal face
                let face = (15.0 + half_side - x.abs() - y * lateral) / SQRT_2;
                assert!((face - 1.5 - 0.8).abs() < 1e-9, "{face}");
                // monotone away from the tile centre and towards the fold side
                let mut prev = p.point_at(0.0);
                for i in 1..=n {
                    let q = p.point_at(i as f64 * step);
                    assert!(q.0.abs() >= prev.0.abs() - 1e-12);
                    assert!(q.1 * lateral >= prev.1 * lateral - 1e-12);
                    prev = q;
                }
            }
        }
    }

    #[test]
    fn folded_pair_ends_twice_the_clearance_apart() {
        // tile j's second path L and tile j+1's first path L, tile j+1 turned 90 degrees
        // about the hinge: the two final points are 2k apart (k = r + wall, or c if given).
        for d in [
            Design::thesis(),
            Design {
                wall: 0.5,
                ..Design::thesis()
            },
            Design {
                c: Some(2.8),
                ..Design::thesis()
            },
        ] {
            let a = MagnetPath::new(PathKind::L, PathEnd::Second, &d)
                .unwrap()
                .end_point();
            let b = MagnetPath::new(PathKind::L, PathEnd::First, &d)
                .unwrap()
                .end_point();
            let next = crate::kinematics::joint_transform(std::f64::consts::FRAC_PI_2, 30.0);
            let b = next.transform_point(b);
            let k = d.fold_clearance();
            assert!((dist(a, b) - 2.0 * k).abs() < 1e-9, "{}", dist(a, b));
        }
        assert!((2.0 * Design::thesis().fold_clearance() - 4.6).abs() < 1e-12);
    }

    #[test]
    fn tangents_are_unit_and_follow_the_path() {
        let d = Design::thesis();
        for s in [0.0, 0.3] {
            for kind in PathKind::ALL {
                for end in [PathEnd::First, PathEnd::Second] {
                    let p = MagnetPath::new(kind, end, &d.with_s(s)).unwrap();
                    let sign = if end == PathEnd::First { -1.0 } else { 1.0 };
                    // leaves its rest point away from the tile centre, or along its arc
                    // when it has no straight part
                    let t0 = p.tangent_at(0.0);
                    if kind == PathKind::S || s > 0.0 {
                        assert_eq!(t0, (sign, 0.0), "{kind:?} {end:?} s {s}");
                    }
                    let len = p.length();
                    for i in 0..=20 {
                        let u = len * i as f64 / 20.0;
                        let t = p.tangent_at(u);
                        assert!((t.0.hypot(t.1) - 1.0).abs() < 1e-12);
                        // a small step forwards moves along the tangent
                        let (a, b) = (
                            p.point_at((u - 1e-4).max(0.0)),
                            p.point_at((u + 1e-4).min(len)),
                        );
                        let step = (b.0 - a.0, b.1 - a.1);
                        let cos = (step.0 * t.0 + step.1 * t.1) / step.0.hypot(step.1);
                        assert!(cos > 0.999, "{kind:?} {end:?} s {s} u {u}: {cos}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_tangent_is_the_arcs_and_the_point_is_point_at() {
        let d = Design::thesis();
        for s in [0.0, 0.3] {
            for kind in [PathKind::L, PathKind::R] {
                for end in [PathEnd::First, PathEnd::Second] {
                    let p = MagnetPath::new(kind, end, &d.with_s(s)).unwrap();
                    let len = p.length();
                    for i in 0..=40 {
                        let u = len * i as f64 / 40.0;
                        let (point, t) = p.point_and_tangent_at(u);
                        assert_eq!(point, p.point_at(u), "{kind:?} {end:?} s {s} u {u}");
                        let fd = p.tangent_at(u);
                        assert!((t.0 - fd.0).hypot(t.1 - fd.1) < 1e-8, "{u}");
                        // a chord centred on u, on the arc, is parallel to the tangent (the
                        // tangent itself is the direction of such a chord 1e-6 long)
                        let h = 1e-5 * len;
                        if u - h > s && u + h < len {
                            let (a, b) = (p.point_at(u - h), p.point_at(u + h));
                            let chord = ((b.0 - a.0) / (2.0 * h), (b.1 - a.1) / (2.0 * h));
                            let err = (chord.0 - t.0).hypot(chord.1 - t.1);
                            assert!(err < 1e-8, "{kind:?} {end:?} s {s} u {u}: {err}");
                        }
                    }
                }
            }
        }
    }
}
