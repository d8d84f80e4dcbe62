//! The reference force integrator: the chain's motion from the pair forces of
//! [`crate::physics`] (SPEC (6.11), (6.12)), integrated in time, against which the event
//! engine's inequalities are measured (issue 6). It shares the physics and the vocabulary of
//! its results ([`crate::timeline`]) with the event engine, and nothing else.
//!
//! - The model ([`Model`]): overdamped dynamics, magnets held to their paths, joints turning
//!   under the magnets' torque and stopped by their walls, forces within a chain-index cutoff.
//! - Two integrators ([`Method`]): Dormand-Prince 5(4) (explicit) and ROS2 (Rosenbrock, for
//!   stiff cases), the latter with a banded Jacobian and LU.
//! - [`run_reference`]: the hybrid driver, which locates every event on real integrator steps
//!   and switches the unknowns' modes there; its result ([`ReferenceRun`]) carries the
//!   engine's event kinds and summary fields.
//! - [`scenes`]: the scenes `fold-validate` runs; [`validate`]: errors against run time (the
//!   work-precision table and plot); [`stiff`]: the stiff cases and their study.
//! - The pictures' data from the reference's recorded states ([`reference_state`],
//!   [`reference_energy`], [`reference_transition`]).
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

mod banded;
mod control;
mod dense;
mod driver;
mod dynamics;
mod dynamics_kind;
mod event_log;
pub mod experiments;
mod forces;
pub(crate) mod inertial;
pub(crate) mod integrators;
mod locate;
mod model_options;
mod options;
mod pictures;
mod recorder;
mod run_result;
mod run_source;
pub mod scenes;
pub mod stiff;
pub mod validate;
mod verdict;

pub use driver::run_reference;
pub use dynamics::{Model, ModelError, ModelOptions, BALANCE_TOLERANCE};
// the unknowns' modes, for the event engine's local solves (which switch them as here)
pub(crate) use dynamics::Mode;
pub use dynamics_kind::Dynamics;
pub use integrators::{Method, StepStats};
pub use options::{Recording, ReferenceError, ReferenceOptions};
pub use pictures::{
    reference_energy, reference_final_state, reference_state, reference_state_near,
    reference_transition, state_budget, state_energy, STATE_BUDGET_BYTES,
};
pub use run_result::ReferenceRun;
pub(crate) use run_source::joint_angle_samples;
pub use stiff::{run_stiff_study, select_cases, StiffCase, StiffError, StiffStudy, STIFF_CASES};
