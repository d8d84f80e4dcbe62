//! One quantity of a run against time, as the viewer plays it: a magnet's travel along its
//! path or a joint's angle, a piecewise-linear curve that holds its first value until it
//! starts and its last value after it ends. Made by sampling a closed form adaptively
//! ([`Track::sample`], the event engine) or by thinning recorded values
//! ([`Track::from_samples`], the reference integrator), each within a stated tolerance.

/// How closely a magnet's travel track follows the run, mm: 1 um, far below a pixel at any
/// zoom the viewer offers on 30 mm tiles.
pub(crate) const TRAVEL_TOLERANCE: f64 = 1e-3;

/// How closely a joint's angle track follows the run, radians: 1e-5 rad. A tile `n` tiles
/// beyond a hinge moves by at most `1e-5 * n * w` (3 um per 10 tiles on 30 mm tiles).
pub(crate) const ANGLE_TOLERANCE: f64 = 1e-5;

/// Deepest halving of an interval in [`Track::sample`] (8 * 2^16 intervals at most).
const MAX_DEPTH: u32 = 16;

/// A quantity against time: `points[0].1` until `start`, then linear between the points
/// `(start + dt, value)` (`dt` increasing from 0), then the last value.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Track {
    /// When the quantity starts to change, s.
    pub start: f64,
    /// `(seconds after start, value)`, in time order; empty means a constant 0.
    pub points: Vec<(f64, f64)>,
}

impl Track {
    /// How closely a magnet's travel track follows the run, mm: 1 um, far below a pixel at
    /// any zoom the viewer offers on 30 mm tiles.
    pub const TRAVEL_TOLERANCE: f64 = TRAVEL_TOLERANCE;
    /// How closely a joint's angle track follows the run, radians: 1e-5 rad (a tile `n` tiles
    /// beyond a hinge moves by at most `1e-5 * n * w`).
    pub const ANGLE_TOLERANCE: f64 = ANGLE_TOLERANCE;

    /// A quantity that never changes.
    pub fn constant(value: f64) -> Track {
        Track {
            start: 0.0,
            points: vec![(0.0, value)],
        }
    }

    /// Whether the quantity never changes.
    pub fn is_constant(&self) -> bool {
        self.points.len() < 2
    }

    /// When it stops changing, s (`start` for a constant).
    pub fn end(&self) -> f64 {
        self.start + self.points.last().map_or(0.0, |p| p.0)
    }

    /// The value at time `t`.
    pub fn value_at(&self, t: f64) -> f64 {
        let dt = t - self.start;
        let pts = &self.points;
        let i = pts.partition_point(|p| p.0 < dt);
        match (i.checked_sub(1).and_then(|j| pts.get(j)), pts.get(i)) {
            (Some(&(ta, va)), Some(&(tb, vb))) if tb > ta => va + (vb - va) * (dt - ta) / (tb - ta),
            (_, Some(&(_, v))) | (Some(&(_, v)), None) => v,
            (None, None) => 0.0,
        }
    }

    /// `f(dt)` for `dt` in `[0, duration]`, starting at `start`: eight equal intervals, each
    /// halved until `f` at its midpoint lies within `tolerance` of the chord (at most 16
    /// times), so the track follows a smooth `f` within about `tolerance`.
    pub fn sample(start: f64, duration: f64, tolerance: f64, f: impl Fn(f64) -> f64) -> Track {
        let duration = if duration.is_finite() {
            duration.max(0.0)
        } else {
            0.0
        };
        let mut points = vec![(0.0, f(0.0))];
        if duration > 0.0 {
            let n0 = 8;
            for i in 0..n0 {
                let t0 = duration * i as f64 / n0 as f64;
                let t1 = duration * (i + 1) as f64 / n0 as f64;
                let a = points.last().map_or(0.0, |p| p.1);
                refine(&f, (t0, a), (t1, f(t1)), tolerance, 0, &mut points);
            }
        }
        Track { start, points }
    }

    /// The track through the recorded `(time, value)` samples (in time order), thinned: a
    /// sample is kept only where dropping it would move the line by more than `tolerance`
    /// (Douglas-Peucker). Starts at the last sample before the value first changes.
    pub fn from_samples(samples: &[(f64, f64)], tolerance: f64) -> Track {
        let Some(&(t0, v0)) = samples.first() else {
            return Track::constant(0.0);
        };
        let first = samples.iter().position(|s| s.1 != v0);
        let Some(first) = first else {
            return Track {
                start: t0,
                points: vec![(0.0, v0)],
            };
        };
        let v_end = samples[samples.len() - 1].1;
        let last = samples
            .iter()
            .rposition(|s| s.1 != v_end)
            .map_or(0, |i| i + 1);
        let run = &samples[first - 1..=last.max(first)];
        let keep = douglas_peucker(run, tolerance);
        let start = run[0].0;
        Track {
            start,
            points: keep
                .into_iter()
                .map(|i| (run[i].0 - start, run[i].1))
                .collect(),
        }
    }
}

fn refine(
    f: &impl Fn(f64) -> f64,
    (t0, a): (f64, f64),
    (t1, b): (f64, f64),
    tolerance: f64,
    depth: u32,
    out: &mut Vec<(f64, f64)>,
) {
    let tm = 0.5 * (t0 + t1);
    let m = f(tm);
    if depth < MAX_DEPTH && (m - 0.5 * (a + b)).abs() > tolerance {
        refine(f, (t0, a), (tm, m), tolerance, depth + 1, out);
        refine(f, (tm, m), (t1, b), tolerance, depth + 1, out);
    } else {
        out.push((t1, b));
    }
}

/// Indices of the samples kept by Douglas-Peucker at `tolerance` (vertical distance to the
/// chord), always the first and the last.
fn douglas_peucker(s: &[(f64, f64)], tolerance: f64) -> Vec<usize> {
    let n = s.len();
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0, n - 1)];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (ta, va) = s[a];
        let (tb, vb) = s[b];
        let mut worst = (0.0, a);
        for (i, &(t, v)) in s.iter().enumerate().take(b).skip(a + 1) {
            let line = if tb > ta {
                va + (vb - va) * (t - ta) / (tb - ta)
            } else {
                va
            };
            let d = (v - line).abs();
            if d > worst.0 {
                worst = (d, i);
            }
        }
        if worst.0 > tolerance {
            keep[worst.1] = true;
            stack.push((a, worst.1));
            stack.push((worst.1, b));
        }
    }
    (0..n).filter(|&i| keep[i]).collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;

    #[test]
    fn sampled_track_follows_a_smooth_law_within_its_tolerance() {
        let law = |dt: f64| 5.0 - (5.0f64.powi(5) - 300.0 * dt).max(0.0).powf(0.2);
        let tr = Track::sample(2.0, 10.0, 1e-3, law);
        assert!(
            tr.points.len() > 8 && tr.points.len() < 2000,
            "{}",
            tr.points.len()
        );
        for i in 0..=10_000 {
            let dt = 10.0 * i as f64 / 10_000.0;
            let err = (tr.value_at(2.0 + dt) - law(dt)).abs();
            assert!(err < 2e-3, "{dt}: {err}");
        }
        assert_eq!(tr.value_at(0.0), law(0.0));
        assert_eq!(tr.value_at(100.0), law(10.0));
        assert_eq!(tr.end(), 12.0);
    }

    #[test]
    fn thinned_samples_start_where_the_value_changes_and_keep_the_shape() {
        let mut s: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 * 0.1, 0.0)).collect();
        for (i, p) in s.iter_mut().enumerate().skip(40).take(30) {
            p.1 = ((i - 39) as f64 * 0.05).sin();
        }
        let last = s[69].1;
        for p in s.iter_mut().skip(70) {
            p.1 = last;
        }
        let tr = Track::from_samples(&s, 1e-4);
        assert!((tr.start - 3.9).abs() < 1e-12, "{}", tr.start);
        assert!((tr.end() - 6.9).abs() < 1e-12, "{}", tr.end());
        assert!(tr.points.len() < 31);
        for &(t, v) in &s {
            assert!((tr.value_at(t) - v).abs() <= 1e-4, "{t}");
        }
        let flat = Track::from_samples(&[(0.0, 2.0), (1.0, 2.0)], 1e-3);
        assert!(flat.is_constant() && flat.value_at(5.0) == 2.0);
    }
}
