//! Will it fold when printed? The chance that a chain folds when every tile is printed and
//! every magnet bought within stated tolerances, the joints where failures begin, how the
//! smallest margin moves with each parameter, and a search of the design for the fastest
//! assembly that still folds often enough.
//!
//! A sample draws each tile's parameters independently ([`Tolerances`], seeded per sample:
//! SplitMix64) and decides by the margins ([`crate::margins`]): the chain folds when
//! every start and every fold margin is positive. That is a quasi-static criterion, checked
//! against the force-integrated reference on short chains in the test suite; it is what makes
//! ten thousand samples of a hundred tiles cost seconds.
//!
//! ```
//! use foldchain::tolerance::{Study, StudyOptions};
//! use foldchain::{Chain, Design};
//!
//! let chain = Chain::parse("SSS").unwrap();
//! let opts = StudyOptions::default().with_samples(200);
//! let s = Study::run(&chain, &[Design::thesis()], &opts).unwrap();
//! assert_eq!(s.samples, 200);
//! assert!(s.interval.0 <= s.probability && s.probability <= s.interval.1);
//! ```

mod optimize;
mod sample;
mod sensitivity;
mod study;
mod tolerances;
mod wilson;

pub use optimize::{Candidate, Search, SearchOptions};
pub(crate) use sample::{draw_designs, nudged};
pub use sensitivity::Sensitivity;
pub(crate) use study::study;
pub use study::{FailureCount, MarginSpread, Study, StudyOptions};
pub use tolerances::{Parameter, Printer, ToleranceError, Tolerances};
pub(crate) use wilson::{wilson_interval, Z95};
