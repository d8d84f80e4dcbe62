//! How a chain moved on the water during a run ([`FreeMotion`]), as `summary.json` states it:
//! the fastest tile, where and when, and how far the end tiles turned (computed by
//! `crate::model::Model::free_motion`).

/// How the chain moved on the water during a run.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FreeMotion {
    /// The fastest any tile's centre moved, m/s (0 without a fold).
    pub max_tile_speed_m_s: f64,
    /// The tile that moved fastest (null without a fold).
    pub fastest_tile: Option<usize>,
    /// When, s (null without a fold).
    pub fastest_at_s: Option<f64>,
    /// The joint whose turn moved it (null without a fold).
    pub fastest_joint: Option<usize>,
    /// How far the first tile (the RI end) turned on the water over the run, degrees
    /// (positive anticlockwise).
    pub first_tile_turn_deg: f64,
    /// How far the last tile turned on the water over the run, degrees.
    pub last_tile_turn_deg: f64,
}
