//! How the smallest margin moves with each parameter: central finite differences, the
//! parameter moved on every tile at once.

use crate::margins::{margins, ChainModel, MarginError, MarginOptions};
use crate::tolerance::{nudged, Parameter, Tolerances};
use crate::{Chain, Design};

/// The finite-difference step: 0.01 mm for lengths, 0.5% for the remanence (small against
/// every tolerance, large against the margins' rounding).
fn step(p: Parameter) -> f64 {
    match p {
        Parameter::Br => 0.005,
        _ => 0.01,
    }
}

/// One parameter's sensitivity.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sensitivity {
    /// The parameter.
    pub parameter: Parameter,
    /// d(smallest margin) / d(parameter), per mm (per unit of relative change for `br`).
    pub per_unit: f64,
    /// `per_unit` times the parameter's tolerance: how far the tolerance alone moves the
    /// smallest margin, to first order.
    pub over_tolerance: f64,
    /// The step used, mm (relative for `br`).
    pub step: f64,
}

impl Sensitivity {
    /// Every parameter's sensitivity, at the `nominal` designs (one, or one per tile).
    pub fn all(
        chain: &Chain,
        nominal: &[Design],
        tol: &Tolerances,
        opts: &MarginOptions,
    ) -> Result<Vec<Sensitivity>, MarginError> {
        sensitivities(chain, nominal, tol, opts)
    }
}

/// The smallest margin of `chain` with every tile's design moved in `p` by `delta`.
fn smallest(
    chain: &Chain,
    nominal: &[Design],
    p: Parameter,
    delta: f64,
    opts: &MarginOptions,
) -> Result<f64, MarginError> {
    let designs: Vec<Design> = nominal.iter().map(|d| nudged(d, p, delta)).collect();
    let model = ChainModel::new(chain, &designs)?;
    Ok(margins(&model, opts)
        .weakest()
        .map_or(f64::INFINITY, |w| w.margin()))
}

/// Every parameter's sensitivity, at the nominal designs.
pub(crate) fn sensitivities(
    chain: &Chain,
    nominal: &[Design],
    tol: &Tolerances,
    opts: &MarginOptions,
) -> Result<Vec<Sensitivity>, MarginError> {
    Parameter::ALL
        .iter()
        .map(|&p| {
            let h = step(p);
            let up = smallest(chain, nominal, p, h, opts)?;
            let down = smallest(chain, nominal, p, -h, opts)?;
            let per_unit = (up - down) / (2.0 * h);
            Ok(Sensitivity {
                parameter: p,
                per_unit,
                over_tolerance: per_unit * tol.get(p),
                step: h,
            })
        })
        .collect()
}
