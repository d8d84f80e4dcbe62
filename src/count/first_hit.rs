//! The first tile of a fold's straight tail that would hit a given placed tile, decided once
//! per lattice offset.
//!
//! While joint `d` folds, tiles `0..=d` are in place and tiles `d + 1, d + 2, ...` form a
//! straight tail turning a quarter turn about the hinge, whatever letters follow. In tile `d`'s
//! frame (centre at the origin, chain along +x, a left fold; a right fold is the mirror image)
//! tail tile `k` (tile `d + k`) starts at `(k w, 0)` and the hinge is at `(w/2, side/2)`: every
//! fold moves its tail the same way. Whether tail tile `k` meets a placed tile is therefore a
//! function of that tile's offset alone ([`super::lattice::canonical_offset`], an exact
//! lattice point), and so is the first `k` that meets it. [`FirstHits`] computes it with the
//! collision module's tail test (the closed-form sweep `TurningPair::quarter_contact`, the one
//! [`crate::collision::check_word`] uses: the first contact is a vertex's circular arc crossing
//! an edge, solved exactly, no sampling) and remembers it; a few thousand offsets serve a
//! whole search.
//!
//! [`TailWindow`] is the cheap test the search runs before looking an offset up: a placed tile
//! whose centre lies outside it cannot be met by the first `k` tail tiles.

use rustc_hash::FxHashMap;

use crate::collision::{unit_tail_frame, TailHits, NO_TAIL_HIT};
use crate::exact::ExactPoint;

use super::lattice::pack;
use super::MAX_COUNT_TILES;

/// No tail tile meets the offset.
pub(super) const NEVER: u8 = u8::MAX;

/// Where a tail's tiles can reach, in the canonical frame relative to the hinge, for screening
/// placed tiles before their offsets are looked up. In `f32` with a slack of [`SCREEN_SLACK`]:
/// the search's `f32` centres are sums of at most 40 steps, each within 3e-8 w of exact, and
/// every coordinate is below 64 w (a rounding of at most 4e-6 w), so a tile screened out is one
/// that no tail tile can meet.
#[derive(Clone, Copy, Debug)]
pub(super) struct TailWindow {
    /// The hinge in tile `d`'s frame (left fold).
    pub hinge: (f32, f32),
    /// Smallest `x - hinge.x` of a placed centre that a tail tile can meet. A tail centre
    /// starts at `(k - 1/2, -side/2)` from the hinge and turns a quarter turn counter-clockwise,
    /// so its `x` stays at least `side/2` and its `y` at least `-side/2`; two tiles meet only
    /// with centres closer than two circumradii.
    pub min_x: f32,
    /// Smallest `y - hinge.y` of a placed centre that a tail tile can meet.
    pub min_y: f32,
    /// Per `k`: the squared distance from the hinge beyond which no tail tile up to `k` can
    /// meet a placed tile (tail centre `k`'s distance plus two circumradii).
    reach2: [f32; MAX_COUNT_TILES + 1],
}

/// The screening slack, tile widths.
const SCREEN_SLACK: f64 = 1e-3;

impl TailWindow {
    /// The squared reach of the first `k` tail tiles (`k >= 1`).
    #[inline]
    pub fn reach2(&self, k: usize) -> f32 {
        self.reach2[k.min(MAX_COUNT_TILES)]
    }
}

/// First hits by canonical offset, for one touching tolerance: the collision check's exact
/// tail test ([`TailHits`]), remembered under the search's packed keys.
#[derive(Clone, Debug)]
pub(super) struct FirstHits {
    tail: TailHits,
    window: TailWindow,
    memo: FxHashMap<u64, u8>,
}

impl FirstHits {
    /// An empty memo for outlines inset by `tolerance` (see
    /// [`crate::collision::CheckOptions::tolerance`]).
    pub fn new(tolerance: f64) -> FirstHits {
        let (radius, half_side, hinge) = unit_tail_frame();
        let mut reach2 = [0.0; MAX_COUNT_TILES + 1];
        for (k, r) in reach2.iter_mut().enumerate() {
            let tail_distance = (k as f64 - hinge.x).hypot(hinge.y);
            *r = (tail_distance + 2.0 * radius + SCREEN_SLACK).powi(2) as f32;
        }
        FirstHits {
            tail: TailHits::new(tolerance),
            window: TailWindow {
                hinge: (hinge.x as f32, hinge.y as f32),
                min_x: (half_side - 2.0 * radius - SCREEN_SLACK) as f32,
                min_y: (-half_side - 2.0 * radius - SCREEN_SLACK) as f32,
                reach2,
            },
            memo: FxHashMap::default(),
        }
    }

    /// The window of the tail.
    pub fn window(&self) -> &TailWindow {
        &self.window
    }

    /// The first tail index `k >= 1` whose tile meets a placed tile at canonical offset
    /// `offset` while the fold turns, or [`NEVER`]. The folding tile itself (offset zero) is
    /// never tested against tile `d + 1`, its hinged neighbour.
    #[inline]
    pub fn get(&mut self, offset: ExactPoint) -> u8 {
        let key = pack(offset);
        if let Some(&k) = self.memo.get(&key) {
            return k;
        }
        let k = self.compute(offset);
        self.memo.insert(key, k);
        k
    }

    /// The exact sweep test along the tail (the collision check's), within the search's
    /// longest chain.
    fn compute(&self, offset: ExactPoint) -> u8 {
        match self.tail.first_hit(offset) {
            NO_TAIL_HIT => NEVER,
            k if k as usize <= MAX_COUNT_TILES => k as u8,
            _ => NEVER,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::CheckOptions;
    use crate::exact::Surd;
    use crate::Fold;

    fn hits() -> FirstHits {
        FirstHits::new(CheckOptions::default().tolerance)
    }

    #[test]
    fn ring_closes_and_a_fifth_tile_hits() {
        // while joint 2 of LL.. folds, tail tile 1 (tile 3: the ring LLL) closes against
        // tile 0 without overlap, and tail tile 2 (tile 4: LLLL) swings into it
        let p = crate::kinematics::final_poses(&crate::FoldWord::parse("LL").unwrap());
        let off = super::super::lattice::canonical_offset(p[0].centre, p[2], Fold::L);
        assert_eq!(hits().get(off), 2);
    }

    #[test]
    fn folding_tile_is_not_its_neighbours_obstacle() {
        assert!(hits().get(ExactPoint::ORIGIN) >= 2);
        // a tile right behind the hinge side is never reached by the tail
        let behind = ExactPoint::new(Surd::new(-2, 0), Surd::ZERO);
        assert_eq!(hits().get(behind), NEVER);
    }

    #[test]
    fn window_holds_every_hit() {
        // every offset met by some tail tile lies inside the window the search tests first
        let mut h = hits();
        let w = *h.window();
        let mut met = 0;
        for xa in -6..=16i64 {
            for xb in -8..=8i64 {
                for ya in -6..=6i64 {
                    for yb in -8..=8i64 {
                        let off = ExactPoint::new(Surd::new(xa, xb), Surd::new(ya, yb));
                        let k = h.get(off);
                        if k == NEVER {
                            continue;
                        }
                        met += 1;
                        let (x, y) = off.to_f64(1.0);
                        let (a, c) = (x as f32 - w.hinge.0, y as f32 - w.hinge.1);
                        assert!(a >= w.min_x && c >= w.min_y, "{off:?} {k}");
                        assert!(a * a + c * c <= w.reach2(k as usize), "{off:?} {k}");
                    }
                }
            }
        }
        assert!(met > 1000, "{met}");
    }
}
