//! The event engine: when every magnet moves and every joint folds, derived from the
//! geometry of the paths (SPEC section 4, thesis chapter 6), as an ordered queue of discrete
//! events; the fold schedule it implies; and the energy of the chain over time.
//!
//! - [`run`]: the event queue and its rules ([`EngineOptions`], [`StartRule`], the speed law
//!   [`SpeedLaw`]); its result is a [`Timeline`], in the vocabulary of [`crate::timeline`].
//! - [`Timeline::joint_angles_at`]: the fold law; [`Timeline::checked_summary`]: the folds
//!   as tracks checked for collisions; [`RunSource::energy`](crate::timeline::RunSource::energy):
//!   the total dipole energy.
//!
//! ```
//! use foldchain::engine::{run, EngineOptions};
//! use foldchain::timeline::{Outcome, SpeedLaw, TileDesigns};
//! use foldchain::{Chain, Design};
//!
//! // sequential assembly: s = e/3, one magnet moving at a time
//! let d = Design::thesis();
//! let designs = TileDesigns::global(d.with_s(d.e / 3.0));
//! let chain = Chain::parse("S*19").unwrap();
//! let tl = run(&chain, &designs, &EngineOptions::default().with_speed(SpeedLaw::Unit)).unwrap();
//! assert_eq!(tl.outcome, Outcome::Completed);
//! assert_eq!(tl.max_moving_magnets(), 1);
//! ```

mod energy;
mod fold_law;
mod local;
mod queue;
mod result;
mod run;
mod run_source;
mod run_state;
mod schedule;
mod speed;
mod start_rule;
mod trigger;

pub(crate) use energy::energy_curve;
pub(crate) use local::DEFAULT_LOCAL_TOLERANCE;
pub(crate) use result::fold_angle;
pub(crate) use result::joint_angles_at;
pub use result::Timeline;
pub use run::{run, EngineError, EngineMethod, EngineOptions};
pub(crate) use schedule::fold_schedule;
pub use start_rule::StartRule;
pub(crate) use start_rule::DRIVE_TOLERANCE;

// The shared vocabulary the engine's results are written in, where the command-line tools and
// the pictures have long found it (one home: `crate::timeline`, `crate::physics`).
pub use crate::timeline::{
    CollisionReport, EnergySample, Event, EventKind, FoldRecord, Geometry, Outcome, SValue,
    SpeedLaw, Summary, TileDesigns,
};

/// The engine's timeline of `word` with the thesis design and the default options, for tests.
#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
pub(crate) fn thesis_timeline(word: &str) -> Timeline {
    run(
        &crate::Chain::parse(word).unwrap(),
        &TileDesigns::default(),
        &EngineOptions::default(),
    )
    .unwrap()
}
