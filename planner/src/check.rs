//! The collision check every plan passes before it is returned: sequential folding from
//! tile 0 with every fold sweep checked (`foldchain::collision::check_word`), and a memo of
//! verdicts for the cell router, which checks the same prefixes again and again (routes of
//! different cell orders and decompositions share their first cells and joins), with the
//! router's work counter ([`CheckMemo::spend`]): the units of work one width's routing
//! spent, summed over threads, so that the cell planner's search budget is counted the same
//! whatever the threads' order.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use foldchain::{Fold, FoldWord};

/// Checks that the chain folds without self-intersection; the error says where it does not.
pub(crate) fn check_folds(word: &FoldWord) -> Result<(), String> {
    foldchain::collision::check_word(word, &foldchain::collision::CheckOptions::default())
        .map_err(|c| c.to_string())
}

/// Verdicts of [`check_folds`] by fold word (the check depends on the word only), shared
/// between threads, and the work the router spent (see [`CheckMemo::spend`]).
#[derive(Default)]
pub(crate) struct CheckMemo {
    verdicts: Mutex<HashMap<Vec<Fold>, bool>>,
    work: AtomicU64,
}

impl CheckMemo {
    /// Counts `units` of work: a lattice tile the row programme prices, or a fold a route's
    /// check folds. Every unit is counted whether or not a memo answers, so the total depends
    /// on the search alone, not on timing.
    pub(crate) fn spend(&self, units: usize) {
        self.work.fetch_add(units as u64, Ordering::Relaxed);
    }

    /// The units of work counted so far.
    pub(crate) fn work(&self) -> u64 {
        self.work.load(Ordering::Relaxed)
    }

    /// True if the chain of `folds` folds without self-intersection.
    pub(crate) fn folds_cleanly(&self, folds: &[Fold]) -> bool {
        self.spend(folds.len());
        let known = self
            .verdicts
            .lock()
            .ok()
            .and_then(|m| m.get(folds).copied());
        if let Some(v) = known {
            return v;
        }
        let ok = check_folds(&FoldWord::from_folds(folds.to_vec())).is_ok();
        if let Ok(mut m) = self.verdicts.lock() {
            m.insert(folds.to_vec(), ok);
        }
        ok
    }
}
