//! The law a run's times are in: overdamped motion under the pair's attraction against a
//! drag, the inertial dynamics (magnets with mass, tiles with rotational inertia), or one
//! millimetre per second (the thesis' transition diagram, figure 6.3).

use crate::physics::DEFAULT_DRAG;

/// The speed law.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpeedLaw {
    /// Overdamped motion under the pair's `1/r^4` attraction, drag coefficient in N s/m.
    Overdamped {
        /// Drag coefficient, N s/m.
        drag: f64,
    },
    /// 1 mm per second: the transition diagram's timeline.
    Unit,
    /// The inertial dynamics (the design's masses and drags, [`crate::Design`]) of the engine's local solves:
    /// magnets with mass against a drag, tiles with rotational inertia, bouncing at path ends
    /// and walls. A kinematic engine given it moves its magnets by the overdamped law with
    /// this drag (the kinematic speed laws have no mass).
    Inertial {
        /// Drag of a magnet in its channel, N s/m.
        drag: f64,
    },
}

impl Default for SpeedLaw {
    /// Overdamped with the overdamped model's default magnet drag, 5 N s/m.
    fn default() -> SpeedLaw {
        SpeedLaw::Overdamped { drag: DEFAULT_DRAG }
    }
}
