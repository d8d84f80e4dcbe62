//! The free-body reference: every tile a rigid body in the plane, floating, nothing
//! anchored (issue 27). Each tile has its mass and moment of inertia and the water's drag on
//! it (the design's water: linear film drag, optionally quadratic form drag); the magnets slide on
//! their paths under the pair forces of [`crate::physics`] as in the model
//! ([`crate::model`]); the RI rides on tile 0. A joint that is not turning holds its two
//! tiles together, so the chain is a few rigid groups joined by the turning joints, each a
//! revolute hinge: the groups' accelerations come from the articulated-body recursion
//! (floating base), exact and O(groups) per evaluation, and the pair forces cost O(cutoff^2)
//! per turning joint and O(cutoff) per moving magnet, so a step costs what moves, not the
//! chain's length. It is stepped with the crate's Dormand-Prince (the `ode` module) by a
//! stepping loop like the joint-angle reference's inertial one, with the same events.
//!
//! With no water drag the chain's linear and angular momentum stay what they were (zero from
//! rest): the pair forces are internal and central, and a fold meeting its wall is an
//! impulse inside the chain.
//!
//! The run is a [`ReferenceRun`](crate::reference::ReferenceRun) (in
//! [`FreeBodyRun::run`]): the chain's shape in tile 0's frame, its events, folds and
//! outcome, with tile 0's path in the world beside it.
//!
//! ```
//! use foldchain::reference::{run_free_body, FreeBodyOptions};
//! use foldchain::timeline::{Outcome, TileDesigns};
//! use foldchain::Chain;
//!
//! let chain = Chain::parse("SLS").unwrap();
//! let run = run_free_body(&chain, &TileDesigns::default(), &FreeBodyOptions::default()).unwrap();
//! assert_eq!(run.run.outcome, Outcome::Completed);
//! assert_eq!(run.run.folded_joints(), vec![1]);
//! ```

mod driver;
pub(crate) mod groups;
mod options;
mod run;
mod spatial;
pub(crate) mod system;
pub(crate) mod tile_body;

pub use driver::run_free_body;
pub(crate) use driver::{run_coupled, setup};
pub use options::FreeBodyOptions;
pub use run::FreeBodyRun;
pub use system::Momentum;
