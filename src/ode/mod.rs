//! The numerics both simulations step the model with ([`crate::model`]): one of each thing.
//!
//! - [`dopri`](self::dopri): Dormand-Prince 5(4), explicit, adaptive; the tableau and the
//!   stages of a step, for whole-chain and small unit states alike.
//! - [`rosenbrock`](self::rosenbrock): the linearly implicit family for stiff stretches,
//!   ROS2 with a banded Jacobian (whole chains) and RODAS4 (a unit's few components).
//! - [`Stepper`]: one step of a whole-chain [`System`] by either [`Method`], with its error.
//! - [`Dense`] and [`hermite`]: the dense output of a step (Dormand-Prince's continuous
//!   extension, or the cubic Hermite on its ends).
//! - [`locate`](self::locate): where in a step an event happens (Illinois on a margin, or
//!   bisection on a condition), on the dense output.
//! - [`StepControl`] and [`integral`](self::control::integral): the step-size laws.
//!
//! The stepping loops that switch the model's modes at located events are the simulations'
//! own (the reference's drivers, the engine's unit solve); each is written from these parts.

mod band;
mod control;
mod dense;
pub(crate) mod dopri;
pub(crate) mod locate;
pub(crate) mod rosenbrock;
mod stepper;

pub(crate) use control::{integral, StepControl};
pub(crate) use dense::{hermite, Dense};
pub use stepper::{Method, StepStats};
pub(crate) use stepper::{Stepper, System};
