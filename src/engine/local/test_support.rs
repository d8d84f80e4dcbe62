//! What the local solves' tests share: a word's chain solved with chosen options.

#![allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)

use crate::engine::local::relaxation::{solve_chain_with, ChainSolution};
use crate::engine::local::solve::{InertialModel, SolveOptions};
use crate::model::{Dynamics, Model, ModelOptions};
use crate::timeline::{start_fraction, TileDesigns};
use crate::{Chain, Design};

/// How a test solves a chain: the tolerance and step limit of the engine's runs, the rest
/// chosen.
#[derive(Clone, Copy)]
pub(crate) struct Options {
    /// The thesis design's `s`, mm.
    pub s: f64,
    pub dynamics: Dynamics,
    /// The cache and the sharing of shapes.
    pub reuse: bool,
    /// RODAS4 where an inertial unit is stiff.
    pub rosenbrock: bool,
    /// Units at rest checking their release only past a few input nodes.
    pub rest_skip: bool,
    /// Threads of the sweeps.
    pub threads: usize,
}

/// `word`'s chain solved with `o`.
pub(crate) fn solve_word(word: &str, o: Options) -> ChainSolution {
    let chain = Chain::parse(word).unwrap();
    let model = Model::new(
        &chain,
        &TileDesigns::global(Design::thesis().with_s(o.s)),
        &ModelOptions {
            dynamics: o.dynamics,
            ..ModelOptions::default()
        },
    )
    .unwrap();
    let inertial = InertialModel::new(&model);
    let opts = SolveOptions {
        tol: 1e-8,
        start_fraction: start_fraction(&model.geometry),
        max_steps: 1_000_000,
        inertial: inertial.as_ref(),
        rosenbrock: o.rosenbrock,
        rest_skip: o.rest_skip,
        coupled: None,
        horizon: f64::INFINITY,
    };
    solve_chain_with(&model, opts, o.reuse, o.threads)
}

/// Every word of 1 to `max` letters (S, L, R).
pub(crate) fn words(max: usize) -> Vec<String> {
    let mut all = Vec::new();
    let mut level = vec![String::new()];
    for _ in 0..max {
        level = level
            .iter()
            .flat_map(|w| ['S', 'L', 'R'].map(|c| format!("{w}{c}")))
            .collect();
        all.extend(level.iter().cloned());
    }
    all
}

/// `word`'s model with the thesis design at `s` mm, inertial dynamics.
pub(crate) fn inertial_model(word: &str, s: f64) -> Model {
    let chain = Chain::parse(word).unwrap();
    Model::new(
        &chain,
        &TileDesigns::global(Design::thesis().with_s(s)),
        &ModelOptions::default().with_dynamics(Dynamics::Inertial),
    )
    .unwrap()
}
