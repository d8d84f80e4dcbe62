//! The event engine: when every magnet moves and every joint folds, derived from the
//! geometry of the paths (SPEC section 4, thesis chapter 6), as an ordered queue of discrete
//! events; the fold schedule it implies; and the energy of the chain over time.
//!
//! ```
//! use foldchain::engine::{run, EngineOptions, Outcome, SpeedLaw, TileDesigns};
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

mod designs;
mod energy;
mod event;
mod fold;
mod geometry;
mod run;
mod speed;
mod start_rule;
mod summary;

pub use designs::{BadSValue, DesignsError, SValue, TileDesigns, TileOverride};
pub use energy::{energy_curve, EnergySample};
pub use event::{Event, EventKind};
pub use fold::{fold_angle, fold_schedule, joint_angles_at, ANGLE_TOLERANCE};
pub use geometry::{Geometry, Trigger, LENGTH_TOLERANCE};
pub use run::{joint_of_magnet, run, EngineError, EngineOptions, FoldRecord, Outcome, Timeline};
pub use speed::{Motion, SpeedLaw, DEFAULT_DRAG};
pub use start_rule::{StartRule, DRIVE_TOLERANCE};
pub use summary::{CollisionReport, Summary};
