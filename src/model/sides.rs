//! What a turning joint swings: the two sides of the chain either side of it, each a rigid
//! body free on the water, and the effective inertia and drag of the joint's angle when the
//! chain's total momentum stays zero (nothing is anchored: SPEC section 1, issue 27).
//!
//! **Two free bodies on a pin.** Side A (the tiles up to the joint, with the RI) and side B
//! (the tiles after it) turn about the joint's hinge `H`, which itself moves. With `m` the
//! total mass, `s_X` a side's first moment about `H` (mass times the offset of its centre of
//! mass) and `J_X` its second moment about `H` (the sum of `m r^2` and of each body's own
//! inertia), the kinetic energy of the pair with no net momentum, as a function of the
//! joint's angle `phi` alone, is `T = I(phi) phi'^2 / 2` with
//!
//! `I(phi) = (a b - c^2) / (a + b + 2c)`, `a = J_A - |s_A|^2 / m`, `b = J_B - |s_B|^2 / m`,
//! `c = -(s_A . R(phi) s_B) / m`
//!
//! (the Schur complement of the pair's mass matrix over the hinge's velocity, then the
//! relative rotation with the common rotation eliminated). A short side about a long one
//! turns almost alone: for a head of `k` tiles against a tail of `n`, `I` tends to the head's
//! own inertia about the hinge as `n` grows, instead of the tail's (`n^3`). The same algebra
//! on the drags (the water film under each tile: a translational drag at its centre and a
//! rotational one about it) gives the effective drag `g(phi)` of an overdamped turn, since the
//! drag forces of a free pair also have no net force or torque. The joint then follows
//! `I phi'' + I'(phi) phi'^2 / 2 + g phi' = tau` (the Lagrange equation of `T` with the drag),
//! or `g phi' = tau` overdamped.
//!
//! **Which configuration.** Each side is taken rigid in the shape it has while the joint
//! turns in sequential folding: the folds before the joint made (their final angles), the
//! chain after it straight; every magnet at its rest point, riding with its tile, as in the
//! free-body reference (`reference::free_body`'s tile bodies; side A's magnets at their final
//! points made a fold at the chain's first joint 0.8-1.4% slower, docs/physics.md). The
//! free-body reference integrates the sides as they really are, and measures what the rigid
//! sequential shape costs.

use std::f64::consts::FRAC_PI_2;

use kurbo::{Point, Vec2};

use crate::physics::TileBody;
use crate::timeline::Geometry;
use crate::Octagon;

/// Mass moments of a set of point bodies in the plane: total, centre of mass, and second
/// moment about the centre (the bodies' own inertias included). Combined by the parallel-axis
/// rule, so long sums lose no precision to large offsets.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Moments {
    /// Total mass (or drag), kg (or N s/m).
    pub(crate) m: f64,
    /// Centre of mass, m.
    pub(crate) c: Point,
    /// Second moment about `c`, kg m^2 (or N m s).
    pub(crate) jc: f64,
}

impl Moments {
    /// One body of mass `m` at `c` with its own inertia `ic` about `c`.
    pub(crate) fn body(m: f64, c: Point, ic: f64) -> Moments {
        Moments { m, c, jc: ic }
    }

    /// The moments of both sets together.
    pub(crate) fn add(self, o: Moments) -> Moments {
        let m = self.m + o.m;
        if m <= 0.0 {
            return Moments {
                m: 0.0,
                c: self.c,
                jc: self.jc + o.jc,
            };
        }
        let c = Point::new(
            (self.m * self.c.x + o.m * o.c.x) / m,
            (self.m * self.c.y + o.m * o.c.y) / m,
        );
        let jc = self.jc + o.jc + self.m * (self.c - c).hypot2() + o.m * (o.c - c).hypot2();
        Moments { m, c, jc }
    }

    /// The first moment `m (c - h)` and the second moment about `h`.
    pub(crate) fn about(&self, h: Point) -> (Vec2, f64) {
        let d = self.c - h;
        (d * self.m, self.jc + self.m * d.hypot2())
    }

    /// The same bodies moved by a rotation of `angle` about the origin, then a shift `by`.
    #[cfg(test)]
    pub(crate) fn moved(&self, angle: f64, by: Vec2) -> Moments {
        let (s, co) = angle.sin_cos();
        let c = Point::new(
            co * self.c.x - s * self.c.y + by.x,
            s * self.c.x + co * self.c.y + by.y,
        );
        Moments { c, ..*self }
    }
}

/// The two sides of a joint about its hinge, in the frame of the tile before it at angle 0:
/// what [`TwoBody::at`] needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TwoBody {
    /// `J_A - |s_A|^2 / m`.
    a: f64,
    /// `J_B - |s_B|^2 / m`.
    b: f64,
    /// `|s_A| |s_B| / m`.
    k: f64,
    /// The angle from `s_A` to `s_B` at `phi = 0`.
    delta: f64,
}

impl TwoBody {
    /// The pair of sides `a` and `b` (moments in one frame) turning about `hinge`.
    #[cfg(test)]
    pub(crate) fn new(a: &Moments, b: &Moments, hinge: Point) -> TwoBody {
        let (sa, ja) = a.about(hinge);
        let (sb, jb) = b.about(hinge);
        TwoBody::of((a.m, sa, ja), (b.m, sb, jb))
    }

    /// The pair of sides given by mass, first moment and second moment about the hinge,
    /// both in the frame of the tile before the joint at angle 0.
    pub(crate) fn of((ma, sa, ja): (f64, Vec2, f64), (mb, sb, jb): (f64, Vec2, f64)) -> TwoBody {
        let m = ma + mb;
        if m <= 0.0 {
            return TwoBody {
                a: ja,
                b: jb,
                k: 0.0,
                delta: 0.0,
            };
        }
        TwoBody {
            a: ja - sa.hypot2() / m,
            b: jb - sb.hypot2() / m,
            k: sa.hypot() * sb.hypot() / m,
            delta: sb.y.atan2(sb.x) - sa.y.atan2(sa.x),
        }
    }

    /// The coefficient's bits, for a cache key.
    pub(crate) fn bits(&self) -> [u64; 4] {
        [
            self.a.to_bits(),
            self.b.to_bits(),
            self.k.to_bits(),
            self.delta.to_bits(),
        ]
    }

    /// Side A's angular velocity per unit rate of the joint's angle at `phi`, with no net
    /// angular momentum (or drag torque): `-(b + c) / (a + b + 2c)`. Near -1 when side A is
    /// the lighter (it turns, the other barely), near 0 when it is the heavier.
    pub(crate) fn common_turn(&self, phi: f64) -> f64 {
        let c = -self.k * (phi + self.delta).cos();
        let den = self.a + self.b + 2.0 * c;
        if den <= 0.0 {
            return -0.5;
        }
        -(self.b + c) / den
    }

    /// The effective coefficient of the joint's angle at `phi` (radians, the sign of the
    /// turn) and its derivative by `phi`.
    pub(crate) fn at(&self, phi: f64) -> (f64, f64) {
        let (s, co) = (phi + self.delta).sin_cos();
        let c = -self.k * co;
        let den = self.a + self.b + 2.0 * c;
        if den <= 0.0 {
            return (0.0, 0.0);
        }
        let value = (self.a * self.b - c * c) / den;
        // dI/dc = -2 (c + a)(c + b) / den^2, dc/dphi = k sin(phi + delta)
        let slope = -2.0 * (c + self.a) * (c + self.b) / (den * den) * (self.k * s);
        (value, slope)
    }
}

/// A folding joint's two sides: their inertia and their water drag about its hinge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sides {
    /// The mass moments (magnets, the RI and the tiles).
    pub(crate) inertia: TwoBody,
    /// The drag moments (the tiles' water film).
    pub(crate) drag: TwoBody,
    /// The first mass moments about the hinge (for the hinge's own motion).
    pub(crate) mass_first: FirstMoments,
    /// The first drag moments about the hinge.
    pub(crate) drag_first: FirstMoments,
}

/// Both sides' total and first moments about the hinge, in the frame of the tile before the
/// joint at angle 0 (side B straight, before it turns).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FirstMoments {
    /// The two sides' total (mass, kg, or drag, N s/m).
    pub(crate) total: f64,
    /// Side A's first moment about the hinge.
    pub(crate) a: Vec2,
    /// Side B's first moment about the hinge at angle 0.
    pub(crate) b: Vec2,
    /// Side B's second moment about the hinge (kg m^2, or N m s).
    pub(crate) jb: f64,
    /// Side B's total (kg, or N s/m).
    pub(crate) mb: f64,
}

impl Sides {
    /// The velocity field of a turn at unit rate (1 rad/s of the joint's angle, at angle
    /// `phi`) with no net momentum (`inertial`: the mass weights; else the drag weights, the
    /// overdamped pair's force-free motion): side A's angular velocity, side B's, and the
    /// hinge's velocity (m/s), in the frame of the tile before the joint.
    pub(crate) fn unit_turn(&self, phi: f64, inertial: bool) -> (f64, f64, Vec2) {
        let (two, first) = if inertial {
            (&self.inertia, &self.mass_first)
        } else {
            (&self.drag, &self.drag_first)
        };
        let omega_a = two.common_turn(phi);
        let omega_b = omega_a + 1.0;
        let (s, c) = phi.sin_cos();
        let sb = Vec2::new(c * first.b.x - s * first.b.y, s * first.b.x + c * first.b.y);
        let perp = |v: Vec2| Vec2::new(-v.y, v.x);
        let hinge = if first.total > 0.0 {
            -(perp(first.a) * omega_a + perp(sb) * omega_b) / first.total
        } else {
            Vec2::ZERO
        };
        (omega_a, omega_b, hinge)
    }
}

/// Each joint's sides (`None` for a joint that does not fold), for the chain of `geometry`
/// whose folding joints turn by `signs` (+1 left, -1 right, 0 rigid). O(tiles).
pub(crate) fn joint_sides(geometry: &Geometry, signs: &[f64]) -> Vec<Option<Sides>> {
    let tiles = geometry.tiles();
    let joints = tiles.saturating_sub(1);
    let mm = 1e-3;
    let oct = Octagon::new(geometry.w);
    let body = |t: usize| TileBody::of(geometry.design(t));
    let magnet_mass = |k: usize| geometry.design(k / 2).magnet_mass * 1e-3;
    // side B: the tiles after each joint, straight, magnets at rest, in the straight frame
    // (tile t's centre at (t w, 0)); suffix sums from the chain's end
    let mut after_mass = vec![Moments::default(); tiles + 1];
    let mut after_drag = vec![Moments::default(); tiles + 1];
    for t in (0..tiles).rev() {
        let b = body(t);
        let centre = Point::new(t as f64 * geometry.w * mm, 0.0);
        let mut mass = Moments::body(b.mass, centre, b.inertia);
        for k in [2 * t, 2 * t + 1] {
            let (x, y) = geometry.path(k).rest();
            mass = mass.add(Moments::body(
                magnet_mass(k),
                Point::new(centre.x + x * mm, y * mm),
                0.0,
            ));
        }
        after_mass[t] = mass.add(after_mass[t + 1]);
        after_drag[t] = Moments::body(b.drag, centre, b.rotational_drag).add(after_drag[t + 1]);
    }
    // side A: the tiles up to each joint, every fold before it made, magnets at their rest
    // points (riding with their tile, as in the free body), the RI with tile 0; prefix sums
    // in the world frame of the folded chain
    let angles: Vec<f64> = signs.iter().map(|s| s * FRAC_PI_2).collect();
    let ri = geometry.ri();
    let mut before_mass = Moments::body(
        geometry.design(0).magnet_mass * 1e-3,
        Point::new(ri.position.x * mm, ri.position.y * mm),
        0.0,
    );
    let mut before_drag = Moments::default();
    let mut out = vec![None; joints];
    let mut t = 0;
    crate::kinematics::for_each_pose_at_angles(&angles, geometry.w, |pose| {
        let b = body(t);
        let at = |p: (f64, f64)| {
            let (x, y) = pose.transform_point(p);
            Point::new(x * mm, y * mm)
        };
        let mut mass = Moments::body(b.mass, at((0.0, 0.0)), b.inertia);
        for k in [2 * t, 2 * t + 1] {
            mass = mass.add(Moments::body(
                magnet_mass(k),
                at(geometry.path(k).rest()),
                0.0,
            ));
        }
        before_mass = before_mass.add(mass);
        before_drag = before_drag.add(Moments::body(b.drag, at((0.0, 0.0)), b.rotational_drag));
        if t < joints && signs[t] != 0.0 {
            let h = oct.hinge(signs[t] > 0.0);
            // side A about the hinge, turned into tile t's frame
            let hinge = at(h);
            let turn = |(s, j): (Vec2, f64)| {
                let (sn, cs) = (-pose.angle).sin_cos();
                (Vec2::new(cs * s.x - sn * s.y, sn * s.x + cs * s.y), j)
            };
            let (sa, ja) = turn(before_mass.about(hinge));
            let (da, ga) = turn(before_drag.about(hinge));
            // side B about the hinge in the straight frame, where tile t's frame is shifted
            let hinge_b = Point::new((t as f64 * geometry.w + h.0) * mm, h.1 * mm);
            let (sb, jb) = after_mass[t + 1].about(hinge_b);
            let (db, gb) = after_drag[t + 1].about(hinge_b);
            out[t] = Some(Sides {
                inertia: TwoBody::of((before_mass.m, sa, ja), (after_mass[t + 1].m, sb, jb)),
                drag: TwoBody::of((before_drag.m, da, ga), (after_drag[t + 1].m, db, gb)),
                mass_first: FirstMoments {
                    total: before_mass.m + after_mass[t + 1].m,
                    a: sa,
                    b: sb,
                    jb,
                    mb: after_mass[t + 1].m,
                },
                drag_first: FirstMoments {
                    total: before_drag.m + after_drag[t + 1].m,
                    a: da,
                    b: db,
                    jb: gb,
                    mb: after_drag[t + 1].m,
                },
            });
        }
        t += 1;
    });
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::reference::free_body::tile_body::TileBodies;
    use crate::timeline::TileDesigns;
    use crate::Chain;

    /// Each joint's fold sign in `word`: +1 for L, -1 for R, 0 for S.
    fn fold_signs(word: &str) -> Vec<f64> {
        word.chars()
            .map(|c| match c {
                'L' => 1.0,
                'R' => -1.0,
                _ => 0.0,
            })
            .collect()
    }

    /// The free-body reference's two sides of joint `j` of `word` about its hinge, at the
    /// joint's angle `phi` (radians, the fold's sign), the folds before it made and the chain
    /// after it straight: each tile the free body's rigid body ([`TileBodies`]: plate, magnets
    /// riding with it, the RI on tile 0) at its pose. Returns `J_A`, `J_B` about the hinge and
    /// each side's `J - |s|^2 / m` (`m` both sides' mass) and the pair's inertia `I(phi)` with
    /// no net momentum, computed directly from the poses.
    fn free_body_sides(word: &str, j: usize, phi: f64) -> (f64, f64, f64, f64, f64) {
        let g =
            Geometry::from_designs(&Chain::parse(word).unwrap(), &TileDesigns::default()).unwrap();
        let bodies = TileBodies::new(&g, |t| g.design(t).magnet_mass * 1e-3);
        let signs = fold_signs(word);
        let angles: Vec<f64> = (0..signs.len())
            .map(|k| match k.cmp(&j) {
                std::cmp::Ordering::Less => signs[k] * FRAC_PI_2,
                std::cmp::Ordering::Equal => phi,
                std::cmp::Ordering::Greater => 0.0,
            })
            .collect();
        let poses = crate::kinematics::poses_at_angles(&angles, g.w);
        let mm = 1e-3;
        let (hx, hy) = poses[j].transform_point(Octagon::new(g.w).hinge(signs[j] > 0.0));
        let hinge = Point::new(hx * mm, hy * mm);
        let side = |range: std::ops::Range<usize>| {
            range.fold(Moments::default(), |acc, t| {
                let b = bodies.tiles[t];
                let local = (b.s[0] / b.m / mm, b.s[1] / b.m / mm);
                let (x, y) = poses[t].transform_point(local);
                let jc = b.j - (b.s[0] * b.s[0] + b.s[1] * b.s[1]) / b.m;
                acc.add(Moments::body(b.m, Point::new(x * mm, y * mm), jc))
            })
        };
        let (a, b) = (side(0..j + 1), side(j + 1..g.tiles()));
        let ((sa, ja), (sb, jb)) = (a.about(hinge), b.about(hinge));
        let m = a.m + b.m;
        let (aa, bb, c) = (ja - sa.hypot2() / m, jb - sb.hypot2() / m, -sa.dot(sb) / m);
        (ja, jb, aa, bb, (aa * bb - c * c) / (aa + bb + 2.0 * c))
    }

    #[test]
    fn joint_sides_weigh_the_sides_as_the_free_body_does() {
        // at rest and mid-fold, for a fold at the chain's first joint (L, LS: the RI's side is
        // one tile), further on (SSL, SLS) and after a made fold (LL's second joint)
        let mut worst: f64 = 0.0;
        for (word, j) in [
            ("L", 0),
            ("LS", 0),
            ("RS", 0),
            ("SSL", 2),
            ("SLS", 1),
            ("LL", 1),
        ] {
            let g = Geometry::from_designs(&Chain::parse(word).unwrap(), &TileDesigns::default())
                .unwrap();
            let signs = fold_signs(word);
            let sides = joint_sides(&g, &signs)[j].unwrap();
            for frac in [0.0, 0.5, 1.0] {
                let phi = signs[j] * frac * FRAC_PI_2;
                let (ja, jb, a, b, want) = free_body_sides(word, j, phi);
                let (got, _) = sides.inertia.at(phi);
                let two = sides.inertia;
                println!(
                    "{word} joint {j} at {frac} of the fold: free body J_A {ja:.4e} J_B {jb:.4e} \
                     a {a:.4e} b {b:.4e} I {want:.5e}; joint_sides a {:.4e} ({:+.2}%) b {:.4e} \
                     ({:+.2}%) I {got:.5e} ({:+.3}%)",
                    two.a,
                    100.0 * (two.a - a) / a,
                    two.b,
                    100.0 * (two.b - b) / b,
                    100.0 * (got - want) / want
                );
                worst = worst.max((got - want).abs() / want);
            }
        }
        assert!(worst < 1e-9, "worst {worst}");
    }

    /// A straight bar of `n` point masses `w` apart from `x0` along x, each with `ic`.
    fn bar(n: usize, x0: f64, w: f64, m: f64, ic: f64) -> Moments {
        (0..n).fold(Moments::default(), |acc, i| {
            acc.add(Moments::body(m, Point::new(x0 + i as f64 * w, 0.0), ic))
        })
    }

    #[test]
    fn two_equal_bars_hinged_at_their_ends() {
        // two thin bars of mass M and length L hinged end to end, free: by hand (zero
        // momentum, equal and opposite turns), I(phi) = M L^2 (5/48 - cos(phi)/16), from
        // M L^2 / 24 straight to 5 M L^2 / 48 at right angles
        let n = 2000;
        let (mass, len) = (1.0, 1.0);
        let (m, w) = (mass / n as f64, len / n as f64);
        let a = bar(n, -len + 0.5 * w, w, m, 0.0);
        let b = bar(n, 0.5 * w, w, m, 0.0);
        let pair = TwoBody::new(&a, &b, Point::ORIGIN);
        for phi in [0.0, 0.5, 1.0, std::f64::consts::FRAC_PI_2] {
            let want = mass * len * len * (5.0 / 48.0 - phi.cos() / 16.0);
            let (got, slope) = pair.at(phi);
            // the point bars' own inertia differs from a thin bar's by (w/L)^2
            assert!((got - want).abs() < 1e-6 * want, "{phi}: {got} {want}");
            let h = 1e-6;
            let fd = (pair.at(phi + h).0 - pair.at(phi - h).0) / (2.0 * h);
            assert!((slope - fd).abs() < 1e-6 * want, "{phi}: {slope} {fd}");
        }
    }

    #[test]
    fn a_short_head_turns_about_a_long_tail_at_its_own_inertia() {
        // a head of 3 tiles against tails of 10, 100 and 1000: the joint's inertia tends to the
        // head's own about the hinge (the tail barely turns), not the tail's
        let (m, w, ic) = (5e-3, 0.03, 4e-7);
        let head = bar(3, -2.5 * w, w, m, ic);
        let (_, j_head) = head.about(Point::ORIGIN);
        let mut last = 0.0;
        for n in [10, 100, 1000] {
            let tail = bar(n, 0.5 * w, w, m, ic);
            let (i, _) = TwoBody::new(&head, &tail, Point::ORIGIN).at(0.0);
            assert!(i < j_head && i > last, "{n}: {i} {j_head}");
            last = i;
        }
        // measured: 0.46, 0.92 and 0.991 of the head's second moment about the hinge
        assert!((last - j_head).abs() < 0.02 * j_head, "{last} {j_head}");
    }

    #[test]
    fn moments_add_by_the_parallel_axis_rule() {
        let a = Moments::body(2.0, Point::new(1.0, 0.0), 0.5);
        let b = Moments::body(1.0, Point::new(-2.0, 3.0), 0.25);
        let s = a.add(b);
        let (first, second) = s.about(Point::ORIGIN);
        assert!((first.x - 0.0).abs() < 1e-15 && (first.y - 3.0).abs() < 1e-15);
        assert!(
            (second - (0.5 + 2.0 + 0.25 + 13.0)).abs() < 1e-12,
            "{second}"
        );
        let moved = s.moved(std::f64::consts::FRAC_PI_2, Vec2::new(1.0, 0.0));
        let (_, j) = moved.about(Point::new(1.0, 0.0));
        assert!((j - second).abs() < 1e-12);
    }
}
