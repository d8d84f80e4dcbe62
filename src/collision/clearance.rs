//! How close a folding chain's tiles come: the smallest clearance between two tiles that are
//! not neighbours over a timed fold schedule ([`closest_approach`]), signed (negative: the
//! depth of an overlap), with the two tiles, the moment and the joint turning then.
//!
//! Each pair of tiles `i < j - 1` is followed on its own clock in the frame of tile `i`, where
//! tile `j` moves by the turns of the joints between them. Within a window of time every
//! joint turns no faster than its fastest chord there (a track is piecewise linear, so over
//! one of its chords a joint turns at exactly the chord's rate), and a point of tile `j` lies at
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
//! Only the pairs that may come as near as the nearest pair of the final shape are followed
//! ([`super::clearance_pairs`] finds them without visiting every pair): the cost grows with
//! the pairs that come near (about linearly with the chain for a chain folding a few joints
//! at a time), not with the square of the chain, and the result is bit for bit what
//! following every pair gives. The work is bounded: at most [`MAX_TILES`] tiles and a budget
//! of pair evaluations that grows with the chain; past either the clearance is not measured
//! (`None`), never guessed.

use kurbo::Point;

use super::chain_tree::{turn_of, Rigid};
use super::{FoldSchedule, JointTrack};
use crate::Octagon;

/// The most tiles whose clearance is measured: ten million.
pub(crate) const MAX_TILES: usize = 10_000_000;

/// Pair evaluations a measurement may take at least: 30 million (a few seconds).
pub(crate) const MAX_WORK: usize = 30_000_000;

/// Pair evaluations a measurement may take per tile, for chains of more than a thousand
/// tiles (where [`MAX_WORK`] is less).
const WORK_PER_TILE: usize = 30_000;

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
///
/// Only the pairs that may come within a cutoff are followed: the cutoff is an upper bound
/// on the clearance in the shape the schedule ends in (the pairs nearest there, from their
/// centres: two octagons are at most their centres' distance less one inradius each apart),
/// and the pairs come from [`super::clearance_pairs`]. A pair left out never comes as near as
/// the pair that gave the cutoff, whose last sample is taken, so it could never have changed
/// the smallest clearance found: the result is bit for bit what following every pair gives
/// ([`all_pairs`], kept as the tests' oracle), at a cost that grows with the pairs that come
/// near rather than with all of them.
pub(crate) fn closest_approach(
    tiles: usize,
    schedule: &FoldSchedule,
    precision: f64,
) -> Option<Closest> {
    if !(3..=MAX_TILES).contains(&tiles) || precision.is_nan() || precision <= 0.0 {
        return None;
    }
    let joints = tiles - 1;
    let track_of = tracks_by_joint(joints, schedule);
    let rates = Rates::new(&track_of);
    let budget = work_budget(tiles);
    let mut walk = PairWalk::new(&track_of, &rates, precision, joints, budget);
    let samples = sample_times(&rates, tiles);
    let turns: Vec<Vec<Rigid>> = samples
        .iter()
        .map(|&t| (0..joints).map(|k| turn_of(walk.angle(k, t))).collect())
        .collect();
    let last = turns.last()?;
    let cutoff = final_cutoff(last);
    let candidates =
        super::clearance_pairs::pairs_within(tiles, &track_of, rates.t0, cutoff, budget)?;
    // a first bound from every candidate at a few moments (each pair's pose built along
    // the chain from tile `i`, the products `pose` forms, in its order), then the pairs
    // nearest first
    // (sixteen bytes a pair: a long serpentine has millions of candidates)
    let mut pairs: Vec<(f64, u32, u32)> = Vec::with_capacity(candidates.len());
    let mut row: Vec<f64> = Vec::new();
    let mut from = 0;
    while from < candidates.len() {
        let i = candidates[from].0 as usize;
        let to = from + candidates[from..].partition_point(|c| c.0 as usize == i);
        let reach = candidates[to - 1].1 as usize;
        // row[(j - i) * samples + s]: the distance of tiles i and j at sample s
        row.clear();
        row.resize((reach - i + 1) * samples.len(), f64::INFINITY);
        for (s, turns) in turns.iter().enumerate() {
            let mut at = Rigid::IDENTITY;
            let mut c = from;
            for j in i + 1..=reach {
                at = at.then(&turns[j - 1]);
                if c < to && candidates[c].1 as usize == j {
                    row[(j - i) * samples.len() + s] = walk.outline.signed_distance(&at);
                    c += 1;
                }
            }
        }
        walk.work += (reach - i) * samples.len();
        for &(ci, j) in &candidates[from..to] {
            pairs.push((walk.record_row(i, j as usize, &samples, &row), ci, j));
        }
        if walk.work > budget {
            return None;
        }
        from = to;
    }
    // nearest first, ties in the order of the tiles (the order a stable sort of the pairs,
    // pushed in the tiles' order, gives), without a stable sort's buffer
    pairs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    for &(_, i, j) in &pairs {
        if !walk.follow(i as usize, j as usize) {
            return None;
        }
    }
    walk.best
}

/// Each joint's track, by joint (`None`: the joint never turns).
fn tracks_by_joint(joints: usize, schedule: &FoldSchedule) -> Vec<Option<&JointTrack>> {
    let mut track_of: Vec<Option<&JointTrack>> = vec![None; joints];
    for tr in &schedule.tracks {
        if tr.joint < joints && !tr.times.is_empty() {
            track_of[tr.joint] = Some(tr);
        }
    }
    track_of
}

/// The work a measurement of a `tiles`-tile chain may take: [`MAX_WORK`], or
/// [`WORK_PER_TILE`] per tile for longer chains.
fn work_budget(tiles: usize) -> usize {
    MAX_WORK.max(tiles.saturating_mul(WORK_PER_TILE))
}

/// An upper bound on the smallest clearance of the shape at the joints' transforms `turns`
/// (with a slack over the rounding of world coordinates): the least distance between the
/// centres of two tiles that are not neighbours, less one inradius each (the octagons hold
/// their inscribed discs), over tiles `i` and `i + 2` and the pairs whose centres lie within
/// two widths (a grid of cells two widths wide).
fn final_cutoff(turns: &[Rigid]) -> f64 {
    let mut centres = Vec::with_capacity(turns.len() + 1);
    let mut at = Rigid::IDENTITY;
    centres.push(at.apply(Point::ORIGIN));
    for t in turns {
        at = at.then(t);
        centres.push(at.apply(Point::ORIGIN));
    }
    let mut best = f64::INFINITY;
    for i in 0..centres.len().saturating_sub(2) {
        best = best.min((centres[i + 2] - centres[i]).hypot() - 1.0);
    }
    let cell = |p: Point| ((p.x / 2.0).floor() as i64, (p.y / 2.0).floor() as i64);
    let mut grid: rustc_hash::FxHashMap<(i64, i64), Vec<usize>> = Default::default();
    for (i, &c) in centres.iter().enumerate() {
        grid.entry(cell(c)).or_default().push(i);
    }
    let mut extent = 0.0f64;
    for (i, &c) in centres.iter().enumerate() {
        extent = extent.max(c.to_vec2().hypot());
        let (x, y) = cell(c);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for &j in grid.get(&(x + dx, y + dy)).into_iter().flatten() {
                    if j >= i + 2 {
                        best = best.min((centres[j] - c).hypot() - 1.0);
                    }
                }
            }
        }
    }
    best + 1e-7 + 1e-12 * extent
}

/// The pair walk over every pair, as the measurement was before it followed only the pairs
/// that come near: the tests' oracle.
#[cfg(test)]
pub(crate) fn all_pairs(tiles: usize, schedule: &FoldSchedule, precision: f64) -> Option<Closest> {
    if tiles < 3 || precision.is_nan() || precision <= 0.0 {
        return None;
    }
    let joints = tiles - 1;
    let track_of = tracks_by_joint(joints, schedule);
    let rates = Rates::new(&track_of);
    let mut walk = PairWalk::new(&track_of, &rates, precision, joints, usize::MAX);
    let samples = sample_times(&rates, tiles);
    let turns: Vec<Vec<Rigid>> = samples
        .iter()
        .map(|&t| (0..joints).map(|k| turn_of(walk.angle(k, t))).collect())
        .collect();
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    let mut row: Vec<f64> = Vec::new();
    for i in 0..tiles {
        row.clear();
        row.resize((tiles - i) * samples.len(), f64::INFINITY);
        for (s, turns) in turns.iter().enumerate() {
            let mut at = Rigid::IDENTITY;
            for j in i + 1..tiles {
                at = at.then(&turns[j - 1]);
                if j >= i + 2 {
                    row[(j - i) * samples.len() + s] = walk.outline.signed_distance(&at);
                }
            }
        }
        for j in i + 2..tiles {
            pairs.push((walk.record_row(i, j, &samples, &row), i, j));
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

/// The schedule's span and the moments a track jumps.
struct Rates {
    t0: f64,
    span: f64,
    /// Each joint's jumps (a repeated time with another angle), sorted.
    jumps: Vec<Vec<f64>>,
    /// Each joint's chord rates ([`RateTable`]; empty for a joint that never turns).
    tables: Vec<RateTable>,
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
        let mut jumps = vec![Vec::new(); track_of.len()];
        for (k, tr) in track_of.iter().enumerate() {
            let Some(tr) = tr else { continue };
            for w in 0..tr.times.len().saturating_sub(1) {
                let (ta, tb) = (tr.times[w], tr.times[w + 1]);
                if tr.angles[w + 1] != tr.angles[w] && tb <= ta {
                    jumps[k].push(ta);
                }
            }
            jumps[k].dedup();
        }
        Rates {
            t0,
            span: t1 - t0,
            jumps,
            tables: track_of.iter().map(|tr| RateTable::new(*tr)).collect(),
        }
    }

    /// The first jump of the joints `moving` after `t`, or `end` if none comes before it.
    fn first_jump_after(&self, moving: &[usize], t: f64, end: f64) -> f64 {
        moving
            .iter()
            .filter_map(|&k| {
                let jumps = &self.jumps[k];
                jumps.get(jumps.partition_point(|&x| x <= t)).copied()
            })
            .fold(end, f64::min)
    }
}

/// The `|rate|` of the chord of `tr` that ends at its node `i` (0 before the track, after it
/// and over a jump) and when that chord ends (never, past the track's last node).
fn chord_from(tr: &JointTrack, i: usize) -> (f64, f64) {
    let (ts, a) = (&tr.times, &tr.angles);
    let n = ts.len();
    if i >= n {
        return (0.0, f64::INFINITY);
    }
    let rate = if i > 0 && ts[i] > ts[i - 1] {
        ((a[i] - a[i - 1]) / (ts[i] - ts[i - 1])).abs()
    } else {
        0.0
    };
    (rate, ts[i])
}

/// The pairs' walk: the schedule, its rate bounds, and the smallest clearance so far.
struct PairWalk<'a> {
    track_of: &'a [Option<&'a JointTrack>],
    rates: &'a Rates,
    precision: f64,
    outline: Outline,
    work: usize,
    budget: usize,
    best: Option<Closest>,
    /// Each joint's chord hint ([`JointTrack::chord_at`]).
    hints: Vec<usize>,
    /// Each joint's last angle and turn ([`PairWalk::turn`]).
    turns: Vec<Option<(f64, Rigid)>>,
}

impl<'a> PairWalk<'a> {
    fn new(
        track_of: &'a [Option<&'a JointTrack>],
        rates: &'a Rates,
        precision: f64,
        joints: usize,
        budget: usize,
    ) -> PairWalk<'a> {
        PairWalk {
            track_of,
            rates,
            precision,
            outline: Outline::unit(),
            work: 0,
            budget,
            best: None,
            hints: vec![0; joints],
            turns: vec![None; joints],
        }
    }

    /// Joint `k`'s angle at `t`.
    fn angle(&mut self, k: usize, t: f64) -> f64 {
        match self.track_of[k] {
            Some(tr) => tr.chord_at(t, &mut self.hints[k]).0,
            None => 0.0,
        }
    }

    /// Joint `k`'s turn at angle `a` ([`turn_of`]), kept for the next call: most joints
    /// hold their angle over a pair's walk.
    fn turn(&mut self, k: usize, a: f64) -> Rigid {
        match self.turns[k] {
            Some((b, r)) if b.to_bits() == a.to_bits() => r,
            _ => {
                let r = turn_of(a);
                self.turns[k] = Some((a, r));
                r
            }
        }
    }

    /// The stretches of pair `(i, j)` between its `moving` joints (ascending, between `i`
    /// and `j`): `moving.len() + 1` motions, the product of the turns of the joints that never
    /// turn before the first moving joint, between two, and after the last. They hold over
    /// the whole schedule (a joint without a track stays at angle 0), so a pose costs a
    /// product per moving joint rather than per joint between the tiles; the products are
    /// grouped differently than joint by joint, which moves a pose by a few roundings (about
    /// 1e-16 of the chain between the tiles), far below the walk's `precision`.
    fn stretches(&mut self, i: usize, j: usize, moving: &[usize]) -> Vec<Rigid> {
        let mut out = Vec::with_capacity(moving.len() + 1);
        let mut at = Rigid::IDENTITY;
        let mut next = moving.iter().peekable();
        for k in i..j {
            if next.next_if_eq(&&k).is_some() {
                out.push(at);
                at = Rigid::IDENTITY;
                continue;
            }
            at = at.then(&self.turn(k, 0.0));
        }
        out.push(at);
        out
    }

    /// Tile `j`'s pose in tile `i`'s frame at `t`, and in `centres` the centre of tile `k`
    /// in that frame for each joint `k` of `moving` (ascending, between `i` and `j`), from
    /// the pair's [`PairWalk::stretches`].
    fn pose(
        &mut self,
        t: f64,
        moving: &[usize],
        stretches: &[Rigid],
        centres: &mut Vec<Point>,
    ) -> Rigid {
        centres.clear();
        let mut at = stretches[0];
        for (q, &k) in moving.iter().enumerate() {
            centres.push(at.apply(Point::ORIGIN));
            let a = self.angle(k, t);
            at = at.then(&self.turn(k, a)).then(&stretches[q + 1]);
        }
        at
    }

    /// The signed distance of tiles `i` and `j` at `t`, tile widths, the best updated; the
    /// centres of `moving`'s tiles in `centres` ([`PairWalk::pose`]); tile `j`'s centre.
    fn evaluate(
        &mut self,
        (i, j, t): (usize, usize, f64),
        moving: &[usize],
        stretches: &[Rigid],
        centres: &mut Vec<Point>,
    ) -> (f64, Point) {
        let pose = self.pose(t, moving, stretches, centres);
        let d = self.outline.signed_distance(&pose);
        self.record(i, j, t, d);
        (d, pose.apply(Point::ORIGIN))
    }

    /// Counts one evaluation of tiles `i` and `j` at `t`, `d` apart; the best updated.
    fn record(&mut self, i: usize, j: usize, t: f64, d: f64) {
        self.work += 1;
        if self.best.is_none_or(|b| d < b.distance) {
            let joint = self.front(i, j, t);
            self.best = Some(Closest {
                distance: d,
                time: t,
                tiles: (i, j),
                joint,
            });
        }
    }

    /// Records tiles `i` and `j` at every one of the `samples` (their distances in `row`, at
    /// `(j - i) * samples.len() + s`); returns the nearest of them.
    fn record_row(&mut self, i: usize, j: usize, samples: &[f64], row: &[f64]) -> f64 {
        let mut near = f64::INFINITY;
        for (s, &t) in samples.iter().enumerate() {
            let d = row[(j - i) * samples.len() + s];
            self.record(i, j, t, d);
            near = near.min(d);
        }
        near
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
    ///
    /// The step from `t` is as long as tile `j` cannot have moved `room` towards tile `i`.
    /// Two bounds on its speed hold, and the longer step either allows is taken: the chain's
    /// (joint `k` turning at `w_k` moves tile `j`'s points at most `w_k 2 R (j - k)`), and
    /// the pose's: a point of tile `j` is at most `rho_k = |c_j - c_k| + 2 R` from joint
    /// `k`'s hinge now (`c` the centres, the hinge a vertex of tile `k`), and `rho_k` grows
    /// no faster than the joints beyond `k` move tile `j` (`g_k = sum_{m > k} w_m 2 R (j -
    /// m)`), so over a step `s` the tile moves at most `B s + A s^2 / 2` with `B = sum w_k
    /// rho_k` and `A = sum w_k g_k`. The pose's bound is the tight one for tiles far apart
    /// along the chain and near in the plane, the pairs that cost most steps.
    fn follow(&mut self, i: usize, j: usize) -> bool {
        let moving: Vec<usize> = (i..j).filter(|&k| self.track_of[k].is_some()).collect();
        let (t0, t_end) = (self.rates.t0, self.rates.t0 + self.rates.span);
        let mut centres: Vec<Point> = Vec::with_capacity(moving.len());
        let stretches = self.stretches(i, j, &moving);
        if moving.is_empty() {
            self.evaluate((i, j, t0), &moving, &stretches, &mut centres);
            return true;
        }
        // each moving joint's lever: 2 R (j - k)
        let lever: Vec<f64> = moving
            .iter()
            .map(|&k| 2.0 * self.outline.circumradius * (j - k) as f64)
            .collect();
        let mut scratch = StepScratch::new(moving.len());
        let mut at = vec![0usize; moving.len()];
        let mut t = t0;
        loop {
            if self.work > self.budget {
                return false;
            }
            let (d, cj) = self.evaluate((i, j, t), &moving, &stretches, &mut centres);
            if t >= t_end {
                return true;
            }
            // each moving joint's reach to tile j now: rho_k, never above its lever
            let rho: Vec<f64> = centres
                .iter()
                .zip(&lever)
                .map(|(c, &l)| ((cj - *c).hypot() + 2.0 * self.outline.circumradius).min(l))
                .collect();
            let m = self.best.map_or(d, |b| b.distance);
            // an overlap is measured to a hundredth of its depth besides the precision (a
            // tile passing through another keeps a flat depth that would cost a step per
            // precision)
            let room = d - m + self.precision + OVERLAP_PRECISION * (-m).max(0.0);
            // no step crosses a jump of a joint between the tiles
            let jump = self.rates.first_jump_after(&moving, t, t_end);
            // the rate bound over each moving joint's chords from t on: the chords up to the
            // first breakpoint at which the step they allow ends before it
            // (each joint's count of nodes at or before t: its hint after the evaluation at t)
            for (q, &k) in moving.iter().enumerate() {
                at[q] = self.hints[k];
            }
            let from = StepFrom {
                t,
                jump,
                room,
                moving: &moving,
                at: &at,
                lever: &lever,
                rho: &rho,
            };
            let next = self.next_time(&from, &mut scratch);
            // progress whatever the rounding
            t = if next > t {
                next.min(t_end)
            } else {
                t + 1e-15 * t.abs().max(1.0)
            };
        }
    }
}

impl PairWalk<'_> {
    /// Where the step from `from.t` ends. Over the chords of each moving joint from its chord
    /// at `t` up to the first node at or after a breakpoint `b` (a node time of a moving
    /// joint after `t`), the joints turn no faster than those chords' fastest, which allows
    /// a step to `reach(b)`; the step taken is the one at the first breakpoint `b` with
    /// `reach(b) < b`, or, when no breakpoint before the next jump `j` has it, `reach` at the
    /// first breakpoint at or after `j`, cut at `j`. `reach(b)` does not grow with `b` (the
    /// fastest chords only grow), so the breakpoint is found by galloping and bisection over
    /// the breakpoints, each `reach` a range maximum of each joint's chord rates
    /// ([`RateTable`]) and one unit of work: the same step as widening the chords one
    /// breakpoint at a time, in O(log) evaluations rather than one per breakpoint.
    fn next_time(&mut self, from: &StepFrom, scratch: &mut StepScratch) -> f64 {
        let track_of = self.track_of;
        let times =
            |q: usize| -> &[f64] { track_of[from.moving[q]].map_or(&[][..], |tr| &tr.times[..]) };
        let q_all = from.moving.len();
        let StepScratch {
            fastest,
            lo_at,
            hi_at,
            pivot_at,
        } = scratch;
        // each joint's breakpoints after lo (which does not settle) and before hi (which
        // does) are its nodes lo_at[q] .. hi_at[q]
        let (mut lo, mut hi) = (from.t, f64::INFINITY);
        for q in 0..q_all {
            lo_at[q] = from.at[q];
            hi_at[q] = times(q).len().max(from.at[q]);
        }
        // galloping: the least of each joint's 2^r-th node after t
        for r in 0..usize::BITS - 1 {
            let mut pivot = f64::INFINITY;
            for q in 0..q_all {
                if let Some(&x) = times(q).get(from.at[q] + (1usize << r) - 1) {
                    pivot = pivot.min(x);
                }
            }
            if pivot == f64::INFINITY {
                break;
            }
            for q in 0..q_all {
                // no joint's 2^r-th node lies before the pivot
                let end = (from.at[q] + (1usize << r)).min(hi_at[q]);
                pivot_at[q] = first_at_or_after(times(q), lo_at[q], end, pivot);
            }
            if self.settles(from, pivot, pivot_at, fastest) {
                hi = pivot;
                hi_at[..q_all].copy_from_slice(&pivot_at[..q_all]);
                break;
            }
            lo = pivot;
            for q in 0..q_all {
                lo_at[q] = first_after(times(q), pivot_at[q], hi_at[q], pivot);
            }
        }
        // bisection over the breakpoints between lo and hi: the median of the joint with
        // the most of them
        loop {
            let mut widest: Option<usize> = None;
            for q in 0..q_all {
                let span = hi_at[q].saturating_sub(lo_at[q]);
                if span > 0 && widest.is_none_or(|w| span > hi_at[w] - lo_at[w]) {
                    widest = Some(q);
                }
            }
            let Some(w) = widest else { break };
            let pivot = times(w)[(lo_at[w] + hi_at[w]) / 2];
            for q in 0..q_all {
                pivot_at[q] = first_at_or_after(times(q), lo_at[q], hi_at[q], pivot);
            }
            if self.settles(from, pivot, pivot_at, fastest) {
                hi = pivot;
                hi_at[..q_all].copy_from_slice(&pivot_at[..q_all]);
            } else {
                lo = pivot;
                for q in 0..q_all {
                    lo_at[q] = first_after(times(q), pivot_at[q], hi_at[q], pivot);
                }
            }
        }
        debug_assert!(lo < hi);
        let reach = self.reach(from, hi_at, fastest);
        if hi < from.jump {
            reach
        } else {
            reach.min(from.jump)
        }
    }

    /// Whether the step over the chords up to breakpoint `b` ends before it (or `b` is at or
    /// past the next jump), each joint's first node at or after `b` in `upto`: see
    /// [`PairWalk::next_time`].
    fn settles(&mut self, from: &StepFrom, b: f64, upto: &[usize], fastest: &mut [f64]) -> bool {
        b >= from.jump || self.reach(from, upto, fastest) < b
    }

    /// Where a step from `from.t` can reach over the chords of each moving joint `q` from
    /// its chord at `t` to the one ending at its node `upto[q]` (past the track: to its end),
    /// each joint's fastest chord there in `fastest`; one unit of work.
    fn reach(&mut self, from: &StepFrom, upto: &[usize], fastest: &mut [f64]) -> f64 {
        self.work += 1;
        for (q, &k) in from.moving.iter().enumerate() {
            let n = self.track_of[k].map_or(0, |tr| tr.times.len());
            fastest[q] = if from.at[q] >= n {
                0.0
            } else {
                self.rates.tables[k].max(from.at[q], upto[q].min(n - 1))
            };
        }
        let (mut speed, mut linear, mut growth, mut beyond) = (0.0, 0.0, 0.0, 0.0);
        for q in (0..from.moving.len()).rev() {
            speed += fastest[q] * from.lever[q];
            linear += fastest[q] * from.rho[q];
            growth += fastest[q] * beyond;
            beyond += fastest[q] * from.lever[q];
        }
        from.t + step_within(from.room, speed, linear, growth)
    }
}

/// The first index of `ts[from..to]` whose time is at or after `x` (`to` if none).
fn first_at_or_after(ts: &[f64], from: usize, to: usize, x: f64) -> usize {
    match ts.get(from..to) {
        Some(part) => from + part.partition_point(|&y| y < x),
        None => to.max(from),
    }
}

/// The first index of `ts[from..to]` whose time is after `x` (`to` if none).
fn first_after(ts: &[f64], from: usize, to: usize, x: f64) -> usize {
    match ts.get(from..to) {
        Some(part) => from + part.partition_point(|&y| y <= x),
        None => to.max(from),
    }
}

/// The working arrays of [`PairWalk::next_time`], one entry per moving joint.
struct StepScratch {
    fastest: Vec<f64>,
    lo_at: Vec<usize>,
    hi_at: Vec<usize>,
    pivot_at: Vec<usize>,
}

impl StepScratch {
    fn new(len: usize) -> StepScratch {
        StepScratch {
            fastest: vec![0.0; len],
            lo_at: vec![0; len],
            hi_at: vec![0; len],
            pivot_at: vec![0; len],
        }
    }
}

/// A step of a pair's walk about to be taken ([`PairWalk::next_time`]).
struct StepFrom<'s> {
    /// The moment the step starts at.
    t: f64,
    /// The next jump of a moving joint after `t` (else the schedule's end).
    jump: f64,
    /// How far the pair may come nearer over the step, tile widths.
    room: f64,
    /// The joints between the pair's tiles that have a track, ascending.
    moving: &'s [usize],
    /// Each moving joint's count of nodes at or before `t`.
    at: &'s [usize],
    /// Each moving joint's lever to the far tile, `2 R (j - k)`.
    lever: &'s [f64],
    /// Each moving joint's reach to the far tile now.
    rho: &'s [f64],
}

/// The `|rate|` of each chord of a track ([`chord_from`] of each of its nodes) and their
/// range maxima: `levels[l][i]` is the largest of the rates of nodes `i .. i + 2^l`.
struct RateTable {
    levels: Vec<Vec<f64>>,
}

impl RateTable {
    fn new(track: Option<&JointTrack>) -> RateTable {
        let Some(tr) = track else {
            return RateTable { levels: Vec::new() };
        };
        let mut levels: Vec<Vec<f64>> =
            vec![(0..tr.times.len()).map(|i| chord_from(tr, i).0).collect()];
        let mut w = 1;
        while 2 * w <= tr.times.len() {
            let prev = &levels[levels.len() - 1];
            let next: Vec<f64> = (0..prev.len() - w)
                .map(|i| prev[i].max(prev[i + w]))
                .collect();
            levels.push(next);
            w *= 2;
        }
        RateTable { levels }
    }

    /// The largest rate of nodes `a ..= b` (`a <= b` < the track's length).
    fn max(&self, a: usize, b: usize) -> f64 {
        let len = b + 1 - a;
        let l = (usize::BITS - 1 - len.leading_zeros()) as usize;
        let level = &self.levels[l];
        level[a].max(level[b + 1 - (1 << l)])
    }
}

/// The longest step over which a tile moving at most `speed`, or at most `linear + growth
/// s` after `s`, cannot cover `room` (infinite when it does not move).
fn step_within(room: f64, speed: f64, linear: f64, growth: f64) -> f64 {
    let chain = if speed > 0.0 {
        room / speed
    } else {
        f64::INFINITY
    };
    // linear s + growth s^2 / 2 = room, in the form without cancellation
    let root = linear * linear + 2.0 * growth * room;
    let pose = if linear > 0.0 || growth > 0.0 {
        2.0 * room / (linear + root.max(0.0).sqrt())
    } else {
        f64::INFINITY
    };
    chain.max(pose)
}

/// The precision of an overlap's depth, besides the absolute one: a hundredth of it.
const OVERLAP_PRECISION: f64 = 0.01;

/// The unit octagon at the origin: its vertices and circumradius, computed once.
struct Outline {
    vertices: [Point; 8],
    circumradius: f64,
}

impl Outline {
    fn unit() -> Outline {
        let o = Octagon::new(1.0);
        Outline {
            vertices: o.vertices().map(|(x, y)| Point::new(x, y)),
            circumradius: o.circumradius(),
        }
    }

    /// The signed distance between the unit octagon at the origin and the one at `pose`:
    /// the gap when apart, minus the overlap depth (the least translation that parts them)
    /// when they overlap.
    ///
    /// Two shortcuts leave the result bit for bit what the full computation gives: octagons
    /// whose centres are more than two circumradii apart (with a relative margin of 1e-9)
    /// are apart, so the separating axes are skipped; and a vertex farther than the nearest
    /// distance found so far (plus 1e-9) from the other octagon's circumscribed circle is
    /// not measured against its edges, since none of them can be nearer.
    fn signed_distance(&self, pose: &Rigid) -> f64 {
        let a = &self.vertices;
        let b: [Point; 8] = a.map(|p| pose.apply(p));
        let r = self.circumradius;
        let cb = pose.apply(Point::ORIGIN);
        let apart = cb.to_vec2().hypot() > 2.0 * r * (1.0 + 1e-9);
        if !apart {
            // separating axes: the face normals of both
            let mut sep = f64::NEG_INFINITY;
            for poly in [a, &b] {
                for e in 0..8 {
                    let (p, q) = (poly[e], poly[(e + 1) % 8]);
                    let n = kurbo::Vec2::new(q.y - p.y, p.x - q.x).normalize();
                    let (mut a0, mut a1) = (f64::INFINITY, f64::NEG_INFINITY);
                    let (mut b0, mut b1) = (f64::INFINITY, f64::NEG_INFINITY);
                    for v in a {
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
        }
        // apart: the nearest vertex of either to an edge of the other
        let mut d = f64::INFINITY;
        for (p, q, centre) in [(a, &b, cb), (&b, a, Point::ORIGIN)] {
            for v in p.iter() {
                if (*v - centre).hypot() - r > d + 1e-9 {
                    continue;
                }
                for e in 0..8 {
                    d = d.min(segment_distance(*v, q[e], q[(e + 1) % 8]));
                }
            }
        }
        d
    }
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
        let at = |x: f64, y: f64, _a: f64| shift(x, y);
        fn shift(x: f64, y: f64) -> Rigid {
            // a translation as the composition of two half turns
            Rigid::rotation_about(Point::new(x / 2.0, y / 2.0), std::f64::consts::PI)
                .then(&Rigid::rotation_about(Point::ORIGIN, std::f64::consts::PI))
        }
        // face to face: touching at 1, apart by 0.25 at 1.25, overlapping by 0.25 at 0.75
        assert!(Outline::unit().signed_distance(&at(1.0, 0.0, 0.0)).abs() < 1e-12);
        assert!((Outline::unit().signed_distance(&at(1.25, 0.0, 0.0)) - 0.25).abs() < 1e-12);
        assert!((Outline::unit().signed_distance(&at(0.75, 0.0, 0.0)) + 0.25).abs() < 1e-12);
        // diagonal faces: the 45 degree face's distance along the diagonal
        // along the diagonal the 45 degree faces meet at a centre distance of 1
        let r = 1.0 / std::f64::consts::SQRT_2;
        let d = Outline::unit().signed_distance(&at(r + 0.1, r + 0.1, 0.0));
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

    /// The engine's fold schedule of `word` with magnet offset `s` mm, inertial.
    fn engine_schedule(word: &str, s: f64) -> FoldSchedule {
        use crate::engine::{fold_schedule, run, EngineOptions};
        use crate::model::{Dynamics, ModelOptions};
        use crate::timeline::TileDesigns;
        use crate::{Chain, Design};
        let chain = Chain::parse(word).unwrap();
        let designs = TileDesigns::global(Design::thesis().with_s(s));
        let model = ModelOptions::default().with_dynamics(Dynamics::Inertial);
        let tl = run(
            &chain,
            &designs,
            &EngineOptions::default().with_model(model),
        )
        .unwrap();
        fold_schedule(&tl)
    }

    /// Every word of `len` letters.
    fn words(len: usize) -> Vec<String> {
        let mut out = vec![String::new()];
        for _ in 0..len {
            out = out
                .iter()
                .flat_map(|w| ['S', 'L', 'R'].map(|c| format!("{w}{c}")))
                .collect();
        }
        out
    }

    /// Following only the pairs that come near gives bit for bit what following every pair
    /// gives: every 6-letter word at s = 0 and 0.05 mm, engine schedules (sequential and
    /// overlapping folds, collided runs with overlaps), at a run's precision.
    #[test]
    #[ignore = "slow (1,458 engine runs, 1-3 min): .ci/run runs it"]
    fn the_near_pairs_measure_what_every_pair_measures_on_every_6_letter_word() {
        let precision = crate::simulation::CLEARANCE_PRECISION_MM / 30.0;
        let (mut measured, mut overlaps) = (0, 0);
        for s in [0.0, 0.05] {
            for word in words(6) {
                let sched = engine_schedule(&word, s);
                let fast = closest_approach(7, &sched, precision);
                let slow = all_pairs(7, &sched, precision);
                assert_eq!(fast, slow, "{word} at s = {s}");
                measured += 1;
                overlaps += usize::from(slow.is_some_and(|c| c.distance < 0.0));
            }
        }
        assert!(
            measured == 2 * 729 && overlaps > 20,
            "{measured} {overlaps}"
        );
    }

    /// The same on a sample of 8-letter words, and on random schedules of many joints moving
    /// at once (the test below's).
    #[test]
    fn the_near_pairs_measure_what_every_pair_measures_on_8_letter_words() {
        let precision = crate::simulation::CLEARANCE_PRECISION_MM / 30.0;
        let all = words(8);
        let mut rng = crate::collision::xorshift(11);
        for _ in 0..120 {
            let word = &all[(rng() % all.len() as u64) as usize];
            let sched = engine_schedule(word, 0.05);
            let fast = closest_approach(9, &sched, precision);
            assert_eq!(fast, all_pairs(9, &sched, precision), "{word}");
            assert!(fast.is_some(), "{word}");
        }
        for case in 0..40 {
            let (n, s) = random_schedule(&mut rng, case);
            assert_eq!(
                closest_approach(n, &s, 1e-4),
                all_pairs(n, &s, 1e-4),
                "case {case}"
            );
        }
    }

    /// A random word's schedule with every fold's joint turning over its own random window
    /// (many at once, non-monotone), `n` tiles.
    fn random_schedule(rng: &mut impl FnMut() -> u64, case: usize) -> (usize, FoldSchedule) {
        let mut unit = move || (rng() % 1_000_000) as f64 / 1_000_000.0;
        let n = 5 + case % 12;
        let tracks: Vec<JointTrack> = (0..n - 1)
            .filter_map(|k| {
                let c = ['S', 'L', 'R', 'L', 'R'][(unit() * 5.0) as usize % 5];
                let target = match c {
                    'L' => FRAC_PI_2,
                    'R' => -FRAC_PI_2,
                    _ => return None,
                };
                let start = unit() * 2.0;
                let mid = start + 0.1 + unit();
                let end = mid + 0.1 + unit();
                Some(track(
                    k,
                    &[start, mid, end],
                    &[0.0, target * unit(), target],
                ))
            })
            .collect();
        (n, FoldSchedule { tracks })
    }

    /// On a serpentine of a thousand tiles (rows of 20, sequential folds) the pairs that may
    /// come as near as the final shape's nearest are about one per tile, not half a million
    /// (`tests/clearances.rs` measures such a chain's clearance from the engine's run).
    #[test]
    fn a_long_serpentine_has_few_near_pairs() {
        let mut word = String::new();
        for row in 0..50 {
            if row > 0 {
                word.push_str(if row % 2 == 1 { "LL" } else { "RR" });
            }
            word.push_str(&"S".repeat(if row == 0 { 19 } else { 18 }));
        }
        let w = FoldWord::parse(&word).unwrap();
        let n = w.tiles();
        assert_eq!(n, 1000);
        let sched = FoldSchedule::sequential(&w, 1.0);
        let joints = n - 1;
        let track_of = tracks_by_joint(joints, &sched);
        let rates = Rates::new(&track_of);
        let last: Vec<Rigid> = (0..joints)
            .map(|k| turn_of(track_of[k].map_or(0.0, |t| t.angle_at(rates.t0 + rates.span))))
            .collect();
        let cutoff = final_cutoff(&last);
        // the corners of the U-turns: tiles two apart along the chain, 0.414 apart
        assert!(cutoff < 0.42, "{cutoff}");
        let pairs =
            super::super::clearance_pairs::pairs_within(n, &track_of, rates.t0, cutoff, usize::MAX)
                .unwrap();
        assert!(pairs.len() < 2 * n, "{}", pairs.len());
        // the U-turns' corners, which give the cutoff, are among them
        assert!(pairs.contains(&(19, 21)), "{pairs:?}");
    }

    /// One step of the pair search keeps every pair that comes within the cutoff over the
    /// step: random chains of 5 to 80 tiles at random angles, random joints turning at random
    /// rates for up to 0.4 rad, every pair sampled at 201 moments of the step. Steps far
    /// longer than the search takes (it turns a joint at most 1/32 rad a step), so that
    /// its motion bounds, not the sampling of its steps, decide.
    #[test]
    fn a_step_of_the_pair_search_keeps_every_pair_that_comes_near() {
        let mut rng = crate::collision::xorshift(29);
        let mut unit = move || (rng() % 1_000_000) as f64 / 1_000_000.0;
        let (mut near, mut found_total) = (0, 0);
        for case in 0..150 {
            let n = 5 + (unit() * 75.0) as usize;
            let angles: Vec<f64> = (0..n - 1)
                .map(|_| {
                    if unit() < 0.6 {
                        0.0
                    } else {
                        (unit() - 0.5) * std::f64::consts::PI
                    }
                })
                .collect();
            let mut rates: Vec<(usize, f64)> = Vec::new();
            for k in 0..n - 1 {
                if unit() < [0.05, 0.2, 0.6][case % 3] {
                    rates.push((k, (unit() - 0.5) * 2.0));
                }
            }
            let dt = 0.4 * unit();
            let cutoff = [-0.05, 0.3, 1.5][case % 3];
            let joints: Vec<(usize, f64)> = rates.iter().map(|&(k, w)| (k, w.abs())).collect();
            let found =
                super::super::clearance_pairs::one_look(angles.clone(), &joints, dt, cutoff);
            found_total += found.len();
            for q in 0..=200 {
                let tau = dt * q as f64 / 200.0;
                let mut now = angles.clone();
                for &(k, w) in &rates {
                    now[k] += w * tau;
                }
                for i in 0..n {
                    let mut at = Rigid::IDENTITY;
                    for j in i + 1..n {
                        at = at.then(&turn_of(now[j - 1]));
                        let between = rates.iter().any(|&(k, _)| i <= k && k < j);
                        if j >= i + 2 && between && Outline::unit().signed_distance(&at) < cutoff {
                            let pair = (i as u32, j as u32);
                            assert!(
                                found.binary_search(&pair).is_ok(),
                                "case {case}: {pair:?} at {tau}"
                            );
                            near += 1;
                        }
                    }
                }
            }
        }
        assert!(near > 1000 && found_total > 0, "{near} {found_total}");
    }

    /// The step the walk takes, as it was found before the breakpoints were searched: the
    /// chords widened one breakpoint at a time (without a cap) while the step reaches past
    /// them.
    fn widened_step(walk: &PairWalk, from: &StepFrom) -> f64 {
        let n = from.moving.len();
        let (mut fastest, mut ends, mut cursor) = (vec![0.0; n], vec![0.0; n], vec![0; n]);
        for (q, &k) in from.moving.iter().enumerate() {
            let tr = walk.track_of[k].unwrap();
            cursor[q] = from.at[q];
            (fastest[q], ends[q]) = chord_from(tr, cursor[q]);
        }
        loop {
            let (mut speed, mut linear, mut growth, mut beyond) = (0.0, 0.0, 0.0, 0.0);
            for q in (0..n).rev() {
                speed += fastest[q] * from.lever[q];
                linear += fastest[q] * from.rho[q];
                growth += fastest[q] * beyond;
                beyond += fastest[q] * from.lever[q];
            }
            let limit = ends.iter().copied().fold(from.jump, f64::min);
            let reach = from.t + step_within(from.room, speed, linear, growth);
            if reach < limit || limit >= from.jump {
                return reach.min(limit);
            }
            for (q, &k) in from.moving.iter().enumerate() {
                if ends[q] <= limit {
                    let tr = walk.track_of[k].unwrap();
                    cursor[q] += 1;
                    let (rate, end) = chord_from(tr, cursor[q]);
                    fastest[q] = fastest[q].max(rate);
                    ends[q] = end;
                }
            }
        }
    }

    /// The breakpoint search ([`PairWalk::next_time`]) takes exactly the step that widening
    /// the chords one at a time takes, on random tracks of many chords (some of them at
    /// repeated times, some jumps) and random pairs, rooms and moments.
    #[test]
    fn the_breakpoint_search_takes_the_widened_step() {
        let mut rng = crate::collision::xorshift(5);
        let mut unit = move || (rng() % 1_000_000) as f64 / 1_000_000.0;
        for case in 0..300 {
            let joints = 1 + case % 6;
            let tracks: Vec<JointTrack> = (0..joints)
                .map(|k| {
                    let nodes = 1 + (unit() * [3.0, 40.0, 700.0][case % 3]) as usize;
                    let (mut t, mut a) = (unit(), 0.0);
                    let (mut times, mut angles) = (Vec::new(), Vec::new());
                    for _ in 0..nodes {
                        let r = unit();
                        if r < 0.1 && !times.is_empty() {
                            // a repeated time: a jump or a node at the same angle
                        } else {
                            t += 1e-3 + unit() * unit() * 0.1;
                        }
                        if r >= 0.05 {
                            a = (a + (unit() - 0.5) * 0.2).clamp(-FRAC_PI_2, FRAC_PI_2);
                        }
                        times.push(t);
                        angles.push(a);
                    }
                    track(k, &times, &angles)
                })
                .collect();
            let sched = FoldSchedule { tracks };
            let track_of = tracks_by_joint(joints, &sched);
            let rates = Rates::new(&track_of);
            let walk = PairWalk::new(&track_of, &rates, 1e-4, joints, usize::MAX);
            let moving: Vec<usize> = (0..joints).collect();
            let far = joints + 1 + (unit() * 20.0) as usize;
            let lever: Vec<f64> = moving.iter().map(|&k| 2.0 * (far - k) as f64).collect();
            for _ in 0..20 {
                let t = rates.t0 + rates.span * unit() * 1.02;
                let at: Vec<usize> = moving
                    .iter()
                    .map(|&k| track_of[k].unwrap().times.partition_point(|&x| x <= t))
                    .collect();
                let rho: Vec<f64> = lever.iter().map(|&l| l * unit()).collect();
                let jump = rates.first_jump_after(&moving, t, rates.t0 + rates.span);
                let room = 10f64.powf(-4.0 + 5.0 * unit());
                let from = StepFrom {
                    t,
                    jump,
                    room,
                    moving: &moving,
                    at: &at,
                    lever: &lever,
                    rho: &rho,
                };
                let old = widened_step(&walk, &from);
                let mut w = PairWalk::new(&track_of, &rates, 1e-4, joints, usize::MAX);
                let new = w.next_time(&from, &mut StepScratch::new(joints));
                assert_eq!(
                    new.to_bits(),
                    old.to_bits(),
                    "case {case}: t {t} room {room}"
                );
            }
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
            for q in 0..=2000 {
                let t = rates.t0 + rates.span * q as f64 / 2000.0;
                let angles = s.angles_at(n - 1, t);
                for i in 0..n {
                    let mut at = Rigid::IDENTITY;
                    for j in i + 1..n {
                        at = at.then(&turn_of(angles[j - 1]));
                        if j >= i + 2 {
                            sampled = sampled.min(Outline::unit().signed_distance(&at));
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
