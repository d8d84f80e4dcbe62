//! A magnet path in the closed form the viewer's script evaluates: a straight part along the
//! tile axis from the rest point, then (curved paths) a circular arc, recovered from the
//! path's own points ([`MagnetPath::point_at`]) so the page places magnets where the library
//! does.

use foldchain::magnet_path::{MagnetPath, PathEnd};

/// A path as the page evaluates it: the point at arc length `u` is
/// `(rest + dir * u, 0)` on the straight part, and on the arc
/// `centre + radius * (cos phi, sin phi)` with `phi = phi0 + turn * (u - straight) / radius`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PathForm {
    /// Rest point x, tile frame, mm.
    pub rest: f64,
    /// +1 when the path runs towards +x (a tile's second path), -1 otherwise.
    pub dir: f64,
    /// Length of the straight part, mm.
    pub straight: f64,
    /// Whole length, mm.
    pub length: f64,
    /// The arc, `[centre x, centre y, radius, phi0, turn]`, or `None` for a straight path.
    pub arc: Option<[f64; 5]>,
}

impl PathForm {
    /// The closed form of `path`.
    pub fn from_path(path: &MagnetPath) -> PathForm {
        let dir = match path.end {
            PathEnd::First => -1.0,
            PathEnd::Second => 1.0,
        };
        let rest = path.rest().0;
        let length = path.length();
        if !path.is_curved() {
            return PathForm {
                rest,
                dir,
                straight: length,
                length,
                arc: None,
            };
        }
        // the straight part lies exactly on the axis (y = 0); the arc leaves it
        let (mut lo, mut hi) = (0.0, length);
        if path.point_at(0.0).1 != 0.0 {
            hi = 0.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if path.point_at(mid).1 == 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let straight = lo;
        let arc_len = length - straight;
        let p1 = path.point_at(straight);
        let p2 = path.point_at(straight + 0.5 * arc_len);
        let p3 = path.point_at(length);
        let arc = circle_through(p1, p2, p3).map(|(cx, cy, radius)| {
            let phi0 = (p1.1 - cy).atan2(p1.0 - cx);
            let cross = (p2.0 - p1.0) * (p3.1 - p1.1) - (p2.1 - p1.1) * (p3.0 - p1.0);
            let turn = if cross > 0.0 { 1.0 } else { -1.0 };
            [cx, cy, radius, phi0, turn]
        });
        PathForm {
            rest,
            dir,
            straight,
            length,
            arc,
        }
    }

    /// The point at arc length `u` (clamped), tile frame, mm: what the page computes.
    pub fn point_at(&self, u: f64) -> (f64, f64) {
        let u = u.clamp(0.0, self.length);
        match self.arc {
            Some([cx, cy, r, phi0, turn]) if u > self.straight => {
                let phi = phi0 + turn * (u - self.straight) / r;
                (cx + r * phi.cos(), cy + r * phi.sin())
            }
            _ => (self.rest + self.dir * u.min(self.straight), 0.0),
        }
    }
}

/// The circle through three points: `(centre x, centre y, radius)`, `None` when collinear.
fn circle_through(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> Option<(f64, f64, f64)> {
    let d = 2.0 * (a.0 * (b.1 - c.1) + b.0 * (c.1 - a.1) + c.0 * (a.1 - b.1));
    if d.abs() < 1e-12 {
        return None;
    }
    let (a2, b2, c2) = (
        a.0 * a.0 + a.1 * a.1,
        b.0 * b.0 + b.1 * b.1,
        c.0 * c.0 + c.1 * c.1,
    );
    let ux = (a2 * (b.1 - c.1) + b2 * (c.1 - a.1) + c2 * (a.1 - b.1)) / d;
    let uy = (a2 * (c.0 - b.0) + b2 * (a.0 - c.0) + c2 * (b.0 - a.0)) / d;
    Some((ux, uy, ((a.0 - ux).powi(2) + (a.1 - uy).powi(2)).sqrt()))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use foldchain::{Design, PathKind};

    #[test]
    fn closed_form_places_magnets_where_the_library_does() {
        let d = Design::thesis();
        for design in [d, d.with_s(0.0), d.with_s(d.e / 3.0)] {
            for kind in [PathKind::S, PathKind::L, PathKind::R] {
                for end in [PathEnd::First, PathEnd::Second] {
                    let path = MagnetPath::new(kind, end, &design).unwrap();
                    let form = PathForm::from_path(&path);
                    assert_eq!(form.arc.is_some(), path.is_curved());
                    for i in 0..=1000 {
                        let u = path.length() * i as f64 / 1000.0;
                        let (a, b) = (form.point_at(u), path.point_at(u));
                        let err = (a.0 - b.0).hypot(a.1 - b.1);
                        assert!(err < 1e-9, "{kind:?} {end:?} s={} u={u}: {err}", design.s);
                    }
                }
            }
        }
    }
}
