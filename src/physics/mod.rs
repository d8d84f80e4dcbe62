//! The physics both simulations share: the pair law between two magnets, what a force does
//! to the chain (its drive along a magnet's path, its torque about a hinge), which pairs
//! interact (chain index, polarity and the cutoff), the reaction initiator, the drags, a tile as a rigid body on the water, and
//! the chain's dipole energy.
//!
//! The event engine's force start rule ([`crate::engine::StartRule::Force`]) and the
//! reference integrator ([`crate::reference`]) ask these questions of the same functions, so
//! a change of the model (a finite-cylinder law for [`ForceLaw`], say) is made here once and
//! holds for both.
//!
//! Units: positions in millimetres (as the tiles' frames), forces in newtons, torques in
//! newton metres, moments in A m^2, energies in joules.
//!
//! ```
//! use foldchain::physics::ForceLaw;
//! use foldchain::Design;
//! use kurbo::Point;
//!
//! // two attracting poles 10 mm apart on the x axis pull each other together
//! let law = ForceLaw::default();
//! let f = law.force(Point::new(0.0, 0.0), Point::new(10.0, 0.0), 0.036, 0.036, true);
//! assert!(f.x < 0.0 && f.y == 0.0);
//! // the finite-cylinder law of the thesis' magnets is named like the command line's
//! assert_eq!(ForceLaw::named("cylinder", &Design::thesis()), Some(ForceLaw::cylinder(&Design::thesis())));
//! ```

mod cylinder;
mod dipole;
mod drag;
mod drive;
mod energy;
mod force_law;
mod grid;
mod poles;
mod ri;
mod tile_body;

pub(crate) use drag::magnet_drag;
pub(crate) use drag::DEFAULT_DRAG;
#[cfg(test)]
pub(crate) use drag::DEFAULT_INERTIAL_DRAG;
pub(crate) use drive::{along_path, joints_between, torque_about};
pub(crate) use energy::EnergyUnit;
pub use force_law::ForceLaw;
pub(crate) use grid::pairs_within;
pub(crate) use poles::{neighbours, reach, upstream, Pole, DEFAULT_CUTOFF};
pub(crate) use ri::ReactionInitiator;
pub(crate) use tile_body::TileBody;
