//! The reference force integrator: the chain's motion from the point-dipole forces
//! (SPEC (6.11), (6.12)), integrated in time, against which the event engine's inequalities
//! are measured (issue 6).
//!
//! - [`dynamics`]: the overdamped model, magnets held to their paths, joints turning under
//!   the magnets' torque and stopped by their walls, forces within a chain-index cutoff.
//! - [`integrators`]: Dormand-Prince 5(4) (explicit) and ROS2 (Rosenbrock, for stiff cases).
//! - [`banded`]: the banded Jacobian and LU the stiff integrator uses.
//! - [`events`]: the hybrid driver and [`run_reference`], with the engine's event kinds and
//!   summary fields.
//! - [`scenes`]: the scenes `fold-validate` runs.
//! - `pictures`: the reference's recorded states as the pictures' chain states, energy curve
//!   and transition data.
//! - [`validate`]: errors against run time (the work-precision table and plot).
//!
//! ```
//! use foldchain::reference::{run_reference, Method, ReferenceOptions};
//! use foldchain::engine::{Outcome, TileDesigns};
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

pub mod banded;
pub mod dynamics;
pub mod events;
pub mod integrators;
mod pictures;
pub mod scenes;
pub mod stiff;
pub mod validate;

pub use dynamics::{Model, ModelError, ModelOptions};
pub use events::{run_reference, ReferenceError, ReferenceOptions, ReferenceRun};
pub use integrators::{Method, StepStats};
pub use pictures::{
    reference_energy, reference_final_state, reference_state, reference_state_near,
    reference_transition, state_budget, state_energy, STATE_BUDGET_BYTES,
};
pub use stiff::{run_stiff_study, select_cases, StiffCase, StiffError, StiffStudy, STIFF_CASES};
