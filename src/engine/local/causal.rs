//! A unit's solve that no motion of the sweep before can start before its cause (coupled
//! folds, [`Model::coupled_folds`](crate::model::Model)).
//!
//! A unit reads the units after it on their tracks of the sweep before. Where one of its
//! unknowns started there and a unit after it followed (a magnet releasing the next, which
//! releases the one after), a later sweep in which that unknown starts later still sees the
//! followers move at their old times: they pull the unknown off its rest point, it starts
//! just after them, they follow it again one sweep on, and the sweeps walk the whole train
//! later by its delay each time without end (`LLRS` at s = 0.3: magnets 6, 7, 8 moving
//! 0.037 s later each sweep, where the coupled reference stalls). The fixed point of that
//! walk is the train never starting.
//!
//! So where an unknown starts later than in the sweep before (or not at all), the tracks
//! after the unit that started since its old start are taken as following it: the unit is
//! solved again with them at rest, and, if the unknown starts then, once more with them
//! moved later by as much as its start moved. A unit whose starts did not move later is
//! solved once, as before.

use crate::engine::local::solve::{solve, Solution, SolveOptions};
use crate::engine::local::sweep::SWEEP_TOLERANCE;
use crate::engine::local::trajectory::Track;
use crate::engine::local::unit_forces::{Inputs, UnitForces, Var};

/// The start of unknown `i` of `sol` (its time origin `t0`), absolute.
fn start_of(sol: &Solution, t0: f64, i: usize) -> Option<f64> {
    sol.shapes
        .get(i)
        .and_then(|s| s.as_ref())
        .map(|&(_, start)| t0 + start)
}

/// Unit `w`'s own unknown `i`'s track in `inputs` (the sweep before's).
fn own_track(w: &UnitForces, inputs: &Inputs, i: usize) -> Track {
    match w.vars[i] {
        Var::Magnet(k) => inputs.magnets[k],
        Var::Joint(jj) => inputs.joints[jj],
    }
}

/// Solves unit `w` against `inputs` ([`solve`]), the tracks after it that followed one of
/// its unknowns in the sweep before moved with that unknown's start (the module's rule;
/// with coupled folds only).
pub(crate) fn solve_causal(w: &UnitForces, inputs: Inputs, opts: SolveOptions) -> (f64, Solution) {
    let (t0, sol) = solve(w, inputs, opts);
    if opts.coupled.is_none() {
        return (t0, sol);
    }
    let shapes = inputs.shapes;
    let scale = w.model.time_scale;
    // the earliest old start of an unknown that now starts later, or not at all
    let late = (0..w.vars.len())
        .filter_map(|i| {
            let old = shapes.first_move(own_track(w, &inputs, i))?;
            let tol = SWEEP_TOLERANCE * old.abs().max(scale);
            match start_of(&sol, t0, i) {
                Some(now) if now <= old + tol => None,
                _ => Some((old, i)),
            }
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((old, i)) = late else {
        return (t0, sol);
    };
    // the tracks after the unit that started since
    let last_magnet = w
        .vars
        .iter()
        .filter_map(|v| match v {
            Var::Magnet(k) => Some(*k),
            Var::Joint(_) => None,
        })
        .max()
        .unwrap_or(0);
    let first_joint = (w.j + 1).max(0) as usize;
    let follows = |t: &Track| shapes.first_move(*t).is_some_and(|a| a >= old);
    let followers = |shift: Option<f64>| {
        let moved = |t: &Track| match shift {
            _ if !follows(t) => *t,
            None => Track::REST,
            Some(d) => Track {
                shape: t.shape,
                offset: t.offset + d,
            },
        };
        let magnets: Vec<Track> = (inputs.magnets.iter().enumerate())
            .map(|(k, t)| if k > last_magnet { moved(t) } else { *t })
            .collect();
        let joints: Vec<Track> = (inputs.joints.iter().enumerate())
            .map(|(jj, t)| if jj >= first_joint { moved(t) } else { *t })
            .collect();
        (magnets, joints)
    };
    let any = inputs.magnets.iter().skip(last_magnet + 1).any(follows)
        || inputs.joints.iter().skip(first_joint).any(follows);
    if !any {
        return (t0, sol);
    }
    let (magnets, joints) = followers(None);
    let at_rest = Inputs {
        shapes,
        magnets: &magnets,
        joints: &joints,
    };
    let (t1, alone) = solve(w, at_rest, opts);
    if t1 != t0 {
        return (t0, sol);
    }
    let Some(now) = start_of(&alone, t1, i) else {
        // it never starts without them: nor do they
        return (t1, alone);
    };
    if now <= old {
        return (t0, sol);
    }
    let (magnets, joints) = followers(Some(now - old));
    let shifted = Inputs {
        shapes,
        magnets: &magnets,
        joints: &joints,
    };
    let (t2, again) = solve(w, shifted, opts);
    if t2 != t0 {
        return (t0, sol);
    }
    (t2, again)
}
