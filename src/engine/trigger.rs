//! The distance rule's geometry (SPEC section 4, thesis 6.2-6.4): where on a moving magnet's
//! path the next magnet becomes equidistant from its two neighbours, and so starts.
//!
//! Magnet `m` starts when it is as far from magnet `m - 1` as from magnet `m + 1`, both at
//! their rest points except `m - 1`, which is moving. On a straight path that is `4s` along
//! (thesis 6.2); the engine finds the point on the real curve, so `4s`, `s = e/3` and the
//! curved-path limit all come out of the same root search. It is decided on the mover's path
//! alone, so it is cached per path kind and design and costs nothing per magnet.

use kurbo::Point;
use rustc_hash::FxHashMap;

use crate::timeline::{Geometry, LENGTH_TOLERANCE};

/// Samples per path in the search for the first sign change before bisection. Paths are a
/// line and one arc, so the distance function has at most one extremum: 256 samples cannot
/// step over a crossing and back.
const SCAN_STEPS: usize = 256;

/// Where a moving magnet starts its successor, or why it does not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Trigger {
    /// At arc length `u` (mm) along the mover's path.
    At(f64),
    /// Never: the mover comes nearest to starting it at arc length `u` (mm), where the next
    /// magnet is still `shortfall` mm nearer its partner than its other neighbour.
    Never {
        /// Arc length of the mover's nearest approach to the trigger (mm).
        u: f64,
        /// How far the trigger is missed there (mm).
        shortfall: f64,
        /// Whether that point is before the path end (a curved path's closest approach).
        before_end: bool,
    },
}

/// The triggers found so far, by (mover parity, mover's path, the two designs involved).
#[derive(Debug, Default)]
pub(crate) struct Triggers {
    cache: FxHashMap<(bool, u32, u32, u32), Trigger>,
}

impl Triggers {
    /// Where on magnet `m - 1`'s path magnet `m` starts (`1 <= m <= magnets - 2`).
    pub(crate) fn trigger(&mut self, g: &Geometry, m: usize) -> Trigger {
        let key = (
            m % 2 == 1,
            g.path_id(m - 1),
            g.design_index(m / 2),
            g.design_index(m.div_ceil(2)),
        );
        *self.cache.entry(key).or_insert_with(|| find_trigger(g, m))
    }
}

/// Whether the RI at the tile edge is nearer magnet 0 than magnet 1 is (6.2): then magnet 0
/// starts on contact. Returns the two distances (RI, partner).
pub(crate) fn ri_starts_first_magnet(g: &Geometry) -> (bool, f64, f64) {
    let r0 = g.rest_in(0, 0);
    let ri = g.ri().position.distance(r0);
    let partner = g.rest_in(1, 0).distance(r0);
    (ri < partner - LENGTH_TOLERANCE * g.w, ri, partner)
}

fn find_trigger(g: &Geometry, m: usize) -> Trigger {
    let frame = (m - 1) / 2;
    let mover = *g.path(m - 1);
    let rm = g.rest_in(m, frame);
    let target = g.rest_in(m + 1, frame).distance(rm);
    let offset = ((m - 1) / 2) as f64 * g.w - frame as f64 * g.w;
    let gap = |u: f64| {
        let (x, y) = mover.point_at(u);
        Point::new(x + offset, y).distance(rm) - target
    };
    let tol = LENGTH_TOLERANCE * g.w;
    let len = mover.length();
    let g0 = gap(0.0);
    if g0.abs() <= tol {
        return Trigger::At(0.0);
    }
    let sign0 = g0.signum();
    let mut best = (0.0, g0.abs());
    let mut prev = 0.0;
    for i in 1..=SCAN_STEPS {
        let u = len * i as f64 / SCAN_STEPS as f64;
        let v = gap(u);
        if v.signum() != sign0 {
            // a true crossing in [prev, u]: bisect on the sign alone
            let (mut lo, mut hi) = (prev, u);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if gap(mid).signum() == sign0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            // the sequential edge (s = e/3): a crossing within rounding of the path end is
            // at the end, so the next magnet starts exactly as this one arrives
            return Trigger::At(if len - hi <= tol { len } else { hi });
        }
        if v.abs() < best.1 {
            best = (u, v.abs());
        }
        prev = u;
    }
    // no crossing: the sequential edge (s = e/3) meets the trigger at the path end
    if gap(len).abs() <= tol {
        return Trigger::At(len);
    }
    // refine the nearest approach (golden-section on the bracket around the best sample)
    let step = len / SCAN_STEPS as f64;
    let (mut lo, mut hi) = ((best.0 - step).max(0.0), (best.0 + step).min(len));
    for _ in 0..100 {
        let m1 = lo + (hi - lo) * 0.382;
        let m2 = lo + (hi - lo) * 0.618;
        if gap(m1).abs() < gap(m2).abs() {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let u = 0.5 * (lo + hi);
    let shortfall = gap(u).abs();
    let before_end = u < len - tol;
    Trigger::Never {
        u: if before_end { u } else { len },
        shortfall,
        before_end,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::{Chain, Design};

    fn geometry(chain: &str, design: Design) -> Geometry {
        Geometry::new(&Chain::parse(chain).unwrap(), vec![design], Vec::new()).unwrap()
    }

    #[test]
    fn straight_trigger_is_four_s() {
        for s in [0.0, 0.1, 0.3, 1.0, 4.7 / 3.0] {
            let g = geometry("SSSS", Design::thesis().with_s(s));
            let mut t = Triggers::default();
            for m in 1..=8 {
                match t.trigger(&g, m) {
                    Trigger::At(u) => assert!((u - 4.0 * s).abs() < 1e-9, "s {s} m {m}: {u}"),
                    other => panic!("s {s} m {m}: {other:?}"),
                }
            }
        }
        let g = geometry("SSSS", Design::thesis().with_s(1.7));
        assert!(matches!(
            Triggers::default().trigger(&g, 1),
            Trigger::Never {
                before_end: false,
                ..
            }
        ));
    }

    #[test]
    fn curved_trigger_comes_before_closest_approach() {
        // thesis design: a curved path starts the next magnet; with the thesis' layout
        // c = 2.8 mm at the final point, a larger s (still < e/3) does not, because the curve
        // turns away first. Against the default 0.8 mm wall the curve reaches farther.
        let g = geometry("SLS", Design::thesis());
        let m = 4; // magnet 3, on tile 1 second path (L), starts magnet 4
        let t = Triggers::default().trigger(&g, m);
        assert!(matches!(t, Trigger::At(_)), "{t:?}");
        let g = geometry("SLS", Design::thesis().with_s(0.5));
        let t = Triggers::default().trigger(&g, m);
        assert!(matches!(t, Trigger::At(_)), "{t:?}");
        let old = Design {
            c: Some(2.8),
            ..Design::thesis().with_s(0.5)
        };
        let g = geometry("SLS", old);
        match Triggers::default().trigger(&g, m) {
            Trigger::Never { before_end, .. } => assert!(before_end),
            t => panic!("{t:?}"),
        }
    }

    #[test]
    fn the_ri_starts_magnet_0_unless_6_2_fails() {
        // thesis design: the RI sits c + a = 7.8 mm from magnet 0, its partner b = 14.4 mm
        let (starts, ri, partner) = ri_starts_first_magnet(&geometry("SS", Design::thesis()));
        assert!(starts, "{ri} {partner}");
        assert!(
            (ri - 7.8).abs() < 1e-9 && (partner - 14.4).abs() < 1e-9,
            "{ri} {partner}"
        );
        // s = 3 mm: c + a = d/2 + s = 10.5 mm, b = d - 2s = 9 mm, so (6.2) c + a < b fails
        let (starts, ri, partner) =
            ri_starts_first_magnet(&geometry("SS", Design::thesis().with_s(3.0)));
        assert!(!starts, "{ri} {partner}");
        assert!(
            (ri - 10.5).abs() < 1e-9 && (partner - 9.0).abs() < 1e-9,
            "{ri} {partner}"
        );
    }
}
