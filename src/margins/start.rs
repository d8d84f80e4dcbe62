//! The drive margin of one magnet's start.
//!
//! Magnet `m` waits at rest while the chain before it moves. The margins pose that wait
//! quasi-statically, one pair at a time, as propagation goes:
//! - magnet 0 waits for nothing: the reaction initiator pulls it from the start;
//! - magnet 1 waits while magnet 0 runs its path towards the RI;
//! - magnet `2j + 2` (the far magnet of joint `j`'s pair) waits while magnet `2j + 1` runs
//!   its path towards it;
//! - magnet `2j + 3` waits while its partner `2j + 2` leaves it: the pair of joint `j`
//!   closes, magnet `2j + 1` from where it stood when `2j + 2` started to its end, `2j + 2`
//!   from rest to its end, both at the same fraction of the way; then joint `j` folds, if it
//!   is a fold, as long as its torque turns it.
//!
//! Everything before the moving magnets stands at its path's end with its folds complete;
//! `m` and everything after it rest. The movers stop where the force along their own path
//! (a closing pair: the sum of its two) vanishes, so the sweep ends there: that is the stall
//! the reference integrator shows at the end of `SL` and `LL` on the thesis layout. The
//! drive margin is the largest force along `m`'s path over the sweep, over the bond force of
//! `m`'s tile: positive means `m` starts, and by how much; negative means it never starts.

use std::f64::consts::FRAC_PI_2;

use crate::margins::placed_tiles::{PlacedTiles, State};
use crate::margins::{ChainModel, MarginOptions, StartMargin};
use crate::ode::locate::halve;
use crate::physics::ForceLaw;
use crate::timeline::joint_of_magnet;
use crate::Fold;

/// Bisection steps locating a start or a stall: 2^-32 of the movers' way (about 2 pm).
const BISECTIONS: usize = 32;

/// Golden-section steps refining an interior maximum: 0.618^24 of two samples' spacing.
const GOLDEN_STEPS: usize = 24;

/// A quasi-static state: magnets before `ends_below` at their ends, joints before
/// `folded_below` folded, up to two magnets at given travels and one joint at a given angle.
#[derive(Clone, Copy)]
pub(crate) struct Posed<'a> {
    pub(crate) model: &'a ChainModel,
    pub(crate) ends_below: usize,
    pub(crate) folded_below: usize,
    pub(crate) moving: [Option<(usize, f64)>; 2],
    pub(crate) turn: Option<(usize, f64)>,
}

impl State for Posed<'_> {
    fn travel(&self, k: usize) -> f64 {
        for (i, u) in self.moving.iter().flatten() {
            if *i == k {
                return *u;
            }
        }
        if k < self.ends_below {
            self.model.length(k)
        } else {
            0.0
        }
    }

    fn angle(&self, j: usize) -> f64 {
        match self.turn {
            Some((i, a)) if i == j => a,
            _ if j < self.folded_below => full_angle(self.model.fold(j)),
            _ => 0.0,
        }
    }
}

/// The signed angle of a completed fold, radians.
pub(crate) fn full_angle(fold: Fold) -> f64 {
    match fold {
        Fold::S => 0.0,
        Fold::L => FRAC_PI_2,
        Fold::R => -FRAC_PI_2,
    }
}

/// The drive margin of magnet `m` (see the module documentation). For an odd `m >= 3`,
/// `partner_start` is where magnet `m - 2` stood when magnet `m - 1` started, mm along its
/// path (the `start_travel` of magnet `m - 1`'s margin).
pub(crate) fn start_margin(
    model: &ChainModel,
    opts: &MarginOptions,
    m: usize,
    partner_start: f64,
) -> StartMargin {
    let (law, cutoff) = (opts.force_law, opts.cutoff);
    let bond = model.bond_force(law, m / 2);
    let last = model.magnets() - 1;
    let joint = joint_of_magnet(m);
    let lo = m.saturating_sub(1 + cutoff).saturating_sub(1);
    let mut window = PlacedTiles::new(if lo <= cutoff { 0 } else { lo }, (m + cutoff).min(last));
    let rest = Posed {
        model,
        ends_below: 0,
        folded_below: 0,
        moving: [None, None],
        turn: None,
    };
    if m == 0 {
        window.place(model, &rest);
        let drive = window.drive(model, law, cutoff, 0, 0.0);
        return StartMargin {
            magnet: 0,
            joint,
            margin: drive / bond,
            at_travel: 0.0,
            start_travel: (drive > 0.0).then_some(0.0),
            mover_stall: None,
        };
    }
    let mut sweep = Sweep {
        model,
        law,
        cutoff,
        m,
        window: &mut window,
        base: rest,
        pair: None,
    };
    if m % 2 == 1 && m >= 3 {
        // the pair of joint j = (m - 3) / 2 closes from (partner_start, 0)
        let (a, b) = (m - 2, m - 1);
        sweep.base.ends_below = a;
        sweep.base.folded_below = (m - 3) / 2;
        sweep.pair = Some((a, partner_start.clamp(0.0, model.length(a)), b));
    } else {
        sweep.base.ends_below = m - 1;
        sweep.base.folded_below = (m - 1) / 2;
    }
    let threshold = crate::engine::DRIVE_TOLERANCE * bond;
    let n = opts.path_samples.max(2);
    let mut best = (f64::NEG_INFINITY, 0.0);
    let mut start = None;
    let mut stall = None;
    let mut prev = (0.0, f64::NEG_INFINITY);
    for i in 0..=n {
        let x = i as f64 / n as f64;
        let (dm, dv) = sweep.at(x);
        if start.is_none() && dm > threshold {
            start = Some(if i == 0 {
                0.0
            } else {
                sweep.first_positive(prev.0, x, threshold)
            });
        }
        if i > 0 && i < n && dv <= threshold && !sweep.fold_takes_over(x) {
            // the movers stop between the last sample and this one: find where
            let (a, _) = halve(
                (prev.0, x),
                BISECTIONS,
                |_, _| false,
                |mid| sweep.at(mid).1 <= threshold,
            );
            let (dm_stop, _) = sweep.at(a);
            if dm_stop > best.0 {
                best = (dm_stop, a);
            }
            stall = Some(a);
            break;
        }
        if dm > best.0 {
            best = (dm, x);
        }
        prev = (x, dm);
    }
    if stall.is_none() && best.1 > 0.0 && best.1 < 1.0 {
        best = sweep.refine_maximum(best, 1.0 / n as f64);
    }
    let fold_joint = (m % 2 == 1 && m >= 3)
        .then(|| (m - 3) / 2)
        .filter(|&j| model.fold(j) != Fold::S);
    if let (None, Some(j)) = (stall, fold_joint) {
        sweep.turn_fold(
            j,
            opts.fold_samples.max(1),
            threshold,
            &mut best,
            &mut start,
        );
    }
    let mover_len = model.length(m - 1);
    StartMargin {
        magnet: m,
        joint,
        margin: best.0 / bond,
        at_travel: best.1 * mover_len,
        start_travel: start.map(|x| sweep.mover_travel(x)),
        mover_stall: stall.map(|x| sweep.mover_travel(x)),
    }
}

impl Sweep<'_, '_> {
    /// The closed pair's fold `j` turning while the torque turns it (`samples` steps of its
    /// quarter turn): the drive on magnet `m` at each step raises `best` (at fraction 1) and
    /// starts it past `threshold`.
    fn turn_fold(
        &mut self,
        j: usize,
        samples: usize,
        threshold: f64,
        best: &mut (f64, f64),
        start: &mut Option<f64>,
    ) {
        let (model, law, cutoff, m) = (self.model, self.law, self.cutoff, self.m);
        let full = full_angle(model.fold(j));
        let mut state = Posed {
            ends_below: m,
            moving: [None, None],
            ..self.base
        };
        for i in 0..=samples {
            state.turn = Some((j, full * i as f64 / samples as f64));
            self.window.place(model, &state);
            let dm = self.window.drive(model, law, cutoff, m, 0.0);
            if dm > best.0 {
                *best = (dm, 1.0);
            }
            if start.is_none() && dm > threshold {
                *start = Some(1.0);
            }
            if self.window.torque(model, law, cutoff, j, full.signum()) <= 0.0 {
                break;
            }
        }
    }

    /// An interior maximum `best` (drive, fraction) of the samples `h` apart refined by
    /// golden-section search between its neighbours; `best` if the search finds no more.
    fn refine_maximum(&mut self, best: (f64, f64), h: f64) -> (f64, f64) {
        let (mut a, mut b) = ((best.1 - h).max(0.0), (best.1 + h).min(1.0));
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..GOLDEN_STEPS {
            let (x1, x2) = (b - g * (b - a), a + g * (b - a));
            if self.at(x1).0 > self.at(x2).0 {
                b = x2;
            } else {
                a = x1;
            }
        }
        let x = 0.5 * (a + b);
        let dm = self.at(x).0;
        if dm > best.0 {
            (dm, x)
        } else {
            best
        }
    }
}

/// A sweep of the movers before magnet `m`, by the fraction `x` of their way.
struct Sweep<'a, 'w> {
    model: &'a ChainModel,
    law: ForceLaw,
    cutoff: usize,
    m: usize,
    window: &'w mut PlacedTiles,
    base: Posed<'a>,
    /// A closing pair `(a, where a starts, b)`; `None`: magnet `m - 1` alone.
    pair: Option<(usize, f64, usize)>,
}

impl Sweep<'_, '_> {
    /// Where magnet `m - 1` stands at fraction `x`, mm along its path.
    fn mover_travel(&self, x: f64) -> f64 {
        x * self.model.length(self.m - 1)
    }

    /// `(drive on m, drive on the movers)` at fraction `x`, N.
    fn at(&mut self, x: f64) -> (f64, f64) {
        let model = self.model;
        let v = self.m - 1;
        let mut state = self.base;
        match self.pair {
            Some((a, from, b)) => {
                let ua = from + x * (model.length(a) - from);
                state.moving = [Some((a, ua)), Some((b, x * model.length(b)))];
            }
            None => state.moving = [Some((v, x * model.length(v))), None],
        }
        self.window.place(model, &state);
        let dm = self.window.drive(model, self.law, self.cutoff, self.m, 0.0);
        let mut dv = 0.0;
        for (k, u) in state.moving.iter().flatten() {
            dv += self.window.drive(model, self.law, self.cutoff, *k, *u);
        }
        (dm, dv)
    }

    /// Whether a closing pair that balances at fraction `x` turns its fold there instead
    /// (the torque about its hinge turns the joint): the pair then closes through the fold.
    fn fold_takes_over(&mut self, x: f64) -> bool {
        let Some((a, _, _)) = self.pair else {
            return false;
        };
        let j = (a - 1) / 2;
        let fold = self.model.fold(j);
        if fold == Fold::S {
            return false;
        }
        self.at(x);
        self.window.torque(
            self.model,
            self.law,
            self.cutoff,
            j,
            full_angle(fold).signum(),
        ) > 0.0
    }

    /// The first fraction in `(a, b]` where the drive on `m` exceeds `threshold`, knowing it
    /// does at `b` and not at `a`.
    fn first_positive(&mut self, a: f64, b: f64, threshold: f64) -> f64 {
        halve(
            (a, b),
            BISECTIONS,
            |_, _| false,
            |mid| self.at(mid).0 > threshold,
        )
        .1
    }
}
