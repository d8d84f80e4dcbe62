//! What the sweeps keep besides the tracks ([`crate::engine::local::relaxation`]): the cache of
//! unit solutions shared by every sweep ([`Cache`]), a sweep's shapes by kind of unknown
//! ([`Library`]) and each shape's anchor crossing ([`Anchors`]).
//!
//! **Which entries a look-up sees.** Two sweeps may run at once, the later one trailing the
//! earlier by a few units ([`Cache::lag`]). So that a unit's solution does not depend on
//! which entries the other thread has made yet, every entry is tagged with the sweep and the
//! unit that made it, and a look-up by unit `u` of sweep `k` sees exactly the entries of the
//! sweeps before `k - 1`, those of sweep `k - 1` at units up to `u + lag`, and those of sweep
//! `k` before `u`: whatever the threads and their timing. Of several visible entries under
//! one key it takes the earliest made (the one a single thread met first).

use std::sync::{Arc, Mutex, PoisonError};

use rustc_hash::FxHashMap;

use crate::engine::local::solve::Solution;
use crate::engine::local::trajectory::{Shape, Shapes, Track, REST};

/// A unit's solution as the cache keeps it: shape ids instead of shapes.
#[derive(Debug)]
pub(crate) struct Entry {
    /// Each unknown's shape id and start (local time), if it moved.
    pub(crate) shapes: Vec<Option<(u32, f64)>>,
    /// The solution, shapes taken out.
    pub(crate) solution: Solution,
}

/// The sweep (from 1) and the unit that made an entry: entries sort in the order a single
/// thread makes them.
pub(crate) type Tag = (usize, usize);

/// The entries under one key, tagged.
type Tagged = Vec<(Tag, Arc<Entry>)>;

/// Every unit solution of a run under its key, tagged ([`Tag`]).
pub(crate) struct Cache {
    /// How many units past its own a unit may see of the sweep before its own.
    lag: usize,
    map: Mutex<FxHashMap<Vec<i64>, Tagged>>,
}

impl Cache {
    /// An empty cache whose look-ups see `lag` units ahead into the sweep before.
    pub(crate) fn new(lag: usize) -> Cache {
        Cache {
            lag,
            map: Mutex::new(FxHashMap::default()),
        }
    }

    /// How many units past its own a unit waits for, and sees, of the sweep before.
    pub(crate) fn lag(&self) -> usize {
        self.lag
    }

    /// Whether a look-up at `at` sees an entry made at `tag`.
    fn visible(&self, at: Tag, tag: Tag) -> bool {
        let ((k, u), (s, v)) = (at, tag);
        s + 1 < k || (s + 1 == k && v <= u + self.lag) || (s == k && v < u)
    }

    /// The entry under `key` that a look-up at `at` sees, if any.
    pub(crate) fn get(&self, key: &[i64], at: Tag) -> Option<Arc<Entry>> {
        let map = self.map.lock().unwrap_or_else(PoisonError::into_inner);
        map.get(key)?
            .iter()
            .filter(|(tag, _)| self.visible(at, *tag))
            .min_by_key(|(tag, _)| *tag)
            .map(|(_, e)| e.clone())
    }

    /// Stores `entry`, made at `at`, under `key`.
    pub(crate) fn insert(&self, key: &[i64], at: Tag, entry: Arc<Entry>) {
        let mut map = self.map.lock().unwrap_or_else(PoisonError::into_inner);
        match map.get_mut(key) {
            Some(list) => list.push((at, entry)),
            None => {
                map.insert(key.to_vec(), vec![(at, entry)]);
            }
        }
    }
}

/// Each shape's crossing of a fraction of its path from its start, found once.
pub(crate) struct Anchors {
    fraction: f64,
    /// By shape id: infinite never reached.
    local: FxHashMap<u32, f64>,
}

impl Anchors {
    /// Crossings of `fraction`.
    pub(crate) fn new(fraction: f64) -> Anchors {
        Anchors {
            fraction,
            local: FxHashMap::default(),
        }
    }

    /// When `track` reaches the fraction, if it does.
    pub(crate) fn crossing(&mut self, shapes: &Shapes, track: Track) -> Option<f64> {
        if track.shape == REST {
            return None;
        }
        let fraction = self.fraction;
        let t = *self.local.entry(track.shape).or_insert_with(|| {
            shapes
                .get(track.shape)
                .crossing(fraction)
                .unwrap_or(f64::INFINITY)
        });
        t.is_finite().then_some(track.offset + t)
    }
}

/// The shapes a sweep stored, by kind of unknown (a magnet's path, a joint's fold) with their
/// ends: the shapes a new one may be a copy of. A sweep shares only the shapes it made itself
/// (a shape of the sweep before, matched within the tolerance, would stop the sweeps'
/// progress there).
#[derive(Default)]
pub(crate) struct Library {
    by_kind: FxHashMap<(bool, i64), Vec<(f64, u32)>>,
}

impl Library {
    /// A stored shape of `kind` that agrees with `shape` within `tol` from their starts on
    /// and ends within `dt` of it.
    pub(crate) fn find(
        &self,
        shapes: &Shapes,
        kind: (bool, i64),
        shape: &Shape,
        tol: f64,
        dt: f64,
    ) -> Option<u32> {
        let end = shape.end();
        self.by_kind.get(&kind)?.iter().find_map(|&(e, id)| {
            ((e - end).abs() <= dt && shapes.get(id).close_shifted(shape, 0.0, tol, dt))
                .then_some(id)
        })
    }

    /// Stores shape `id` of `kind` ending at `end`.
    pub(crate) fn add(&mut self, kind: (bool, i64), end: f64, id: u32) {
        self.by_kind.entry(kind).or_default().push((end, id));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_look_up_sees_the_entries_its_tag_allows_the_earliest_first() {
        let cache = Cache::new(2);
        let entry = |rhs| {
            Arc::new(Entry {
                shapes: Vec::new(),
                solution: Solution {
                    rhs,
                    ..Solution::default()
                },
            })
        };
        let (key, other) = ([1, 2, 3], [1, 2]);
        // made out of order, as two threads may make them
        cache.insert(&key, (2, 7), entry(27));
        cache.insert(&key, (1, 50), entry(150));
        cache.insert(&other, (3, 4), entry(34));
        cache.insert(&other, (2, 10), entry(210));
        let seen = |key: &[i64], at| cache.get(key, at).map(|e| e.solution.rhs);
        // a sweep sees its own earlier units
        assert_eq!(seen(&key, (1, 50)), None);
        assert_eq!(seen(&key, (1, 51)), Some(150));
        assert_eq!(seen(&key, (2, 7)), None);
        assert_eq!(seen(&key, (2, 8)), Some(27));
        // and the sweep before up to 2 units ahead, the earliest made first
        assert_eq!(seen(&key, (2, 47)), Some(27));
        assert_eq!(seen(&key, (2, 48)), Some(150));
        assert_eq!(seen(&other, (3, 4)), None);
        assert_eq!(seen(&other, (3, 5)), Some(34));
        assert_eq!(seen(&other, (3, 7)), Some(34));
        assert_eq!(seen(&other, (3, 8)), Some(210));
        // and every entry of the sweeps before that, but none of a later sweep
        assert_eq!(seen(&key, (3, 0)), Some(150));
        assert_eq!(seen(&other, (4, 0)), Some(210));
        assert_eq!(seen(&other, (1, 100)), None);
        assert_eq!(seen(&[1], (4, 0)), None);
    }
}
