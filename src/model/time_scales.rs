//! The model's two time scales on a chain: a magnet's and a fold's. Where they differ by
//! decades the model is stiff (the stiff study of `fold-validate --stiff`).

use std::f64::consts::FRAC_PI_2;

use crate::model::{Model, ModelError, ModelOptions};
use crate::timeline::TileDesigns;
use crate::Chain;

/// The model's two time scales on a chain.
///
/// ```
/// use foldchain::model::{ModelOptions, TimeScales};
/// use foldchain::timeline::TileDesigns;
/// use foldchain::Chain;
///
/// let chain = Chain::parse("SLLS").unwrap();
/// let scales = TimeScales::of(&chain, &TileDesigns::default(), &ModelOptions::default()).unwrap();
/// // with the default drags a fold is faster than a magnet: nothing is stiff
/// assert!(scales.ratio() < 1.0);
/// // a thousand times the rotational drag makes the folds the slower
/// let heavy = ModelOptions::default().with_rotational_drag(1e3 * ModelOptions::default().rotational_drag);
/// assert!(TimeScales::of(&chain, &TileDesigns::default(), &heavy).unwrap().ratio() > 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct TimeScales {
    /// A magnet's time scale, s: its path travelled at the bonded rest force's speed.
    pub magnet_s: f64,
    /// A fold's, s: a quarter turn at the bonded rest torque against the rotational drag,
    /// `rotational_drag * (pi/2) / torque_scale`. An estimate: the torque on a real fold
    /// changes as it turns and its magnets move.
    pub fold_s: f64,
}

impl TimeScales {
    /// The time scales of the model of `chain` with `designs` and `opts`.
    pub fn of(
        chain: &Chain,
        designs: &TileDesigns,
        opts: &ModelOptions,
    ) -> Result<TimeScales, ModelError> {
        let model = Model::new(chain, designs, opts)?;
        Ok(TimeScales {
            magnet_s: model.time_scale,
            fold_s: model.options().rotational_drag * FRAC_PI_2 / model.torque_scale,
        })
    }

    /// The fold's time scale over the magnets': far above 1 is stiff.
    pub fn ratio(&self) -> f64 {
        self.fold_s / self.magnet_s
    }
}
