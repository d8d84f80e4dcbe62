//! The chain at rest, in the straight frame: every magnet's path, and the two geometric
//! questions the engine asks of it. Where on a moving magnet's path does the next magnet
//! become equidistant from its two neighbours (and so start)? Does an inter-tile pair close
//! or diverge?
//!
//! Magnet `k` is magnet `k mod 2` of tile `k / 2` (0 = the first path, facing the reaction
//! initiator). Even magnets move towards magnet `k - 1` (magnet 0 towards the RI), odd ones
//! towards `k + 1`: joint `j` is closed by the pair `(2j + 1, 2j + 2)`. The RI is held on the
//! chain axis at the outer edge of tile 0 (`x = -d`), as in inequality (6.2).
//!
//! Magnet `m` starts when it is as far from magnet `m - 1` as from magnet `m + 1`, both at
//! their rest points except `m - 1`, which is moving. On a straight path that is `4s` along
//! (thesis 6.2); the engine finds the point on the real curve, so `4s`, `s = e/3` and the
//! curved-path limit all come out of the same root search.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use crate::magnet_path::{MagnetPath, PathEnd, PathError};
use crate::{Chain, Design, PathKind};

/// Lengths closer than this many tile widths count as equal: 1e-9 w (30 pm on 30 mm tiles).
/// Far above the rounding of the rest points and `s = e/3` given as a fraction (about 1e-15
/// relative) and far below anything physical, so the sequential edge `s = e/3` triggers at
/// the path end rather than stalling on a rounding error.
pub const LENGTH_TOLERANCE: f64 = 1e-9;

/// Samples per path in the search for the first sign change before bisection. Paths are a
/// line and one arc, so the distance function has at most one extremum: 256 samples cannot
/// step over a crossing and back.
const SCAN_STEPS: usize = 256;

/// A small multiply-rotate hasher for the engine's caches, whose keys are a few small
/// integers: SipHash's protection against hostile keys buys nothing here and costs a third
/// of the engine's time on a million tiles.
#[derive(Default, Clone, Copy)]
pub(crate) struct FastHasher(u64);

impl Hasher for FastHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    fn write_u32(&mut self, x: u32) {
        self.write_u64(x as u64);
    }
    fn write_u8(&mut self, x: u8) {
        self.write_u64(x as u64);
    }
    fn write_usize(&mut self, x: usize) {
        self.write_u64(x as u64);
    }
}

/// A hash map with [`FastHasher`].
pub(crate) type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// Where a moving magnet starts its successor, or why it does not.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Trigger {
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

/// The resting chain's geometry, with per-design caches.
#[derive(Debug)]
pub struct Geometry {
    /// Tile width, mm.
    pub w: f64,
    /// Half tile length, mm.
    pub d: f64,
    designs: Vec<Design>,
    tile_design: Vec<u32>,
    paths: Vec<MagnetPath>,
    path_index: FastMap<(PathKind, bool, u32), u32>,
    path_of: Vec<u32>,
    trigger_cache: FastMap<(bool, u32, u32, u32), Trigger>,
    tiles: Vec<crate::Tile>,
}

impl Geometry {
    /// The geometry of `chain` with per-tile designs `designs` (index per tile, empty when all
    /// tiles use `designs[0]`).
    pub fn new(
        chain: &Chain,
        designs: Vec<Design>,
        tile_design: Vec<u32>,
    ) -> Result<Geometry, PathError> {
        let d0 = designs[0];
        let mut g = Geometry {
            w: d0.tile_width,
            d: d0.d,
            designs,
            tile_design,
            paths: Vec::new(),
            path_index: FastMap::default(),
            path_of: Vec::with_capacity(2 * chain.len()),
            trigger_cache: FastMap::default(),
            tiles: chain.tiles().to_vec(),
        };
        // Build every path kind used, up front, so later look-ups cannot fail.
        for t in 0..g.tiles.len() {
            for second in [false, true] {
                let id = g.ensure_path(t, second)?;
                g.path_of.push(id);
            }
        }
        Ok(g)
    }

    fn ensure_path(&mut self, tile: usize, second: bool) -> Result<u32, PathError> {
        let di = self.design_index(tile);
        let kind = if second {
            self.tiles[tile].second
        } else {
            self.tiles[tile].first
        };
        let key = (kind, second, di);
        if let Some(&i) = self.path_index.get(&key) {
            return Ok(i);
        }
        let end = if second {
            PathEnd::Second
        } else {
            PathEnd::First
        };
        let p = MagnetPath::new(kind, end, &self.designs[di as usize])?;
        self.paths.push(p);
        let i = (self.paths.len() - 1) as u32;
        self.path_index.insert(key, i);
        Ok(i)
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.tiles.len()
    }

    /// Number of magnets (two per tile).
    pub fn magnets(&self) -> usize {
        2 * self.tiles.len()
    }

    /// The tiles.
    pub fn chain_tiles(&self) -> &[crate::Tile] {
        &self.tiles
    }

    /// The design index of a tile.
    pub fn design_index(&self, tile: usize) -> u32 {
        self.tile_design.get(tile).copied().unwrap_or(0)
    }

    /// The design of a tile.
    pub fn design(&self, tile: usize) -> &Design {
        &self.designs[self.design_index(tile) as usize]
    }

    /// The index of magnet `k`'s path in [`Geometry::path_table`].
    pub fn path_id(&self, k: usize) -> u32 {
        self.path_of[k]
    }

    /// Every distinct path.
    pub fn path_table(&self) -> &[MagnetPath] {
        &self.paths
    }

    /// Magnet `k`'s path (tile frame).
    pub fn path(&self, k: usize) -> &MagnetPath {
        &self.paths[self.path_id(k) as usize]
    }

    /// Magnet `k`'s rest point in the frame of tile `frame_tile` (straight chain).
    fn rest_in(&self, k: usize, frame_tile: usize) -> (f64, f64) {
        let (x, y) = self.path(k).rest();
        (x + (k / 2) as f64 * self.w - frame_tile as f64 * self.w, y)
    }

    /// Magnet `k`'s path end in the frame of tile `frame_tile` (straight chain).
    fn end_in(&self, k: usize, frame_tile: usize) -> (f64, f64) {
        let (x, y) = self.path(k).end_point();
        (x + (k / 2) as f64 * self.w - frame_tile as f64 * self.w, y)
    }

    /// The RI's position in tile 0's frame.
    pub fn ri_position(&self) -> (f64, f64) {
        (-self.d, 0.0)
    }

    /// Whether the RI at the tile edge is nearer magnet 0 than magnet 1 is (6.2): then
    /// magnet 0 starts on contact. Returns the two distances (RI, partner).
    pub fn ri_starts_first_magnet(&self) -> (bool, f64, f64) {
        let r0 = self.rest_in(0, 0);
        let ri = dist(self.ri_position(), r0);
        let partner = dist(self.rest_in(1, 0), r0);
        (ri < partner - LENGTH_TOLERANCE * self.w, ri, partner)
    }

    /// The distance between the final points of magnet `k` and the one it heads for, in
    /// the final shape (a folding pair measured after its fold: `2c`, as a straight pair):
    /// used by the speed law.
    pub fn end_gap(&self, k: usize) -> f64 {
        if k == 0 {
            return dist(self.end_in(0, 0), self.ri_position());
        }
        let (a, b) = if k % 2 == 1 { (k, k + 1) } else { (k - 1, k) };
        if b >= self.magnets() {
            return 0.0;
        }
        let j = a / 2;
        let pa = self.path(a).end_point();
        let pb = self.path(b).end_point();
        let angle = match (self.tiles[j].second, self.tiles[j + 1].first) {
            (PathKind::L, PathKind::L) => std::f64::consts::FRAC_PI_2,
            (PathKind::R, PathKind::R) => -std::f64::consts::FRAC_PI_2,
            _ => 0.0,
        };
        let pb = crate::kinematics::joint_transform(angle, self.w).transform_point(pb);
        dist(pa, pb)
    }

    /// Whether the pair closing joint `j` diverges: its path ends lie farther apart than its
    /// magnets at rest, so their attraction cannot draw them along their paths. This is the
    /// geometric form of Table 7.1's "propagation inhibited" (LR and RL pairs). Returns
    /// `(diverges, end distance, rest distance)`.
    pub fn pair_diverges(&self, j: usize) -> (bool, f64, f64) {
        let (a, b) = (2 * j + 1, 2 * j + 2);
        let end = dist(self.end_in(a, j), self.end_in(b, j));
        let rest = dist(self.rest_in(a, j), self.rest_in(b, j));
        (end > rest + LENGTH_TOLERANCE * self.w, end, rest)
    }

    /// Where on magnet `m - 1`'s path magnet `m` starts (`1 <= m <= magnets - 2`).
    pub fn trigger(&mut self, m: usize) -> Trigger {
        let key = (
            m % 2 == 1,
            self.path_id(m - 1),
            self.design_index(m / 2),
            self.design_index(m.div_ceil(2)),
        );
        if let Some(&t) = self.trigger_cache.get(&key) {
            return t;
        }
        let t = self.find_trigger(m);
        self.trigger_cache.insert(key, t);
        t
    }

    fn find_trigger(&self, m: usize) -> Trigger {
        let frame = (m - 1) / 2;
        let mover = *self.path(m - 1);
        let rm = self.rest_in(m, frame);
        let target = dist(self.rest_in(m + 1, frame), rm);
        let offset = ((m - 1) / 2) as f64 * self.w - frame as f64 * self.w;
        let g = |u: f64| {
            let (x, y) = mover.point_at(u);
            dist((x + offset, y), rm) - target
        };
        let tol = LENGTH_TOLERANCE * self.w;
        let len = mover.length();
        let g0 = g(0.0);
        if g0.abs() <= tol {
            return Trigger::At(0.0);
        }
        let sign0 = g0.signum();
        let mut best = (0.0, g0.abs());
        let mut prev = 0.0;
        for i in 1..=SCAN_STEPS {
            let u = len * i as f64 / SCAN_STEPS as f64;
            let v = g(u);
            if v.signum() != sign0 {
                // a true crossing in [prev, u]: bisect on the sign alone
                let (mut lo, mut hi) = (prev, u);
                for _ in 0..80 {
                    let mid = 0.5 * (lo + hi);
                    if g(mid).signum() == sign0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                // the sequential edge (s = e/3): a crossing within rounding of the path end
                // is at the end, so the next magnet starts exactly as this one arrives
                return Trigger::At(if len - hi <= tol { len } else { hi });
            }
            if v.abs() < best.1 {
                best = (u, v.abs());
            }
            prev = u;
        }
        // no crossing: the sequential edge (s = e/3) meets the trigger at the path end
        if g(len).abs() <= tol {
            return Trigger::At(len);
        }
        // refine the nearest approach (golden-section on the bracket around the best sample)
        let step = len / SCAN_STEPS as f64;
        let (mut lo, mut hi) = ((best.0 - step).max(0.0), (best.0 + step).min(len));
        for _ in 0..100 {
            let m1 = lo + (hi - lo) * 0.382;
            let m2 = lo + (hi - lo) * 0.618;
            if g(m1).abs() < g(m2).abs() {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        let u = 0.5 * (lo + hi);
        let shortfall = g(u).abs();
        let before_end = u < len - tol;
        Trigger::Never {
            u: if before_end { u } else { len },
            shortfall,
            before_end,
        }
    }
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::JointOutcome;

    fn geometry(chain: &str, design: Design) -> Geometry {
        Geometry::new(&Chain::parse(chain).unwrap(), vec![design], Vec::new()).unwrap()
    }

    #[test]
    fn straight_trigger_is_four_s() {
        for s in [0.0, 0.1, 0.3, 1.0, 4.7 / 3.0] {
            let mut g = geometry("SSSS", Design::thesis().with_s(s));
            for m in 1..=8 {
                match g.trigger(m) {
                    Trigger::At(u) => assert!((u - 4.0 * s).abs() < 1e-9, "s {s} m {m}: {u}"),
                    t => panic!("s {s} m {m}: {t:?}"),
                }
            }
        }
        let mut g = geometry("SSSS", Design::thesis().with_s(1.7));
        assert!(matches!(
            g.trigger(1),
            Trigger::Never {
                before_end: false,
                ..
            }
        ));
    }

    #[test]
    fn pair_divergence_is_table_7_1() {
        for a in PathKind::ALL {
            for b in PathKind::ALL {
                let chain = Chain::from_tiles(vec![
                    crate::Tile::new(PathKind::S, a),
                    crate::Tile::new(b, PathKind::S),
                ])
                .unwrap();
                let g = Geometry::new(&chain, vec![Design::thesis()], Vec::new()).unwrap();
                let (diverges, end, rest) = g.pair_diverges(0);
                let table = JointOutcome::from_paths(a, b) == JointOutcome::Inhibited;
                assert_eq!(diverges, table, "{a}{b}: ends {end} rest {rest}");
            }
        }
    }

    #[test]
    fn curved_trigger_comes_before_closest_approach() {
        // thesis design: a curved path starts the next magnet; a larger s (still < e/3)
        // does not, because the curve turns away first.
        let mut g = geometry("SLS", Design::thesis());
        let m = 4; // magnet 3, on tile 1 second path (L), starts magnet 4
        assert!(matches!(g.trigger(m), Trigger::At(_)), "{:?}", g.trigger(m));
        let mut g = geometry("SLS", Design::thesis().with_s(0.5));
        match g.trigger(m) {
            Trigger::Never { before_end, .. } => assert!(before_end),
            t => panic!("{t:?}"),
        }
    }
}
