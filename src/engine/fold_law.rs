//! The engine's fold angle law.
//!
//! A fold is driven by its pair of magnets (tile `j`'s second, tile `j+1`'s first). Its
//! progress is the mean fraction of their paths travelled,
//! `p = (u_a / L_a + u_b / L_b) / 2`; the fold starts when the second magnet starts (at
//! `p = p0`, the first one's fraction at its trigger point, halved) and the joint angle is
//! `theta = theta_final * (p - p0) / (1 - p0)`, reaching 90 degrees when both magnets have
//! arrived. It is monotone and continuous; under the overdamped law it speeds up as the pair
//! closes.

use std::f64::consts::FRAC_PI_2;

use crate::timeline::FoldRecord;

/// The signed angle (radians, positive = left) of `fold` at time `t`, given the fractions of
/// their paths its two magnets have travelled then.
pub(crate) fn fold_angle_from(fold: &FoldRecord, t: f64, frac_a: f64, frac_b: f64) -> f64 {
    let target = fold.fold.quarter_turns() as f64 * FRAC_PI_2;
    if t <= fold.start {
        return 0.0;
    }
    if t >= fold.end {
        return target;
    }
    let p = 0.5 * (frac_a + frac_b);
    let x = if fold.p0 < 1.0 {
        ((p - fold.p0) / (1.0 - fold.p0)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    target * x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Fold;

    #[test]
    fn the_angle_runs_from_straight_to_a_quarter_turn() {
        let f = FoldRecord {
            joint: 0,
            fold: Fold::R,
            start: 1.0,
            end: 2.0,
            p0: 0.2,
        };
        assert_eq!(fold_angle_from(&f, 0.5, 0.0, 0.0), 0.0);
        assert_eq!(fold_angle_from(&f, 2.5, 1.0, 1.0), -FRAC_PI_2);
        // halfway from p0 to 1
        let a = fold_angle_from(&f, 1.5, 0.6, 0.6);
        assert!((a + 0.5 * FRAC_PI_2).abs() < 1e-15, "{a}");
        // clamped while the pair's progress is still below p0
        assert_eq!(fold_angle_from(&f, 1.1, 0.1, 0.1), 0.0);
    }
}
