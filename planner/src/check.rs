//! The collision check every plan passes before it is returned: sequential folding from
//! tile 0 with every fold sweep checked (`foldchain::collision::check_word`).

use foldchain::FoldWord;

/// Checks that the chain folds without self-intersection; the error says where it does not.
pub(crate) fn check_folds(word: &FoldWord) -> Result<(), String> {
    foldchain::collision::check_word(word, &foldchain::collision::CheckOptions::default())
        .map_err(|c| c.to_string())
}
