//! The thesis' folding order: joints fold one after another from the reaction-initiator end.
//!
//! While joint `k` folds, tiles `0..=k` already sit at their final poses and tiles after `k`
//! form a straight tail that turns 90 degrees about joint `k`'s hinge. A fixed tile can only
//! meet a tail tile whose centre passes at a similar distance from the hinge, so for each
//! fixed tile near the swept sector (found with a parry2d BVH) only a handful of tail tiles
//! are tested, each in closed form ([`super::sweep::first_contact`]).

use std::f64::consts::FRAC_PI_2;

use parry2d_f64::bounding_volume::Aabb;
use parry2d_f64::math::Vector;
use parry2d_f64::partitioning::Bvh;

use crate::exact::{ExactPose, QuarterTurns};
use crate::{kinematics, Chain, FoldWord, Octagon};

use super::sweep::{first_contact_within, quarter_contact_within, V2};
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

/// Geometry shared by the sweep checks, at tile width 1.
pub(crate) struct TileGeometry {
    /// Inset outline, centred at the origin (the octagon is symmetric under quarter turns, so
    /// the heading does not change it).
    pub outline: [V2; 8],
    /// Circumradius of the full outline.
    pub radius: f64,
    /// Half the side, the hinge's offset across the chain.
    pub half_side: f64,
}

impl TileGeometry {
    pub fn new(tolerance: f64) -> TileGeometry {
        let o = Octagon::new(1.0);
        TileGeometry {
            outline: o.inset_vertices(tolerance),
            radius: o.circumradius(),
            half_side: 0.5 * o.side(),
        }
    }

    /// Whether a tile centred at `fixed`, and one centred at `moving` turning a quarter turn
    /// about `pivot` (the way `theta`'s sign says), can meet at all: the moving centre stays
    /// in the quadrant spanned by its start direction and that direction turned, so the fixed
    /// centre must be within two circumradii of that quadrant.
    pub fn may_meet(&self, moving: V2, fixed: V2, pivot: V2, theta: f64) -> bool {
        let (mx, my) = (moving.0 - pivot.0, moving.1 - pivot.1);
        let rr = (mx * mx + my * my).sqrt();
        if rr == 0.0 {
            return true;
        }
        let u0 = (mx / rr, my / rr);
        let u1 = if theta >= 0.0 {
            (-u0.1, u0.0)
        } else {
            (u0.1, -u0.0)
        };
        let p = (fixed.0 - pivot.0, fixed.1 - pivot.1);
        let margin = -2.0 * self.radius - 1e-9;
        p.0 * u0.0 + p.1 * u0.1 >= margin && p.0 * u1.0 + p.1 * u1.1 >= margin
    }

    pub fn at(&self, c: V2) -> [V2; 8] {
        self.outline.map(|(x, y)| (x + c.0, y + c.1))
    }

    /// Range of tail offsets `t` (tile `k + 1 + t`) whose centres pass within `2 r` of the
    /// distance `d` from the hinge; the tail centre `t` is at distance
    /// `sqrt((1/2 + t)^2 + (half_side)^2)`.
    pub fn tail_range(&self, d: f64, tail_len: usize) -> Option<(usize, usize)> {
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

pub(crate) fn unit(h: QuarterTurns) -> V2 {
    match h.get() {
        0 => (1.0, 0.0),
        1 => (0.0, 1.0),
        2 => (-1.0, 0.0),
        _ => (0.0, -1.0),
    }
}

/// The axis-aligned box of the sector swept by points within `radius` of the pivot at angles
/// in `[a0, a1]` (radians, `a0 <= a1`).
pub(crate) fn sector_box(pivot: V2, radius: f64, a0: f64, a1: f64) -> (V2, V2) {
    let mut lo = pivot;
    let mut hi = pivot;
    let mut add = |a: f64| {
        let p = (pivot.0 + radius * a.cos(), pivot.1 + radius * a.sin());
        lo = (lo.0.min(p.0), lo.1.min(p.1));
        hi = (hi.0.max(p.0), hi.1.max(p.1));
    };
    add(a0);
    add(a1);
    let mut k = (a0 / FRAC_PI_2).ceil();
    while k * FRAC_PI_2 <= a1 {
        add(k * FRAC_PI_2);
        k += 1.0;
    }
    (lo, hi)
}

struct Sweeper<'a> {
    poses: &'a [ExactPose],
    centres: Vec<V2>,
    geo: TileGeometry,
    bvh: Bvh,
    inserted: usize,
}

impl<'a> Sweeper<'a> {
    fn new(poses: &'a [ExactPose], tolerance: f64) -> Sweeper<'a> {
        Sweeper {
            poses,
            centres: poses.iter().map(|p| p.centre.to_f64(1.0)).collect(),
            geo: TileGeometry::new(tolerance),
            bvh: Bvh::new(),
            inserted: 0,
        }
    }

    fn run(mut self, word: &FoldWord) -> Result<(), Collision> {
        for (k, &fold) in word.folds().iter().enumerate() {
            // tiles 0..=k are in place for this sweep and every later one
            while self.inserted <= k {
                let c = self.centres[self.inserted];
                let r = self.geo.radius;
                let aabb = Aabb::new(Vector::new(c.0 - r, c.1 - r), Vector::new(c.0 + r, c.1 + r));
                self.bvh.insert(aabb, self.inserted as u32);
                self.inserted += 1;
            }
            let Some(hinge) = kinematics::exact_hinge(self.poses[k], fold) else {
                continue;
            };
            if let Some(c) = self.sweep(
                k,
                hinge.to_f64(1.0),
                fold.quarter_turns() as f64 * FRAC_PI_2,
            ) {
                return Err(c);
            }
        }
        Ok(())
    }

    /// Checks the sweep of joint `k` about `pivot` by `theta`; the first contact, if any.
    fn sweep(&self, k: usize, pivot: V2, theta: f64) -> Option<Collision> {
        let n = self.centres.len();
        let tail_len = n - k - 1;
        let ck = self.centres[k];
        let u = unit(self.poses[k].heading);
        let tail_centre = |t: usize| -> V2 {
            let s = (t + 1) as f64;
            (ck.0 + s * u.0, ck.1 + s * u.1)
        };
        // the sector the tail's centres sweep
        let first = tail_centre(0);
        let last = tail_centre(tail_len - 1);
        let ang = |p: V2| (p.1 - pivot.1).atan2(p.0 - pivot.0);
        let base = ang(last);
        let mut a_first = ang(first);
        // keep the two angles on the same branch
        while a_first - base > std::f64::consts::PI {
            a_first -= std::f64::consts::TAU;
        }
        while base - a_first > std::f64::consts::PI {
            a_first += std::f64::consts::TAU;
        }
        let (mut a0, mut a1) = (base.min(a_first), base.max(a_first));
        if theta >= 0.0 {
            a1 += theta;
        } else {
            a0 += theta;
        }
        let far = ((last.0 - pivot.0).powi(2) + (last.1 - pivot.1).powi(2)).sqrt();
        let (lo, hi) = sector_box(pivot, far, a0, a1);
        let r = self.geo.radius;
        let query = Aabb::new(
            Vector::new(lo.0 - r, lo.1 - r),
            Vector::new(hi.0 + r, hi.1 + r),
        );

        let mut best: Option<(f64, usize, usize)> = None;
        for i in self.bvh.intersect_aabb(&query) {
            let i = i as usize;
            let ci = self.centres[i];
            let d = ((ci.0 - pivot.0).powi(2) + (ci.1 - pivot.1).powi(2)).sqrt();
            let Some((t0, t1)) = self.geo.tail_range(d, tail_len) else {
                continue;
            };
            let fixed = self.geo.at(ci);
            for t in t0..=t1 {
                let j = k + 1 + t;
                if i == k && j == k + 1 {
                    continue; // hinged neighbours: they only touch at the hinge and the closing walls
                }
                let c = tail_centre(t);
                if !self.geo.may_meet(c, ci, pivot, theta) {
                    continue;
                }
                let moving = self.geo.at(c);
                let r = self.geo.radius;
                if !quarter_contact_within(&moving, c, &fixed, ci, r, pivot, theta > 0.0) {
                    continue;
                }
                if let Some(phi) = first_contact_within(&moving, c, &fixed, ci, r, pivot, theta) {
                    if best.is_none_or(|(b, bi, bj)| (phi, i, j) < (b, bi, bj)) {
                        best = Some((phi, i, j));
                    }
                }
            }
        }
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
        let geo = TileGeometry::new(tolerance);
        let centres: Vec<V2> = poses.iter().map(|p| p.centre.to_f64(1.0)).collect();
        for (k, &fold) in word.folds().iter().enumerate() {
            let Some(h) = kinematics::exact_hinge(poses[k], fold) else {
                continue;
            };
            let pivot = h.to_f64(1.0);
            let theta = fold.quarter_turns() as f64 * FRAC_PI_2;
            let u = unit(poses[k].heading);
            let mut best: Option<(f64, usize, usize)> = None;
            for j in k + 1..centres.len() {
                let s = (j - k) as f64;
                let c = (centres[k].0 + s * u.0, centres[k].1 + s * u.1);
                for (i, &ci) in centres.iter().enumerate().take(k + 1) {
                    if i == k && j == k + 1 {
                        continue;
                    }
                    if let Some(phi) = first_contact_within(
                        &geo.at(c),
                        c,
                        &geo.at(ci),
                        ci,
                        geo.radius,
                        pivot,
                        theta,
                    ) {
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
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
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
    fn valid_final_shape_can_collide_while_folding() {
        // LSLLSR: the final shape is clean, but while joint 3 folds the still-straight tail
        // swings tile 6 through tile 0.
        let w = FoldWord::parse("LSLLSR").unwrap();
        assert!(check_word(&w, &CheckOptions::default().with_final_only(true)).is_ok());
        let c = check_word(&w, &CheckOptions::default()).unwrap_err();
        assert_eq!((c.joint, c.tiles), (Some(3), (0, 6)));
    }

    #[test]
    fn sector_box_covers_quadrant() {
        let (lo, hi) = sector_box((0.0, 0.0), 2.0, -0.1, FRAC_PI_2 + 0.1);
        assert!(
            lo.0 <= -0.19
                && lo.1 <= -0.19
                && (hi.0 - 2.0).abs() < 1e-12
                && (hi.1 - 2.0).abs() < 1e-12
        );
    }

    #[test]
    fn tail_range_brackets_the_distance() {
        let g = TileGeometry::new(0.0);
        let (a, b) = g.tail_range(5.0, 100).unwrap();
        assert!(a <= 3 && b >= 5, "{a} {b}");
        assert!(g.tail_range(100.0, 10).is_none());
    }
}
