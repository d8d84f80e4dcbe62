//! A unit's events and switches: the overdamped model's switch conditions (as the
//! reference's event conditions decide them), the inertial model's releases, bounces and
//! rests at a wall, the events a switch means (with the trigger a start implies), and the
//! overdamped settling test.

use crate::engine::local::solve::step::interpolate;
use crate::engine::local::solve::{LocalEvent, Solver, M, Z};
use crate::engine::local::unit_forces::Var;
use crate::model::{at_wall, InertialModel};
use crate::model::{Mode, Model};
use crate::ode::locate::bisect;
use crate::timeline::EventKind;

/// The mode overdamped unknown `g` (reference state index) switches to, as the reference's
/// event conditions decide.
pub(super) fn condition(model: &Model, g: usize, mode: Mode, y: f64, drive: f64) -> Option<Mode> {
    match mode {
        Mode::AtStart if drive > model.threshold(g) => Some(Mode::Free),
        Mode::AtEnd if -drive > model.threshold(g) => Some(Mode::Free),
        Mode::Free if y >= 1.0 => Some(Mode::AtEnd),
        Mode::Free if y <= 0.0 && drive <= model.threshold(g) => Some(Mode::AtStart),
        _ => None,
    }
}

impl Solver<'_> {
    /// Whether anything switches (or a start is to be reported) at `z` with drives `d`.
    pub(super) fn any_switch(&self, z: &[f64; Z], d: &[f64; M]) -> bool {
        let model = self.w.model;
        (0..self.m).any(|i| {
            let g = self.globals[i];
            let switch = match self.opts.inertial {
                None => condition(model, g, self.modes[i], z[i], d[i]).is_some(),
                Some(im) => match self.modes[i] {
                    Mode::Free => at_wall(z[i], z[self.m + i]),
                    mode => im.released(model, g, mode, d[i]),
                },
            };
            switch || self.report_due(i, z[i])
        })
    }

    /// Whether a free inertial unknown meets a wall or a start is to be reported at `z`:
    /// the switches that read positions and velocities only.
    pub(super) fn any_kinematic_switch(&self, z: &[f64; Z]) -> bool {
        (0..self.m).any(|i| {
            (self.modes[i] == Mode::Free && at_wall(z[i], z[self.m + i]))
                || self.report_due(i, z[i])
        })
    }

    /// Whether a clamped inertial unknown is released by drives `d`.
    pub(super) fn any_release(&self, im: &InertialModel, d: &[f64; M]) -> bool {
        (0..self.m).any(|i| {
            let mode = self.modes[i];
            mode != Mode::Free && im.released(self.w.model, self.globals[i], mode, d[i])
        })
    }

    /// The first switch inside a step from `(t0, z0, f0)` to `(t1, z1, f1)`, which has one
    /// at its end, by bisection on the dense output down to `1e-13` of the time (or of
    /// `scale`): the last time found without a switch, the first found with one, the state
    /// there. `kinematic`: only the switches that read no drives (an inertial unit's walls
    /// and starts to report).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn bisect_switch(
        &mut self,
        (t0, t1): (f64, f64),
        (z0, f0): (&[f64; Z], &[f64; Z]),
        (z1, f1): (&[f64; Z], &[f64; Z]),
        scale: f64,
        kinematic: bool,
    ) -> (f64, f64, [f64; Z]) {
        let dim = self.dim();
        let mut z_hi = *z1;
        let (lo, hi) = bisect((t0, t1), scale, |mid| {
            let zm = interpolate(dim, t0, t1, z0, f0, z1, f1, mid);
            let switch = if kinematic {
                self.any_kinematic_switch(&zm)
            } else {
                let mut dm = [0.0; M];
                if self.switches_need_drives() {
                    self.drives(mid, &zm, &mut dm);
                }
                self.any_switch(&zm, &dm)
            };
            if switch {
                z_hi = zm;
            }
            switch
        });
        (lo, hi, z_hi)
    }

    /// How far the clamped unknowns are from a release with drives `d`: the largest of
    /// their drives past their thresholds, in drive scales (negative: none released).
    pub(super) fn release_margin(&self, d: &[f64; M]) -> f64 {
        let model = self.w.model;
        (0..self.m)
            .map(|i| {
                let g = self.globals[i];
                let th = match self.opts.inertial {
                    Some(im) => im.threshold(model, g),
                    None => model.threshold(g),
                };
                let past = match self.modes[i] {
                    Mode::AtStart => d[i] - th,
                    Mode::AtEnd => -d[i] - th,
                    Mode::Free => return f64::NEG_INFINITY,
                };
                past / model.drive_scale(g)
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Whether [`Solver::any_switch`] reads the drives: an overdamped unit's switches, or
    /// a clamped inertial unknown's release (a free inertial unknown switches on its
    /// position and velocity alone: a wall, a start to report).
    pub(super) fn switches_need_drives(&self) -> bool {
        self.opts.inertial.is_none() || self.modes[..self.m].iter().any(|&x| x != Mode::Free)
    }

    pub(super) fn report_due(&self, i: usize, y: f64) -> bool {
        matches!(self.w.vars[i], Var::Magnet(_))
            && !self.reported[i]
            && self.modes[i] != Mode::AtStart
            && self.opts.start_fraction > 0.0
            && y >= self.opts.start_fraction
    }

    /// Unknown `i` switches to `next` at `tau`, its rate going from `before` to `after`.
    pub(super) fn switch(
        &mut self,
        i: usize,
        tau: f64,
        next: Mode,
        (y, before, after): (f64, f64, f64),
    ) {
        if self.started[i].is_nan() {
            self.started[i] = tau;
        }
        self.node(i, tau, y, before);
        self.node(i, tau, y, after);
        self.modes[i] = next;
    }

    /// The overdamped switches of unknown `i` at `(tau, z)` with drives `d`.
    pub(super) fn switch_first_order(
        &mut self,
        i: usize,
        tau: f64,
        z: &mut [f64; Z],
        d: &[f64; M],
    ) {
        let model = self.w.model;
        let g = self.globals[i];
        let before = self.modes[i];
        let rate_before = model.rate(g, z[i], d[i], before);
        let Some(next) = condition(model, g, before, z[i], d[i]) else {
            return;
        };
        match next {
            Mode::AtEnd => z[i] = 1.0,
            Mode::AtStart => z[i] = 0.0,
            Mode::Free => {}
        }
        let rate_after = model.rate(g, z[i], d[i], next);
        let rb = if before == Mode::AtStart {
            0.0
        } else {
            rate_before
        };
        self.switch(i, tau, next, (z[i], rb, rate_after));
        if let Some(kind) = self.switch_event(i, before, next) {
            self.event(i, tau, kind, z);
        }
    }

    /// The inertial switches of unknown `i` at `(tau, z)` with drives `d`: a release, a
    /// bounce or a rest at a wall.
    pub(super) fn switch_second_order(
        &mut self,
        im: &InertialModel,
        i: usize,
        tau: f64,
        z: &mut [f64; Z],
        d: &[f64; M],
    ) {
        let model = self.w.model;
        let (g, m) = (self.globals[i], self.m);
        let before = self.modes[i];
        if before != Mode::Free {
            if im.released(model, g, before, d[i]) {
                z[m + i] = 0.0;
                self.switch(i, tau, Mode::Free, (z[i], 0.0, 0.0));
                if let Some(kind) = self.switch_event(i, before, Mode::Free) {
                    self.event(i, tau, kind, z);
                }
            }
            return;
        }
        let wall = if z[i] >= 1.0 {
            1.0
        } else if z[i] <= 0.0 {
            0.0
        } else {
            return;
        };
        z[i] = wall;
        let v = z[m + i];
        if !at_wall(wall, v) {
            return;
        }
        // a coupled joint's drive holds its velocity's terms: what presses it on is its
        // acceleration alone, as the coupled reference weighs its rebound
        let press = match (self.opts.coupled, self.w.vars[i]) {
            (Some(_), Var::Joint(_)) => {
                let acc = im.acceleration(g, wall, d[i], v);
                im.joint_drive_for(g, wall, 0.0, acc).unwrap_or(d[i])
            }
            _ => d[i],
        };
        match im.bounce(g, wall, v, press) {
            Some(rebound) => {
                z[m + i] = rebound;
                self.node(i, tau, wall, v);
                self.node(i, tau, wall, rebound);
            }
            None => {
                let next = if wall == 1.0 {
                    Mode::AtEnd
                } else {
                    Mode::AtStart
                };
                z[m + i] = 0.0;
                self.switch(i, tau, next, (wall, v, 0.0));
                if let Some(kind) = self.switch_event(i, before, next) {
                    self.event(i, tau, kind, z);
                }
            }
        }
    }

    /// The event unknown `i` switching from `before` to `next` means, if any (a fold's
    /// start and end and a magnet's start, when reported at the switch, once each).
    pub(super) fn switch_event(&mut self, i: usize, before: Mode, next: Mode) -> Option<EventKind> {
        match (self.w.vars[i], before, next) {
            (Var::Magnet(_), Mode::AtStart, Mode::Free) => {
                if self.opts.start_fraction > 0.0 || self.reported[i] {
                    None
                } else {
                    self.reported[i] = true;
                    Some(EventKind::MagnetStarts)
                }
            }
            (Var::Magnet(_), Mode::Free, Mode::AtEnd) => Some(EventKind::MagnetArrives),
            (Var::Joint(_), Mode::AtStart, Mode::Free) if !self.reported[i] => {
                self.reported[i] = true;
                Some(EventKind::FoldStarts)
            }
            (Var::Joint(_), Mode::Free, Mode::AtEnd) if !self.closed[i] => {
                self.closed[i] = self.opts.inertial.is_some();
                Some(EventKind::FoldEnds)
            }
            _ => None,
        }
    }

    /// Records event `kind` of unknown `i` at `tau` with the unit at `z`, with the trigger
    /// it implies: a magnet starting while the one before it has moved.
    pub(super) fn event(&mut self, i: usize, tau: f64, kind: EventKind, z: &[f64; Z]) {
        let base = 2 * self.w.j;
        let rel = match self.w.vars[i] {
            Var::Magnet(k) => k as i64 - base as i64,
            Var::Joint(_) => 0,
        };
        if kind == EventKind::FoldStarts {
            self.sol.p0 = 0.5 * (z[0] + z[1]);
        }
        if kind == EventKind::MagnetStarts {
            if let Var::Magnet(k) = self.w.vars[i] {
                if k >= 1 {
                    let before = k - 1;
                    let moved = match self.w.vars.iter().position(|&v| v == Var::Magnet(before)) {
                        Some(p) => self.modes[p] != Mode::AtStart || z[p] > 0.0,
                        None => {
                            let tr = self.inputs.magnets[before];
                            self.inputs
                                .shapes
                                .first_move(tr)
                                .is_some_and(|t0| t0 <= self.t_ref + tau)
                        }
                    };
                    if moved {
                        self.sol.events.push(LocalEvent {
                            time: tau,
                            kind: EventKind::TriggerReached,
                            rel: rel - 1,
                        });
                    }
                }
            }
        }
        self.sol.events.push(LocalEvent {
            time: tau,
            kind,
            rel,
        });
        self.last_event = tau;
    }

    /// Whether every free unknown settles on a stable balance inside its range (the
    /// reference's test: its own rate falls as it moves, and the linearised distance left is
    /// under the tolerance); overdamped units.
    pub(super) fn settled(&mut self, tau: f64, y: &[f64; Z], f: &[f64; Z], free: &[usize]) -> bool {
        let mut yy = *y;
        let mut d = [0.0; M];
        let mut r = [0.0; Z];
        for &i in free {
            let delta = if y[i] > 0.5 { -1e-7 } else { 1e-7 };
            yy[i] += delta;
            self.deriv(tau, &yy, &mut d, &mut r);
            yy[i] = y[i];
            let lambda = (r[i] - f[i]) / delta;
            let left = (f[i] / lambda).abs();
            if lambda >= 0.0 || left > self.opts.tol.max(1e-6) || y[i] < left || 1.0 - y[i] < left {
                return false;
            }
        }
        true
    }
}
