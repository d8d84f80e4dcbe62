//! How much room a chain has to fold: how firmly each magnet is held at rest before the
//! reaction initiator comes, the drive margin of every magnet's start and the torque margin
//! of every fold, from the shared physics ([`crate::physics`]) on quasi-static
//! configurations of the chain (see [`start`](self) and [`fold`](self) below, in
//! [`Margins::of`]'s documentation). A chain whose every margin is positive folds as designed in
//! this model; the smallest margin says how near it is to stalling, and where.
//!
//! Margins are fractions of the bond force of the magnet's tile
//! ([`ForceLaw::bonded_rest_force`]): a drive margin of 0.01 is a net pull along the path of
//! 1% of the force that holds a tile's two magnets together.
//!
//! ```
//! use foldchain::margins::{MarginOptions, Margins};
//! use foldchain::{Chain, Design};
//!
//! let chain = Chain::parse("SLLS").unwrap();
//! let m = Margins::of(&chain, &[Design::thesis()], &MarginOptions::default()).unwrap();
//! assert_eq!(m.starts.len(), 2 * chain.len() - 1);
//! assert_eq!(m.folds.len(), 2);
//! assert!(m.folds_as_designed(), "{:?}", m.weakest());
//! ```

mod fold;
mod hold;
mod model;
mod placed_tiles;
mod start;

pub(crate) use model::ChainModel;
pub use model::MarginError;

use crate::physics::{ForceLaw, DEFAULT_CUTOFF};
use crate::{Chain, Design};

/// How the margins are computed. Default: the point-dipole law, the physics' default
/// chain-index cutoff (3), 32 samples along a mover's path and 16 over a fold's turn.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct MarginOptions {
    /// The pair law.
    pub force_law: ForceLaw,
    /// Pairs at most this many apart in chain index interact (at least 1).
    pub cutoff: usize,
    /// Samples of the mover's path (its stall and the best drive are then refined).
    pub path_samples: usize,
    /// Samples of a fold's quarter turn.
    pub fold_samples: usize,
}

impl Default for MarginOptions {
    fn default() -> MarginOptions {
        MarginOptions {
            force_law: ForceLaw::default(),
            cutoff: DEFAULT_CUTOFF,
            path_samples: 32,
            fold_samples: 16,
        }
    }
}

impl MarginOptions {
    /// Another pair law.
    pub fn with_force_law(mut self, force_law: ForceLaw) -> MarginOptions {
        self.force_law = force_law;
        self
    }

    /// Another chain-index cutoff (taken as at least 1).
    pub fn with_cutoff(mut self, cutoff: usize) -> MarginOptions {
        self.cutoff = cutoff;
        self
    }
}

/// The drive margin of one magnet's start.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StartMargin {
    /// The magnet.
    pub magnet: usize,
    /// The joint it belongs to (magnets `2j + 1` and `2j + 2` belong to joint `j`).
    pub joint: usize,
    /// The largest force along its path while it waits, over its tile's bond force.
    pub margin: f64,
    /// Where magnet `m - 1` was when that force was largest, mm along its path.
    pub at_travel: f64,
    /// Where magnet `m - 1` was when the force first turned `m` forwards, mm along its path
    /// (`None`: it never did).
    pub start_travel: Option<f64>,
    /// Where magnet `m - 1` stops, mm along its path, when the force along the movers' own
    /// paths vanishes before their ends.
    pub mover_stall: Option<f64>,
}

/// How firmly one magnet is held at rest before the reaction initiator comes.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HoldMargin {
    /// The magnet.
    pub magnet: usize,
    /// The force holding it at its rest point (against its path's direction), over its
    /// tile's bond force; negative: the chain actuates itself there (inequality (6.1)).
    pub margin: f64,
}

/// The torque margin of one fold.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FoldMargin {
    /// The joint.
    pub joint: usize,
    /// The smallest torque over the turn, over the bond force times the pair's lever.
    pub margin: f64,
    /// The angle turned where the torque was smallest, degrees.
    pub at_degrees: f64,
}

/// Where a chain's smallest margin is.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Weakest {
    /// A magnet's start.
    Start {
        /// The magnet.
        magnet: usize,
        /// Its joint.
        joint: usize,
        /// The margin.
        margin: f64,
    },
    /// A fold.
    Fold {
        /// The joint.
        joint: usize,
        /// The margin.
        margin: f64,
    },
    /// A magnet held at rest.
    Hold {
        /// The magnet.
        magnet: usize,
        /// Its joint.
        joint: usize,
        /// The margin.
        margin: f64,
    },
}

impl Weakest {
    /// The margin.
    pub fn margin(&self) -> f64 {
        match *self {
            Weakest::Start { margin, .. }
            | Weakest::Fold { margin, .. }
            | Weakest::Hold { margin, .. } => margin,
        }
    }

    /// The joint.
    pub fn joint(&self) -> usize {
        match *self {
            Weakest::Start { joint, .. }
            | Weakest::Fold { joint, .. }
            | Weakest::Hold { joint, .. } => joint,
        }
    }
}

impl std::fmt::Display for Weakest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Weakest::Start {
                magnet,
                joint,
                margin,
            } => write!(
                f,
                "{:+.2}% at magnet {magnet}'s start (joint {joint})",
                100.0 * margin
            ),
            Weakest::Fold { joint, margin } => {
                write!(f, "{:+.2}% at joint {joint}'s fold", 100.0 * margin)
            }
            Weakest::Hold {
                magnet,
                joint,
                margin,
            } => write!(
                f,
                "{:+.2}% holding magnet {magnet} at rest (joint {joint})",
                100.0 * margin
            ),
        }
    }
}

/// Every margin of a chain.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Margins {
    /// One per magnet, in chain order: how firmly the resting chain holds it.
    pub holds: Vec<HoldMargin>,
    /// One per magnet the design means to start, in chain order.
    pub starts: Vec<StartMargin>,
    /// One per joint the design means to fold, in chain order.
    pub folds: Vec<FoldMargin>,
}

impl Margins {
    /// Every margin of `chain` with `designs` (one design for every tile, or one per tile)
    /// under `opts`: each start's, hold's and fold's room, and the weakest of them (see the
    /// module documentation for the poses they are taken in). The designs' parameters are
    /// validated, not their inequalities: a design that breaks them has margins that say so.
    ///
    /// ```
    /// use foldchain::margins::{MarginOptions, Margins};
    /// use foldchain::{Chain, Design};
    ///
    /// let chain = Chain::parse("SLLS").unwrap();
    /// let m = Margins::of(&chain, &[Design::thesis()], &MarginOptions::default()).unwrap();
    /// assert!(m.folds_as_designed());
    /// ```
    pub fn of(
        chain: &Chain,
        designs: &[Design],
        opts: &MarginOptions,
    ) -> Result<Margins, MarginError> {
        Ok(margins(&ChainModel::new(chain, designs)?, opts))
    }

    /// The smallest margin of all, and where.
    pub fn weakest(&self) -> Option<Weakest> {
        let starts = self.starts.iter().map(|s| Weakest::Start {
            magnet: s.magnet,
            joint: s.joint,
            margin: s.margin,
        });
        let folds = self.folds.iter().map(|f| Weakest::Fold {
            joint: f.joint,
            margin: f.margin,
        });
        let holds = self.holds.iter().map(|h| Weakest::Hold {
            magnet: h.magnet,
            joint: crate::timeline::joint_of_magnet(h.magnet),
            margin: h.margin,
        });
        holds
            .chain(starts)
            .chain(folds)
            .min_by(|a, b| a.margin().total_cmp(&b.margin()))
    }

    /// The first failure (a margin <= 0): the weakest hold that fails, since a chain that
    /// actuates itself fails before the reaction initiator comes; else the first start or
    /// fold in the order propagation meets them, where a failing chain stops.
    pub fn first_failure(&self) -> Option<Weakest> {
        if let Some(h) = self
            .holds
            .iter()
            .filter(|h| h.margin <= 0.0)
            .min_by(|a, b| a.margin.total_cmp(&b.margin))
        {
            return Some(Weakest::Hold {
                magnet: h.magnet,
                joint: crate::timeline::joint_of_magnet(h.magnet),
                margin: h.margin,
            });
        }
        let start = self.starts.iter().find(|s| s.margin <= 0.0);
        let fold = self.folds.iter().find(|f| f.margin <= 0.0);
        // a fold of joint j comes after the start of magnet 2j + 2 (its pair's second magnet)
        let start_at = start.map(|s| (s.magnet, 0));
        let fold_at = fold.map(|f| (2 * f.joint + 2, 1));
        match (start_at, fold_at) {
            (None, None) => None,
            (Some(a), Some(b)) if b < a => fold.map(|f| Weakest::Fold {
                joint: f.joint,
                margin: f.margin,
            }),
            (Some(_), _) => start.map(|s| Weakest::Start {
                magnet: s.magnet,
                joint: s.joint,
                margin: s.margin,
            }),
            (None, Some(_)) => fold.map(|f| Weakest::Fold {
                joint: f.joint,
                margin: f.margin,
            }),
        }
    }

    /// Whether every margin is positive: the chain folds as designed in this model.
    pub fn folds_as_designed(&self) -> bool {
        self.first_failure().is_none()
    }
}

/// Every margin of the chain (see the module documentation and [`ChainModel`]).
///
/// **Criterion, stated.** Every magnet must be held at rest before the reaction initiator
/// comes (the chain at rest, the RI absent: inequality (6.1) with every pair within the
/// cutoff). Each start is judged with everything before the mover arrived and
/// folded and everything after the waiting magnet at rest; each fold with its pair and
/// everything before it arrived and everything after it at rest. Where assembly overlaps
/// (`s < e/3`) the real chain is somewhere between these poses; the test suite checks the
/// verdict against the force-integrated reference on the three-tile experiments.
pub(crate) fn margins(model: &ChainModel, opts: &MarginOptions) -> Margins {
    let opts = MarginOptions {
        cutoff: opts.cutoff.max(1),
        ..*opts
    };
    Margins {
        holds: hold::hold_margins(model, &opts),
        starts: {
            let mut starts: Vec<StartMargin> = Vec::new();
            for m in model.starting_magnets() {
                // where magnet m - 2 stood when m - 1 started (or, if it never did, where the
                // drive on m - 1 came nearest to starting it)
                let partner_start = match starts.len().checked_sub(1).map(|i| starts[i]) {
                    Some(prev) if m % 2 == 1 => prev.start_travel.unwrap_or(prev.at_travel),
                    _ => 0.0,
                };
                starts.push(start::start_margin(model, &opts, m, partner_start));
            }
            starts
        },
        folds: model
            .folding_joints()
            .map(|j| fold::fold_margin(model, &opts, j))
            .collect(),
    }
}
