//! The first tile of a fold's straight tail that meets a placed tile, decided once per lattice
//! offset (the same idea as the counting search's memo, `crate::count`, for tails of any
//! length).
//!
//! While joint `k` folds in the sequential check, tiles `0..=k` sit at their final poses and
//! tiles `k + 1, k + 2, ...` form a straight tail turning a quarter turn about the hinge. In
//! tile `k`'s frame (centre at the origin, chain along +x; a right fold mirrored into a left
//! one) tail tile `m` (tile `k + m`) starts at `(m w, 0)` and the hinge is at `(w/2, side/2)`,
//! whatever the fold and the heading. Whether tail tile `m` meets a placed tile is therefore a
//! function of that tile's offset in this frame ([`canonical_offset`], an exact lattice point),
//! and so is the first such `m`. [`TailHits`] computes it with the closed-form sweep test
//! ([`super::sweep::TurningPair::quarter_contact`]: the first contact is a vertex's circular arc
//! crossing an edge, no sampling) and remembers it, so that repeated shapes (every U-turn of a
//! serpentine) cost one lookup.

use kurbo::Point;
use rustc_hash::FxHashMap;

use crate::exact::{ExactPoint, ExactPose, QuarterTurns};
use crate::{Fold, Octagon};

use super::sweep::TurningPair;

/// No tail tile meets the offset.
pub(crate) const NEVER: u32 = u32::MAX;

/// Slack, in tile widths, on the distance tests that choose which tail tiles get the exact
/// test: far above the rounding of `f64` coordinates up to `2e7 w` (the longest chain, about
/// `4e-9 w`), so a tail tile left out is one the exact test would reject.
const SLACK: f64 = 1e-6;

/// The offset of the tile centred at `fixed` from the tile at `at`, in the frame of `at`
/// (centre at the origin, chain along +x), mirrored (y negated) for a right fold, so that
/// every fold is seen as a left fold.
pub(super) fn canonical_offset(fixed: ExactPoint, at: ExactPose, fold: Fold) -> ExactPoint {
    let back = QuarterTurns::new(-i64::from(at.heading.get()));
    let d = (fixed - at.centre).rotated(back);
    if fold == Fold::R {
        ExactPoint::new(d.x, -d.y)
    } else {
        d
    }
}

/// Where the tail of a left fold can reach, in the canonical frame: a placed centre can be met
/// only inside this window (relative to the hinge), for the first `m` tail tiles only within
/// [`TailHits::reach`]`(m)` of the hinge.
#[derive(Clone, Copy, Debug)]
pub(super) struct TailWindow {
    /// The hinge in tile `k`'s frame.
    pub hinge: Point,
    /// Smallest `x - hinge.x` of a placed centre that a tail tile can meet. A tail centre
    /// starts at `(m - 1/2, -side/2)` from the hinge and turns a quarter turn counter-clockwise
    /// to `(side/2, m - 1/2)`, so its `x` stays at least `side/2` and its `y` at least
    /// `-side/2`; two tiles meet only with centres closer than two circumradii.
    pub min_x: f64,
    /// Smallest `y - hinge.y` of a placed centre that a tail tile can meet.
    pub min_y: f64,
}

/// The measures of a fold's tail on tiles of width 1 that bound which placed tiles it can
/// meet: the octagon's circumradius, half its side, and the hinge of a left fold (the
/// folding tile's frame).
pub(crate) fn unit_tail_frame() -> (f64, f64, Point) {
    let o = Octagon::new(1.0);
    let hinge = Point::from(
        Octagon::exact_hinge(Fold::L)
            .unwrap_or(ExactPoint::ORIGIN)
            .to_f64(1.0),
    );
    (o.circumradius(), 0.5 * o.side(), hinge)
}

/// First hits by canonical offset, for one touching tolerance (also the counting search's
/// exact test, through [`TailHits::first_hit`]).
#[derive(Clone, Debug)]
pub(crate) struct TailHits {
    outline: [Point; 8],
    radius: f64,
    window: TailWindow,
    memo: OffsetMemo,
}

/// Not yet computed, in a block of [`OffsetMemo`] (a first hit is far below it: an offset
/// kept in the blocks lies within `2^13` widths, so its first hit within about `2^14`).
const UNKNOWN: u32 = u32::MAX - 1;
/// Offsets kept in the blocks have every coordinate's `a` and `b` (half widths) in
/// `-BOUND..BOUND`; farther ones go to the map.
const BOUND: i64 = 1 << 14;

/// One cache line of first hits: 4 by 4 neighbouring offsets of one class.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Block([u32; 16]);

/// First hits by offset, kept so that neighbouring offsets share memory: the placed tiles a
/// fold's scan looks up come row by row, and neighbours in a row differ in one coordinate's
/// rational part only. Offsets with the same `1/sqrt2` parts (and parities of the rational
/// parts) form a class; within it, 4 by 4 neighbouring offsets share a [`Block`], found
/// through a small map (and the last block used, which consecutive lookups mostly hit).
/// A pure memo: the value for an offset is the same as a plain map's.
#[derive(Clone, Debug, Default)]
struct OffsetMemo {
    /// Block index by packed block key.
    index: FxHashMap<u64, u32>,
    blocks: Vec<Block>,
    /// The last block key looked up and its index.
    last: Option<(u64, u32)>,
    /// Offsets beyond [`BOUND`].
    far: FxHashMap<ExactPoint, u32>,
}

impl OffsetMemo {
    /// The block key of `offset` and its slot in the block, or `None` beyond [`BOUND`].
    fn key(offset: ExactPoint) -> Option<(u64, usize)> {
        let [xa, xb, ya, yb] = [offset.x.a, offset.x.b, offset.y.a, offset.y.b].map(|v| {
            // in 0..2^15 when within the bound
            (-BOUND..BOUND).contains(&v).then_some((v + BOUND) as u64)
        });
        let (xa, xb, ya, yb) = (xa?, xb?, ya?, yb?);
        // 15 + 15 bits of the class, 12 + 12 of the block, 2 of parity
        let key =
            xb | yb << 15 | (xa >> 3) << 30 | (ya >> 3) << 42 | (xa & 1) << 54 | (ya & 1) << 55;
        let slot = ((xa >> 1) & 3) | ((ya >> 1) & 3) << 2;
        Some((key, slot as usize))
    }

    /// The memo's entry for `offset`, [`UNKNOWN`] when none.
    fn get(&mut self, offset: ExactPoint) -> u32 {
        match OffsetMemo::key(offset) {
            Some((key, slot)) => match self.block(key, false) {
                Some(b) => self.blocks[b].0[slot],
                None => UNKNOWN,
            },
            None => self.far.get(&offset).copied().unwrap_or(UNKNOWN),
        }
    }

    /// Keeps `m` for `offset`.
    fn insert(&mut self, offset: ExactPoint, m: u32) {
        match OffsetMemo::key(offset) {
            Some((key, slot)) => {
                if let Some(b) = self.block(key, true) {
                    self.blocks[b].0[slot] = m;
                }
            }
            None => {
                self.far.insert(offset, m);
            }
        }
    }

    /// The index of block `key`, made (all [`UNKNOWN`]) when `make`.
    fn block(&mut self, key: u64, make: bool) -> Option<usize> {
        if let Some((k, b)) = self.last {
            if k == key {
                return Some(b as usize);
            }
        }
        let b = match self.index.get(&key) {
            Some(&b) => b,
            None if make => {
                let b = u32::try_from(self.blocks.len()).ok()?;
                self.blocks.push(Block([UNKNOWN; 16]));
                self.index.insert(key, b);
                b
            }
            None => return None,
        };
        self.last = Some((key, b));
        Some(b as usize)
    }
}

impl TailHits {
    /// An empty memo for outlines inset by `tolerance` (see [`super::CheckOptions::tolerance`]).
    pub(crate) fn new(tolerance: f64) -> TailHits {
        let (radius, half_side, hinge) = unit_tail_frame();
        TailHits {
            outline: Octagon::new(1.0).inset_vertices(tolerance).map(Point::from),
            radius,
            window: TailWindow {
                hinge,
                min_x: half_side - 2.0 * radius - SLACK,
                min_y: -half_side - 2.0 * radius - SLACK,
            },
            memo: OffsetMemo::default(),
        }
    }

    /// The window of the tail.
    pub(super) fn window(&self) -> TailWindow {
        self.window
    }

    /// Distance from the hinge of tail centre `m`.
    fn tail_distance(&self, m: f64) -> f64 {
        let h = self.window.hinge;
        (m - h.x).hypot(h.y)
    }

    /// How far from the hinge a placed centre met by one of the first `m` tail tiles can lie.
    pub(super) fn reach(&self, m: usize) -> f64 {
        self.tail_distance(m as f64) + 2.0 * self.radius + SLACK
    }

    /// The first tail index `m >= 1` whose tile meets a placed tile at canonical offset
    /// `offset` while the fold turns, or [`NEVER`]. The folding tile itself (offset zero) is
    /// never tested against tile `k + 1`, its hinged neighbour.
    pub(super) fn get(&mut self, offset: ExactPoint) -> u32 {
        let m = self.memo.get(offset);
        if m != UNKNOWN {
            return m;
        }
        let m = self.first_hit(offset);
        self.memo.insert(offset, m);
        m
    }

    /// A lower bound on [`TailHits::get`] for a placed centre at distance `d` from the hinge
    /// (within `1e-6` of the exact distance): the first tail index the sweep test looks at for
    /// such a centre (see [`TailHits::first_hit`]), less one for rounding. The growing check
    /// uses it through [`TailHits::no_sooner_than`].
    #[cfg(test)]
    fn least_hit(&self, d: f64) -> usize {
        let h = self.window.hinge;
        let inner = (d - 2.0 * self.radius - SLACK - 1e-6).max(0.0);
        let along = (inner * inner - h.y * h.y).max(0.0).sqrt();
        // `as` truncates and saturates: the floor for every value (a negative one, or NaN,
        // gives 0 either way), without a call into libm on baseline x86-64
        ((h.x + along) as usize).saturating_sub(2).max(1)
    }

    /// A distance from the hinge at and beyond which `least_hit` (a lower bound on
    /// [`TailHits::get`] by distance: the first tail index the sweep test looks at for a
    /// centre that far, less one for rounding) is at least `b`, a little beyond the least
    /// such distance for rounding: a placed centre that far (within `1e-6`) is met, if at all,
    /// no sooner than tail index `b`. Worked out once per `b` and compared with each placed
    /// tile's distance, it saves a bound (a square root) per tile.
    pub(super) fn no_sooner_than(&self, b: usize) -> f64 {
        if b <= 1 {
            return f64::NEG_INFINITY; // every first hit is at least 1
        }
        // `least_hit(d) >= b` once `h.x + along >= b + 2`, so once the distance less the
        // contact range is at least the hinge's distance from tail centre `b + 2` (plus the
        // relative and absolute margins, far above the rounding of these few operations)
        let h = self.window.hinge;
        let along = b as f64 + 2.0 - h.x;
        let d = 2.0 * self.radius + SLACK + 1e-6 + along.hypot(h.y);
        d * (1.0 + 1e-9) + 1e-7
    }

    fn at(&self, c: Point) -> [Point; 8] {
        self.outline.map(|v| v + c.to_vec2())
    }

    /// The first tail index met at `offset`, or [`NEVER`], without the memo: the exact sweep
    /// test along the tail, nearest tile first, over the tail tiles whose centres pass within
    /// two circumradii (and the slack) of the placed centre.
    pub(crate) fn first_hit(&self, offset: ExactPoint) -> u32 {
        let p = Point::from(offset.to_f64(1.0));
        let h = self.window.hinge;
        let dp = p.distance(h);
        let apart = 2.0 * self.radius + SLACK;
        // the first tail centre not nearer the hinge than dp - apart
        let inner = (dp - apart).max(0.0);
        let along = (inner * inner - h.y * h.y).max(0.0).sqrt();
        // `as u32` is the floor here (see `least_hit`)
        let first = ((h.x + along) as u32).saturating_sub(1).max(1);
        let fixed = self.at(p);
        for m in first.. {
            let dm = self.tail_distance(f64::from(m));
            if dm - dp > apart {
                break; // this tail centre and every later one pass beyond the tile
            }
            if dp - dm > apart || (m == 1 && offset == ExactPoint::ORIGIN) {
                continue;
            }
            let c = Point::new(f64::from(m), 0.0);
            if TurningPair::new(&self.at(c), c, &fixed, p, self.radius, h).quarter_contact(true) {
                return m;
            }
        }
        NEVER
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::Surd;
    use crate::kinematics::final_poses;
    use crate::FoldWord;

    /// An empty memo at the default tolerance.
    fn memo() -> TailHits {
        TailHits::new(crate::collision::CheckOptions::default().tolerance)
    }

    #[test]
    fn mirrored_folds_share_offsets() {
        // while joint 2 of LL.. folds, tail tile 1 (tile 3: the ring LLL) closes against
        // tile 0 without overlap and tail tile 2 (tile 4) swings into it; RR is its mirror
        let left = final_poses(&FoldWord::parse("LL").unwrap());
        let right = final_poses(&FoldWord::parse("RR").unwrap());
        let off = canonical_offset(left[0].centre, left[2], Fold::L);
        assert_eq!(canonical_offset(right[0].centre, right[2], Fold::R), off);
        assert_eq!(memo().get(off), 2);
        // the folding tile is never its hinged neighbour's obstacle; a tile behind it is
        // never reached
        assert!(memo().get(ExactPoint::ORIGIN) >= 2);
        assert_eq!(
            memo().get(ExactPoint::new(Surd::new(-2, 0), Surd::ZERO)),
            NEVER
        );
    }

    /// The distance beyond which first hits are at least `b` is one where the bound by
    /// distance is at least `b`, and not much beyond the first such distance.
    #[test]
    fn no_sooner_than_brackets_the_bound() {
        let h = memo();
        let mut prev = f64::NEG_INFINITY;
        for b in 1..3000usize {
            let t = h.no_sooner_than(b);
            assert!(t >= prev, "{b}");
            prev = t;
            // every distance from the threshold on gives the bound b or more
            for step in 0..200 {
                let d = t + f64::from(step) * 0.01;
                assert!(h.least_hit(d) >= b, "{b} {d}");
            }
            // a distance a little before it (by more than the margins) gives less
            if b > 1 {
                assert!(h.least_hit(t - 1e-4) < b, "{b} {t}");
            }
        }
    }

    #[test]
    fn far_offsets_are_met_by_far_tail_tiles() {
        // a tile ahead-left of the hinge, about 700 widths out, 45 degrees round the sweep:
        // met by a tail tile at about its distance, by no tail tile much nearer the hinge
        let mut h = memo();
        let off = ExactPoint::new(Surd::new(0, 1414), Surd::new(0, 1414));
        let m = h.get(off);
        let d = Point::from(off.to_f64(1.0)).distance(h.window().hinge);
        assert!(m != NEVER && (f64::from(m) - d).abs() < 2.0, "{m} {d}");
        assert!(d <= h.reach(m as usize) && d > h.reach(m as usize - 3));
        // the lower bound by distance is below the first hit, and close to it
        let least = h.least_hit(d);
        assert!(
            least <= m as usize && least + 4 >= m as usize,
            "{m} {least}"
        );
    }

    #[test]
    fn memo_agrees_with_every_tail_tile_tried() {
        // lattice offsets around the hinge: the memo's first hit is the first of tail tiles
        // 1..=24 that the sweep test meets (no distance band), and every offset met lies in
        // the window and within the reach
        let mut h = memo();
        let w = h.window();
        let r = Octagon::new(1.0).circumradius();
        let mut met = 0;
        for (xa, xb, ya, yb) in (0..20i64 * 13 * 9 * 13).map(|c| {
            (
                c % 20 - 4,
                (c / 20) % 13 - 6,
                (c / 260) % 9 - 2,
                (c / 2340) % 13 - 6,
            )
        }) {
            let off = ExactPoint::new(Surd::new(xa, xb), Surd::new(ya, yb));
            let p = Point::from(off.to_f64(1.0));
            let fixed = h.at(p);
            let plain = (1..=24u32)
                .find(|&m| {
                    let c = Point::new(f64::from(m), 0.0);
                    !(m == 1 && off == ExactPoint::ORIGIN)
                        && TurningPair::new(&h.at(c), c, &fixed, p, r, w.hinge)
                            .quarter_contact(true)
                })
                .unwrap_or(NEVER);
            let m = h.get(off);
            assert_eq!(m, plain, "{off:?}");
            if m != NEVER {
                met += 1;
                assert!(
                    p.x - w.hinge.x >= w.min_x && p.y - w.hinge.y >= w.min_y,
                    "{off:?}"
                );
                assert!(p.distance(w.hinge) <= h.reach(m as usize), "{off:?} {m}");
                // the bound the growing check skips lookups by never exceeds a first hit
                let least = h.least_hit(p.distance(w.hinge));
                assert!(least <= m as usize, "{off:?} {m} {least}");
                // and the distance beyond which that bound reaches b is past every
                // distance where it is below b
                let d = p.distance(w.hinge);
                for b in 1..=least + 2 {
                    if d >= h.no_sooner_than(b) {
                        assert!(least >= b, "{off:?} {b} {least}");
                    }
                }
            }
        }
        assert!(met > 500, "{met}");
    }
}
