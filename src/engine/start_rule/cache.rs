//! The force rule's cache: a start search's answer, kept by the integer description of the
//! neighbourhood it was asked in.
//!
//! Magnet `m`'s start, measured from its mover's start `t0`, depends only on what lies within
//! the cutoff of `m`: the paths of those magnets (path ids: kind, tile end and design), the
//! tiles' designs, the folds of the joints between them, the speed laws of the magnets behind
//! `m` (their lengths and end gaps, exactly), whether the chain ends or the RI lies within
//! reach, and when each magnet behind `m` started, relative to `t0`. The key holds all of
//! these as integers: the offsets rounded to [`FORCE_OFFSET_QUANTUM`] of the clock's scale, and a
//! magnet that has arrived (and whose fold, if any, has closed) as "at rest at its path end",
//! whatever its offset. Along a straight run, or the rows of a serpentine, the same
//! neighbourhood comes back magnet after magnet once the transient from the RI or a U-turn
//! has died out, and the search is skipped.
//!
//! Two neighbourhoods with one key differ by less than one quantum in each offset (some 100
//! units of the clock's last bit), so the cached start differs from the exact one by about a
//! quantum times the start's sensitivity to a neighbour's start (of order one): within the
//! rule's stated [`START_TOLERANCE`](crate::engine::start_rule::START_TOLERANCE) (the tests check it against the uncached
//! search).

use rustc_hash::FxHashMap;

use crate::engine::run_state::RunState;
use crate::engine::start_rule::answer::ForceStart;
use crate::engine::start_rule::neighbourhood::ARRIVED_MARGIN;
use crate::physics::reach;
use crate::timeline::Geometry;

/// Offsets in a key are rounded to this fraction of the clock's scale (the larger of `t0` and
/// the mover's duration, rounded up to a power of two): 2^-46, 64 to 128 units of the clock's
/// last bit. Above the rounding of the start times themselves (a few units: a steady run
/// keeps its key), and a cached start is as near the exact one as the clock resolves.
pub(crate) const FORCE_OFFSET_QUANTUM: f64 = 1.0 / 70_368_744_177_664.0;

/// A key's entry for a magnet at rest at its path end.
const AT_REST: u64 = u64::MAX;

/// The force rule's answers by neighbourhood, for one run.
#[derive(Debug, Default)]
pub(crate) struct ForceCache {
    map: FxHashMap<Box<[u64]>, ForceStart>,
    key: Vec<u64>,
    /// Searches answered from the cache.
    pub(crate) hits: u64,
    /// Searches made.
    pub(crate) misses: u64,
}

impl ForceCache {
    /// Fills the key of magnet `m`'s neighbourhood, its mover having started at `t0`;
    /// `false` when the run's progress cannot be keyed (the local solves' tracks).
    fn fill_key(
        &mut self,
        g: &Geometry,
        progress: &RunState<'_>,
        cutoff: usize,
        m: usize,
        t0: f64,
    ) -> bool {
        if progress.solved.is_some() {
            return false;
        }
        let n = g.magnets();
        let within = reach(m, cutoff, n);
        let (lo, hi) = (*within.start(), *within.end());
        let (tlo, thi) = (lo / 2, hi / 2);
        let scale = t0.abs().max(progress.motion(m - 1).duration());
        if !(scale > 0.0 && scale.is_finite()) {
            return false;
        }
        let exponent = scale.log2().ceil() as i32;
        let q = 2f64.powi(exponent) * FORCE_OFFSET_QUANTUM;
        let key = &mut self.key;
        key.clear();
        let near_end = |d: usize| d.min(cutoff.saturating_add(1)) as u64;
        key.extend([
            (m % 2) as u64,
            near_end(m),
            near_end(n - 1 - m),
            exponent as i64 as u64,
        ]);
        key.extend((lo..=hi).map(|k| u64::from(g.path_id(k))));
        key.extend((tlo..=thi).map(|t| u64::from(g.design_index(t))));
        key.extend((tlo..thi).map(|j| g.joint_fold(j).quarter_turns() as i64 as u64));
        for k in lo..m {
            let motion = progress.motion(k);
            key.extend([motion.length.to_bits(), motion.rho.to_bits()]);
        }
        for k in lo..m - 1 {
            let Some(start) = progress.start_of(k) else {
                return false;
            };
            let settled = start + progress.motion(k).duration() * (1.0 + ARRIVED_MARGIN);
            // the fold k drives, if any: its angle depends on k's start until it closes
            let joint = if k % 2 == 1 {
                Some(k / 2)
            } else {
                (k / 2).checked_sub(1)
            };
            let folding = joint
                .and_then(|j| progress.fold_at(j))
                .is_some_and(|f| f.end > t0);
            if settled <= t0 && !folding {
                key.push(AT_REST);
            } else {
                key.push(((t0 - start) / q).round() as i64 as u64);
            }
        }
        true
    }

    /// Magnet `m`'s start from the cache, or from `search` (then kept), `t0` being its
    /// mover's start.
    pub(crate) fn start(
        &mut self,
        g: &Geometry,
        progress: &RunState<'_>,
        cutoff: usize,
        m: usize,
        t0: f64,
        search: impl FnOnce() -> ForceStart,
    ) -> ForceStart {
        if !self.fill_key(g, progress, cutoff, m, t0) {
            self.misses += 1;
            return search();
        }
        if let Some(&hit) = self.map.get(self.key.as_slice()) {
            self.hits += 1;
            return hit.shifted(t0);
        }
        self.misses += 1;
        let found = search();
        self.map
            .insert(self.key.as_slice().into(), found.shifted(-t0));
        found
    }
}
