//! The chain at rest, in the straight frame, that both simulations move: every magnet's path
//! under the per-tile designs, the rest and end points, the reaction initiator, and whether
//! an inter-tile pair closes or diverges.
//!
//! Magnet `k` is magnet `k mod 2` of tile `k / 2` (0 = the first path, facing the reaction
//! initiator). Even magnets move towards magnet `k - 1` (magnet 0 towards the RI), odd ones
//! towards `k + 1`: joint `j` is closed by the pair `(2j + 1, 2j + 2)`. The RI is held on the
//! chain axis at the outer edge of tile 0 (`x = -d`, [`crate::physics::ReactionInitiator`]).

use kurbo::Point;
use rustc_hash::FxHashMap;

use crate::magnet_path::{MagnetPath, PathEnd, PathError};
use crate::physics::ReactionInitiator;
use crate::timeline::{DesignsError, TileDesigns};
use crate::{Chain, Design, Fold, PathKind, Tile};

/// Lengths closer than this many tile widths count as equal: 1e-9 w (30 pm on 30 mm tiles).
/// Far above the rounding of the rest points and `s = e/3` given as a fraction (about 1e-15
/// relative) and far below anything physical, so the sequential edge `s = e/3` triggers at
/// the path end rather than stalling on a rounding error.
pub(crate) const LENGTH_TOLERANCE: f64 = 1e-9;

/// Why the geometry of a chain cannot be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub(crate) enum GeometryError {
    /// A design parameter out of range.
    #[error("design: {0}")]
    Design(#[from] DesignsError),
    /// A curved path that cannot be built.
    #[error("{0}")]
    Path(#[from] PathError),
}

/// The resting chain's geometry: one path per distinct (kind, end, design).
#[derive(Clone, Debug)]
pub struct Geometry {
    /// Tile width, mm.
    pub w: f64,
    /// Half tile length, mm.
    pub d: f64,
    designs: Vec<Design>,
    tile_design: Vec<u32>,
    paths: Vec<MagnetPath>,
    path_of: Vec<u32>,
    tiles: Vec<Tile>,
}

impl Geometry {
    /// The geometry of `chain` with `designs`, checked (`design` names them in errors).
    pub(crate) fn from_designs(
        chain: &Chain,
        designs: &TileDesigns,
    ) -> Result<Geometry, GeometryError> {
        designs.validate("design")?;
        let (list, per_tile) = designs.resolve(chain.len());
        Ok(Geometry::new(chain, list, per_tile)?)
    }

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
            path_of: Vec::with_capacity(2 * chain.len()),
            tiles: chain.tiles().to_vec(),
        };
        // Build every path kind used, up front, so later look-ups cannot fail.
        let mut index: FxHashMap<(PathKind, PathEnd, u32), u32> = FxHashMap::default();
        for t in 0..g.tiles.len() {
            for (kind, end) in [
                (g.tiles[t].first, PathEnd::First),
                (g.tiles[t].second, PathEnd::Second),
            ] {
                let di = g.design_index(t);
                let id = match index.get(&(kind, end, di)) {
                    Some(&id) => id,
                    None => {
                        g.paths
                            .push(MagnetPath::new(kind, end, &g.designs[di as usize])?);
                        let id = (g.paths.len() - 1) as u32;
                        index.insert((kind, end, di), id);
                        id
                    }
                };
                g.path_of.push(id);
            }
        }
        Ok(g)
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
    pub fn chain_tiles(&self) -> &[Tile] {
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

    /// The fold joint `j` makes when it closes: L or R for an LL or RR pair, S otherwise
    /// (straight, or LR and RL, which never close).
    pub fn joint_fold(&self, j: usize) -> Fold {
        match (self.tiles[j].second, self.tiles[j + 1].first) {
            (PathKind::L, PathKind::L) => Fold::L,
            (PathKind::R, PathKind::R) => Fold::R,
            _ => Fold::S,
        }
    }

    /// Magnet `k`'s rest point in the frame of tile `frame_tile` (straight chain).
    pub(crate) fn rest_in(&self, k: usize, frame_tile: usize) -> Point {
        let (x, y) = self.path(k).rest();
        Point::new(x + (k / 2) as f64 * self.w - frame_tile as f64 * self.w, y)
    }

    /// Magnet `k`'s path end in the frame of tile `frame_tile` (straight chain).
    pub(crate) fn end_in(&self, k: usize, frame_tile: usize) -> Point {
        let (x, y) = self.path(k).end_point();
        Point::new(x + (k / 2) as f64 * self.w - frame_tile as f64 * self.w, y)
    }

    /// The reaction initiator: tile 0's design at the tile edge.
    pub(crate) fn ri(&self) -> ReactionInitiator {
        ReactionInitiator::of(self.design(0))
    }

    /// The RI's position in tile 0's frame, mm.
    pub fn ri_position(&self) -> (f64, f64) {
        self.ri().position.into()
    }

    /// Whether the pair closing joint `j` diverges: its path ends lie farther apart than its
    /// magnets at rest, so their attraction cannot draw them along their paths. This is the
    /// geometric form of Table 7.1's "propagation inhibited" (LR and RL pairs). Returns
    /// `(diverges, end distance, rest distance)`.
    pub fn pair_diverges(&self, j: usize) -> (bool, f64, f64) {
        let (a, b) = (2 * j + 1, 2 * j + 2);
        let end = self.end_in(a, j).distance(self.end_in(b, j));
        let rest = self.rest_in(a, j).distance(self.rest_in(b, j));
        (end > rest + LENGTH_TOLERANCE * self.w, end, rest)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::JointOutcome;

    #[test]
    fn pair_divergence_is_table_7_1() {
        for a in PathKind::ALL {
            for b in PathKind::ALL {
                let chain =
                    Chain::from_tiles(vec![Tile::new(PathKind::S, a), Tile::new(b, PathKind::S)])
                        .unwrap();
                let g = Geometry::new(&chain, vec![Design::thesis()], Vec::new()).unwrap();
                let (diverges, end, rest) = g.pair_diverges(0);
                let table = JointOutcome::from_paths(a, b) == JointOutcome::Inhibited;
                assert_eq!(diverges, table, "{a}{b}: ends {end} rest {rest}");
                let fold = JointOutcome::from_paths(a, b).to_fold().unwrap_or(Fold::S);
                assert_eq!(g.joint_fold(0), fold, "{a}{b}");
            }
        }
    }

    #[test]
    fn paths_are_shared_per_kind_end_and_design() {
        let chain = Chain::parse("SLLSLL").unwrap();
        let d = Design::thesis();
        let g = Geometry::new(&chain, vec![d, d.with_s(0.1)], vec![0, 0, 0, 1, 1, 1, 1]).unwrap();
        assert_eq!(g.magnets(), 14);
        // every magnet's path is the one its tile's kind, end and design make
        for k in 0..g.magnets() {
            let tile = g.chain_tiles()[k / 2];
            let (kind, end) = if k % 2 == 0 {
                (tile.first, PathEnd::First)
            } else {
                (tile.second, PathEnd::Second)
            };
            let want = MagnetPath::new(kind, end, g.design(k / 2)).unwrap();
            assert_eq!(*g.path(k), want, "{k}");
        }
        let mut ids: Vec<u32> = (0..g.magnets()).map(|k| g.path_id(k)).collect();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), g.path_table().len());
        // bad designs are named
        let bad = TileDesigns::global(Design { s: -1.0, ..d });
        let e = Geometry::from_designs(&chain, &bad).unwrap_err();
        assert!(e.to_string().starts_with("design: "), "{e}");
    }
}
