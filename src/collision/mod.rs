//! Self-intersection of a folding chain: does any pair of tiles overlap with positive area,
//! in the final shape or at any moment of any fold?
//!
//! - [`check_word`] follows the thesis' sequential folding from the reaction-initiator end:
//!   while joint `k` folds, everything after it is still straight and turns 90 degrees about
//!   joint `k`'s hinge. Each sweep is checked in closed form: the first contact
//!   of a turning octagon with a fixed one is the smallest angle at which a vertex's circular
//!   arc crosses an edge, so nothing between samples can be missed. Whether a fold's tail
//!   meets a placed tile depends only on that tile's exact lattice offset from the folding
//!   tile, so a memo of first hits by offset decides each fold with a few lookups; only a fold
//!   that collides is swept pair by pair for the contact angle.
//! - The timed check (crate-private; [`crate::simulate`] and the runs' `check` methods call
//!   it) takes joint angles as functions of time (several joints moving at once, as the event
//!   engine produces for small `s`) and checks every moving part against every other by
//!   conservative advancement on parry2d distances, reporting the first contact.
//! - The final shape is checked exactly ([`check_word`] with [`CheckOptions::final_only`]): final tile centres are integer combinations of `w`
//!   and `w/sqrt2` ([`crate::exact`]), so overlap against touching needs no tolerance there.
//!
//! **Tolerance.** Touching (a shared face or vertex) is allowed, overlap is not. During a
//! sweep the outlines are inset by [`CheckOptions::tolerance`] (default `1e-7 w`, 3 nm on
//! 30 mm tiles) on every face, so tiles that close face to face, like the last tile of the
//! `LLL` ring against the first, count as touching, while any overlap deeper than twice the
//! tolerance is a collision. The default lies far above the rounding of the arc computations
//! (about `1e-16` of the chain's extent, `1e-10 w` at a million tiles) and far below anything
//! physical.

mod advancement;
mod block_cover;
mod block_pairs;
mod blocks;
mod chain_tree;
mod clearance;
mod clearance_pairs;
pub(crate) use clearance::closest_approach;
mod first_hit;
pub(crate) use first_hit::{unit_tail_frame, TailHits, NEVER as NO_TAIL_HIT};
mod index_boxes;
mod lattice;
mod pieces;
mod prefix;
mod schedule;
mod sequential;
mod sweep;
mod windows;

pub(crate) use advancement::check_schedule;
pub(crate) use lattice::final_overlap;
pub use prefix::PrefixCheck;
pub(crate) use schedule::{FoldSchedule, JointTrack, ScheduleError};
pub use sequential::{check_chain, check_word, Verdict};

// for the counting search (`crate::count`), which grows words with the same exact tests
pub(crate) use lattice::lattice_overlap;

use std::fmt;

/// How a chain is checked.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
#[non_exhaustive]
pub struct CheckOptions {
    /// Overlap depth, in tile widths, below which two outlines count as touching: each outline
    /// is inset by this much during sweeps. Default `1e-7`.
    pub tolerance: f64,
    /// Check only the final shape, not the fold sweeps. Default `false`.
    pub final_only: bool,
    /// The deepest overlap, mm, that a simulated run's check ([`crate::simulate`],
    /// [`crate::reference::ReferenceRun::checked_summary`]) counts as touching: a graze,
    /// reported with its clearance ([`crate::timeline::Clearance`]) rather than as a
    /// collision. Default `0.01` (10 um). Not used by the sequential checks of words
    /// ([`check_word`], [`check_chain`]), which follow exact poses.
    ///
    /// Why 10 um: it is a run's numerical resolution of a contact, not a physical allowance.
    /// The two simulations follow one physics, and their fold tracks agree within a few
    /// 1e-6 rad where compared (the engine's schedule follows its law within 1e-6 rad on
    /// chains up to 100 tiles, the reference's tracks run through its recorded states and
    /// wall contacts): on a 9-tile chain's 240 mm lever about 1 um. Their clearances are held
    /// to agree within 5 um (`tests/clearances.rs`; SRLSLLSR at s = 0.05: 0.06 um apart), so
    /// with a tolerance of twice that an overlap counted by one is, in the other, at least
    /// an overlap half as deep. The grazes the verdict scans met overlap by 3 to 5 um and last
    /// 2e-5 s (SLRRRL at s = 0, BENCHMARKS.md), and 10 um is a fifteenth of the 0.15 mm the
    /// finest printed tiles are made to (`foldchain-print`'s resin clearance): a contact that
    /// shallow is not one a printed chain could tell from touching.
    pub overlap_mm: f64,
    /// Whether a simulated run's check also measures its smallest clearance
    /// ([`crate::timeline::Clearance`]); the verdict does not depend on it. Default `true`;
    /// the design search ([`crate::tolerance::Search`]), which ranks candidates by verdict
    /// and assembly time, turns it off (on a 200-tile chain the measurement is most of a
    /// run's work).
    pub clearance: bool,
}

impl Default for CheckOptions {
    fn default() -> CheckOptions {
        CheckOptions {
            tolerance: 1e-7,
            final_only: false,
            overlap_mm: 0.01,
            clearance: true,
        }
    }
}

impl CheckOptions {
    /// Measure a simulated run's smallest clearance (`true`, the default) or not.
    pub fn with_clearance(mut self, clearance: bool) -> CheckOptions {
        self.clearance = clearance;
        self
    }

    /// Only the final shape (`true`) or every sweep too (`false`).
    pub fn with_final_only(mut self, final_only: bool) -> CheckOptions {
        self.final_only = final_only;
        self
    }

    /// Another overlap tolerance of simulated runs, mm (see [`CheckOptions::overlap_mm`]).
    pub fn with_overlap_mm(mut self, overlap_mm: f64) -> CheckOptions {
        self.overlap_mm = overlap_mm;
        self
    }

    /// The touching tolerance of a simulated run's check of tiles `width_mm` wide, tile
    /// widths: each outline inset by half the overlap tolerance, at least by `tolerance`.
    pub(crate) fn run_tolerance(&self, width_mm: f64) -> f64 {
        self.tolerance.max(0.5 * self.overlap_mm / width_mm)
    }

    /// Another touching tolerance, in tile widths.
    pub fn with_tolerance(mut self, tolerance: f64) -> CheckOptions {
        self.tolerance = tolerance;
        self
    }
}

/// The first overlap found.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Collision {
    /// The joint folding when the tiles met (0 = nearest the reaction initiator); `None` for
    /// an overlap found in the final shape.
    ///
    /// It is the *fold front*: the highest joint between the two tiles that is turning at the
    /// contact. In sequential folding that is the one fold in progress (the joints before it
    /// have closed, those after it are straight). When folds overlap in time (inertial
    /// dynamics, small `s`) several joints between the tiles turn at once and each moves them;
    /// the front is the latest of those folds to have started, the same one sequential
    /// folding would name. The rule asks only which joints turn, not how fast: two runs of
    /// the same physics (the event engine's schedule and the reference's recorded one) name
    /// the same joint unless one of them starts or ends a fold between their two contact
    /// times, whereas the fastest joint at the contact (the rule before) flipped between
    /// joints turning at nearly the same rate. A joint whose fold has ended
    /// (it closed at its wall) but that moves again (an inertial fold released from its wall)
    /// is named only when no joint between the tiles whose fold goes on turns: the
    /// reference's recorded states keep such tiny motions, the engine's closed folds do not.
    pub joint: Option<usize>,
    /// How far that joint had turned, in degrees (90 for the final shape).
    pub angle_deg: f64,
    /// The time of contact, for checks of a timed schedule.
    pub time: Option<f64>,
    /// The two tiles, lower index first.
    pub tiles: (usize, usize),
}

impl fmt::Display for Collision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (a, b) = self.tiles;
        match (self.joint, self.time) {
            (Some(j), Some(t)) => write!(
                f,
                "tiles {a} and {b} collide at t = {t:.6} s while joint {j} folds (at {:.3} degrees)",
                self.angle_deg
            ),
            (Some(j), None) => {
                write!(f, "tiles {a} and {b} collide while joint {j} folds, at {:.3} degrees", self.angle_deg)
            }
            (None, Some(t)) => write!(f, "tiles {a} and {b} collide at t = {t:.6} s"),
            (None, None) => write!(f, "tiles {a} and {b} overlap in the final shape"),
        }
    }
}

impl std::error::Error for Collision {}

/// A small xorshift generator, for the tests' random words and schedules.
#[cfg(test)]
fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
