//! The law a run's times are in: overdamped motion under the pair's attraction against a
//! drag, or one millimetre per second (the thesis' transition diagram, figure 6.3).

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
}

impl Default for SpeedLaw {
    /// Overdamped with [`DEFAULT_DRAG`].
    fn default() -> SpeedLaw {
        SpeedLaw::Overdamped { drag: DEFAULT_DRAG }
    }
}
