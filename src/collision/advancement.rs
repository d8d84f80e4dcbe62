//! Checking a timed fold schedule ([`super::FoldSchedule`]) for self-intersection.
//!
//! A sequential schedule (joints folding one at a time, in chain order) is handed to the exact
//! sweep check ([`super::check_word`]) and the contact angle is turned back into a time.
//!
//! Any other schedule is walked segment by segment: between breakpoints (and the moments a
//! joint passes straight, where its hinge changes side) every joint turns at a constant rate
//! about one hinge. The moving joints cut the chain into rigid blocks; each pair of blocks is
//! checked on its own ([`super::blocks`]): neighbouring blocks exactly, blocks further apart by
//! conservative advancement with a clock per pair of parts, so a step is bounded by the speed
//! of the parts that are near each other, not by the fastest tile anywhere. Poses come from a
//! tree of bounding discs over runs of tiles ([`super::chain_tree`]) that a joint's new angle
//! updates in O(log n), so a segment costs what its moving joints' neighbourhoods cost, not the
//! length of the chain. A pair of blocks is carried past a segment's end while the joints it
//! spans keep their motion ([`super::windows`]) and skipped in the segments until then: a
//! chain folding at many places at once costs each pair its own joints' breakpoints.

use parry2d_f64::shape::ConvexPolygon;

use crate::{FoldWord, Octagon};

use rustc_hash::FxHashMap;

use super::block_cover::BlockCache;
use super::block_pairs::near_pairs;
use super::blocks::{Contact, Segment};
use super::chain_tree::ChainTree;
use super::pieces::{check_in_pieces, piece_count, Piece};
use super::windows::{track_breakpoints, Windows};
use super::{check_word, CheckOptions, FoldSchedule, JointTrack, ScheduleError};

/// Checks a chain folding along `schedule`: every pair of tiles with a moving joint between
/// them, at every moment (or the exact sweep check for a sequential schedule). Returns the
/// first contact with its time.
pub(crate) fn check_schedule(
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
    let Some(shape) = Octagon::new(1.0).to_parry(opts.tolerance) else {
        return Ok(());
    };
    Walk::new(word, &tracks).run(&shape, opts.tolerance)
}

/// Work budget of the conservative advancement of one check, in evaluations of a pair of parts
/// (each a few rotations and a distance): about a minute of work; past it the check reports
/// [`ScheduleError::Undecided`].
const MAX_WORK: usize = 200_000_000;

/// The segments of a schedule, with the tracks that move in each.
struct Walk<'a> {
    joints: usize,
    tracks: &'a [JointTrack],
    /// Breakpoints of every track, and the moments a track passes straight, sorted.
    breakpoints: Vec<f64>,
}

fn first_time(t: &JointTrack) -> f64 {
    t.times.first().copied().unwrap_or(f64::INFINITY)
}

fn last_time(t: &JointTrack) -> f64 {
    t.times.last().copied().unwrap_or(f64::NEG_INFINITY)
}

impl<'a> Walk<'a> {
    fn new(word: &FoldWord, schedule: &'a FoldSchedule) -> Walk<'a> {
        let mut breakpoints: Vec<f64> = Vec::new();
        for tr in &schedule.tracks {
            breakpoints.extend(track_breakpoints(tr));
        }
        breakpoints.sort_by(f64::total_cmp);
        breakpoints.dedup();
        Walk {
            joints: word.joints(),
            tracks: &schedule.tracks,
            breakpoints,
        }
    }

    /// Checks every segment, in [`piece_count`] pieces (see [`super::pieces`]).
    fn run(&self, shape: &ConvexPolygon, tolerance: f64) -> Result<(), ScheduleError> {
        let segments = self.breakpoints.len().saturating_sub(1);
        self.run_in(shape, tolerance, piece_count(segments))
    }

    /// Checks every segment in `pieces` pieces.
    fn run_in(
        &self,
        shape: &ConvexPolygon,
        tolerance: f64,
        pieces: usize,
    ) -> Result<(), ScheduleError> {
        let segments = self.breakpoints.len().saturating_sub(1);
        check_in_pieces(segments, pieces, MAX_WORK, |from, to, budget| {
            self.run_range(shape, tolerance, from, to, budget)
        })
    }

    /// Checks segments `from..to` (segment `i` runs from breakpoint `i` to `i + 1`), with
    /// `budget` pair evaluations.
    fn run_range(
        &self,
        shape: &ConvexPolygon,
        tolerance: f64,
        from: usize,
        to: usize,
        budget: usize,
    ) -> Piece {
        let mut piece = Piece {
            start: self.breakpoints.get(from).copied().unwrap_or(f64::INFINITY),
            best: None,
            inside: false,
            undecided: None,
        };
        let t0 = piece.start;
        if !t0.is_finite() {
            return piece;
        }
        let mut angles = vec![0.0; self.joints];
        for tr in self.tracks {
            angles[tr.joint] = tr.angle_at(t0);
        }
        let mut tree = ChainTree::new(angles, tolerance);
        let mut order: Vec<usize> = (0..self.tracks.len()).collect();
        order.sort_by(|&a, &b| first_time(&self.tracks[a]).total_cmp(&first_time(&self.tracks[b])));
        let mut next = 0;
        let mut active: Vec<usize> = Vec::new();
        let mut work = 0usize;
        let mut windows = Windows::new(self.tracks, self.joints);
        // the tracks that ended before the piece: at their last angle, passed
        for (i, tr) in self.tracks.iter().enumerate() {
            if first_time(tr) <= t0 {
                windows.pass(self.tracks, i, t0);
            }
        }
        // pairs of blocks (by their runs of tiles) advanced past a segment's end: clean until
        let mut certified: FxHashMap<Span, f64> = FxHashMap::default();
        let mut pairs = Vec::new();
        let mut moving: Vec<(usize, f64, f64, f64)> = Vec::new();
        let mut turned: Vec<(usize, f64)> = Vec::new();
        let mut blocks = BlockCache::default();
        let mut hints = vec![0usize; self.tracks.len()];
        let mut ends: Vec<usize> = Vec::new();
        for seg in self.breakpoints[from..=to.min(self.breakpoints.len() - 1)].windows(2) {
            let (ta, tb) = (seg[0], seg[1]);
            if tb <= ta {
                continue;
            }
            while next < order.len() && first_time(&self.tracks[order[next]]) < tb {
                active.push(order[next]);
                next += 1;
            }
            // bring the tree to the angles at ta; note the joints that turn until tb, with
            // their chords' rates (kept past tb until the track's next breakpoint)
            moving.clear();
            turned.clear();
            active.retain(|&ti| {
                let tr = &self.tracks[ti];
                windows.pass(self.tracks, ti, ta);
                let (a0, rate) = tr.chord_at(ta, &mut hints[ti]);
                if last_time(tr) <= ta {
                    turned.push((tr.joint, a0));
                    return false;
                }
                if rate != 0.0 {
                    moving.push((tr.joint, a0, rate, tr.ended.unwrap_or(f64::INFINITY)));
                } else {
                    turned.push((tr.joint, a0));
                }
                true
            });
            // the tree holds the angles of the joints that stand still (those inside the
            // blocks); a moving joint's is never read, the blocks being placed across it
            for &(k, a) in &turned {
                if tree.angle(k) != a {
                    blocks.turned(k);
                }
            }
            tree.set_angles(turned.iter().copied());
            if moving.is_empty() {
                continue;
            }
            moving.sort_by_key(|m| m.0);
            ends.clear();
            ends.extend(moving.iter().map(|m| m.0));
            ends.push(self.joints);
            let covers = blocks.covers(&tree, &ends);
            let segment = Segment::new(&tree, covers, ta, tb, &moving, tolerance);
            neighbour_contacts(&segment, &windows, &mut certified, tb, &mut piece.best);
            pairs.clear();
            near_pairs(&segment, |a, b| pairs.push((a, b)));
            for &(a, b) in &pairs {
                let span = segment.span(a, b);
                if certified.get(&span).is_some_and(|&t| t >= tb) {
                    continue;
                }
                // the joints inside the span keep their motion until their next breakpoint
                let until = windows.until(span.0, span.3).max(tb);
                match segment.advance(a, b, shape, until, &mut piece.best, &mut work, budget) {
                    Ok(clean) if clean > tb => {
                        certified.insert(span, clean);
                    }
                    Ok(_) => {}
                    Err(e) => {
                        piece.undecided = Some((ta, work, e.time));
                        return piece;
                    }
                }
            }
            if piece.best.is_some_and(|c| c.time <= tb) {
                piece.inside = true;
                return piece;
            }
            if certified.len() > 1 << 16 {
                certified.retain(|_, &mut t| t > tb);
            }
        }
        piece
    }
}

/// Two blocks by their runs of tiles: first and last tile of each.
type Span = (usize, usize, usize, usize);

/// The contacts of neighbouring blocks of `segment` (ending at `tb`), carried like the other
/// pairs: each certified clean until its joints' next breakpoint.
fn neighbour_contacts(
    segment: &Segment,
    windows: &Windows,
    certified: &mut FxHashMap<Span, f64>,
    tb: f64,
    best: &mut Option<Contact>,
) {
    for b in 1..segment.blocks() {
        let span = segment.span(b - 1, b);
        if certified.get(&span).is_some_and(|&t| t >= tb) {
            continue;
        }
        let until = windows.until(span.0, span.3).max(tb);
        segment.rotation_contact(b, until, best);
        if until > tb {
            certified.insert(span, until);
        }
    }
}

#[cfg(test)]
mod tests;
