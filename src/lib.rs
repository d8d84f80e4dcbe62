//! # foldchain
//!
//! Design and simulation of self-folding magnetic tile chains: octagon tiles holding magnets
//! in walled paths, which fold into a shape fixed by the order of the paths once a reaction
//! initiator starts them (the model and the thesis it follows: `docs/physics.md`).
//!
//! This crate is the core model and computes only; the command-line tools live in the
//! `foldchain-cli` crate.
//! - Paths, tiles and joints ([`PathKind`], [`Tile`], [`Fold`]); chains in their three forms
//!   ([`Chain`], [`FoldWord`], JSON); the tile design with the path-length inequalities
//!   ([`Design`]) and its bill of materials ([`BillOfMaterials`]).
//! - Exact and floating-point kinematics of the octagon chain ([`FoldWord::final_poses`],
//!   [`Pose::chain_at_angles`], with exact coordinates in [`exact`]).
//! - Self-intersection, exactly, during every fold and in the final shape ([`collision`]), and
//!   the counts of chains that fold cleanly ([`count`]).
//! - The folding run: the event engine ([`engine`]) and the force-integrated reference
//!   ([`reference`](mod@reference)), both read through one run abstraction
//!   ([`timeline::RunSource`]); their pictures and viewer are the `foldchain-render` crate.
//!
//! ```
//! use foldchain::collision::{check_word, CheckOptions};
//! use foldchain::{Chain, Design};
//!
//! // A tight U-turn: two left folds, one LL tile.
//! let chain = Chain::parse("SSLLSS").unwrap();
//! assert_eq!(chain.to_tile_list(), "SS SS SL LL LS SS SS");
//! let word = chain.to_word().unwrap();
//! let poses = word.final_poses();
//! // the return row runs sqrt2 * w from the first, exactly
//! let w = 30.0;
//! let pitch = poses[4].centre.y.to_f64(w) - poses[2].centre.y.to_f64(w);
//! assert!((pitch - 2f64.sqrt() * w).abs() < 1e-12);
//! // it folds without any two tiles overlapping; five tiles in a ring do not
//! assert!(check_word(&word, &CheckOptions::default()).is_ok());
//! let ring = Chain::parse("LLLL").unwrap().to_word().unwrap();
//! let collision = check_word(&ring, &CheckOptions::default()).unwrap_err();
//! assert_eq!(collision.tiles, (0, 4));
//! // the thesis design satisfies inequalities (6.1) to (6.10)
//! assert!(Design::thesis().check().is_ok());
//! ```

mod bom;
mod chain;
pub mod collision;
pub mod count;
pub mod design;
pub mod engine;
mod engine_choice;
mod error;
pub mod exact;
mod joint;
mod kinematics;
pub mod magnet_path;
pub mod margins;
pub mod model;
mod number_text;
mod octagon;
mod ode;
mod path_kind;
pub mod physics;
mod pose;
mod progress;
pub mod reference;
mod rng;
mod simulation;
mod text_serde;
mod tile;
mod tile_frame;
pub mod timeline;
pub mod tolerance;
mod word;

pub use bom::BillOfMaterials;
pub use chain::Chain;
pub(crate) use chain::MAX_TILES;
pub use design::{Design, DesignError, InequalityCheck, Standing};
pub use engine_choice::AutoEngine;
pub use error::ChainError;
pub use exact::{ExactPoint, ExactPose, QuarterTurns, Surd};
pub use joint::Fold;
pub(crate) use joint::JointOutcome;
pub use number_text::short_number;
pub use octagon::Octagon;
pub use path_kind::PathKind;
pub use pose::Pose;
pub use progress::Progress;
pub use simulation::simulate;
pub use tile::{Part, Tile};
pub use word::FoldWord;
