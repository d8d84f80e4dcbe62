//! Total dipole energy of the chain against time (thesis equation 8.1, figure 7.5), summed
//! over the units of [`crate::physics::EnergyUnit`] (the RI with tile 0, each tile, each
//! joint). Each unit's share changes only while its magnets move or its joint turns, so the
//! curve is a sweep over those windows: `O(tiles + samples * moving)`.

use kurbo::Point;

use crate::engine::result::{fold_angle, Timeline};
use crate::kinematics::joint_transform;
use crate::physics::{EnergyUnit, Pole};
use crate::timeline::EnergySample;

/// The energy (J) of `unit` at time `t`, every magnet of moment `moment`: positions in the
/// frame of the unit's first tile.
fn unit_energy(tl: &Timeline, unit: EnergyUnit, t: f64, moment: f64) -> f64 {
    let local = |k: usize| Point::from(tl.local_position(k, t));
    let ri = tl.geometry.ri().position;
    let law = tl.force_law();
    match unit {
        EnergyUnit::Joint(j) => {
            let angle = tl.fold_at(j).map_or(0.0, |f| fold_angle(tl, f, t));
            let next = joint_transform(angle, tl.geometry.w);
            unit.energy(law, moment, |p| match p {
                Pole::Magnet(k) if k >= 2 * j + 2 => {
                    Point::from(next.transform_point(tl.local_position(k, t)))
                }
                Pole::Magnet(k) => local(k),
                Pole::Ri => ri,
            })
        }
        _ => unit.energy(law, moment, |p| match p {
            Pole::Magnet(k) => local(k),
            Pole::Ri => ri,
        }),
    }
}

/// When `unit`'s energy changes: from the first start to the last arrival of its magnets,
/// and its joint's fold.
fn window(tl: &Timeline, unit: EnergyUnit) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for k in unit.magnets() {
        if let (Some(s), Some(a)) = (tl.start_of(k), tl.arrival_of(k)) {
            lo = lo.min(s);
            hi = hi.max(a);
        }
    }
    if let EnergyUnit::Joint(j) = unit {
        if let Some(f) = tl.fold_at(j) {
            lo = lo.min(f.start);
            hi = hi.max(f.end);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The total energy at `samples` (at least 2) evenly spaced times from 0 to the end of the
/// run.
pub(crate) fn energy_curve(tl: &Timeline, samples: usize) -> Vec<EnergySample> {
    let samples = samples.max(2);
    let moment = tl.geometry.design(0).moment();
    let mut base = 0.0;
    let mut pending: Vec<(f64, f64, EnergyUnit, f64)> = Vec::new();
    for u in EnergyUnit::all(tl.tiles()) {
        let rest = unit_energy(tl, u, f64::NEG_INFINITY, moment);
        base += rest;
        if let Some((lo, hi)) = window(tl, u) {
            pending.push((lo, hi, u, rest));
        }
    }
    pending.sort_by(|a, b| a.0.total_cmp(&b.0));
    let end = tl.duration();
    let mut out = Vec::with_capacity(samples);
    let mut next = 0;
    let mut active: Vec<(f64, f64, EnergyUnit, f64)> = Vec::new();
    let mut finished_delta = 0.0;
    for i in 0..samples {
        let t = end * i as f64 / (samples - 1) as f64;
        while next < pending.len() && pending[next].0 <= t {
            active.push(pending[next]);
            next += 1;
        }
        let mut delta = 0.0;
        active.retain(|&(_, hi, u, rest)| {
            if hi <= t {
                finished_delta += unit_energy(tl, u, f64::INFINITY, moment) - rest;
                false
            } else {
                delta += unit_energy(tl, u, t, moment) - rest;
                true
            }
        });
        out.push(EnergySample {
            time: t,
            energy_j: base + finished_delta + delta,
        });
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests may unwrap (CONTRIBUTING)
mod tests {
    use super::*;
    use crate::engine::thesis_timeline;

    #[test]
    fn energy_falls_and_matches_a_direct_sum() {
        let tl = thesis_timeline("SSLS");
        let curve = energy_curve(&tl, 50);
        assert!(curve.last().unwrap().energy_j < curve[0].energy_j);
        // the sweep agrees with summing every unit directly
        let moment = crate::Design::thesis().moment();
        for s in &curve {
            let direct: f64 = EnergyUnit::all(tl.tiles())
                .map(|u| unit_energy(&tl, u, s.time, moment))
                .sum();
            assert!(
                (direct - s.energy_j).abs() < 1e-12 * direct.abs(),
                "{} {}",
                direct,
                s.energy_j
            );
        }
    }
}
