//! The physical model both simulations integrate: the chain's unknowns (each magnet's
//! fraction of path travelled, each folding joint's fraction of fold made), the drives on
//! them from the pair forces of [`crate::physics`], how they answer the drives (overdamped
//! rates or inertial accelerations, [`Dynamics`]), where each is held ([`Mode`]: at its
//! start, free, at its end) and when it switches, and how a run ended from the state it came
//! to rest in.
//!
//! The event engine ([`crate::engine`]) integrates it one joint at a time, the reference
//! ([`crate::reference`](mod@crate::reference)) the whole chain at once; both step it with the
//! integrators of the crate's `ode` module, so the two differ only in what they integrate together.
//!
//! ```
//! use foldchain::model::{Model, ModelOptions};
//! use foldchain::timeline::TileDesigns;
//! use foldchain::Chain;
//!
//! // a straight tile, a tight U-turn (two left folds), a straight tile: a magnet unknown per
//! // magnet, a fold unknown per folding joint
//! let chain = Chain::parse("SLLS").unwrap();
//! let model = Model::new(&chain, &TileDesigns::default(), &ModelOptions::default()).unwrap();
//! assert_eq!(model.len(), 10 + 2);
//! assert!(model.joint_var(0).is_none() && model.joint_var(1).is_some());
//! ```

mod chain_model;
mod coefficients;
mod dynamics;
mod forces;
mod free_motion;
mod mode;
mod options;
mod sides;
mod verdict;

pub(crate) use chain_model::Unknown;
pub use chain_model::{Model, ModelError, BALANCE_TOLERANCE};
pub(crate) use coefficients::{at_wall, InertialModel};
pub use dynamics::Dynamics;
pub(crate) use forces::Forces;
pub(crate) use mode::{condition, Mode};
pub use options::ModelOptions;
pub(crate) use verdict::RestState;
