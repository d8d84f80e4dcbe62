//! One unit's local solve: its unknowns integrated in time with every other magnet and
//! joint on its track (upstream: solved; downstream: at rest, or the previous sweep's),
//! by Dormand-Prince 5(4) with adaptive steps; the rates and the switches between modes
//! (at rest, free, at the end) are the reference model's ([`crate::reference::Model`]),
//! and every switch is located by bisection on the dense output (cubic Hermite on the
//! step's ends), the drives evaluated there.
//!
//! Time runs from the unit's own origin `t_ref` (the first moment an input moves), so
//! that a unit whose inputs repeat an earlier unit's, shifted in time, has the same
//! solution shifted ([`crate::engine::local`]'s cache).

use crate::engine::local::trajectory::{hermite, Shape};
use crate::engine::local::window::{Inputs, Scratch, Var, Window};
use crate::reference::integrators::{A, E};
use crate::reference::{Mode, Model};
use crate::timeline::EventKind;

/// Dormand-Prince 5(4) stage times (the tableau is the reference's).
const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

/// Most unknowns of a unit.
const M: usize = 3;

/// Options of a local solve.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SolveOptions {
    /// Tolerance on the unknowns (fractions of a path or of a fold).
    pub(crate) tol: f64,
    /// A magnet's start is reported when it has travelled this fraction of its path (0: when
    /// it is first driven off its rest point).
    pub(crate) start_fraction: f64,
    /// Most steps before the solve gives up.
    pub(crate) max_steps: usize,
}

/// An event of a unit, its index relative to the unit (magnets: `k - 2j`; joints: 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LocalEvent {
    /// Local time, s.
    pub(crate) time: f64,
    /// What.
    pub(crate) kind: EventKind,
    /// Magnet index minus `2j`, or 0 for the joint.
    pub(crate) rel: i64,
}

/// A unit's solution, in its local time.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solution {
    /// Each unknown's shape and when it starts (local time), if it ever moved.
    pub(crate) shapes: Vec<Option<(Shape, f64)>>,
    /// The unit's events.
    pub(crate) events: Vec<LocalEvent>,
    /// The fold's pair progress when it started.
    pub(crate) p0: f64,
    /// Final modes, values and drives of the unknowns.
    pub(crate) modes: Vec<Mode>,
    /// Final values.
    pub(crate) y: Vec<f64>,
    /// Final drives.
    pub(crate) drive: Vec<f64>,
    /// Why the solve gave up, if it did.
    pub(crate) stopped: Option<String>,
    /// Right-hand sides evaluated.
    pub(crate) rhs: u64,
}

/// The mode unknown `g` (reference state index) switches to, as the reference's event
/// conditions decide.
fn condition(model: &Model, g: usize, mode: Mode, y: f64, drive: f64) -> Option<Mode> {
    match mode {
        Mode::AtStart if drive > model.threshold(g) => Some(Mode::Free),
        Mode::AtEnd if -drive > model.threshold(g) => Some(Mode::Free),
        Mode::Free if y >= 1.0 => Some(Mode::AtEnd),
        Mode::Free if y <= 0.0 && drive <= model.threshold(g) => Some(Mode::AtStart),
        _ => None,
    }
}

struct Solver<'a> {
    w: &'a Window<'a>,
    inputs: Inputs<'a>,
    opts: SolveOptions,
    t_ref: f64,
    m: usize,
    globals: [usize; M],
    modes: [Mode; M],
    scratch: Scratch,
    rhs: u64,
    /// Whether each magnet's start has been reported.
    reported: [bool; M],
}

impl Solver<'_> {
    fn drives(&mut self, tau: f64, y: &[f64; M], out: &mut [f64; M]) {
        self.rhs += 1;
        self.w.drives(
            self.t_ref + tau,
            &y[..self.m],
            &self.inputs,
            &mut self.scratch,
            &mut out[..self.m],
        );
    }

    fn rates(&mut self, tau: f64, y: &[f64; M], drive: &mut [f64; M], f: &mut [f64; M]) {
        self.drives(tau, y, drive);
        for i in 0..self.m {
            f[i] = self.w.model.rate(self.globals[i], drive[i], self.modes[i]);
        }
    }

    /// Whether anything switches (or a start is to be reported) at `y` with drives `d`.
    fn any_switch(&self, y: &[f64; M], d: &[f64; M]) -> bool {
        (0..self.m).any(|i| {
            condition(self.w.model, self.globals[i], self.modes[i], y[i], d[i]).is_some()
                || self.report_due(i, y[i])
        })
    }

    fn report_due(&self, i: usize, y: f64) -> bool {
        matches!(self.w.vars[i], Var::Magnet(_))
            && !self.reported[i]
            && self.modes[i] != Mode::AtStart
            && self.opts.start_fraction > 0.0
            && y >= self.opts.start_fraction
    }
}

/// Solves unit `w` against `inputs`.
pub(crate) fn solve(w: &Window, inputs: Inputs, opts: SolveOptions) -> (f64, Solution) {
    let tracks = w.input_tracks(&inputs);
    let first = tracks
        .iter()
        .filter_map(|&t| inputs.shapes.first_move(t))
        .fold(f64::INFINITY, f64::min);
    let last = tracks
        .iter()
        .filter_map(|&t| inputs.shapes.last_move(t))
        .fold(f64::NEG_INFINITY, f64::max);
    // the RI pulls from t = 0
    let t_ref = if w.lo == 0 || !first.is_finite() {
        0.0
    } else {
        first
    };
    let t_last = last - t_ref;
    let m = w.vars.len();
    let mut globals = [0; M];
    for (i, g) in globals.iter_mut().enumerate().take(m) {
        *g = w.global(i);
    }
    let mut s = Solver {
        w,
        inputs,
        opts,
        t_ref,
        m,
        globals,
        modes: [Mode::AtStart; M],
        scratch: Scratch::default(),
        rhs: 0,
        reported: [false; M],
    };
    let model = w.model;
    let mut sol = Solution {
        shapes: vec![None; m],
        ..Solution::default()
    };
    let mut nodes: Vec<Shape> = vec![Shape::default(); m];
    let mut started = [f64::NAN; M];
    let mut y = [0.0; M];
    let mut d = [0.0; M];
    let mut f = [0.0; M];
    let mut tau = 0.0;
    let mut last_event = 0.0;
    let scale = model.time_scale;
    let mut h = scale * 1e-3 * opts.tol.powf(0.2);
    let mut steps = 0usize;
    let next_input_node = |tau: f64| -> Option<f64> {
        // strictly later than tau, whatever the rounding of the offsets
        let t = t_ref + tau;
        let t = t + 1e-13 * t.abs().max(scale);
        tracks
            .iter()
            .filter_map(|&tr| inputs.shapes.next_node(tr, t))
            .fold(None, |a: Option<f64>, b| Some(a.map_or(b, |a| a.min(b))))
            .map(|t| t - t_ref)
    };
    let input_span = |tau: f64| -> f64 {
        // the widest interval of a moving input at tau (steps stay within two of them)
        let t = t_ref + tau;
        let mut span = f64::INFINITY;
        for &tr in &tracks {
            if let (Some(a), Some(b)) = (inputs.shapes.first_move(tr), inputs.shapes.last_move(tr))
            {
                if t < a {
                    span = span.min(a - t);
                } else if t < b {
                    let sh = inputs.shapes.get(tr.shape);
                    let i =
                        sh.t.partition_point(|&x| x <= t - tr.offset)
                            .clamp(1, sh.t.len() - 1);
                    span = span.min(2.0 * (sh.t[i] - sh.t[i - 1]).max(1e-12 * t.abs().max(1.0)));
                }
            }
        }
        span
    };
    loop {
        // switches at tau
        s.drives(tau, &y, &mut d);
        for i in 0..m {
            let before = s.modes[i];
            let rate_before = model.rate(globals[i], d[i], before);
            if let Some(next) = condition(model, globals[i], before, y[i], d[i]) {
                s.modes[i] = next;
                match next {
                    Mode::AtEnd => y[i] = 1.0,
                    Mode::AtStart => y[i] = 0.0,
                    Mode::Free => {}
                }
                let rate_after = model.rate(globals[i], d[i], next);
                if started[i].is_nan() {
                    started[i] = tau;
                }
                let sh = &mut nodes[i];
                sh.t.push(tau);
                sh.y.push(y[i]);
                sh.dy.push(if before == Mode::AtStart {
                    0.0
                } else {
                    rate_before
                });
                sh.t.push(tau);
                sh.y.push(y[i]);
                sh.dy.push(rate_after);
                let kind = match (w.vars[i], before, next) {
                    (Var::Magnet(_), Mode::AtStart, Mode::Free) => {
                        if opts.start_fraction > 0.0 || s.reported[i] {
                            None
                        } else {
                            s.reported[i] = true;
                            Some(EventKind::MagnetStarts)
                        }
                    }
                    (Var::Magnet(_), Mode::Free, Mode::AtEnd) => Some(EventKind::MagnetArrives),
                    (Var::Joint(_), Mode::AtStart, Mode::Free) if !s.reported[i] => {
                        s.reported[i] = true;
                        let (a, b) = (0, 1);
                        sol.p0 = 0.5 * (y[a] + y[b]);
                        Some(EventKind::FoldStarts)
                    }
                    (Var::Joint(_), Mode::Free, Mode::AtEnd) => Some(EventKind::FoldEnds),
                    _ => None,
                };
                if let Some(kind) = kind {
                    push_event(&mut sol, w, &s, i, tau, kind, &y);
                    last_event = tau;
                }
            }
            if s.report_due(i, y[i]) {
                s.reported[i] = true;
                push_event(&mut sol, w, &s, i, tau, EventKind::MagnetStarts, &y);
                last_event = tau;
            }
        }
        let free: Vec<usize> = (0..m).filter(|&i| s.modes[i] == Mode::Free).collect();
        steps += 1;
        if steps > opts.max_steps {
            sol.stopped = Some(format!(
                "local solve of joint {} gave up after {} steps at t = {:.6e} s",
                w.j,
                opts.max_steps,
                t_ref + tau
            ));
            break;
        }
        if free.is_empty() {
            // nothing of the unit moves: step from input node to input node
            let Some(tn) = next_input_node(tau) else {
                break;
            };
            let y0 = y;
            let mut dn = [0.0; M];
            s.drives(tn, &y0, &mut dn);
            if s.any_switch(&y0, &dn) {
                let (mut lo, mut hi) = (tau, tn);
                for _ in 0..60 {
                    if hi - lo <= 1e-13 * hi.abs().max(scale) {
                        break;
                    }
                    let mid = 0.5 * (lo + hi);
                    s.drives(mid, &y0, &mut dn);
                    if s.any_switch(&y0, &dn) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                tau = hi;
            } else {
                tau = tn;
            }
            continue;
        }
        // settled or at rest once the inputs are still
        if tau >= t_last {
            s.rates(tau, &y, &mut d, &mut f);
            let fastest = free.iter().map(|&i| f[i].abs()).fold(0.0, f64::max);
            let since = (tau - last_event).max(scale);
            if fastest * since < 1e-9
                || (fastest * since < 1e-2 && settled(&mut s, tau, &y, &f, &free))
            {
                break;
            }
        }
        // one Dormand-Prince step
        let hmax = input_span(tau);
        h = h.min(hmax);
        let mut k = [[0.0; M]; 7];
        let mut dk = [0.0; M];
        s.rates(tau, &y, &mut dk, &mut k[0]);
        let mut ys = [0.0; M];
        for st in 0..6 {
            for i in 0..m {
                let mut acc = 0.0;
                for (jj, a) in A[st].iter().enumerate().take(st + 1) {
                    acc += a * k[jj][i];
                }
                ys[i] = y[i] + h * acc;
            }
            let mut out = [0.0; M];
            s.rates(tau + C[st] * h, &ys, &mut dk, &mut out);
            k[st + 1] = out;
        }
        let mut sum = 0.0;
        for &i in &free {
            let mut e = 0.0;
            for (jj, c) in E.iter().enumerate() {
                e += c * k[jj][i];
            }
            let sc = opts.tol * (1.0 + y[i].abs().max(ys[i].abs()));
            sum += (h * e / sc).powi(2);
        }
        let err = (sum / free.len() as f64).sqrt();
        if !err.is_finite() || err > 1.0 {
            let fac = if err.is_finite() {
                (0.9 * err.powf(-0.2)).clamp(0.1, 0.9)
            } else {
                0.1
            };
            h *= fac;
            continue;
        }
        let grow = if err > 0.0 {
            (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
        } else {
            5.0
        };
        let (t0, y0, f0) = (tau, y, k[0]);
        let (t1, y1, f1) = (tau + h, ys, k[6]);
        // an event inside the step?
        let mut d1 = [0.0; M];
        s.drives(t1, &y1, &mut d1);
        if s.any_switch(&y1, &d1) {
            let interp = |t: f64| {
                let mut out = [0.0; M];
                for i in 0..m {
                    out[i] = hermite(t0, t1, (y0[i], f0[i]), (y1[i], f1[i]), t);
                }
                out
            };
            let (mut lo, mut hi) = (t0, t1);
            let mut y_hi = y1;
            for _ in 0..60 {
                if hi - lo <= 1e-13 * hi.abs().max(scale) {
                    break;
                }
                let mid = 0.5 * (lo + hi);
                let ym = interp(mid);
                let mut dm = [0.0; M];
                s.drives(mid, &ym, &mut dm);
                if s.any_switch(&ym, &dm) {
                    hi = mid;
                    y_hi = ym;
                } else {
                    lo = mid;
                }
            }
            for &i in &free {
                // the rate at the event, from the interpolant's slope
                let dt = 1e-9 * (t1 - t0);
                let slope = (hermite(t0, t1, (y0[i], f0[i]), (y1[i], f1[i]), hi)
                    - hermite(t0, t1, (y0[i], f0[i]), (y1[i], f1[i]), hi - dt))
                    / dt;
                nodes[i].t.push(hi);
                nodes[i].y.push(y_hi[i].clamp(0.0, 1.0));
                nodes[i].dy.push(slope);
            }
            for i in 0..m {
                y[i] = if s.modes[i] == Mode::Free {
                    y_hi[i].clamp(0.0, 1.0)
                } else {
                    y[i]
                };
            }
            tau = hi;
            h = h.max(1e-6 * scale);
            continue;
        }
        for &i in &free {
            nodes[i].t.push(t1);
            nodes[i].y.push(y1[i]);
            nodes[i].dy.push(f1[i]);
        }
        tau = t1;
        y = y1;
        h *= grow;
    }
    s.drives(tau, &y, &mut d);
    for i in 0..m {
        if !started[i].is_nan() {
            let mut sh = std::mem::take(&mut nodes[i]);
            let origin = started[i];
            for t in &mut sh.t {
                *t -= origin;
            }
            sol.shapes[i] = Some((sh, origin));
        }
    }
    sol.modes = s.modes[..m].to_vec();
    sol.y = y[..m].to_vec();
    sol.drive = d[..m].to_vec();
    sol.rhs = s.rhs;
    sol.events.sort_by(|a, b| {
        a.time
            .total_cmp(&b.time)
            .then((a.kind, a.rel).cmp(&(b.kind, b.rel)))
    });
    (t_ref, sol)
}

/// Records event `kind` of unknown `i` at `tau`, with the trigger it implies: a magnet
/// starting while the one before it has moved.
fn push_event(
    sol: &mut Solution,
    w: &Window,
    s: &Solver,
    i: usize,
    tau: f64,
    kind: EventKind,
    y: &[f64; M],
) {
    let base = 2 * w.j;
    let rel = match w.vars[i] {
        Var::Magnet(k) => k as i64 - base as i64,
        Var::Joint(_) => 0,
    };
    if kind == EventKind::MagnetStarts {
        if let Var::Magnet(k) = w.vars[i] {
            if k >= 1 {
                let before = k - 1;
                let moved = match w.vars.iter().position(|&v| v == Var::Magnet(before)) {
                    Some(p) => s.modes[p] != Mode::AtStart || y[p] > 0.0,
                    None => {
                        let tr = s.inputs.magnets[before];
                        s.inputs
                            .shapes
                            .first_move(tr)
                            .is_some_and(|t0| t0 <= s.t_ref + tau)
                    }
                };
                if moved {
                    sol.events.push(LocalEvent {
                        time: tau,
                        kind: EventKind::TriggerReached,
                        rel: rel - 1,
                    });
                }
            }
        }
    }
    sol.events.push(LocalEvent {
        time: tau,
        kind,
        rel,
    });
}

/// Whether every free unknown settles on a stable balance inside its range (the
/// reference's test: its own rate falls as it moves, and the linearised distance left is
/// under the tolerance).
fn settled(s: &mut Solver, tau: f64, y: &[f64; M], f: &[f64; M], free: &[usize]) -> bool {
    let mut yy = *y;
    let mut d = [0.0; M];
    let mut r = [0.0; M];
    for &i in free {
        let delta = if y[i] > 0.5 { -1e-7 } else { 1e-7 };
        yy[i] += delta;
        s.rates(tau, &yy, &mut d, &mut r);
        yy[i] = y[i];
        let lambda = (r[i] - f[i]) / delta;
        let left = (f[i] / lambda).abs();
        if lambda >= 0.0 || left > s.opts.tol.max(1e-6) || y[i] < left || 1.0 - y[i] < left {
            return false;
        }
    }
    true
}
