//! The drags that set the pace of the motion: of a magnet sliding in its channel (the
//! dynamics' defaults, [`magnet_drag`]), and of a tile gliding on the water
//! ([`crate::physics::TileBody`]). The thesis gives none; each is an estimate, and every time
//! of an overdamped run scales linearly with them.

use crate::Design;

/// Default drag of a magnet in its channel in the overdamped model, N s/m: 5, an assumed
/// value that makes a straight-path move of the thesis design take about a third of a
/// second (the overdamped model is the stiff limit of negligible mass, for validation).
pub(crate) const DEFAULT_DRAG: f64 = 5.0;

/// Default drag of a magnet in its channel in the inertial model, N s/m: 0.05. Estimate:
/// water pushed round a 3 mm magnet and sheared in a thin film under its 7 mm^2 base
/// (Stokes-like drag of a 3 mm body in water, `6 pi eta r` = 3e-5 N s/m, is the floor; a
/// 1-10 um film of water under the base gives `eta A / h` = 7e-4 to 7e-3 N s/m, of silicone
/// oil up to 1 N s/m): range 1e-3 to 1 N s/m. With the 0.265 g magnet its inertial time
/// `m / gamma` is 5 ms, short against a move (tens of ms): the motion is inertial but well
/// damped, and the magnet bounces at its path's end as the thesis saw (7.3.1).
pub(crate) const DEFAULT_INERTIAL_DRAG: f64 = 0.05;

/// The drag of a magnet in its channel, N s/m: the design's, or the dynamics' default
/// (`DEFAULT_INERTIAL_DRAG` when `inertial`, else `DEFAULT_DRAG`).
pub(crate) fn magnet_drag(design: &Design, inertial: bool) -> f64 {
    design.magnet_drag.unwrap_or(if inertial {
        DEFAULT_INERTIAL_DRAG
    } else {
        DEFAULT_DRAG
    })
}
