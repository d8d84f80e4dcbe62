//! The tile-width search: the width at which a planner's best plan holds about the asked
//! number of tiles. Rows hold whole tiles and a plan gains or loses whole rows, so the count
//! is a step function of the width; the search takes secant-like steps on the square root of
//! the count (the count goes as 1 / w^2), then optional small nudges around the best width,
//! and keeps the width whose count misses the target least. A planner whose plans at some
//! width fail a later check (they collide, or leave a part of the shape empty) says so with
//! their count; the search then also tries widths a little either side of the nearest such
//! width, where the rows fall on the shape at other phases.

/// The tile width (user units) at which `tiles` tiles of a serpentine with row pitch `pitch`
/// (tile widths) take `area`: one column of width w times the pitch per tile.
pub(crate) fn width_for(area: f64, tiles: usize, pitch: f64) -> f64 {
    (area / (tiles as f64 * pitch)).sqrt()
}

/// About how many tiles of width `w` a serpentine with row pitch `pitch` lays over `area`.
pub(crate) fn tiles_for(area: f64, w: f64, pitch: f64) -> usize {
    (area / (w * w * pitch)) as usize
}

/// How one planner searches.
pub(crate) struct SizeSearch {
    /// Steps (secant, or bisection once two widths bracket the target) from the first width.
    pub secant_steps: usize,
    /// Factors tried on the best width after the steps, in order: while its count still
    /// misses by more than the tolerance, or always when `explore` is set (a count within
    /// the tolerance with a better cost then wins).
    pub nudges: &'static [f64],
    /// Counts within this many tiles of the target are equally good: among them the
    /// cheaper wins. The steps stop once the count is within it.
    pub tolerance: usize,
    /// Try every nudge even once a count is within the tolerance, for a better cost.
    pub explore: bool,
    /// When a width gives no plan: `Some(f)` tries `f` times that width next, `None` stops.
    pub shrink_when_empty: Option<f64>,
    /// Factors tried in turn on the width whose rejected plans (see [`Attempt::Rejected`])
    /// missed the target least, after the steps, while no plan within the tolerance is found.
    pub retries: &'static [f64],
    /// A plan within the tolerance ends the steps; it ends the retries only if its cost is
    /// at most this (`f64::INFINITY`: any plan; 0 for a planner whose cost says what a plan
    /// lacks, so that the retries look for a width whose plan lacks nothing). The steps do
    /// not go on for a plan that lacks something: once within the tolerance they only
    /// bisect towards the same count, where the retries try other phases.
    pub settle_cost: f64,
}

/// What a planner made at one width.
pub(crate) enum Attempt<T> {
    /// No plan at all.
    Nothing,
    /// Plans of about this many tiles, all rejected by a later check.
    Rejected(usize),
    /// A plan: its tile count, its cost, and the planner's answer.
    Plan(usize, f64, T),
}

/// What the search found: the width and the planner's answer there.
pub(crate) struct Found<T> {
    pub w: f64,
    pub plans: T,
}

impl SizeSearch {
    /// Searches from width `w` for `target` tiles. `solve(w)` returns, for the best plan at
    /// `w`, its tile count and its cost (lower is better: equal misses beyond the tolerance,
    /// or misses within it, keep the cheaper), with the planner's answer; or `None` when
    /// there is no plan at `w`. A width tried before (to 1e-12) is not solved again.
    ///
    /// The count falls as the width grows, in whole rows: once one width gives more tiles
    /// than the target and another fewer, the next width is their geometric mean
    /// (bisection), so a count between two row steps is found when some width gives it.
    pub(crate) fn run<T>(
        &self,
        target: usize,
        w: f64,
        mut solve: impl FnMut(f64) -> Option<(usize, f64, T)>,
    ) -> Option<Found<T>> {
        self.run_checked(target, w, |w| match solve(w) {
            Some((n, cost, plans)) => Attempt::Plan(n, cost, plans),
            None => Attempt::Nothing,
        })
    }

    /// [`SizeSearch::run`] for a planner whose plans may be rejected at some widths: a width
    /// whose plans were all rejected steers the steps by its count like any other but is
    /// never the answer; a rejected count within the tolerance ends the steps, and the
    /// [`SizeSearch::retries`] around the rejected width that missed least follow while no
    /// plan within the tolerance is found.
    pub(crate) fn run_checked<T>(
        &self,
        target: usize,
        w: f64,
        solve: impl FnMut(f64) -> Attempt<T>,
    ) -> Option<Found<T>> {
        self.run_budgeted(target, w, usize::MAX, solve)
    }

    /// [`SizeSearch::run_checked`] that solves at most `budget` widths (steps, nudges and
    /// retries together, in that order): a deterministic bound on the work of a search whose
    /// every width costs much (a long chain routed through many cells), counted in widths,
    /// never in time. The best plan among the widths solved is the answer.
    pub(crate) fn run_budgeted<T>(
        &self,
        target: usize,
        mut w: f64,
        budget: usize,
        mut solve: impl FnMut(f64) -> Attempt<T>,
    ) -> Option<Found<T>> {
        // every width tried is solved once: the budget counts them
        let spent = |tried: &[f64]| tried.len() >= budget;
        // (miss beyond the tolerance, width) of the rejected width that missed least
        let mut rejected: Option<(usize, f64)> = None;
        // (miss beyond the tolerance, cost, width, answer)
        let mut best: Option<(usize, f64, f64, T)> = None;
        let mut tried: Vec<f64> = Vec::new();
        // widths known to give more tiles than the target (largest) and fewer (smallest)
        let (mut too_many, mut too_few): (Option<f64>, Option<f64>) = (None, None);
        let better = |best: &Option<(usize, f64, f64, T)>, m: usize, c: f64| {
            best.as_ref()
                .is_none_or(|(bm, bc, ..)| m < *bm || (m == *bm && c < *bc))
        };
        // once a count is within the tolerance the steps stop (exploring: the nudges follow)
        let mut settled = false;
        for step in 0..self.secant_steps + self.nudges.len() {
            if step < self.secant_steps && settled {
                continue;
            }
            if step >= self.secant_steps {
                match &best {
                    None => break,
                    Some((0, c, ..)) if !self.explore && *c <= self.settle_cost => break,
                    Some((_, _, bw, _)) => w = bw * self.nudges[step - self.secant_steps],
                }
            }
            if tried.iter().any(|&t| (t - w).abs() < 1e-12 * t) {
                continue;
            }
            if spent(&tried) {
                break;
            }
            tried.push(w);
            let (n, plan) = match solve(w) {
                Attempt::Plan(n, cost, plans) => (n, Some((cost, plans))),
                Attempt::Rejected(n) => (n, None),
                Attempt::Nothing => match self.shrink_when_empty {
                    Some(f) if step < self.secant_steps => {
                        w *= f;
                        continue;
                    }
                    Some(_) => continue,
                    None => break,
                },
            };
            let miss = n.abs_diff(target).saturating_sub(self.tolerance);
            let at = w;
            if n > target {
                too_many = Some(too_many.map_or(at, |t: f64| t.max(at)));
            } else if n < target {
                too_few = Some(too_few.map_or(at, |t: f64| t.min(at)));
            }
            match plan {
                Some((cost, plans)) => {
                    if better(&best, miss, cost) {
                        best = Some((miss, cost, at, plans));
                    }
                }
                None => {
                    if rejected.is_none_or(|(m, _)| miss < m) {
                        rejected = Some((miss, at));
                    }
                    // the steps would stay at this count: the retries try other widths
                    if miss == 0 && step < self.secant_steps {
                        break;
                    }
                }
            }
            if step < self.secant_steps {
                let good = best.as_ref().is_some_and(|b| b.0 == 0);
                if good && !self.explore {
                    break;
                }
                settled |= good;
                w = match (too_many, too_few) {
                    (Some(a), Some(b)) if a < b => (a * b).sqrt(),
                    _ => w * (n.max(1) as f64 / target as f64).sqrt(),
                };
            }
        }
        // retries around the rejected width that missed least, or around the best plan's
        // width when that plan lacks something (its cost above `settle_cost`)
        let base = match (&best, rejected) {
            (Some(b), _) if b.0 == 0 && b.1 > self.settle_cost => Some(b.2),
            (_, Some((_, w))) => Some(w),
            _ => None,
        };
        if let Some(base) = base {
            for &f in self.retries {
                if best
                    .as_ref()
                    .is_some_and(|b| b.0 == 0 && b.1 <= self.settle_cost)
                {
                    break;
                }
                let w = base * f;
                if tried.iter().any(|&t| (t - w).abs() < 1e-12 * t) {
                    continue;
                }
                if spent(&tried) {
                    break;
                }
                tried.push(w);
                if let Attempt::Plan(n, cost, plans) = solve(w) {
                    let miss = n.abs_diff(target).saturating_sub(self.tolerance);
                    if better(&best, miss, cost) {
                        best = Some((miss, cost, w, plans));
                    }
                }
            }
        }
        best.map(|(_, _, w, plans)| Found { w, plans })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A count that goes as 1 / w^2 in whole tiles: the search lands within the tolerance,
    /// and reports the width it found the count at.
    #[test]
    fn finds_a_width_near_the_target() {
        let count = |w: f64| (5000.0 / (w * w)).floor() as usize;
        let s = SizeSearch {
            secant_steps: 8,
            nudges: &[0.98, 1.02],
            tolerance: 2,
            explore: false,
            shrink_when_empty: Some(0.97),
            retries: &[],
            settle_cost: f64::INFINITY,
        };
        let f = s
            .run(500, 5.0, |w| Some((count(w), 0.0, count(w))))
            .unwrap();
        assert!(f.plans.abs_diff(500) <= 2, "{} tiles at {}", f.plans, f.w);
        assert_eq!(count(f.w), f.plans);
    }

    /// Counts in steps of 11 tiles (whole rows) but for a narrow band of widths giving the
    /// target: the bisection between a width above and one below finds it.
    #[test]
    fn bisection_finds_a_count_between_row_steps() {
        let count = |w: f64| {
            if (9.99..10.0).contains(&w) {
                107
            } else {
                11 * (1000.0 / (w * w)).floor() as usize
            }
        };
        let s = SizeSearch {
            secant_steps: 16,
            nudges: &[],
            tolerance: 0,
            explore: false,
            shrink_when_empty: None,
            retries: &[],
            settle_cost: f64::INFINITY,
        };
        let f = s
            .run(107, 9.5, |w| Some((count(w), 0.0, count(w))))
            .unwrap();
        assert_eq!(f.plans, 107, "width {}", f.w);
    }

    /// Within the tolerance the cheaper count wins when exploring.
    #[test]
    fn exploring_buys_fit_within_the_tolerance() {
        let count = |w: f64| (10_000.0 / (w * w)).round() as usize;
        let cost = |n: usize| if n % 7 == 0 { 0.0 } else { 1.0 };
        let s = SizeSearch {
            secant_steps: 6,
            nudges: &[0.99, 1.01, 0.995, 1.005, 0.998, 1.002],
            tolerance: 5,
            explore: true,
            shrink_when_empty: None,
            retries: &[],
            settle_cost: f64::INFINITY,
        };
        let f = s
            .run(100, 10.0, |w| Some((count(w), cost(count(w)), count(w))))
            .unwrap();
        assert!(
            f.plans.abs_diff(100) <= 5 && f.plans % 7 == 0,
            "{}",
            f.plans
        );
    }

    /// Plans rejected at the width the steps settle on: the retries around it find a
    /// width whose plan passes, and a rejected width is never the answer.
    #[test]
    fn retries_around_a_rejected_width() {
        let count = |w: f64| (10_000.0 / (w * w)).round() as usize;
        // plans pass only at widths a little above 10.04 (count 99 or less)
        let s = SizeSearch {
            secant_steps: 8,
            nudges: &[],
            tolerance: 3,
            explore: false,
            shrink_when_empty: None,
            retries: &[0.995, 1.005, 0.99, 1.01],
            settle_cost: f64::INFINITY,
        };
        let mut widths = Vec::new();
        let f = s
            .run_checked(100, 10.0, |w| {
                widths.push(w);
                if w > 10.04 {
                    Attempt::Plan(count(w), 0.0, count(w))
                } else {
                    Attempt::Rejected(count(w))
                }
            })
            .unwrap();
        assert!(
            f.w > 10.04 && f.plans.abs_diff(100) <= 3,
            "{} at {}",
            f.plans,
            f.w
        );
        assert!(widths.len() >= 3, "{widths:?}");
        // without retries the same search finds nothing
        let none = SizeSearch { retries: &[], ..s }.run_checked(100, 10.0, |w| {
            if w > 10.04 {
                Attempt::Plan(count(w), 0.0, count(w))
            } else {
                Attempt::Rejected(count(w))
            }
        });
        assert!(none.is_none());
    }

    /// A budget of widths bounds the steps and the retries together, and the best plan
    /// among the widths solved is the answer; without a budget the same search solves more.
    #[test]
    fn a_budget_bounds_the_widths_solved() {
        let count = |w: f64| (10_000.0 / (w * w)).round() as usize;
        let s = SizeSearch {
            secant_steps: 10,
            nudges: &[],
            tolerance: 0,
            explore: false,
            shrink_when_empty: None,
            retries: &[0.995, 1.005, 0.99, 1.01],
            settle_cost: 0.0,
        };
        // every plan lacks something (cost 1): the retries would all run
        let mut widths = Vec::new();
        let f = s
            .run_budgeted(100, 12.0, 3, |w| {
                widths.push(w);
                Attempt::Plan(count(w), 1.0, count(w))
            })
            .unwrap();
        assert_eq!(widths.len(), 3, "{widths:?}");
        let best = widths
            .iter()
            .map(|&w| count(w).abs_diff(100))
            .min()
            .unwrap();
        assert_eq!(f.plans.abs_diff(100), best);
        let mut all = 0;
        s.run_checked(100, 12.0, |w| {
            all += 1;
            Attempt::Plan(count(w), 1.0, count(w))
        });
        assert!(all > 3, "{all}");
    }

    #[test]
    fn no_plan_anywhere_is_none_and_stops_when_told() {
        let mut calls = 0;
        let s = SizeSearch {
            secant_steps: 5,
            nudges: &[],
            tolerance: 1,
            explore: false,
            shrink_when_empty: None,
            retries: &[],
            settle_cost: f64::INFINITY,
        };
        let f = s.run(10, 1.0, |_| {
            calls += 1;
            None::<(usize, f64, ())>
        });
        assert!(f.is_none());
        assert_eq!(calls, 1);
    }
}
