//! The Wilson score interval of a binomial proportion (Wilson 1927; Agresti and Coull,
//! "Approximate is better than exact", The American Statistician 52, 1998): unlike the
//! normal approximation it stays inside `[0, 1]` and is sound when every sample folds.

/// z for a two-sided 95% interval.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The Wilson interval `(low, high)` for `successes` of `trials` at normal quantile `z`;
/// `(0, 1)` for no trials.
pub fn wilson_interval(successes: u64, trials: u64, z: f64) -> (f64, f64) {
    if trials == 0 {
        return (0.0, 1.0);
    }
    let n = trials as f64;
    let p = successes as f64 / n;
    let z2 = z * z;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = z / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textbook_values() {
        // Agresti and Coull's example form: 0 of 10 gives (0, 0.2775)
        let (lo, hi) = wilson_interval(0, 10, Z95);
        assert_eq!(lo, 0.0);
        assert!((hi - 0.2775).abs() < 1e-4, "{hi}");
        let (lo, hi) = wilson_interval(50, 100, Z95);
        assert!((lo - 0.4038).abs() < 1e-4 && (hi - 0.5962).abs() < 1e-4);
        let (lo, hi) = wilson_interval(10_000, 10_000, Z95);
        assert!(hi == 1.0 && (lo - 0.99962).abs() < 1e-5, "{lo}");
    }
}
