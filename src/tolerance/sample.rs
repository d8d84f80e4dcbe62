//! One printed chain: each tile's design drawn within the tolerances around its nominal
//! design, and a design nudged in one parameter (for sensitivities).

use crate::rng::SplitMix64;
use crate::tolerance::{Parameter, Tolerances};
use crate::Design;

/// `design` with parameter `p` moved by `delta` (mm, or relative for the remanence).
///
/// The wall moves the curved paths' final point only ([`Design::wall`]; a design that
/// gives `c` keeps its final points there); the width moves
/// `d = w/2` with it; `s` and the wall are kept `>= 0`.
pub fn nudged(design: &Design, p: Parameter, delta: f64) -> Design {
    let mut d = *design;
    match p {
        Parameter::S => d.s = (d.s + delta).max(0.0),
        Parameter::E => d.e += delta,
        Parameter::Wall => d.wall = (d.wall + delta).max(0.0),
        Parameter::Width => {
            d.tile_width += delta;
            d.d += 0.5 * delta;
        }
        Parameter::Br => d.remanence *= 1.0 + delta,
        Parameter::Diameter => d.magnet_diameter += delta,
        Parameter::Height => d.magnet_height += delta,
    }
    d
}

/// Every tile's design for sample `index` of a study seeded with `seed`: each parameter of
/// each tile drawn uniformly within `nominal +- tol`, in [`Parameter::ALL`]'s order, tile
/// by tile (so a sample's draws do not depend on threads or shards).
pub fn draw_designs(
    nominal: &[Design],
    tiles: usize,
    tol: &Tolerances,
    seed: u64,
    index: u64,
    out: &mut Vec<Design>,
) {
    let mut rng = SplitMix64::for_sample(seed, index);
    out.clear();
    for t in 0..tiles {
        let mut d = nominal[if nominal.len() == 1 { 0 } else { t }];
        for p in Parameter::ALL {
            let u = rng.symmetric();
            d = nudged(&d, p, tol.get(p) * u);
        }
        out.push(d);
    }
}
