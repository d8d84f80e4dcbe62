//! One point of a run's energy curve (thesis figure 7.5).

/// The chain's total dipole energy at one time.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct EnergySample {
    /// Time, s.
    pub time: f64,
    /// Total energy, J.
    pub energy_j: f64,
}
