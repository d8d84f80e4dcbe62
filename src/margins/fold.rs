//! The torque margin of one fold.
//!
//! Joint `j` folds once its pair (magnets `2j + 1`, `2j + 2`) has closed. The margins pose
//! it quasi-statically: every magnet up to the pair at its path's end, every earlier fold
//! complete, everything after the pair at rest, and the joint turned through its quarter
//! turn. Only pairs that straddle the joint turn the part after it (forces inside that part
//! have no net torque about the hinge). The torque margin is the smallest torque in the
//! fold's direction over the turn, over the bond force of the pair's tile times the lever of
//! the pair's second magnet about the hinge (the torque the bond force would give at the
//! pair): positive means the fold turns all the way, negative that it stops or never starts.

use crate::margins::placed_tiles::{PlacedTiles, State};
use crate::margins::start::full_angle;
use crate::margins::{ChainModel, FoldMargin, MarginOptions};

/// The quasi-static state of joint `j`'s fold at angle `turn`.
struct Folding<'a> {
    model: &'a ChainModel,
    joint: usize,
    turn: f64,
}

impl State for Folding<'_> {
    fn travel(&self, k: usize) -> f64 {
        if k <= 2 * self.joint + 2 {
            self.model.length(k)
        } else {
            0.0
        }
    }

    fn angle(&self, j: usize) -> f64 {
        if j < self.joint {
            full_angle(self.model.fold(j))
        } else if j == self.joint {
            self.turn
        } else {
            0.0
        }
    }
}

/// The torque margin of joint `j`'s fold (see the module documentation).
pub(crate) fn fold_margin(model: &ChainModel, opts: &MarginOptions, j: usize) -> FoldMargin {
    let (law, cutoff) = (opts.force_law, opts.cutoff);
    let full = full_angle(model.fold(j));
    let sign = full.signum();
    let last = model.magnets() - 1;
    let lo = (2 * j + 2).saturating_sub(cutoff);
    let hi = (2 * j + 1 + cutoff).min(last);
    let mut w = PlacedTiles::new(if lo < cutoff { 0 } else { lo }, hi);
    let n = opts.fold_samples.max(1);
    let mut worst = (f64::INFINITY, 0.0);
    let mut lever = 0.0;
    for i in 0..=n {
        let turn = full * i as f64 / n as f64;
        w.place(
            model,
            &Folding {
                model,
                joint: j,
                turn,
            },
        );
        if i == 0 {
            lever = w.lever(model, j, 2 * j + 2, sign > 0.0);
        }
        let t = w.torque(model, law, cutoff, j, sign);
        if t < worst.0 {
            worst = (t, turn.abs().to_degrees());
        }
    }
    let scale = model.bond_force(law, j) * lever * 1e-3;
    FoldMargin {
        joint: j,
        margin: worst.0 / scale,
        at_degrees: worst.1,
    }
}
