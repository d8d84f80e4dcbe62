//! The physical model both simulations integrate: the chain's unknowns (each magnet's
//! fraction of path travelled, each folding joint's fraction of fold made), the drives on
//! them from the pair forces of [`crate::physics`], how they answer the drives (overdamped
//! rates or inertial accelerations, [`Dynamics`]), where each is held (its mode: at its
//! start, free, at its end) and when it switches, and how a run ended from the state it came
//! to rest in.
//!
//! The event engine ([`crate::engine`]) integrates it one joint at a time, the reference
//! ([`crate::reference`](mod@crate::reference)) the whole chain at once; both step it with the
//! integrators of the crate's `ode` module, so the two differ only in what they integrate together.
//!
//! Public: the model of a chain ([`Model`], which a reference run's states index), its
//! options ([`ModelOptions`], [`Dynamics`]) and why it cannot be built ([`ModelError`]).
//!
//! ```
//! use foldchain::model::{Dynamics, ModelOptions};
//!
//! // the defaults: overdamped, the dipole law, three neighbours each way
//! let opts = ModelOptions::default();
//! assert_eq!(opts.dynamics, Dynamics::Overdamped);
//! assert_eq!(opts.cutoff, ModelOptions::DEFAULT_CUTOFF);
//! // the masses, drags and the water are the design's (`foldchain::Design`)
//! let inertial = opts.with_dynamics(Dynamics::Inertial);
//! assert!(inertial.dynamics.is_inertial());
//! ```

mod chain_model;
mod coefficients;
mod dynamics;
mod forces;
mod free_motion;
mod mode;
mod options;
pub(crate) mod sides;
mod verdict;

pub use chain_model::Model;
pub use chain_model::ModelError;
pub(crate) use chain_model::{parameters, Allow, Unknown};
pub(crate) use coefficients::{at_wall, InertialModel, REST_HEIGHT};
pub use dynamics::Dynamics;
pub(crate) use forces::Forces;
pub(crate) use mode::{condition, Mode};
pub use options::ModelOptions;
pub(crate) use verdict::{undecided_margin, RestState};
