//! How long work says how far it has got: one trait for every callback of the libraries
//! (`foldchain` and `foldchain-planner`), so that a tool shows one progress display
//! whatever it runs.
//!
//! A closure `Fn(&str, u64, u64) + Sync` is a [`Progress`]; so is `()`, progress that goes
//! nowhere.
//!
//! ```
//! use foldchain::Progress;
//! use std::sync::atomic::{AtomicU64, Ordering};
//! let seen = AtomicU64::new(0);
//! let progress = |_stage: &str, done: u64, _total: u64| {
//!     seen.fetch_max(done, Ordering::Relaxed);
//! };
//! progress.update("samples", 3, 10);
//! assert_eq!(seen.load(Ordering::Relaxed), 3);
//! ```

/// Receives `done` of `total` units of the stage `stage` (a total of 0: not counted). Called
/// from any thread, often: an implementation should be cheap.
pub trait Progress: Sync {
    /// `done` of `total` units of `stage`.
    fn update(&self, stage: &str, done: u64, total: u64);
}

impl<F: Fn(&str, u64, u64) + Sync> Progress for F {
    fn update(&self, stage: &str, done: u64, total: u64) {
        self(stage, done, total)
    }
}

/// Progress that goes nowhere.
impl Progress for () {
    fn update(&self, _stage: &str, _done: u64, _total: u64) {}
}
