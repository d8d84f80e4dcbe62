//! The reference force integrator: the whole chain's motion under the model of
//! [`crate::model`] (the pair forces of [`crate::physics`], SPEC (6.11), (6.12)), integrated
//! in time at once, against which the event engine is measured (issue 6). It shares the model,
//! the numerics (the crate's `ode` module) and the vocabulary of its results ([`crate::timeline`]) with
//! the event engine, and nothing else.
//!
//! - Two integrators ([`Method`]): Dormand-Prince 5(4) (explicit) and ROS2 (Rosenbrock, for
//!   stiff cases), the latter with a banded Jacobian and LU.
//! - [`run_reference`]: the hybrid driver, which locates every event on real integrator steps
//!   and switches the unknowns' modes there; its result ([`ReferenceRun`]) carries the
//!   engine's event kinds and summary fields.
//! - The pictures' data from the reference's recorded states, through
//!   [`RunSource`](crate::timeline::RunSource) (the stiff cases and the study of both
//!   integrators on them are the `foldchain-validation` crate's).
//!
//! ```
//! use foldchain::reference::{run_reference, Method, ReferenceOptions};
//! use foldchain::timeline::{Outcome, TileDesigns};
//! use foldchain::Chain;
//!
//! // a straight tile, a tight U-turn (two left folds), a straight tile
//! let chain = Chain::parse("SLLS").unwrap();
//! let opts = ReferenceOptions::default().with_method(Method::Ros2).with_tolerance(1e-4);
//! let run = run_reference(&chain, &TileDesigns::default(), &opts).unwrap();
//! assert_eq!(run.outcome, Outcome::Completed);
//! assert_eq!(run.folded_joints(), vec![1, 2]);
//! // the same fields as the event engine's summary.json
//! assert_eq!(run.to_summary().result, "completed");
//! ```

mod driver;
mod event_log;
pub mod free_body;
pub(crate) mod inertial;
mod locate;
mod options;
mod pictures;
mod recorder;
mod run_result;
mod run_source;
mod stepping;

pub use crate::ode::{Method, StepStats};
pub use driver::run_reference;
pub use free_body::{run_free_body, FreeBodyOptions, FreeBodyRun};
pub use options::{Recording, ReferenceError, ReferenceOptions};
pub(crate) use pictures::{pair_energies, state_budget};
pub use run_result::ReferenceRun;
pub(crate) use run_source::joint_angle_samples;
