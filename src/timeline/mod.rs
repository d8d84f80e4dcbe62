//! What a run is about and what it produces, in the words both simulations share: the
//! designs of the tiles and the chain at rest they make ([`TileDesigns`], [`Geometry`]); the
//! events, folds and outcome of a run ([`Event`], [`FoldRecord`], [`Outcome`]), its energy
//! curve ([`EnergySample`]), its summary ([`Summary`]) and its `timeline.json`
//! ([`RunSource::timeline_json`]); and the run itself as its readers see it ([`RunSource`]): the chain at
//! any time ([`ChainState`]), the transition diagram's data ([`TransitionData`]) and each
//! magnet's travel and joint's angle against time ([`Track`]).
//!
//! The event engine ([`crate::engine`]) and the reference integrator ([`crate::reference`])
//! both produce these, and neither imports them from the other, so their results are
//! written, drawn and compared alike; the pictures and the viewer (the `foldchain-render`
//! crate) read runs through [`RunSource`] alone.
//!
//! ```
//! use foldchain::engine::{run, EngineOptions};
//! use foldchain::timeline::{Outcome, RunResult, TileDesigns};
//! use foldchain::Chain;
//!
//! let tl = run(&Chain::parse("SLLS").unwrap(), &TileDesigns::default(), &EngineOptions::default()).unwrap();
//! assert_eq!(tl.outcome, Outcome::Completed);
//! let summary = tl.summary();
//! assert!(summary.completed);
//! assert_eq!(summary.result, RunResult::Completed);
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
mod run_result;
mod run_source;
mod speed_law;
mod summary;
mod tile_designs;
mod track;
mod transition;

pub use chain_state::ChainState;
pub(crate) use chain_state::DETAIL_TILES;
pub use energy_sample::EnergySample;
pub(crate) use event::{joint_of_magnet, start_fraction};
pub use event::{Event, EventKind};
pub use fold_record::FoldRecord;
pub use free_motion::FreeMotion;
pub use geometry::Geometry;
pub(crate) use geometry::{GeometryError, LENGTH_TOLERANCE};
pub(crate) use json::{TimelineJson, EVENT_INDEX};
pub use outcome::Outcome;
pub use pair_energies::PairEnergies;
pub(crate) use parameters::design_parameters;
pub use parameters::Parameters;
pub use run_result::RunResult;
pub use run_source::RunSource;
pub use speed_law::SpeedLaw;
pub(crate) use summary::RunFacts;
pub use summary::{Clearance, CollisionReport, Summary};
pub(crate) use tile_designs::TileOverride;
pub use tile_designs::{DesignsError, SValue, TileDesigns};
pub use track::Track;
pub(crate) use track::{ANGLE_TOLERANCE, TRAVEL_TOLERANCE};
pub use transition::{MagnetTrack, TransitionData};
