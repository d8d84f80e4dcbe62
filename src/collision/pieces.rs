//! A long timed schedule checked in pieces of consecutive segments, in parallel.
//!
//! The schedule check ([`super::advancement`]) walks the segments in time order, carrying
//! its chain tree and its certified pairs of blocks from one segment to the next. A piece
//! starts afresh from the chain as it stands at its first segment (a new tree, no pair
//! carried in: some more work, never a different contact), so pieces can run at once. Every
//! contact a piece finds is real, and a piece finds the first contact within its segments;
//! the schedule's first contact is therefore the earliest any piece finds, unless a piece
//! before it ran out of work ([`combine`]). The pieces are cut by the number of segments
//! alone ([`piece_count`]), never by the threads, so the verdict does not depend on them;
//! a piece after one known to hold a contact is skipped, which changes no verdict either.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::blocks::Contact;
use super::ScheduleError;

/// Segments a piece holds at least: 8,192. Shorter schedules are checked in one piece.
pub(crate) const SEGMENTS_PER_PIECE: usize = 8192;
/// Most pieces a schedule is checked in: 8.
pub(crate) const MAX_PIECES: usize = 8;

/// How many pieces a schedule of `segments` segments is checked in: one per
/// [`SEGMENTS_PER_PIECE`], at most [`MAX_PIECES`]. A fresh start costs about a few hundred
/// segments' work (a chain tree at its first moment, every track's next breakpoint).
pub(super) fn piece_count(segments: usize) -> usize {
    (segments / SEGMENTS_PER_PIECE).clamp(1, MAX_PIECES)
}

/// What a run of consecutive segments found.
#[derive(Clone, Copy, Debug)]
pub(super) struct Piece {
    /// The time of its first segment's start.
    pub start: f64,
    /// The earliest contact found (perhaps past the piece, by a pair carried there).
    pub best: Option<Contact>,
    /// Whether `best` lies within the piece: no earlier contact in it.
    pub inside: bool,
    /// Ran out of work in the segment starting at `.0`, after `.1` evaluations, with a pair
    /// stuck at `.2`.
    pub undecided: Option<(f64, usize, f64)>,
}

/// Checks `segments` segments in `pieces` pieces of consecutive segments, `check(from, to,
/// budget)` checking segments `from..to` within `budget` evaluations. A single piece has all
/// of `max_work`; each of several has `2 / pieces` of it (pieces run two at a time on two
/// cores: the check's cost stays about what one piece with the whole budget would take).
pub(super) fn check_in_pieces(
    segments: usize,
    pieces: usize,
    max_work: usize,
    check: impl Fn(usize, usize, usize) -> Piece + Sync,
) -> Result<(), ScheduleError> {
    let pieces = pieces.clamp(1, segments.max(1));
    if pieces == 1 {
        return combine(&[Some(check(0, segments, max_work))]);
    }
    let budget = 2 * max_work / pieces;
    let ranges: Vec<(usize, usize)> = (0..pieces)
        .map(|c| (c * segments / pieces, (c + 1) * segments / pieces))
        .collect();
    // the first piece known to hold a contact: the pieces after it cannot hold an earlier
    // one and are skipped (whichever runs first, the verdict is the same)
    let decided = AtomicUsize::new(usize::MAX);
    let results: Vec<Option<Piece>> = ranges
        .par_iter()
        .enumerate()
        .map(|(i, &(from, to))| {
            if decided.load(Ordering::Relaxed) < i {
                return None;
            }
            let piece = check(from, to, budget);
            if piece.inside {
                decided.fetch_min(i, Ordering::Relaxed);
            }
            Some(piece)
        })
        .collect();
    combine(&results)
}

/// The verdict of pieces in time order (`None`: skipped, after a piece holding a contact).
fn combine(pieces: &[Option<Piece>]) -> Result<(), ScheduleError> {
    let mut best: Option<Contact> = None;
    for piece in pieces.iter().flatten() {
        // a contact found before this piece: everything before it is clean
        if let Some(c) = best.filter(|c| c.time <= piece.start) {
            return Err(c.to_error());
        }
        if let Some(c) = piece.best {
            if c.earlier_than(&best) {
                best = Some(c);
            }
        }
        if piece.inside {
            break;
        }
        if let Some((ta, steps, time)) = piece.undecided {
            // clean up to the segment where the work ran out
            return match best.filter(|c| c.time <= ta) {
                Some(c) => Err(c.to_error()),
                None => Err(ScheduleError::Undecided { steps, time }),
            };
        }
    }
    best.map_or(Ok(()), |c| Err(c.to_error()))
}
