//! The collision check every plan passes before it is returned: sequential folding from
//! tile 0 with every fold sweep checked (`foldchain::collision::check_word`), and the memos
//! of the cell router, which checks its routes as they grow
//! (`foldchain::collision::PrefixCheck`) and meets the same tile offsets again and again.

use std::sync::Mutex;

use foldchain::collision::PrefixCheck;
use foldchain::FoldWord;

/// Checks that the chain folds without self-intersection; the error says where it does not.
pub(crate) fn check_folds(word: &FoldWord) -> Result<(), String> {
    foldchain::collision::check_word(word, &foldchain::collision::CheckOptions::default())
        .map_err(|c| c.to_string())
}

/// Memos of the growing fold check (empty [`PrefixCheck`]s, each holding its memo of first
/// hits by lattice offset), kept between the router's calls and threads: a call takes one,
/// grows its routes from it ([`PrefixCheck::emptied`]) and gives it back. A memo only saves
/// work; it never changes a verdict.
#[derive(Default)]
pub(crate) struct CheckMemo {
    free: Mutex<Vec<PrefixCheck>>,
}

impl CheckMemo {
    /// An empty check with a memo for one thread's use (a new one when none is free).
    pub(crate) fn take(&self) -> PrefixCheck {
        self.free
            .lock()
            .ok()
            .and_then(|mut f| f.pop())
            .unwrap_or_default()
    }

    /// Gives a memo back for the next call.
    pub(crate) fn give(&self, memo: PrefixCheck) {
        if let Ok(mut f) = self.free.lock() {
            f.push(memo.emptied());
        }
    }
}
