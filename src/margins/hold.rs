//! How firmly the resting chain holds each magnet before the reaction initiator comes: the
//! force along each magnet's path with every magnet at rest and the chain straight, the RI
//! absent, negated and over the bond force of the magnet's tile. Positive everywhere is
//! inequality (6.1) with every pair within the cutoff counted: the chain does not actuate by
//! itself. At `s = 0` it is zero (the marginal cascade); a printed tile whose `s` comes out
//! smaller than its neighbour's can make it negative.

use crate::margins::placed_tiles::PlacedTiles;
use crate::margins::start::Posed;
use crate::margins::{ChainModel, HoldMargin, MarginOptions};

/// Every magnet's hold margin.
pub(crate) fn hold_margins(model: &ChainModel, opts: &MarginOptions) -> Vec<HoldMargin> {
    let n = model.magnets();
    let mut window = PlacedTiles::new(0, n - 1);
    window.place(
        model,
        &Posed {
            model,
            ends_below: 0,
            folded_below: 0,
            moving: [None, None],
            turn: None,
        },
    );
    (0..n)
        .map(|m| {
            let drive = window.drive_from(model, opts.force_law, opts.cutoff, m, 0.0, false);
            HoldMargin {
                magnet: m,
                margin: -drive / model.bond_force(opts.force_law, m / 2),
            }
        })
        .collect()
}
