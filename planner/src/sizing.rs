//! The tile-width search: the width at which a planner's best plan holds about the asked
//! number of tiles. Rows hold whole tiles and a plan gains or loses whole rows, so the count
//! is a step function of the width; the search takes secant-like steps on the square root of
//! the count (the count goes as 1 / w^2), then optional small nudges around the best width,
//! and keeps the width whose count misses the target least.

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
    /// Secant steps from the first width.
    pub secant_steps: usize,
    /// Factors tried on the best width after the secant steps, in order, while its count
    /// still misses by more than the tolerance.
    pub nudges: &'static [f64],
    /// The search stops once the count is within this many tiles of the target.
    pub tolerance: usize,
    /// When a width gives no plan: `Some(f)` tries `f` times that width next, `None` stops.
    pub shrink_when_empty: Option<f64>,
}

/// What the search found: the width and the planner's answer there.
pub(crate) struct Found<T> {
    pub w: f64,
    pub plans: T,
}

impl SizeSearch {
    /// Searches from width `w` for `target` tiles. `solve(w)` returns, for the best plan at
    /// `w`, its tile count and its cost (in user units: equal misses keep the cheaper), with
    /// the planner's answer; or `None` when there is no plan at `w`. A width tried before
    /// (to 1e-12) is not solved again: the answer would be the same.
    pub(crate) fn run<T>(
        &self,
        target: usize,
        mut w: f64,
        mut solve: impl FnMut(f64) -> Option<(usize, f64, T)>,
    ) -> Option<Found<T>> {
        // (miss, cost, width, answer)
        let mut best: Option<(usize, f64, f64, T)> = None;
        let mut tried: Vec<f64> = Vec::new();
        for step in 0..self.secant_steps + self.nudges.len() {
            if step >= self.secant_steps {
                match &best {
                    None => break,
                    Some((m, ..)) if *m <= self.tolerance => break,
                    Some((_, _, bw, _)) => w = bw * self.nudges[step - self.secant_steps],
                }
            } else if tried.iter().any(|&t| (t - w).abs() < 1e-12 * t) {
                continue;
            }
            tried.push(w);
            let Some((n, cost, plans)) = solve(w) else {
                match self.shrink_when_empty {
                    Some(f) => {
                        w *= f;
                        continue;
                    }
                    None => break,
                }
            };
            let miss = n.abs_diff(target);
            let at = w;
            if step < self.secant_steps {
                w *= (n as f64 / target as f64).sqrt();
            }
            if best
                .as_ref()
                .is_none_or(|(m, c, ..)| miss < *m || (miss == *m && cost < *c))
            {
                best = Some((miss, cost, at, plans));
            }
            if miss <= self.tolerance {
                break;
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
            shrink_when_empty: Some(0.97),
        };
        let f = s
            .run(500, 5.0, |w| Some((count(w), 0.0, count(w))))
            .unwrap();
        assert!(f.plans.abs_diff(500) <= 2, "{} tiles at {}", f.plans, f.w);
        assert_eq!(count(f.w), f.plans);
    }

    #[test]
    fn no_plan_anywhere_is_none_and_stops_when_told() {
        let mut calls = 0;
        let s = SizeSearch {
            secant_steps: 5,
            nudges: &[],
            tolerance: 1,
            shrink_when_empty: None,
        };
        let f = s.run(10, 1.0, |_| {
            calls += 1;
            None::<(usize, f64, ())>
        });
        assert!(f.is_none());
        assert_eq!(calls, 1);
    }
}
