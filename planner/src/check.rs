//! The collision check every plan passes before it is returned: sequential folding from
//! tile 0 with every fold sweep checked (`foldchain::collision::check_word`), and a memo of
//! verdicts for the cell router, which checks the same prefixes again and again (routes of
//! different decompositions share their first cells and joins).

use std::collections::HashMap;
use std::sync::Mutex;

use foldchain::{Fold, FoldWord};

/// Checks that the chain folds without self-intersection; the error says where it does not.
pub(crate) fn check_folds(word: &FoldWord) -> Result<(), String> {
    foldchain::collision::check_word(word, &foldchain::collision::CheckOptions::default())
        .map_err(|c| c.to_string())
}

/// Verdicts of [`check_folds`] by fold word (the check depends on the word only), shared
/// between threads.
#[derive(Default)]
pub(crate) struct CheckMemo {
    verdicts: Mutex<HashMap<Vec<Fold>, bool>>,
}

impl CheckMemo {
    /// True if the chain of `folds` folds without self-intersection.
    pub(crate) fn folds_cleanly(&self, folds: &[Fold]) -> bool {
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
