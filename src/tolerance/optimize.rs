//! The design search: the fastest assembly whose folding probability under the tolerances
//! stays above a target, inside inequalities (6.1) to (6.10).
//!
//! The search varies the wall (global), `s` on the tiles of straight runs (`SS` tiles) and
//! `s` on the tiles of turns (any curved path), as thesis 6.6 suggests: a chain may assemble
//! simultaneously where it runs straight and sequentially where it turns. For each candidate
//! it checks every tile's design against the inequalities ([`Design::check`]), runs the event
//! engine with its fold schedule's collision check ([`crate::simulate`]) for the assembly
//! time, and estimates the folding probability by a tolerance study (the same seed for every
//! candidate: common random numbers, so candidates differ by their design and not by their
//! draws). The grid's diagonal (one `s` for every tile) is the trade-off of probability
//! against assembly time over `s`.

use crate::collision::CheckOptions;
use crate::engine::EngineOptions;
use crate::margins::MarginError;
use crate::simulate;
use crate::timeline::{TileDesigns, TileOverride};
use crate::tolerance::{nudged, study, Parameter, StudyOptions};
use crate::{Chain, Design, PathKind};

/// What the search tries. Default: target 0.99; `s` from 0.05 to 1.5 mm (below `e/3` of the
/// thesis' `e`); walls 0.2 mm thinner, as designed and 0.2 mm thicker; the study's defaults
/// with 1,000 samples per candidate.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SearchOptions {
    /// The folding probability a design must keep (the lower end of its 95% interval is
    /// not asked for: the estimate itself).
    pub target: f64,
    /// Values of `s` tried, mm.
    pub s_grid: Vec<f64>,
    /// Changes of the wall tried, mm (0 = the base design's).
    pub wall_steps: Vec<f64>,
    /// The tolerance study of each candidate.
    pub study: StudyOptions,
    /// The engine that times the assembly.
    pub engine: EngineOptions,
    /// Search also per-tile `s` (straight runs against turns); `false`: one `s` for all.
    pub per_tile_s: bool,
}

impl Default for SearchOptions {
    fn default() -> SearchOptions {
        SearchOptions {
            target: 0.99,
            s_grid: vec![0.05, 0.1, 0.15, 0.2, 0.3, 0.45, 0.7, 1.0, 1.4],
            wall_steps: vec![-0.2, 0.0, 0.2],
            study: StudyOptions {
                samples: 500,
                ..StudyOptions::default()
            },
            engine: EngineOptions::default(),
            per_tile_s: true,
        }
    }
}

impl SearchOptions {
    /// Another target probability.
    pub fn with_target(mut self, target: f64) -> SearchOptions {
        self.target = target;
        self
    }

    /// Another study of each candidate.
    pub fn with_study(mut self, study: StudyOptions) -> SearchOptions {
        self.study = study;
        self
    }

    /// Another engine to time the assembly.
    pub fn with_engine(mut self, engine: EngineOptions) -> SearchOptions {
        self.engine = engine;
        self
    }

    /// Search per-tile `s` (straight runs against turns) or not.
    pub fn with_per_tile_s(mut self, per_tile_s: bool) -> SearchOptions {
        self.per_tile_s = per_tile_s;
        self
    }
}

/// One design tried.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Candidate {
    /// `s` of the straight-run tiles, mm.
    pub s_straight: f64,
    /// `s` of the turn tiles, mm.
    pub s_turn: f64,
    /// The change of the wall against the base design, mm.
    pub wall_step: f64,
    /// Why the design is out of bounds (an inequality that fails), if it is.
    pub infeasible: Option<String>,
    /// The engine's assembly time, s; `None` when the engine's run does not complete
    /// cleanly.
    pub assembly_s: Option<f64>,
    /// The folding probability under the tolerances, and its 95% interval.
    pub probability: f64,
    /// Its 95% Wilson interval.
    pub interval: (f64, f64),
    /// The nominal design's smallest margin.
    pub nominal_margin: f64,
}

impl Candidate {
    /// The per-tile designs of this candidate for `chain`: `base` with the wall moved, `s`
    /// set per kind (straight runs, turn tiles).
    pub fn designs(&self, chain: &Chain, base: &Design) -> Vec<Design> {
        candidate_designs(chain, base, self)
    }

    /// This candidate as a design file (`{"global": ..., "tiles": [...]}`, the form
    /// [`crate::timeline::TileDesigns::from_json`] reads): `base` with the wall moved and the
    /// straight runs' `s`, the turn tiles' `s` as overrides, runs of turn tiles in one entry.
    pub fn design_file(&self, chain: &Chain, base: &Design) -> serde_json::Value {
        candidate_design_json(chain, base, self)
    }

    /// Whether it is inside the inequalities, assembles cleanly and reaches `target`.
    pub fn meets(&self, target: f64) -> bool {
        self.infeasible.is_none() && self.assembly_s.is_some() && self.probability >= target
    }
}

/// The search's result.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Search {
    /// The base design as given.
    pub base: Candidate,
    /// Every candidate, in grid order.
    pub candidates: Vec<Candidate>,
    /// The fastest candidate that meets the target, if any.
    pub best: Option<Candidate>,
    /// The most probable candidate that assembles cleanly inside the inequalities.
    pub most_probable: Option<Candidate>,
}

impl Search {
    /// Searches the grid of `opts` around `base` (its wall and magnets; `s` per kind of
    /// tile): first one `s` for every tile, for every wall step (the trade-off); then, at the
    /// wall step whose best probability is highest, every pair of `s` on straight runs and on
    /// turns.
    pub fn run(chain: &Chain, base: &Design, opts: &SearchOptions) -> Result<Search, MarginError> {
        optimize(chain, base, opts)
    }
}

/// Whether a tile belongs to a turn (it holds a curved path).
fn is_turn(tile: &crate::Tile) -> bool {
    tile.first != PathKind::S || tile.second != PathKind::S
}

/// The per-tile designs of a candidate: the base with the wall moved, `s` set per kind.
pub(crate) fn candidate_designs(chain: &Chain, base: &Design, c: &Candidate) -> Vec<Design> {
    designs_of(chain, base, c.s_straight, c.s_turn, c.wall_step)
}

/// A candidate as a design file (`{"global": ..., "tiles": [...]}`, the form
/// [`TileDesigns::from_json`] reads): the base with the wall moved and the straight runs'
/// `s`, the turn tiles' `s` as overrides, runs of turn tiles in one entry.
pub(crate) fn candidate_design_json(
    chain: &Chain,
    base: &Design,
    c: &Candidate,
) -> serde_json::Value {
    let mut global = nudged(base, Parameter::Wall, c.wall_step).with_s(c.s_straight);
    // the grid's steps are decimal: keep the file free of binary rounding
    global.wall = (global.wall * 1e9).round() / 1e9;
    let mut tiles: Vec<serde_json::Value> = Vec::new();
    let turns: Vec<bool> = chain.tiles().iter().map(is_turn).collect();
    let mut i = 0;
    while i < turns.len() {
        if turns[i] && c.s_turn != c.s_straight {
            let from = i;
            while i + 1 < turns.len() && turns[i + 1] {
                i += 1;
            }
            tiles.push(serde_json::json!({"from": from, "to": i, "s": c.s_turn}));
        }
        i += 1;
    }
    serde_json::json!({"global": global, "tiles": tiles})
}

fn designs_of(
    chain: &Chain,
    base: &Design,
    s_straight: f64,
    s_turn: f64,
    wall: f64,
) -> Vec<Design> {
    let walled = nudged(base, Parameter::Wall, wall);
    chain
        .tiles()
        .iter()
        .map(|t| walled.with_s(if is_turn(t) { s_turn } else { s_straight }))
        .collect()
}

/// The engine's designs of a candidate (overrides for the turn tiles).
fn tile_designs(chain: &Chain, designs: &[Design], s_straight: f64, s_turn: f64) -> TileDesigns {
    let overrides = chain
        .tiles()
        .iter()
        .enumerate()
        .filter(|(_, t)| is_turn(t))
        .map(|(i, _)| TileOverride {
            from: i,
            to: i,
            s: Some(s_turn),
            e: None,
        })
        .collect();
    TileDesigns::with_overrides(designs[0].with_s(s_straight), overrides)
}

/// Evaluates one candidate.
pub fn evaluate(
    chain: &Chain,
    base: &Design,
    (s_straight, s_turn, wall_step): (f64, f64, f64),
    opts: &SearchOptions,
) -> Result<Candidate, MarginError> {
    let designs = designs_of(chain, base, s_straight, s_turn, wall_step);
    let infeasible = designs
        .iter()
        .find_map(|d| d.check().err())
        .map(|e| e.to_string());
    let engine_designs = tile_designs(chain, &designs, s_straight, s_turn);
    let assembly_s = match simulate(
        chain,
        &engine_designs,
        &opts.engine,
        // the verdict and the time rank a candidate; its clearance is not reported
        &CheckOptions::default().with_clearance(false),
    ) {
        Ok((_, summary)) if summary.completed => Some(summary.duration_s),
        _ => None,
    };
    let s = study(chain, &designs, &opts.study)?;
    Ok(Candidate {
        s_straight,
        s_turn,
        wall_step,
        infeasible,
        assembly_s,
        probability: s.probability,
        interval: s.interval,
        nominal_margin: s.nominal.weakest().map_or(f64::INFINITY, |w| w.margin()),
    })
}

/// Searches the grid of `opts` around `base` (its wall and magnets; `s` per kind of tile):
/// first one `s` for every tile, for every wall step (the trade-off); then, at the wall step
/// whose best probability is highest, every pair of `s` on straight runs and on turns.
pub(crate) fn optimize(
    chain: &Chain,
    base: &Design,
    opts: &SearchOptions,
) -> Result<Search, MarginError> {
    let base_candidate = evaluate(chain, base, (base.s, base.s, 0.0), opts)?;
    let mut candidates = Vec::new();
    for &w in &opts.wall_steps {
        for &s in &opts.s_grid {
            candidates.push(evaluate(chain, base, (s, s, w), opts)?);
        }
    }
    let best_wall = candidates
        .iter()
        .filter(|c| c.infeasible.is_none() && c.assembly_s.is_some())
        .max_by(|a, b| a.probability.total_cmp(&b.probability))
        .map(|c| c.wall_step);
    if let (true, Some(w)) = (opts.per_tile_s, best_wall) {
        for &a in &opts.s_grid {
            for &b in &opts.s_grid {
                if a != b {
                    candidates.push(evaluate(chain, base, (a, b, w), opts)?);
                }
            }
        }
    }
    let best = candidates
        .iter()
        .filter(|c| c.meets(opts.target))
        .min_by(|a, b| {
            let t = |c: &Candidate| c.assembly_s.unwrap_or(f64::INFINITY);
            t(a).total_cmp(&t(b))
                .then(b.probability.total_cmp(&a.probability))
        })
        .cloned();
    let most_probable = candidates
        .iter()
        .filter(|c| c.infeasible.is_none() && c.assembly_s.is_some())
        .max_by(|a, b| {
            a.probability.total_cmp(&b.probability).then(
                b.assembly_s
                    .unwrap_or(f64::INFINITY)
                    .total_cmp(&a.assembly_s.unwrap_or(f64::INFINITY)),
            )
        })
        .cloned();
    Ok(Search {
        base: base_candidate,
        candidates,
        best,
        most_probable,
    })
}
