//! How close a folding chain's tiles come: the smallest clearance between two tiles that are
//! not neighbours over a timed fold schedule ([`closest_approach`]), signed (negative: the
//! depth of an overlap), with the two tiles, the moment and the joint turning then.
//!
//! Each pair of tiles `i < j - 1` is followed on its own clock in the frame of tile `i`, where
//! tile `j` moves by the turns of the joints between them. Within a window of time every
//! joint turns no faster than its fastest chord there (the schedule's time is cut into
//! buckets, each joint's fastest chord noted per bucket), and a point of tile `j` lies at
//! most `2 R (j - k)` from the hinge of joint `k` (`R` the circumradius: a hinge is a vertex
//! of both its tiles, and consecutive centres are at most `2 R` apart), so the pair's
//! distance changes no faster than `V = sum_k |rate_k| 2 R (j - k)`. From a moment where the
//! pair is `d` apart and the smallest clearance found so far is `m`, the pair cannot come
//! closer than `m - precision` for `(d - m + precision) / V`: conservative advancement on the
//! minimum instead of on contact. The result is within `precision` above the true minimum
//! (plus a hundredth of the depth of an overlap), never below it. The distance of two octagons is
//! exact: separating axes for the overlap depth (the minimum translation of two convex
//! polygons lies along a face normal) and vertex to edge distances when apart.
//!
//! The work is bounded: at most [`MAX_TILES`] tiles (pairs are followed one by one, so the
//! cost grows with the square of the chain) and a budget of pair evaluations; past either
//! the clearance is not measured (`None`), never guessed.

use kurbo::Point;

use super::chain_tree::{turn_of, Rigid};
use super::{FoldSchedule, JointTrack};
use crate::Octagon;

/// The most tiles whose clearance is measured: 1,000 (half a million pairs).
pub(crate) const MAX_TILES: usize = 1_000;

/// Pair evaluations a measurement may take: 30 million (a few seconds).
pub(crate) const MAX_WORK: usize = 30_000_000;

/// Buckets the schedule's time is cut into for the joints' rate bounds.
const BUCKETS: usize = 4096;

/// The closest approach of two tiles that are not neighbours, tile widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Closest {
    /// The clearance, tile widths: negative for an overlap, its depth.
    pub(crate) distance: f64,
    /// When (the schedule's time), s.
    pub(crate) time: f64,
    /// The two tiles, lower first.
    pub(crate) tiles: (usize, usize),
    /// The fold front then: the highest joint between the tiles that turns and whose fold
    /// goes on, else the highest that turns; `None` when none turns (the chain at rest).
    pub(crate) joint: Option<usize>,
}

/// The smallest clearance between two tiles of a `tiles`-tile chain that are not neighbours,
/// over `schedule` (validated) and the shape it ends in, within `precision` tile widths;
/// `None` for a chain of more than [`MAX_TILES`] tiles or when the work budget ran out, and
/// for a chain of fewer than three tiles (no pair that is not neighbours).
pub(crate) fn closest_approach(
    tiles: usize,
    schedule: &FoldSchedule,
    precision: f64,
) -> Option<Closest> {
    if !(3..=MAX_TILES).contains(&tiles) || precision.is_nan() || precision <= 0.0 {
        return None;
    }
    let joints = tiles - 1;
    let mut track_of: Vec<Option<&JointTrack>> = vec![None; joints];
    for tr in &schedule.tracks {
        if tr.joint < joints && !tr.times.is_empty() {
            track_of[tr.joint] = Some(tr);
        }
    }
    let rates = Rates::new(&track_of);
    let mut walk = PairWalk {
        track_of: &track_of,
        rates: &rates,
        precision,
        octagon: Octagon::new(1.0),
        circumradius: Octagon::new(1.0).circumradius(),
        work: 0,
        best: None,
        hints: vec![0; joints],
    };
    // a first bound from every pair at a few moments, then the pairs nearest first
    let samples = sample_times(&rates, tiles);
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for i in 0..tiles {
        for j in i + 2..tiles {
            let near = samples
                .iter()
                .map(|&t| walk.evaluate(i, j, t))
                .fold(f64::INFINITY, f64::min);
            pairs.push((near, i, j));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(_, i, j) in &pairs {
        if !walk.follow(i, j) {
            return None;
        }
    }
    walk.best
}

/// Moments at which every pair is looked at first: the schedule's start and end and evenly
/// between, fewer for long chains.
fn sample_times(rates: &Rates, tiles: usize) -> Vec<f64> {
    let pairs = tiles * tiles / 2;
    let k = (MAX_WORK / 10 / pairs.max(1)).clamp(2, 64);
    (0..k)
        .map(|s| rates.t0 + rates.span * s as f64 / (k - 1) as f64)
        .collect()
}

/// Each joint's fastest turn per bucket of time, and the moments a track jumps.
struct Rates {
    t0: f64,
    span: f64,
    width: f64,
    /// `fastest[k][b]`: joint `k`'s largest `|rate|` over the chords meeting bucket `b`.
    fastest: Vec<Vec<f64>>,
    /// Each joint's jumps (a repeated time with another angle), sorted.
    jumps: Vec<Vec<f64>>,
}

impl Rates {
    fn new(track_of: &[Option<&JointTrack>]) -> Rates {
        let (mut t0, mut t1) = (f64::INFINITY, f64::NEG_INFINITY);
        for tr in track_of.iter().flatten() {
            t0 = t0.min(tr.times[0]);
            t1 = t1.max(tr.times[tr.times.len() - 1]);
        }
        if !t0.is_finite() {
            (t0, t1) = (0.0, 0.0);
        }
        let span = t1 - t0;
        let width = span / BUCKETS as f64;
        let mut fastest = vec![Vec::new(); track_of.len()];
        let mut jumps = vec![Vec::new(); track_of.len()];
        for (k, tr) in track_of.iter().enumerate() {
            let Some(tr) = tr else { continue };
            let mut f = vec![0.0f64; BUCKETS];
            for w in 0..tr.times.len().saturating_sub(1) {
                let (ta, tb) = (tr.times[w], tr.times[w + 1]);
                let da = (tr.angles[w + 1] - tr.angles[w]).abs();
                if da == 0.0 {
                    continue;
                }
                if tb <= ta {
                    jumps[k].push(ta);
                    continue;
                }
                let rate = da / (tb - ta);
                let (ba, bb) = (bucket(t0, width, ta), bucket(t0, width, tb));
                for v in &mut f[ba..=bb] {
                    *v = v.max(rate);
                }
            }
            fastest[k] = f;
            jumps[k].dedup();
        }
        Rates {
            t0,
            span,
            width,
            fastest,
            jumps,
        }
    }

    /// The bucket holding `t`.
    fn bucket(&self, t: f64) -> usize {
        bucket(self.t0, self.width, t)
    }

    /// When bucket `b` ends.
    fn bucket_end(&self, b: usize) -> f64 {
        if b + 1 >= BUCKETS {
            f64::INFINITY
        } else {
            self.t0 + self.width * (b + 1) as f64
        }
    }
}

fn bucket(t0: f64, width: f64, t: f64) -> usize {
    if width.is_nan() || width <= 0.0 || t <= t0 {
        return 0;
    }
    (((t - t0) / width) as usize).min(BUCKETS - 1)
}

/// The pairs' walk: the schedule, its rate bounds, and the smallest clearance so far.
struct PairWalk<'a> {
    track_of: &'a [Option<&'a JointTrack>],
    rates: &'a Rates,
    precision: f64,
    octagon: Octagon,
    circumradius: f64,
    work: usize,
    best: Option<Closest>,
    /// Each joint's chord hint ([`JointTrack::chord_at`]).
    hints: Vec<usize>,
}

impl PairWalk<'_> {
    /// Joint `k`'s angle at `t`.
    fn angle(&mut self, k: usize, t: f64) -> f64 {
        match self.track_of[k] {
            Some(tr) => tr.chord_at(t, &mut self.hints[k]).0,
            None => 0.0,
        }
    }

    /// Tile `j`'s pose in tile `i`'s frame at `t`.
    fn pose(&mut self, i: usize, j: usize, t: f64) -> Rigid {
        let mut at = Rigid::IDENTITY;
        for k in i..j {
            let a = self.angle(k, t);
            at = at.then(&turn_of(a));
        }
        at
    }

    /// The signed distance of tiles `i` and `j` at `t`, tile widths; the best updated.
    fn evaluate(&mut self, i: usize, j: usize, t: f64) -> f64 {
        self.work += 1;
        let pose = self.pose(i, j, t);
        let d = signed_distance(&self.octagon, &pose);
        if self.best.is_none_or(|b| d < b.distance) {
            let joint = self.front(i, j, t);
            self.best = Some(Closest {
                distance: d,
                time: t,
                tiles: (i, j),
                joint,
            });
        }
        d
    }

    /// The fold front between tiles `i` and `j` at `t`.
    fn front(&mut self, i: usize, j: usize, t: f64) -> Option<usize> {
        let mut turning = None;
        for k in (i..j).rev() {
            let Some(tr) = self.track_of[k] else { continue };
            if tr.chord_at(t, &mut self.hints[k]).1 == 0.0 {
                continue;
            }
            if tr.ended.is_none_or(|e| e > t) {
                return Some(k);
            }
            turning = turning.or(Some(k));
        }
        turning
    }

    /// Follows pair `(i, j)` over the schedule; `false` when the work budget ran out.
    fn follow(&mut self, i: usize, j: usize) -> bool {
        let moving: Vec<usize> = (i..j).filter(|&k| self.track_of[k].is_some()).collect();
        let (t0, t_end) = (self.rates.t0, self.rates.t0 + self.rates.span);
        if moving.is_empty() {
            self.evaluate(i, j, t0);
            return true;
        }
        // each moving joint's lever: 2 R (j - k)
        let lever: Vec<f64> = moving
            .iter()
            .map(|&k| 2.0 * self.circumradius * (j - k) as f64)
            .collect();
        let mut fastest = vec![0.0f64; moving.len()];
        let mut t = t0;
        loop {
            if self.work > MAX_WORK {
                return false;
            }
            let d = self.evaluate(i, j, t);
            if t >= t_end {
                return true;
            }
            let m = self.best.map_or(d, |b| b.distance);
            // an overlap is measured to a hundredth of its depth besides the precision (a
            // tile passing through another keeps a flat depth that would cost a step per
            // precision)
            let room = d - m + self.precision + OVERLAP_PRECISION * (-m).max(0.0);
            // no step crosses a jump of a joint between the tiles
            let mut jump = t_end;
            for &k in &moving {
                let jumps = &self.rates.jumps[k];
                if let Some(&x) = jumps.get(jumps.partition_point(|&x| x <= t)) {
                    jump = jump.min(x);
                }
            }
            // the rate bound over buckets b..=bb, widened while the step it allows reaches
            // past them (at most MAX_WIDEN buckets a step)
            let b = self.rates.bucket(t);
            fastest.iter_mut().for_each(|f| *f = 0.0);
            let mut bb = b;
            let next = loop {
                self.work += 1;
                let mut speed = 0.0;
                for (q, &k) in moving.iter().enumerate() {
                    fastest[q] = fastest[q].max(self.rates.fastest[k][bb]);
                    speed += fastest[q] * lever[q];
                }
                let limit = self.rates.bucket_end(bb).min(jump);
                let reach = if speed > 0.0 {
                    t + room / speed
                } else {
                    f64::INFINITY
                };
                let settled =
                    reach < limit || limit >= jump || bb + 1 >= BUCKETS || bb - b >= MAX_WIDEN;
                // (a bucket that ends at t by rounding is passed)
                if settled && limit > t {
                    break reach.min(limit);
                }
                bb += 1;
            };
            // progress whatever the rounding
            t = if next > t {
                next.min(t_end)
            } else {
                t + 1e-15 * t.abs().max(1.0)
            };
        }
    }
}

/// The precision of an overlap's depth, besides the absolute one: a hundredth of it.
const OVERLAP_PRECISION: f64 = 0.01;

/// The most buckets one step of a pair may span.
const MAX_WIDEN: usize = 256;

/// The signed distance between the unit octagon at the origin and the one at `pose`: the
/// gap when apart, minus the overlap depth (the least translation that parts them) when
/// they overlap.
fn signed_distance(octagon: &Octagon, pose: &Rigid) -> f64 {
    let a: [Point; 8] = octagon.vertices().map(|(x, y)| Point::new(x, y));
    let b: [Point; 8] = a.map(|p| pose.apply(p));
    // separating axes: the face normals of both
    let mut sep = f64::NEG_INFINITY;
    for poly in [&a, &b] {
        for e in 0..8 {
            let (p, q) = (poly[e], poly[(e + 1) % 8]);
            let n = kurbo::Vec2::new(q.y - p.y, p.x - q.x).normalize();
            let (mut a0, mut a1) = (f64::INFINITY, f64::NEG_INFINITY);
            let (mut b0, mut b1) = (f64::INFINITY, f64::NEG_INFINITY);
            for v in &a {
                let x = v.to_vec2().dot(n);
                a0 = a0.min(x);
                a1 = a1.max(x);
            }
            for v in &b {
                let x = v.to_vec2().dot(n);
                b0 = b0.min(x);
                b1 = b1.max(x);
            }
            sep = sep.max((b0 - a1).max(a0 - b1));
        }
    }
    if sep <= 0.0 {
        return sep;
    }
    // apart: the nearest vertex of either to an edge of the other
    let mut d = f64::INFINITY;
    for (p, q) in [(&a, &b), (&b, &a)] {
        for v in p.iter() {
            for e in 0..8 {
                d = d.min(segment_distance(*v, q[e], q[(e + 1) % 8]));
            }
        }
    }
    d
}

fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.hypot2()).clamp(0.0, 1.0);
    (p - (a + ab * t)).hypot()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;
    use crate::collision::{check_schedule, CheckOptions, ScheduleError};
    use crate::FoldWord;

    #[test]
    fn distances_of_two_octagons() {
        let o = Octagon::new(1.0);
        let at = |x: f64, y: f64, _a: f64| shift(x, y);
        fn shift(x: f64, y: f64) -> Rigid {
            // a translation as the composition of two half turns
            Rigid::rotation_about(Point::new(x / 2.0, y / 2.0), std::f64::consts::PI)
                .then(&Rigid::rotation_about(Point::ORIGIN, std::f64::consts::PI))
        }
        // face to face: touching at 1, apart by 0.25 at 1.25, overlapping by 0.25 at 0.75
        assert!(signed_distance(&o, &at(1.0, 0.0, 0.0)).abs() < 1e-12);
        assert!((signed_distance(&o, &at(1.25, 0.0, 0.0)) - 0.25).abs() < 1e-12);
        assert!((signed_distance(&o, &at(0.75, 0.0, 0.0)) + 0.25).abs() < 1e-12);
        // diagonal faces: the 45 degree face's distance along the diagonal
        // along the diagonal the 45 degree faces meet at a centre distance of 1
        let r = 1.0 / std::f64::consts::SQRT_2;
        let d = signed_distance(&o, &at(r + 0.1, r + 0.1, 0.0));
        assert!((d - 0.1 * std::f64::consts::SQRT_2).abs() < 1e-12, "{d}");
    }

    fn track(joint: usize, times: &[f64], angles: &[f64]) -> JointTrack {
        JointTrack {
            joint,
            times: times.to_vec(),
            angles: angles.to_vec(),
            ended: times.last().copied(),
        }
    }

    #[test]
    fn a_ring_closes_touching() {
        // LLL: the last tile closes face to face on the first: clearance 0 at the end
        let s = FoldSchedule {
            tracks: (0..3)
                .map(|k| track(k, &[k as f64, k as f64 + 1.0], &[0.0, FRAC_PI_2]))
                .collect(),
        };
        let c = closest_approach(4, &s, 1e-6).unwrap();
        assert!(c.distance.abs() <= 1e-6, "{c:?}");
        assert_eq!(c.tiles, (0, 3));
    }

    /// The clearance agrees with the collision check (an overlap exactly when the check finds
    /// a contact) and with a dense sampling of every pair (never above the smallest sample,
    /// and near it).
    #[test]
    fn clearances_agree_with_the_check_and_with_sampling() {
        let mut rng = crate::collision::xorshift(7);
        let mut unit = move || (rng() % 1_000_000) as f64 / 1_000_000.0;
        let (mut apart, mut overlapping) = (0, 0);
        for case in 0..60 {
            let n = 5 + case % 5;
            let letters: Vec<char> = (0..n - 1)
                .map(|_| ['S', 'L', 'R', 'L', 'R'][(unit() * 5.0) as usize % 5])
                .collect();
            let word: String = letters.iter().collect();
            let Ok(w) = FoldWord::parse(&word) else {
                continue;
            };
            let tracks: Vec<JointTrack> = letters
                .iter()
                .enumerate()
                .filter(|(_, c)| **c != 'S')
                .map(|(k, c)| {
                    let target = if *c == 'L' { FRAC_PI_2 } else { -FRAC_PI_2 };
                    let start = unit() * 2.0;
                    let mid = start + 0.1 + unit();
                    let end = mid + 0.1 + unit();
                    track(k, &[start, mid, end], &[0.0, target * unit(), target])
                })
                .collect();
            let s = FoldSchedule { tracks };
            // 3 um on 30 mm tiles (a tile turning about a vertex of the other keeps its
            // distance: a flat minimum, a step per precision while it lasts)
            let precision = 1e-4;
            let c = closest_approach(n, &s, precision).unwrap();
            // every pair at 2,001 moments
            let rates = Rates::new(&{
                let mut t: Vec<Option<&JointTrack>> = vec![None; n - 1];
                for tr in &s.tracks {
                    t[tr.joint] = Some(tr);
                }
                t
            });
            let mut sampled = f64::INFINITY;
            let o = Octagon::new(1.0);
            for q in 0..=2000 {
                let t = rates.t0 + rates.span * q as f64 / 2000.0;
                let angles = s.angles_at(n - 1, t);
                for i in 0..n {
                    let mut at = Rigid::IDENTITY;
                    for j in i + 1..n {
                        at = at.then(&turn_of(angles[j - 1]));
                        if j >= i + 2 {
                            sampled = sampled.min(signed_distance(&o, &at));
                        }
                    }
                }
            }
            let slack = precision + 0.01 * (-sampled).max(0.0);
            assert!(c.distance <= sampled + slack, "{word}: {c:?} {sampled}");
            assert!(c.distance >= sampled - 0.02, "{word}: {c:?} {sampled}");
            let hit = matches!(
                check_schedule(&w, &s, &CheckOptions::default().with_tolerance(1e-9)),
                Err(ScheduleError::Collision(_))
            );
            if c.distance > precision {
                assert!(!hit, "{word}: {c:?}");
                apart += 1;
            } else if c.distance < -precision {
                assert!(hit, "{word}: {c:?}");
                overlapping += 1;
            }
        }
        assert!(apart >= 10 && overlapping >= 10, "{apart} {overlapping}");
    }
}
