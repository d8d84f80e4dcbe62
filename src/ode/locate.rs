//! Where an event happens inside a step: the earliest moment a condition holds, found on the
//! step's dense output ([`crate::ode::Dense`], [`crate::ode::hermite`]) without new steps.
//!
//! - [`illinois`]: the earliest root of a continuous margin (positive before the event, zero
//!   or negative once it holds), bracketed by the Illinois method (regula falsi that halves
//!   the kept end's value, with a bisection whenever a bracket fails to halve). Each trial
//!   costs one margin: nothing on the state, one force evaluation on a drive. The reference
//!   locates its mode switches so, to `1e-3` of its tolerance times the step.
//! - [`bisect`]: the moment a yes-or-no condition starts to hold, by bisection down to
//!   `1e-13` of the time: for conditions that are not margins (a wall met with the velocity
//!   outwards, a start to report) and wherever every trial costs the same (the event
//!   engine's units).

/// The earliest root of `g` in `[lo, hi]`, given `g(lo) = g_lo > 0` and `g(hi) = g_hi <= 0`,
/// to a bracket of `width` (at most 100 trials): the upper end of the final bracket, where
/// `g` is zero or negative.
pub(crate) fn illinois(
    (mut lo, mut g_lo): (f64, f64),
    (mut hi, mut g_hi): (f64, f64),
    width: f64,
    mut g: impl FnMut(f64) -> f64,
) -> f64 {
    // the side kept twice in a row, for the Illinois halving (-1 low, 1 high)
    let mut kept = 0i32;
    let mut iters = 0;
    while hi - lo > width && iters < 100 {
        iters += 1;
        let before = hi - lo;
        let secant = lo + (hi - lo) * g_lo / (g_lo - g_hi);
        let mid = if secant.is_finite() && secant > lo && secant < hi {
            secant
        } else {
            0.5 * (lo + hi)
        };
        let gm = g(mid);
        if gm <= 0.0 {
            hi = mid;
            g_hi = gm;
            if kept == -1 {
                g_lo *= 0.5;
            }
            kept = -1;
        } else {
            lo = mid;
            g_lo = gm;
            if kept == 1 {
                g_hi *= 0.5;
            }
            kept = 1;
        }
        // a bracket that did not halve: bisect once
        if hi - lo > 0.5 * before && hi - lo > width {
            let mid = 0.5 * (lo + hi);
            let gm = g(mid);
            if gm <= 0.0 {
                hi = mid;
                g_hi = gm;
            } else {
                lo = mid;
                g_lo = gm;
            }
            kept = 0;
        }
    }
    hi
}

/// The first moment in `(lo, hi]` at which `holds` (false at `lo`, true at `hi`) becomes
/// true, by bisection until the bracket is within `1e-13` of the time (or of `scale` near
/// zero), at most 60 halvings: the last time found false and the first found true.
pub(crate) fn bisect(
    bracket: (f64, f64),
    scale: f64,
    holds: impl FnMut(f64) -> bool,
) -> (f64, f64) {
    halve(
        bracket,
        60,
        |lo, hi| hi - lo <= 1e-13 * hi.abs().max(scale),
        holds,
    )
}

/// Halves the bracket `(lo, hi)` at most `halvings` times, until `narrow(lo, hi)`: the
/// midpoint becomes the upper end where `holds` there, the lower end where it does not.
pub(crate) fn halve(
    (mut lo, mut hi): (f64, f64),
    halvings: usize,
    narrow: impl Fn(f64, f64) -> bool,
    mut holds: impl FnMut(f64) -> bool,
) -> (f64, f64) {
    for _ in 0..halvings {
        if narrow(lo, hi) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn illinois_finds_the_root_in_few_trials() {
        // a cubic with one root in the bracket at 0.3: g = (0.3 - x)(1 + x^2)
        let g = |x: f64| (0.3 - x) * (1.0 + x * x);
        let mut trials = 0;
        let hi = illinois((0.0, g(0.0)), (1.0, g(1.0)), 1e-12, |x| {
            trials += 1;
            g(x)
        });
        assert!(g(hi) <= 0.0 && (hi - 0.3).abs() < 1e-12, "{hi}");
        assert!(trials < 20, "{trials}");
    }

    #[test]
    fn bisection_brackets_the_switch() {
        let (lo, hi) = bisect((0.0, 1.0), 1.0, |t| t >= 0.625);
        assert!(lo < 0.625 && hi >= 0.625 && hi - lo <= 1e-13);
    }
}
