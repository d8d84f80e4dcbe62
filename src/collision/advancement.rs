//! Checking a timed fold schedule ([`super::FoldSchedule`]) for self-intersection.
//!
//! Between breakpoints every joint turns at a constant rate, which bounds how fast any point
//! of tile `j` can move relative to tile `i`: by the sum over the moving joints `k` between
//! them of `|rate_k| * ((j - k) + r)` tile widths per second (`r` the circumradius), since a
//! point of tile `j` is at most that far from hinge `k`. Conservative advancement then steps
//! time by the parry2d distance between each close pair over that bound, so no contact can be
//! stepped over; pairs far apart are bounded together by the fastest tile. Pairs with no
//! moving joint between them keep their distance and are skipped. Tiles in neighbouring rigid
//! blocks turn about one hinge relative to each other and are checked exactly, as sequential
//! folding is.
//!
//! A sequential schedule (joints folding one at a time, in chain order) is handed to the
//! exact sweep check ([`super::check_word`]) and the contact angle is turned back into a time.

use kurbo::{Point, Rect};
use parry2d_f64::partitioning::{Bvh, BvhBuildStrategy};
use parry2d_f64::query;
use parry2d_f64::shape::ConvexPolygon;

use crate::{kinematics, FoldWord, Octagon, Pose};

use super::sweep::{first_contact_within, sector_box};
use super::{bounding_box, check_word, CheckOptions, Collision, FoldSchedule, ScheduleError};

/// Checks a chain folding along `schedule`: every pair of tiles with a moving joint between
/// them, at every moment, by conservative advancement on parry2d distances (or the exact
/// sweep check for a sequential schedule). Returns the first contact with its time.
pub fn check_schedule(
    word: &FoldWord,
    schedule: &FoldSchedule,
    opts: &CheckOptions,
) -> Result<(), ScheduleError> {
    schedule.validate(word)?;
    let mut tracks = schedule.clone();
    tracks.tracks.sort_by_key(|t| t.joint);
    if tracks.is_sequential_for(word) {
        return check_word(word, opts).map_err(|mut c| {
            if let Some(j) = c.joint {
                if let Some(tr) = tracks.tracks.iter().find(|t| t.joint == j) {
                    c.time = Some(tr.time_at_turn(c.angle_deg.to_radians()));
                }
            }
            ScheduleError::Collision(c)
        });
    }
    Advancer::new(word, &tracks, opts.tolerance).run()
}

/// Conservative advancement over a general schedule, at tile width 1.
struct Advancer<'a> {
    joints: usize,
    schedule: &'a FoldSchedule,
    shape: Option<ConvexPolygon>,
    radius: f64,
    tolerance: f64,
    breakpoints: Vec<f64>,
}

/// Margin by which tile boxes are grown to find close pairs, in tile widths: pairs further
/// apart cannot meet within a step in which no tile moves more than this. Larger margins take
/// fewer, longer steps over more pairs; 3 was the fastest of 0.25, 1, 3 and 8 on a
/// 1,000-tile serpentine folding all at once (s = 0) and with overlapping folds (s = 0.1).
const MARGIN: f64 = 3.0;
/// Distance (tile widths, between inset outlines) at which two tiles count as in contact.
const CONTACT: f64 = 1e-12;
/// Work budget of the conservative advancement of one check, in tile-steps (steps times
/// tiles): about a minute of work; past it the check reports [`ScheduleError::Undecided`].
const MAX_WORK: usize = 400_000_000;

/// Which pairs conservative advancement follows.
#[derive(Clone, Copy)]
enum PairSet {
    /// Pairs two or more rigid blocks apart (neighbouring blocks are checked exactly).
    BlocksApart,
    /// Every pair with a moving joint between them.
    AllMoving,
}

impl<'a> Advancer<'a> {
    fn new(word: &FoldWord, schedule: &'a FoldSchedule, tolerance: f64) -> Advancer<'a> {
        let mut breakpoints: Vec<f64> = schedule
            .tracks
            .iter()
            .flat_map(|t| t.times.iter().copied())
            .collect();
        breakpoints.sort_by(f64::total_cmp);
        breakpoints.dedup();
        let o = Octagon::new(1.0);
        Advancer {
            joints: word.joints(),
            schedule,
            shape: o.to_parry(tolerance),
            radius: o.circumradius(),
            tolerance,
            breakpoints,
        }
    }

    /// Walks the schedule segment by segment (between breakpoints every joint turns at a
    /// constant rate). The moving joints cut the chain into blocks that are rigid during the
    /// segment. Tiles in neighbouring blocks turn about one hinge relative to each other, which
    /// is checked exactly (first contact of vertex arcs with edges, as for sequential
    /// folding); tiles two or more blocks apart move in a compound way and are checked by
    /// conservative advancement.
    fn run(&self) -> Result<(), ScheduleError> {
        let Some(shape) = &self.shape else {
            return Ok(());
        };
        let mut steps = 0usize;
        for seg in 0..self.breakpoints.len().saturating_sub(1) {
            let (ta, tb) = (self.breakpoints[seg], self.breakpoints[seg + 1]);
            if tb <= ta {
                continue;
            }
            let a_start = self.schedule.angles_at(self.joints, ta);
            let a_end = self.schedule.angles_at(self.joints, tb);
            let moving: Vec<usize> = (0..self.joints)
                .filter(|&k| a_end[k] != a_start[k])
                .collect();
            if moving.is_empty() {
                continue;
            }
            // a joint crossing straight within the segment changes hinge: no single rotation
            let single_hinge = moving.iter().all(|&k| a_start[k] * a_end[k] >= 0.0);
            let exact = if single_hinge {
                self.exact_rotations(&moving, &a_start, &a_end, ta, tb)
            } else {
                None
            };
            let limit = exact.as_ref().map_or(tb, |c| c.time.unwrap_or(tb));
            let pairs = if single_hinge {
                PairSet::BlocksApart
            } else {
                PairSet::AllMoving
            };
            if single_hinge && moving.len() < 2 {
                if let Some(c) = exact {
                    return Err(ScheduleError::Collision(c));
                }
                continue;
            }
            match self.advance(shape, ta, limit, &moving, pairs, &mut steps)? {
                Some(c) => return Err(ScheduleError::Collision(c)),
                None => {
                    if let Some(c) = exact {
                        return Err(ScheduleError::Collision(c));
                    }
                }
            }
        }
        Ok(())
    }

    /// The first contact, within `[ta, tb]`, between tiles of neighbouring blocks: for each
    /// moving joint `k`, the block after it turns about hinge `k` relative to the block before.
    fn exact_rotations(
        &self,
        moving: &[usize],
        a_start: &[f64],
        a_end: &[f64],
        ta: f64,
        tb: f64,
    ) -> Option<Collision> {
        let n = self.joints + 1;
        let poses = kinematics::poses_at_angles(a_start, 1.0);
        let o = Octagon::new(1.0);
        let inset = o.inset_vertices(self.tolerance);
        let r = self.radius;
        let outline = |p: &Pose| -> [Point; 8] { inset.map(|v| Point::from(p.transform_point(v))) };
        let centre = |p: &Pose| Point::new(p.x, p.y);
        let mut best: Option<(f64, usize, usize, usize, f64)> = None; // (time, i, j, joint, angle)
        for (b, &k) in moving.iter().enumerate() {
            let lo = if b == 0 { 0 } else { moving[b - 1] + 1 };
            let hi = moving.get(b + 1).copied().unwrap_or(n - 1);
            let dtheta = a_end[k] - a_start[k];
            let left = a_start[k] + a_end[k] > 0.0;
            let pivot = Point::from(poses[k].transform_point(o.hinge(left)));
            let boxes: Vec<_> = (lo..=k)
                .map(|i| {
                    let c = centre(&poses[i]);
                    bounding_box(Rect::from_points(c, c).inflate(r, r))
                })
                .collect();
            let bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &boxes);
            for j in k + 1..=hi {
                let c = centre(&poses[j]);
                let rr = (c - pivot).hypot2().sqrt();
                let a0 = (c - pivot).atan2();
                let (s0, s1) = if dtheta >= 0.0 {
                    (a0, a0 + dtheta)
                } else {
                    (a0 + dtheta, a0)
                };
                let query = bounding_box(sector_box(pivot, rr, s0, s1).inflate(r, r));
                let mut moving_outline: Option<[Point; 8]> = None;
                for i in bvh.intersect_aabb(&query) {
                    let i = lo + i as usize;
                    if i == k && j == k + 1 {
                        continue; // hinged neighbours
                    }
                    let ci = centre(&poses[i]);
                    let d = (ci - pivot).hypot2().sqrt();
                    if (d - rr).abs() > 2.0 * r + 1e-9 {
                        continue;
                    }
                    let mv = moving_outline.get_or_insert_with(|| outline(&poses[j]));
                    let fixed = outline(&poses[i]);
                    if let Some(phi) = first_contact_within(mv, c, &fixed, ci, r, pivot, dtheta) {
                        let t = ta + (tb - ta) * phi / dtheta.abs();
                        let angle = (a_start[k] + dtheta.signum() * phi).abs().to_degrees();
                        if best.is_none_or(|bst| t < bst.0) {
                            best = Some((t, i, j, k, angle));
                        }
                    }
                }
            }
        }
        best.map(|(t, i, j, k, angle)| Collision {
            joint: Some(k),
            angle_deg: angle,
            time: Some(t),
            tiles: (i, j),
        })
    }

    /// Conservative advancement over `[ta, limit]` for the pairs `which` selects.
    fn advance(
        &self,
        shape: &ConvexPolygon,
        ta: f64,
        limit: f64,
        moving: &[usize],
        which: PairSet,
        steps: &mut usize,
    ) -> Result<Option<Collision>, ScheduleError> {
        let n = self.joints + 1;
        let span = (limit - ta).max(f64::MIN_POSITIVE);
        let a0 = self.schedule.angles_at(self.joints, ta);
        let a1 = self.schedule.angles_at(self.joints, limit);
        let mut rates = vec![0.0; self.joints];
        for &k in moving {
            rates[k] = ((a1[k] - a0[k]) / span).abs();
        }
        // block of each tile: how many moving joints lie before it
        let mut block = vec![0usize; n];
        for j in 1..n {
            block[j] = block[j - 1] + usize::from(rates[j - 1] > 0.0);
        }
        let selected = |i: usize, j: usize| match which {
            PairSet::BlocksApart => block[j] >= block[i] + 2,
            PairSet::AllMoving => block[j] > block[i],
        };
        // prefix sums for the pair speed bound: sum_{k in [i, j)} w_k ((j - k) + r)
        let mut rate_sum = vec![0.0; n];
        let mut index_rate_sum = vec![0.0; n];
        for k in 0..self.joints {
            rate_sum[k + 1] = rate_sum[k] + rates[k];
            index_rate_sum[k + 1] = index_rate_sum[k] + rates[k] * k as f64;
        }
        let bound = |i: usize, j: usize| -> f64 {
            let w = rate_sum[j] - rate_sum[i];
            let kw = index_rate_sum[j] - index_rate_sum[i];
            j as f64 * w - kw + self.radius * w
        };
        let fastest = (1..n).map(|j| bound(0, j)).fold(0.0, f64::max);
        let budget = (MAX_WORK / n.max(1)).max(1000);
        let mut grid: std::collections::HashMap<(i64, i64), Vec<u32>> =
            std::collections::HashMap::new();
        let mut t = ta;
        while t < limit {
            let angles = self.schedule.angles_at(self.joints, t);
            let poses = kinematics::poses_at_angles(&angles, 1.0);
            // close pairs by a uniform grid of cell size 2 (r + margin): any two tiles whose
            // grown boxes overlap sit in the same or neighbouring cells (O(n) per step, no tree
            // to rebuild)
            let cell = 2.0 * (self.radius + MARGIN);
            grid.clear();
            for (j, p) in poses.iter().enumerate() {
                grid.entry(((p.x / cell).floor() as i64, (p.y / cell).floor() as i64))
                    .or_default()
                    .push(j as u32);
            }
            let mut dt = (limit - t).min(if fastest > 0.0 {
                MARGIN / fastest
            } else {
                f64::INFINITY
            });
            let reach = 2.0 * (self.radius + MARGIN);
            for (j, pj) in poses.iter().enumerate() {
                let (cx, cy) = ((pj.x / cell).floor() as i64, (pj.y / cell).floor() as i64);
                for gx in cx - 1..=cx + 1 {
                    for gy in cy - 1..=cy + 1 {
                        let Some(list) = grid.get(&(gx, gy)) else {
                            continue;
                        };
                        for &i in list {
                            let i = i as usize;
                            if i + 2 > j || !selected(i, j) {
                                continue; // each pair once; hinged neighbours and rigid pairs skipped
                            }
                            let pi = &poses[i];
                            if (pi.x - pj.x).abs() > reach || (pi.y - pj.y).abs() > reach {
                                continue;
                            }
                            let v = bound(i, j);
                            let d = distance(shape, pi, pj);
                            if d <= CONTACT {
                                return Ok(Some(self.collision(i, j, t, &angles, &rates)));
                            }
                            dt = dt.min(d / v);
                        }
                    }
                }
            }
            *steps += 1;
            if *steps > budget {
                return Err(ScheduleError::Undecided {
                    steps: *steps,
                    time: t,
                });
            }
            t += dt.max(1e-15 * (1.0 + t.abs()));
        }
        Ok(None)
    }

    fn collision(&self, i: usize, j: usize, t: f64, angles: &[f64], rates: &[f64]) -> Collision {
        let joint = (i..j)
            .filter(|&k| rates[k] > 0.0)
            .max_by(|&a, &b| rates[a].total_cmp(&rates[b]));
        Collision {
            joint,
            angle_deg: joint.map_or(0.0, |k| angles[k].abs().to_degrees()),
            time: Some(t),
            tiles: (i, j),
        }
    }
}

fn distance(shape: &ConvexPolygon, a: &Pose, b: &Pose) -> f64 {
    query::distance(&a.to_parry(), shape, &b.to_parry(), shape).unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;
    use crate::collision::JointTrack;

    fn word(s: &str) -> FoldWord {
        FoldWord::parse(s).unwrap()
    }

    /// Every joint folding at once, linearly over one second.
    fn simultaneous(w: &FoldWord) -> FoldSchedule {
        FoldSchedule {
            tracks: w
                .folds()
                .iter()
                .enumerate()
                .filter(|(_, f)| f.quarter_turns() != 0)
                .map(|(joint, f)| JointTrack {
                    joint,
                    times: vec![0.0, 1.0],
                    angles: vec![0.0, f.quarter_turns() as f64 * FRAC_PI_2],
                })
                .collect(),
        }
    }

    #[test]
    fn sequential_schedule_uses_exact_check_and_reports_time() {
        let w = word("LLLL");
        let e = check_schedule(
            &w,
            &FoldSchedule::sequential(&w, 2.0),
            &CheckOptions::default(),
        )
        .unwrap_err();
        let ScheduleError::Collision(c) = e else {
            panic!("{e}")
        };
        assert_eq!(c.joint, Some(2));
        let t = c.time.unwrap();
        assert!(t > 4.0 && t < 6.0, "{t}"); // joint 2 folds from t = 4 s to 6 s
        assert!(check_schedule(
            &word("LLL"),
            &FoldSchedule::sequential(&word("LLL"), 1.0),
            &CheckOptions::default()
        )
        .is_ok());
    }

    #[test]
    fn simultaneous_ring_closes_touching() {
        let w = word("LLL");
        assert!(check_schedule(&w, &simultaneous(&w), &CheckOptions::default()).is_ok());
    }

    #[test]
    fn simultaneous_five_in_a_ring_collides_before_the_end() {
        let w = word("LLLL");
        match check_schedule(&w, &simultaneous(&w), &CheckOptions::default()) {
            Err(ScheduleError::Collision(c)) => {
                assert_eq!(c.tiles, (0, 4));
                let t = c.time.unwrap();
                assert!(t > 0.0 && t < 1.0, "{t}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn general_advancement_agrees_with_exact_sweeps() {
        // the same sequential folding, but with a pause in each track so that it is not
        // recognised as sequential: both methods must agree on every word of 5 and 6 tiles.
        for n in [5usize, 6] {
            let mut letters = vec![crate::Fold::S; n - 1];
            let total = 3usize.pow((n - 1) as u32);
            for code in 0..total {
                let mut c = code;
                for l in letters.iter_mut() {
                    *l = crate::Fold::ALL[c % 3];
                    c /= 3;
                }
                let w = FoldWord::from_folds(letters.clone());
                let exact = check_word(&w, &CheckOptions::default()).is_ok();
                let mut s = FoldSchedule::sequential(&w, 1.0);
                for tr in &mut s.tracks {
                    // overlap each fold slightly with the next: not sequential any more
                    tr.times[1] += 0.02;
                }
                let general = match check_schedule(&w, &s, &CheckOptions::default()) {
                    Ok(()) => true,
                    Err(ScheduleError::Collision(_)) => false,
                    Err(e) => panic!("{w}: {e}"),
                };
                assert_eq!(exact, general, "word {w}");
            }
        }
    }

    #[test]
    fn bad_tracks_are_refused_before_any_check() {
        let s = FoldSchedule {
            tracks: vec![JointTrack {
                joint: 5,
                times: vec![0.0],
                angles: vec![0.0],
            }],
        };
        assert!(matches!(
            check_schedule(&word("SL"), &s, &CheckOptions::default()),
            Err(ScheduleError::BadTrack { joint: 5, .. })
        ));
    }
}
