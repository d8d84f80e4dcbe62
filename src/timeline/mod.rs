//! What a run is about and what it produces, in the words both simulations share: the
//! designs of the tiles and the chain at rest they make ([`TileDesigns`], [`Geometry`]); the
//! events, folds and outcome of a run ([`Event`], [`FoldRecord`], [`Outcome`]), its energy
//! curve ([`EnergySample`]), its summary ([`Summary`]) and its `timeline.json`
//! ([`TimelineJson`]); and the run itself as its readers see it ([`RunSource`]): the chain at
//! any time ([`ChainState`]), the transition diagram's data ([`TransitionData`]) and each
//! magnet's travel and joint's angle against time ([`Track`]).
//!
//! The event engine ([`crate::engine`]) and the reference integrator ([`crate::reference`])
//! both produce these, and neither imports them from the other, so their results are
//! written, drawn and compared alike; the pictures and the viewer (the `foldchain-render`
//! crate) read runs through [`RunSource`] alone.
//!
//! ```
//! use foldchain::timeline::{Outcome, RunFacts, SpeedLaw, Summary};
//!
//! let outcome = Outcome::Completed;
//! let summary = Summary::new(RunFacts {
//!     tiles: 3,
//!     outcome: &outcome,
//!     decided_by: "an example",
//!     duration_s: 1.0,
//!     events: 9,
//!     folds: vec![1],
//!     max_moving_magnets: 2,
//!     speed_law: SpeedLaw::Unit,
//! });
//! assert!(summary.completed);
//! assert_eq!(summary.result, "completed");
//! ```

mod chain_state;
mod energy_sample;
mod event;
mod fold_record;
mod free_motion;
mod geometry;
mod json;
mod outcome;
mod pair_energies;
mod parameters;
mod run_source;
mod speed_law;
mod summary;
mod tile_designs;
mod track;
mod transition;

pub use chain_state::{ChainState, DETAIL_TILES};
pub use energy_sample::EnergySample;
pub use event::{joint_of_magnet, start_fraction, Event, EventKind, S0_START_FRACTION};
pub use fold_record::FoldRecord;
pub use free_motion::FreeMotion;
pub use geometry::{Geometry, GeometryError, LENGTH_TOLERANCE};
pub use json::{TimelineJson, EVENT_INDEX};
pub use outcome::Outcome;
pub use pair_energies::PairEnergies;
pub use parameters::Parameters;
pub use run_source::{RunSource, TrackKey};
pub use speed_law::SpeedLaw;
pub use summary::{CollisionReport, RunFacts, Summary};
pub use tile_designs::{BadSValue, DesignsError, SValue, TileDesigns, TileOverride};
pub use track::{Track, ANGLE_TOLERANCE, TRAVEL_TOLERANCE};
pub use transition::{MagnetTrack, TransitionData};
