//! The drags that set the pace of the overdamped motion: of a magnet sliding in its
//! oil-filled channel, and of a joint turning. The thesis gives neither value; both are
//! assumptions, and every time scales linearly with them.

/// Default drag coefficient of a magnet in its channel, N s/m: an assumed value that makes a
/// straight-path move of the thesis design take about a third of a second.
pub(crate) const DEFAULT_DRAG: f64 = 5.0;

/// Default rotational drag of a joint, N m s: the magnet drag [`DEFAULT_DRAG`] times the
/// square of the thesis' magnet radius (1.5 mm), 1.125e-5. With it a fold of the thesis
/// design takes about as long as the magnets' move, as in the event engine's fold law.
pub(crate) const DEFAULT_ROTATIONAL_DRAG: f64 = DEFAULT_DRAG * 1.5e-3 * 1.5e-3;
