//! The reaction initiator (RI): a magnet held on the chain axis at the outer edge of tile 0
//! (`x = -d` in tile 0's frame, as in inequality (6.2)), with the moment of tile 0's
//! magnets and the pole opposite to magnet 0 (magnet `-1` of the chain,
//! [`crate::physics::Pole::Ri`]).

use kurbo::Point;

use crate::Design;

/// Where the RI is and how strong.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReactionInitiator {
    /// Its position in tile 0's frame, mm.
    pub position: Point,
    /// Its moment, A m^2.
    pub moment: f64,
}

impl ReactionInitiator {
    /// The RI at a chain whose tile 0 is built to `design`.
    pub fn of(design: &Design) -> ReactionInitiator {
        ReactionInitiator {
            position: Point::new(-design.d, 0.0),
            moment: design.moment(),
        }
    }
}
