//! Total dipole energy of the chain against time (thesis equation 8.1, figure 7.5).
//!
//! The sum of the pair energies (6.11) over every pair of magnets in the same tile or in
//! neighbouring tiles, and the RI with tile 0's magnets. Pairs two or more tiles apart are
//! left out: they sit at least about `w` apart, against `2c` (5.6 mm) for a bonded pair, so
//! each contributes well under 1% of a bonded pair's energy and changes even less. Each
//! tile's and each joint's share changes only while its magnets move or its joint turns, so
//! the curve is a sweep over those windows: `O(tiles + samples * moving)`.

use crate::dipole::pair_energy;
use crate::engine::fold::fold_angle;
use crate::engine::run::Timeline;
use crate::kinematics::joint_transform;

/// One point of the energy curve.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct EnergySample {
    /// Time, s.
    pub time: f64,
    /// Total energy, J.
    pub energy_j: f64,
}

#[derive(Clone, Copy, Debug)]
enum Unit {
    Ri,
    Tile(usize),
    Joint(usize),
}

fn unit_energy(tl: &Timeline, unit: Unit, t: f64, moment: f64) -> f64 {
    let pair = |p: (f64, f64), q: (f64, f64), attract: bool| {
        let r = ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt() * 1e-3;
        if r > 0.0 {
            pair_energy(moment, r, attract)
        } else {
            0.0
        }
    };
    match unit {
        Unit::Ri => {
            let ri = tl.geometry.ri_position();
            pair(ri, tl.local_position(0, t), true) + pair(ri, tl.local_position(1, t), false)
        }
        Unit::Tile(i) => pair(
            tl.local_position(2 * i, t),
            tl.local_position(2 * i + 1, t),
            true,
        ),
        Unit::Joint(j) => {
            let angle = tl.fold_at(j).map_or(0.0, |f| fold_angle(tl, f, t));
            let next = joint_transform(angle, tl.geometry.w);
            let mut e = 0.0;
            for a in [2 * j, 2 * j + 1] {
                let pa = tl.local_position(a, t);
                for b in [2 * j + 2, 2 * j + 3] {
                    let pb = next.transform_point(tl.local_position(b, t));
                    e += pair(pa, pb, (b - a) % 2 == 1);
                }
            }
            e
        }
    }
}

fn window(tl: &Timeline, unit: Unit) -> Option<(f64, f64)> {
    let magnets: Vec<usize> = match unit {
        Unit::Ri => vec![0, 1],
        Unit::Tile(i) => vec![2 * i, 2 * i + 1],
        Unit::Joint(j) => vec![2 * j, 2 * j + 1, 2 * j + 2, 2 * j + 3],
    };
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for k in magnets {
        if let (Some(s), Some(a)) = (tl.start_of(k), tl.arrival_of(k)) {
            lo = lo.min(s);
            hi = hi.max(a);
        }
    }
    if let Unit::Joint(j) = unit {
        if let Some(f) = tl.fold_at(j) {
            lo = lo.min(f.start);
            hi = hi.max(f.end);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The total energy at `samples` (at least 2) evenly spaced times from 0 to the end of the
/// run.
pub fn energy_curve(tl: &Timeline, samples: usize) -> Vec<EnergySample> {
    let samples = samples.max(2);
    let moment = tl.geometry.design(0).moment();
    let tiles = tl.tiles();
    let mut units = vec![Unit::Ri];
    units.extend((0..tiles).map(Unit::Tile));
    units.extend((0..tiles.saturating_sub(1)).map(Unit::Joint));
    // folds look-up per joint is linear in the folds: index them once
    let mut base = 0.0;
    let mut pending: Vec<(f64, f64, Unit, f64)> = Vec::new();
    for &u in &units {
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
    let mut active: Vec<(f64, f64, Unit, f64)> = Vec::new();
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
    use crate::engine::{run, EngineOptions, TileDesigns};
    use crate::{Chain, Design};

    #[test]
    fn energy_falls_and_matches_a_direct_sum() {
        let chain = Chain::parse("SSLS").unwrap();
        let tl = run(
            &chain,
            &TileDesigns::global(Design::thesis()),
            &EngineOptions::default(),
        )
        .unwrap();
        let curve = energy_curve(&tl, 50);
        assert!(curve.last().unwrap().energy_j < curve[0].energy_j);
        // the sweep agrees with summing every unit directly
        let moment = Design::thesis().moment();
        for s in &curve {
            let mut direct = unit_energy(&tl, Unit::Ri, s.time, moment);
            for i in 0..tl.tiles() {
                direct += unit_energy(&tl, Unit::Tile(i), s.time, moment);
            }
            for j in 0..tl.tiles() - 1 {
                direct += unit_energy(&tl, Unit::Joint(j), s.time, moment);
            }
            assert!(
                (direct - s.energy_j).abs() < 1e-12 * direct.abs(),
                "{} {}",
                direct,
                s.energy_j
            );
        }
    }
}
