//! The thesis' folding order: joints fold one after another from the reaction-initiator end.
//!
//! While joint `k` folds, tiles `0..=k` already sit at their final poses and tiles after `k`
//! form a straight tail that turns 90 degrees about joint `k`'s hinge. Whether the tail meets
//! a placed tile depends only on that tile's exact lattice offset from tile `k`
//! ([`super::first_hit`]): the placed tiles inside the window the tail can reach (found with
//! boxes over runs of consecutive tiles, [`super::index_boxes`]) are looked up in a memo of
//! first hits, so a fold costs a few lookups. Only a fold that the memo says collides is swept
//! pair by pair in world coordinates, in closed form ([`super::sweep`]), for the first contact
//! angle and the two tiles.

use std::f64::consts::FRAC_PI_2;

use kurbo::{Point, Rect, Vec2};

use crate::exact::ExactPose;
use crate::{kinematics, Chain, Fold, FoldWord, Octagon};

use super::first_hit::{canonical_offset, TailHits};
use super::index_boxes::RangeBoxes;
use super::sweep::{swept_query, TurningPair};
use super::{final_overlap, CheckOptions, Collision};

/// The outcome of checking a chain of tiles.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "verdict", rename_all = "snake_case")]
pub enum Verdict {
    /// It folds completely and never overlaps itself.
    Valid,
    /// Propagation stops at this joint (LR or RL pair); the part before it was checked and
    /// folds cleanly.
    Inhibited {
        /// The inhibited joint.
        joint: usize,
    },
    /// Two tiles overlap.
    Collides(Collision),
}

/// Checks a chain of tiles: its joints' outcomes (thesis Table 7.1), then the folding of the
/// part that propagation reaches.
pub fn check_chain(chain: &Chain, opts: &CheckOptions) -> Verdict {
    let word = chain.reached_word();
    if let Err(c) = check_word(&word, opts) {
        return Verdict::Collides(c);
    }
    match chain.first_inhibited() {
        Some(joint) => Verdict::Inhibited { joint },
        None => Verdict::Valid,
    }
}

/// Checks a designed chain folding sequentially from tile 0: every sweep (unless
/// `opts.final_only`) and the final shape. Returns the first collision in folding order.
pub fn check_word(word: &FoldWord, opts: &CheckOptions) -> Result<(), Collision> {
    let poses = kinematics::final_poses(word);
    if !opts.final_only {
        Sweeper::new(&poses, opts.tolerance).run(word)?;
    }
    match final_overlap(&poses) {
        Some(c) => Err(c),
        None => Ok(()),
    }
}

/// The tile of width 1 as the sweeps see it: its inset outline and the measures that bound
/// which tiles can meet.
pub(super) struct UnitTile {
    /// Inset outline, as offsets from the centre (the octagon is symmetric under quarter
    /// turns, so the heading does not change it).
    outline: [Vec2; 8],
    /// Circumradius of the full outline.
    pub(super) radius: f64,
    /// Half the side, the hinge's offset across the chain.
    half_side: f64,
}

impl UnitTile {
    pub(super) fn new(tolerance: f64) -> UnitTile {
        let o = Octagon::new(1.0);
        UnitTile {
            outline: o.inset_vertices(tolerance).map(Vec2::from),
            radius: o.circumradius(),
            half_side: 0.5 * o.side(),
        }
    }

    /// Whether a tile centred at `fixed`, and one centred at `moving` turning a quarter turn
    /// about `pivot` (the way `theta`'s sign says), can meet at all: the moving centre stays
    /// in the quadrant spanned by its start direction and that direction turned, so the fixed
    /// centre must be within two circumradii of that quadrant.
    pub(super) fn may_meet(&self, moving: Point, fixed: Point, pivot: Point, theta: f64) -> bool {
        let m = moving - pivot;
        let rr = m.hypot2().sqrt();
        if rr == 0.0 {
            return true;
        }
        let start = Vec2::new(m.x / rr, m.y / rr);
        let end = if theta >= 0.0 {
            start.turn_90()
        } else {
            -start.turn_90()
        };
        let p = fixed - pivot;
        let margin = -2.0 * self.radius - 1e-9;
        p.dot(start) >= margin && p.dot(end) >= margin
    }

    /// The outline placed with its centre at `c`.
    pub(super) fn at(&self, c: Point) -> [Point; 8] {
        self.outline.map(|v| c + v)
    }

    /// Range of tail offsets `t` (tile `k + 1 + t`) whose centres pass within `2 r` of the
    /// distance `d` from the hinge; the tail centre `t` is at distance
    /// `sqrt((1/2 + t)^2 + (half_side)^2)`.
    pub(super) fn tail_range(&self, d: f64, tail_len: usize) -> Option<(usize, usize)> {
        if tail_len == 0 {
            return None;
        }
        let reach = 2.0 * self.radius + 1e-9;
        let h2 = self.half_side * self.half_side;
        let lo = (d - reach).max(0.0);
        let hi = d + reach;
        let u_lo = (lo * lo - h2).max(0.0).sqrt();
        let u_hi2 = hi * hi - h2;
        if u_hi2 < 0.25 {
            return None;
        }
        let u_hi = u_hi2.sqrt();
        let t_lo = (u_lo - 0.5).max(0.0).floor() as usize;
        let t_hi = ((u_hi - 0.5).ceil().max(0.0) as usize).min(tail_len - 1);
        (t_lo <= t_hi).then_some((t_lo, t_hi))
    }
}

/// The sequential sweeps of one word.
struct Sweeper<'a> {
    poses: &'a [ExactPose],
    centres: Vec<Point>,
    tile: UnitTile,
    boxes: RangeBoxes,
    hits: TailHits,
}

impl<'a> Sweeper<'a> {
    fn new(poses: &'a [ExactPose], tolerance: f64) -> Sweeper<'a> {
        let centres: Vec<Point> = poses
            .iter()
            .map(|p| Point::from(p.centre.to_f64(1.0)))
            .collect();
        Sweeper {
            poses,
            boxes: RangeBoxes::new(&centres),
            centres,
            tile: UnitTile::new(tolerance),
            hits: TailHits::new(tolerance),
        }
    }

    fn run(mut self, word: &FoldWord) -> Result<(), Collision> {
        for (k, &fold) in word.folds().iter().enumerate() {
            // tiles 0..=k are in place for this sweep
            let Some(hinge) = kinematics::exact_hinge(self.poses[k], fold) else {
                continue;
            };
            let pivot = Point::from(hinge.to_f64(1.0));
            if !self.tail_meets_placed(k, fold, pivot) {
                continue;
            }
            let theta = fold.quarter_turns() as f64 * FRAC_PI_2;
            if let Some(c) = self.sweep(k, pivot, theta) {
                return Err(c);
            }
        }
        Ok(())
    }

    /// Whether the tail of joint `k` meets a placed tile, by the first-hit memo: every placed
    /// tile in the window the tail can reach is looked up by its exact offset from tile `k`.
    fn tail_meets_placed(&mut self, k: usize, fold: Fold, pivot: Point) -> bool {
        let tail_len = self.centres.len() - 1 - k;
        let window = self.hits.window();
        let reach = self.hits.reach(tail_len);
        // the canonical frame's axes in the world: along the chain, and to the fold's side
        let u = self.poses[k].heading.unit_vector();
        let v = if fold == Fold::R {
            -u.turn_90()
        } else {
            u.turn_90()
        };
        let ck = self.centres[k];
        let h = window.hinge;
        let (x0, x1) = (h.x + window.min_x, h.x + reach);
        let (y0, y1) = (h.y + window.min_y, h.y + reach);
        let corner = |x: f64, y: f64| ck + x * u + y * v;
        let query = Rect::from_points(corner(x0, y0), corner(x1, y1));
        let Sweeper {
            poses,
            centres,
            boxes,
            hits,
            ..
        } = self;
        let at = poses[k];
        boxes.for_each_in(centres, k, &query, |i| {
            if (centres[i] - pivot).hypot() > reach {
                return false;
            }
            let offset = canonical_offset(poses[i].centre, at, fold);
            hits.get(offset) as usize <= tail_len
        })
    }

    /// Sweeps joint `k` about `pivot` by `theta` pair by pair in world coordinates; the first
    /// contact, if any (the placed tiles near the swept sector against the tail tiles at a
    /// similar distance from the hinge).
    fn sweep(&self, k: usize, pivot: Point, theta: f64) -> Option<Collision> {
        let n = self.centres.len();
        let tail_len = n - k - 1;
        let ck = self.centres[k];
        let u = self.poses[k].heading.unit_vector();
        let tail_centre = |t: usize| -> Point { ck + (t + 1) as f64 * u };
        let r = self.tile.radius;
        let query = swept_query(pivot, tail_centre(0), tail_centre(tail_len - 1), theta, r);

        let mut best: Option<(f64, usize, usize)> = None;
        self.boxes.for_each_in(&self.centres, k, &query, |i| {
            let ci = self.centres[i];
            let d = (ci - pivot).hypot2().sqrt();
            let Some((t0, t1)) = self.tile.tail_range(d, tail_len) else {
                return false;
            };
            let fixed = self.tile.at(ci);
            for t in t0..=t1 {
                let j = k + 1 + t;
                if i == k && j == k + 1 {
                    continue; // hinged neighbours: they only touch at the hinge and the closing walls
                }
                let c = tail_centre(t);
                if !self.tile.may_meet(c, ci, pivot, theta) {
                    continue;
                }
                let moving = self.tile.at(c);
                let pair = TurningPair::new(&moving, c, &fixed, ci, r, pivot);
                if !pair.quarter_contact(theta > 0.0) {
                    continue;
                }
                if let Some(phi) = pair.first_contact(theta) {
                    if best.is_none_or(|(b, bi, bj)| (phi, i, j) < (b, bi, bj)) {
                        best = Some((phi, i, j));
                    }
                }
            }
            false
        });
        best.map(|(phi, i, j)| Collision {
            joint: Some(k),
            angle_deg: phi.to_degrees(),
            time: None,
            tiles: (i, j),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(w: &str) -> Result<(), Collision> {
        check_word(&FoldWord::parse(w).unwrap(), &CheckOptions::default())
    }

    #[test]
    fn ring_is_valid_five_in_a_ring_is_not() {
        assert!(check("LLL").is_ok());
        assert!(check("RRR").is_ok());
        // while joint 2 folds, tiles 3 and 4 are still straight: tile 4 swings into tile 0
        let c = check("LLLL").unwrap_err();
        assert_eq!(c.tiles, (0, 4));
        assert_eq!(c.joint, Some(2));
        assert!(c.angle_deg > 0.0 && c.angle_deg < 90.0, "{c}");
        assert!(check("SLLL").is_err());
        assert!(check("LLLS").is_err());
    }

    #[test]
    fn hinged_neighbours_never_collide() {
        for w in [
            "L", "R", "SL", "LS", "LL", "RR", "LR", "RL", "SLLS", "LSL", "LSSL",
        ] {
            assert!(check(w).is_ok(), "{w}");
        }
    }

    #[test]
    fn inhibited_chain_is_reported() {
        let chain = Chain::parse("SS SL RS SS").unwrap();
        assert_eq!(
            check_chain(&chain, &CheckOptions::default()),
            Verdict::Inhibited { joint: 1 }
        );
        let clean = Chain::parse("SLLS").unwrap();
        assert_eq!(
            check_chain(&clean, &CheckOptions::default()),
            Verdict::Valid
        );
    }

    /// Every pair, every sweep, no broad phase: the reference the fast path must match.
    fn brute_force(word: &FoldWord, tolerance: f64) -> Option<(usize, usize, usize)> {
        let poses = kinematics::final_poses(word);
        let tile = UnitTile::new(tolerance);
        let centres: Vec<Point> = poses
            .iter()
            .map(|p| Point::from(p.centre.to_f64(1.0)))
            .collect();
        for (k, &fold) in word.folds().iter().enumerate() {
            let Some(h) = kinematics::exact_hinge(poses[k], fold) else {
                continue;
            };
            let pivot = Point::from(h.to_f64(1.0));
            let theta = fold.quarter_turns() as f64 * FRAC_PI_2;
            let u = poses[k].heading.unit_vector();
            let mut best: Option<(f64, usize, usize)> = None;
            for j in k + 1..centres.len() {
                let c = centres[k] + (j - k) as f64 * u;
                for (i, &ci) in centres.iter().enumerate().take(k + 1) {
                    if i == k && j == k + 1 {
                        continue;
                    }
                    let (moving, fixed) = (tile.at(c), tile.at(ci));
                    let r = tile.radius;
                    if let Some(phi) =
                        TurningPair::new(&moving, c, &fixed, ci, r, pivot).first_contact(theta)
                    {
                        if best.is_none_or(|b| (phi, i, j) < b) {
                            best = Some((phi, i, j));
                        }
                    }
                }
            }
            if let Some((_, i, j)) = best {
                return Some((k, i, j));
            }
        }
        None
    }

    #[test]
    fn fast_path_matches_brute_force_on_random_words() {
        let mut rng = crate::rng::SplitMix64::new(0x2545_F491_4F6C_DD1D);
        let mut next = || rng.next_u64();
        let mut collided = 0;
        for round in 0..400 {
            let n = 5 + (next() % 60) as usize;
            // mostly straight with some turns, so that many words get far before colliding
            let folds: Vec<crate::Fold> = (0..n)
                .map(|_| match next() % 10 {
                    0 | 1 => crate::Fold::L,
                    2 | 3 => crate::Fold::R,
                    _ => crate::Fold::S,
                })
                .collect();
            let w = FoldWord::from_folds(folds);
            let fast = check_word(&w, &CheckOptions::default())
                .err()
                .map(|c| (c.joint.unwrap_or(usize::MAX), c.tiles.0, c.tiles.1));
            let slow = brute_force(&w, CheckOptions::default().tolerance);
            assert_eq!(fast, slow, "round {round} word {w}");
            collided += fast.is_some() as usize;
        }
        assert!(collided > 50 && collided < 350, "{collided}");
    }

    #[test]
    fn memo_and_world_sweep_agree_on_every_fold() {
        // not only the first collision: at every fold of random words (short ones, and
        // serpentines of up to 600 tiles with random letters mixed in), the first-hit memo says
        // "collides" exactly when the pair-by-pair sweep finds a contact
        let mut next = super::super::xorshift(0x1234_5678_9ABC_DEF1);
        let (mut folds_met, mut folds_clean) = (0, 0);
        for round in 0..120 {
            let w: Vec<Fold> = if round % 2 == 0 {
                (0..5 + next() % 60)
                    .map(|_| [Fold::L, Fold::R, Fold::S, Fold::S, Fold::S][(next() % 5) as usize])
                    .collect()
            } else {
                let row = 3 + (next() % 20) as usize;
                let mut w = Vec::new();
                for r in 0..(600 / row) {
                    w.extend(std::iter::repeat_n(Fold::S, row));
                    let f = if r % 2 == 0 { Fold::L } else { Fold::R };
                    w.extend([f, f]);
                }
                for _ in 0..3 {
                    let at = (next() % w.len() as u64) as usize;
                    w[at] = [Fold::L, Fold::R, Fold::S][(next() % 3) as usize];
                }
                w
            };
            let word = FoldWord::from_folds(w);
            let poses = kinematics::final_poses(&word);
            let mut sweeper = Sweeper::new(&poses, CheckOptions::default().tolerance);
            for (k, &fold) in word.folds().iter().enumerate() {
                let Some(h) = kinematics::exact_hinge(poses[k], fold) else {
                    continue;
                };
                let pivot = Point::from(h.to_f64(1.0));
                let theta = fold.quarter_turns() as f64 * FRAC_PI_2;
                let memo = sweeper.tail_meets_placed(k, fold, pivot);
                let world = sweeper.sweep(k, pivot, theta).is_some();
                assert_eq!(memo, world, "round {round}, joint {k} of {word}");
                if world {
                    folds_met += 1;
                } else {
                    folds_clean += 1;
                }
            }
        }
        assert!(
            folds_met > 1000 && folds_clean > 1000,
            "{folds_met} {folds_clean}"
        );
    }

    #[test]
    fn valid_final_shape_can_collide_while_folding() {
        // LSLLSR: the final shape is clean, but while joint 3 folds the still-straight tail
        // swings tile 6 through tile 0.
        let w = FoldWord::parse("LSLLSR").unwrap();
        assert!(check_word(&w, &CheckOptions::default().with_final_only(true)).is_ok());
        let c = check_word(&w, &CheckOptions::default()).unwrap_err();
        assert_eq!((c.joint, c.tiles), (Some(3), (0, 6)));
    }

    #[test]
    fn tail_range_brackets_the_distance() {
        let g = UnitTile::new(0.0);
        let (a, b) = g.tail_range(5.0, 100).unwrap();
        assert!(a <= 3 && b >= 5, "{a} {b}");
        assert!(g.tail_range(100.0, 10).is_none());
    }
}
