//! The energy of each adjacent pair of magnets and of the whole chain against time, with the
//! phase boundaries: what the thesis' figures 7.7 and 7.8 show of an experiment.

/// The energy curves of a run (thesis figures 7.7, 7.8), one point per recorded state.
#[derive(Clone, Debug, PartialEq)]
pub struct PairEnergies {
    /// The times, s.
    pub times: Vec<f64>,
    /// Per adjacent pair (the RI with magnet 0, then magnet `k` with `k + 1`), its energy at
    /// each time, J.
    pub pairs: Vec<Vec<f64>>,
    /// The chain's total dipole energy at each time, J.
    pub total: Vec<f64>,
    /// The phase boundaries: the times a magnet started or arrived, or a fold started or
    /// ended, s.
    pub phases: Vec<f64>,
}
