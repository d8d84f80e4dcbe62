//! The exact fit areas of a plan (issue 26): the area of the union of the tiles (regular
//! octagons) inside the shape, the area of that union outside it, and the shape's area, by
//! polygon boolean operations, not by sample points.
//!
//! Most tiles lie wholly inside the shape or wholly outside it and touch no other tile but
//! along a face: each adds a whole octagon's area to one side. Only the tiles that an edge
//! of the outline meets (tested against the octagon grown by [`TOUCH`]) and the tiles that
//! overlap another tile (by more than [`TOUCH`]: a plan that folds has none) are handed to
//! `i_overlay`, which unites them and intersects the union with the shape's filled area.
//! `i_overlay` computes on integers: coordinates are snapped to a grid of about 2^-29 of the
//! drawing's extent, so the areas are good to a few 1e-9 of the extent times the outline's
//! length, far below 1e-6 of the shape's area (as the tests check).

use std::f64::consts::{FRAC_1_SQRT_2, SQRT_2};

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::simplify::SimplifyShape;
use i_overlay::float::single::SingleFloatOverlay;
use kurbo::Point;
use rayon::prelude::*;

use crate::centre_grid::CentreGrid;
use crate::shape::Shape;

/// Tile widths by which a tile is grown when testing whether the outline meets it, and by
/// which two tiles must overlap to count as overlapping: touching faces are told from
/// crossings without trusting the last bits of a float, and what is handed to `i_overlay`
/// on this margin is computed exactly anyway.
const TOUCH: f64 = 1e-9;

/// The area of a tile of width 1: a regular octagon across flats 1, `2 (sqrt2 - 1)`.
pub(crate) const OCTAGON_AREA: f64 = 2.0 * (SQRT_2 - 1.0);

/// Half the side of the octagon of width 1: `1/sqrt2 - 1/2`.
const HALF_SIDE: f64 = FRAC_1_SQRT_2 - 0.5;

/// The outward face normals of the octagon (its faces are axis-aligned and diagonal at every
/// heading the chain takes, in the work frame); each face lies 1/2 from the centre.
const NORMALS: [(f64, f64); 8] = [
    (1.0, 0.0),
    (FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (0.0, 1.0),
    (-FRAC_1_SQRT_2, FRAC_1_SQRT_2),
    (-1.0, 0.0),
    (-FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
    (0.0, -1.0),
    (FRAC_1_SQRT_2, -FRAC_1_SQRT_2),
];

/// Areas in the work frame (tile width 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Areas {
    /// The shape's filled area.
    pub shape: f64,
    /// The area of the union of the tiles inside the shape.
    pub covered: f64,
    /// The area of the union of the tiles outside the shape.
    pub outside: f64,
    /// The area of the union of the tiles.
    pub tiles: f64,
}

/// The octagon of width 1 about `c`, counter-clockwise.
fn octagon(c: Point) -> Vec<[f64; 2]> {
    let (a, b) = (0.5, HALF_SIDE);
    [
        (a, -b),
        (a, b),
        (b, a),
        (-b, a),
        (-a, b),
        (-a, -b),
        (-b, -a),
        (b, -a),
    ]
    .iter()
    .map(|&(x, y)| [c.x + x, c.y + y])
    .collect()
}

/// The area of a polygon set as `i_overlay` returns it (each shape an outer contour and its
/// holes; the orientation does not matter here).
fn area_of(shapes: &Polygons) -> f64 {
    let ring = |c: &Vec<[f64; 2]>| {
        let n = c.len();
        (0..n)
            .map(|i| {
                let (p, q) = (c[i], c[(i + 1) % n]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            .abs()
            * 0.5
    };
    shapes
        .iter()
        .map(|s| {
            let mut it = s.iter();
            let outer = it.next().map_or(0.0, ring);
            outer - it.map(ring).sum::<f64>()
        })
        .sum()
}

/// Polygons as `i_overlay` returns them: each an outer contour and its holes.
type Polygons = Vec<Vec<Vec<[f64; 2]>>>;

/// The shape's filled area as simple polygons: each filled path made simple by its own fill
/// rule, then all united.
fn region(shape: &Shape) -> Polygons {
    let mut all: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut simple: Polygons = Vec::new();
    for p in shape.paths() {
        let contours: Vec<Vec<[f64; 2]>> = p
            .rings
            .iter()
            .map(|r| r.points.iter().map(|q| [q.x, q.y]).collect())
            .collect();
        let rule = if p.even_odd {
            FillRule::EvenOdd
        } else {
            FillRule::NonZero
        };
        simple = contours.simplify_shape(rule);
        all.extend(simple.iter().flatten().cloned());
    }
    if shape.paths().len() > 1 {
        // each simple path winds once around its area (holes the other way): non-zero is
        // their union
        simple = all.simplify_shape(FillRule::NonZero);
    }
    simple
}

/// The outline's edges bucketed by bands of height, for "which edges may meet this tile".
struct Bands {
    y0: f64,
    /// Band height (at least one tile width).
    h: f64,
    bands: Vec<Vec<(Point, Point)>>,
}

impl Bands {
    fn new(shape: &Shape) -> Bands {
        let b = shape.bbox();
        // at most 65,536 bands, each at least a tile high
        let h = (b.height() / 65_536.0).max(1.0);
        let n = (b.height() / h).floor() as usize + 1;
        let mut bands: Vec<Vec<(Point, Point)>> = vec![Vec::new(); n];
        for r in shape.rings() {
            for (p, q) in r.edges() {
                let i0 = ((p.y.min(q.y) - b.y0) / h).floor().max(0.0) as usize;
                let i1 = ((p.y.max(q.y) - b.y0) / h).floor().max(0.0) as usize;
                for band in &mut bands[i0.min(n - 1)..=i1.min(n - 1)] {
                    band.push((p, q));
                }
            }
        }
        Bands { y0: b.y0, h, bands }
    }

    /// True if an edge of the outline meets the octagon about `c` grown by [`TOUCH`].
    fn meets(&self, c: Point) -> bool {
        let r = 0.5 + TOUCH;
        let lo = ((c.y - r - self.y0) / self.h).floor();
        let hi = ((c.y + r - self.y0) / self.h).floor();
        if hi < 0.0 || lo >= self.bands.len() as f64 {
            return false;
        }
        let lo = lo.max(0.0) as usize;
        let hi = (hi as usize).min(self.bands.len() - 1);
        self.bands[lo..=hi].iter().flatten().any(|&(p, q)| {
            p.x.min(q.x) <= c.x + r
                && p.x.max(q.x) >= c.x - r
                && p.y.min(q.y) <= c.y + r
                && p.y.max(q.y) >= c.y - r
                && segment_meets_octagon(c, p, q, TOUCH)
        })
    }
}

/// True if the segment `p`-`q` meets the octagon of width 1 about `c` grown by `grow`
/// (Cyrus-Beck: the segment clipped by each face's half-plane in turn).
fn segment_meets_octagon(c: Point, p: Point, q: Point, grow: f64) -> bool {
    let (dx, dy) = (q.x - p.x, q.y - p.y);
    let (rx, ry) = (p.x - c.x, p.y - c.y);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (nx, ny) in NORMALS {
        // n . (r + t d) <= 1/2 + grow
        let room = 0.5 + grow - (nx * rx + ny * ry);
        let rate = nx * dx + ny * dy;
        if rate == 0.0 {
            if room < 0.0 {
                return false;
            }
        } else if rate > 0.0 {
            t1 = t1.min(room / rate);
        } else {
            t0 = t0.max(room / rate);
        }
        if t0 > t1 {
            return false;
        }
    }
    true
}

/// True if the octagons of width 1 about `a` and `b` overlap by more than [`TOUCH`] (their
/// centres lie inside the octagon of width 2 about each other, shrunk by it).
fn overlap(a: Point, b: Point) -> bool {
    let (dx, dy) = ((a.x - b.x).abs(), (a.y - b.y).abs());
    dx < 1.0 - TOUCH && dy < 1.0 - TOUCH && dx + dy < SQRT_2 - TOUCH
}

/// Where a tile lies.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Place {
    Inside,
    Outside,
    /// The outline meets it, or it overlaps another tile: measured by `i_overlay`.
    Measured,
}

/// The exact areas of tiles of width 1 centred at `centres` over `work` (both in the work
/// frame); see the module documentation.
pub(crate) fn areas(work: &Shape, centres: &[Point]) -> Areas {
    let region = region(work);
    let shape = area_of(&region);
    let bands = Bands::new(work);
    let grid = CentreGrid::new(centres);
    let places: Vec<Place> = centres
        .par_iter()
        .enumerate()
        .map(|(i, &c)| {
            let overlaps = grid.any_near(c, |t| t != i && overlap(c, centres[t]));
            if overlaps || bands.meets(c) {
                Place::Measured
            } else if work.contains(c) {
                Place::Inside
            } else {
                Place::Outside
            }
        })
        .collect();
    let count = |p: Place| places.iter().filter(|&&q| q == p).count() as f64;
    let (inside, outside) = (count(Place::Inside), count(Place::Outside));
    let measured: Vec<Vec<[f64; 2]>> = centres
        .iter()
        .zip(&places)
        .filter(|(_, &p)| p == Place::Measured)
        .map(|(&c, _)| octagon(c))
        .collect();
    let (union, within) = if measured.is_empty() {
        (0.0, 0.0)
    } else {
        let union = area_of(&measured.simplify_shape(FillRule::NonZero));
        let within = if region.is_empty() {
            0.0
        } else {
            area_of(&measured.overlay(&region, OverlayRule::Intersect, FillRule::NonZero))
        };
        (union, within.min(union))
    };
    Areas {
        shape,
        covered: inside * OCTAGON_AREA + within,
        outside: outside * OCTAGON_AREA + (union - within),
        tiles: (inside + outside) * OCTAGON_AREA + union,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::shape::Ring;

    /// The relative tolerance the areas are stated to (of the shape's area): see the
    /// module documentation.
    const TOLERANCE: f64 = 1e-6;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Shape {
        Shape::from_rings(vec![Ring::rect(x0, y0, x1, y1)])
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= TOLERANCE * b.abs().max(1.0)
    }

    /// A tight row of n touching tiles exactly filling a strip one tile high: the union
    /// inside is n octagons, nothing outside, whatever n (every tile touches the outline).
    #[test]
    fn a_row_that_fills_a_strip() {
        for n in [1usize, 2, 7, 40] {
            let strip = rect(-0.5, -0.5, n as f64 - 0.5, 0.5);
            let centres: Vec<Point> = (0..n).map(|i| Point::new(i as f64, 0.0)).collect();
            let a = areas(&strip, &centres);
            assert!(close(a.shape, n as f64), "{a:?}");
            assert!(close(a.covered, n as f64 * OCTAGON_AREA), "{n}: {a:?}");
            assert!(a.outside.abs() < TOLERANCE, "{n}: {a:?}");
            assert!(close(a.tiles, n as f64 * OCTAGON_AREA), "{n}: {a:?}");
        }
    }

    /// A row of tiles through the middle of a taller rectangle that cuts the end tiles in
    /// half: inside, n - 1 octagons (two halves), outside two halves; most tiles are
    /// counted whole (they touch no edge).
    #[test]
    fn a_row_cut_at_both_ends() {
        let n = 12;
        let r = rect(0.0, -2.0, (n - 1) as f64, 2.0);
        let centres: Vec<Point> = (0..n).map(|i| Point::new(i as f64, 0.0)).collect();
        let a = areas(&r, &centres);
        assert!(close(a.shape, 4.0 * (n - 1) as f64));
        assert!(close(a.covered, (n - 1) as f64 * OCTAGON_AREA), "{a:?}");
        assert!(close(a.outside, OCTAGON_AREA), "{a:?}");
        assert!(close(a.tiles, n as f64 * OCTAGON_AREA), "{a:?}");
    }

    /// Tight rows sqrt2 apart, filling a band from the first row's lower face to the last
    /// row's upper face: k rows of n tiles cover k n octagons of an area n ((k - 1) sqrt2 +
    /// 1); over an infinite field (k large) that tends to 2 - sqrt2 = 0.586, and a band that
    /// ends flush on the tiles' faces covers more.
    #[test]
    fn tight_rows_flush_in_a_rectangle() {
        let (n, k) = (10usize, 5usize);
        let height = (k - 1) as f64 * SQRT_2 + 1.0;
        let r = rect(-0.5, -0.5, n as f64 - 0.5, height - 0.5);
        let centres: Vec<Point> = (0..k)
            .flat_map(|j| (0..n).map(move |i| Point::new(i as f64, j as f64 * SQRT_2)))
            .collect();
        let a = areas(&r, &centres);
        let expect = (n * k) as f64 * OCTAGON_AREA / (n as f64 * height);
        assert!(close(a.covered / a.shape, expect), "{a:?} vs {expect}");
        assert!(a.covered / a.shape > 2.0 - SQRT_2);
    }

    /// Overlapping tiles count once in the union; a tile outside counts outside.
    #[test]
    fn overlaps_count_once() {
        let r = rect(-5.0, -5.0, 5.0, 5.0);
        let centres = vec![
            Point::new(0.0, 0.0),
            Point::new(0.0, 0.0),
            Point::new(0.5, 0.0),
            Point::new(9.0, 9.0),
        ];
        let a = areas(&r, &centres);
        // the union of the three inside (two of them the same octagon), by a fine grid
        let fine = sampled_union(&centres[..3], 0.5, 2000);
        assert!((a.covered - fine).abs() < 2e-3, "{a:?} vs {fine}");
        assert!(close(a.outside, OCTAGON_AREA), "{a:?}");
        assert!(close(a.tiles, a.covered + OCTAGON_AREA), "{a:?}");
    }

    /// The union of octagons (all inside the test's box) by a fine grid: a check on the
    /// exact measure, good to about the perimeter times the spacing.
    fn sampled_union(centres: &[Point], reach: f64, per_unit: usize) -> f64 {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for c in centres {
            (x0, y0, x1, y1) = (x0.min(c.x), y0.min(c.y), x1.max(c.x), y1.max(c.y));
        }
        let step = 1.0 / per_unit as f64;
        let (x0, y0) = (x0 - reach, y0 - reach);
        let (nx, ny) = (
            ((x1 + reach - x0) / step) as usize,
            ((y1 + reach - y0) / step) as usize,
        );
        let mut hits = 0usize;
        for j in 0..ny {
            let y = y0 + (j as f64 + 0.5) * step;
            for i in 0..nx {
                let x = x0 + (i as f64 + 0.5) * step;
                if centres.iter().any(|c| {
                    let (dx, dy) = ((x - c.x).abs(), (y - c.y).abs());
                    dx <= 0.5 && dy <= 0.5 && dx + dy <= FRAC_1_SQRT_2
                }) {
                    hits += 1;
                }
            }
        }
        hits as f64 * step * step
    }

    /// Tiles over a round shape with a hole at an odd angle: the exact areas agree with a
    /// fine sampling of the same union, inside and outside.
    #[test]
    fn agrees_with_fine_sampling_on_a_ring() {
        let circle = |r: f64, ccw: bool| {
            let mut points: Vec<Point> = (0..90)
                .map(|i| {
                    let t = i as f64 * std::f64::consts::TAU / 90.0;
                    Point::new(r * t.cos() + 0.3, r * t.sin() - 0.2)
                })
                .collect();
            if !ccw {
                points.reverse();
            }
            Ring { points }
        };
        let shape = Shape::from_rings(vec![circle(6.0, true), circle(2.5, false)]);
        let centres: Vec<Point> = (-7..=7)
            .flat_map(|j| (-7..=7).map(move |i| Point::new(i as f64, j as f64 * SQRT_2)))
            .filter(|c| c.x.hypot(c.y) < 7.0)
            .collect();
        let a = areas(&shape, &centres);
        // the sampled part: points inside the octagons and inside (or outside) the shape
        let step = 1.0 / 200.0;
        let (mut inside, mut outside) = (0usize, 0usize);
        for c in &centres {
            for j in 0..200 {
                for i in 0..200 {
                    let (dx, dy) = (
                        -0.5 + (i as f64 + 0.5) * step,
                        -0.5 + (j as f64 + 0.5) * step,
                    );
                    if dx.abs() + dy.abs() > FRAC_1_SQRT_2 {
                        continue;
                    }
                    if shape.contains(Point::new(c.x + dx, c.y + dy)) {
                        inside += 1;
                    } else {
                        outside += 1;
                    }
                }
            }
        }
        let (si, so) = (inside as f64 * step * step, outside as f64 * step * step);
        let tiles = centres.len() as f64 * OCTAGON_AREA;
        assert!((a.covered - si).abs() < 1e-3 * tiles, "{a:?} vs {si}");
        assert!((a.outside - so).abs() < 1e-3 * tiles, "{a:?} vs {so}");
        assert!(close(a.tiles, tiles), "{a:?}");
        assert!(close(a.shape, shape.area()), "{a:?} vs {}", shape.area());
    }

    #[test]
    fn a_segment_along_a_face_meets_it_and_one_beyond_does_not() {
        let c = Point::new(0.0, 0.0);
        let p = |x, y| Point::new(x, y);
        assert!(segment_meets_octagon(c, p(0.5, -3.0), p(0.5, 3.0), TOUCH));
        assert!(!segment_meets_octagon(
            c,
            p(0.51, -3.0),
            p(0.51, 3.0),
            TOUCH
        ));
        // past the diagonal face: x + y = 1/sqrt2 + 0.01
        let d = FRAC_1_SQRT_2 + 0.01;
        assert!(!segment_meets_octagon(c, p(d, 0.0), p(0.0, d), TOUCH));
        assert!(segment_meets_octagon(c, p(-2.0, 0.1), p(2.0, 0.1), TOUCH));
        // wholly inside
        assert!(segment_meets_octagon(c, p(-0.1, 0.0), p(0.1, 0.0), TOUCH));
    }

    /// Several filled paths that touch along edges (a key's head, shaft and tooth, as
    /// separate elements): the region's area is their union's, in the frames the planner
    /// measures in (turned, mirrored, scaled), where the touching paths may come out as
    /// separate polygons.
    #[test]
    fn touching_paths_are_united_in_every_frame() {
        let path = |r: Ring, even_odd: bool| crate::shape::FilledPath {
            rings: vec![r],
            even_odd,
        };
        let key = Shape::from_paths(vec![
            path(Ring::rect(0.0, 0.0, 100.0, 120.0), false),
            path(Ring::rect(100.0, 48.0, 270.0, 72.0), true),
            path(Ring::rect(205.0, 72.0, 223.0, 94.0), false),
        ]);
        let union = 12_000.0 + 4_080.0 + 396.0;
        for (s, k) in [
            (key.clone(), 1.0),
            (key.rotated(0.3).scaled(1.0 / 8.3), 1.0 / 8.3),
            (key.mirrored(-1.0, 1.0).scaled(1.0 / 8.3), 1.0 / 8.3),
            (
                key.rotated(std::f64::consts::FRAC_PI_2)
                    .mirrored(1.0, -1.0)
                    .scaled(0.01),
                0.01,
            ),
        ] {
            let a = areas(&s, &[]);
            assert!(
                close(a.shape, union * k * k),
                "{} vs {}",
                a.shape,
                union * k * k
            );
        }
    }
}
