//! A solved serpentine read back from the row programme ([`crate::rows`]): its rows in chain
//! order, their tile centres and their folds (rows of straight joints, U-turns between them).

use std::f64::consts::FRAC_1_SQRT_2;

use foldchain::Fold;
use kurbo::Point;

use crate::options::Turns;
use crate::rows::Style;

/// A solved serpentine in its lattice frame (unit tiles): row `k` at `y0 + k pitch` runs +x
/// for even `k`, -x for odd, over the columns `x0 + j`.
#[derive(Clone, Debug)]
pub(crate) struct Serpentine {
    pub x0: f64,
    pub y0: f64,
    pub pitch: f64,
    /// (row index k, start column, end column) in chain order.
    pub rows: Vec<(usize, i64, i64)>,
}

impl Serpentine {
    /// The first row `(k, start column)`, or row 0 column 0 for an empty serpentine.
    pub(crate) fn first(&self) -> (usize, i64) {
        self.rows.first().map_or((0, 0), |&(k, s, _)| (k, s))
    }

    /// The last row `(k, end column)`, or row 0 column 0 for an empty serpentine.
    pub(crate) fn last(&self) -> (usize, i64) {
        self.rows.last().map_or((0, 0), |&(k, _, e)| (k, e))
    }

    /// The direction (+1 along +x, -1 along -x) in which row `k` runs.
    pub(crate) fn runs(k: usize) -> f64 {
        if k % 2 == 0 {
            1.0
        } else {
            -1.0
        }
    }

    /// The number of U-turns.
    pub(crate) fn u_turns(&self) -> usize {
        self.rows.len().saturating_sub(1)
    }

    /// The number of tiles of its chain.
    pub(crate) fn tiles(&self, style: Style) -> usize {
        let row_tiles: usize = self
            .rows
            .iter()
            .map(|&(_, s, e)| (e - s).unsigned_abs() as usize + 1)
            .sum();
        // a tight U-turn adds its LL/RR tile, a loose one that and a straight tile
        let turn_tiles = if style.turns == Turns::Loose { 2 } else { 1 };
        row_tiles + turn_tiles * self.u_turns()
    }

    /// The centre of the tile in row `k`, column `j`.
    pub(crate) fn centre(&self, k: usize, j: i64) -> Point {
        Point::new(self.x0 + j as f64, self.y0 + k as f64 * self.pitch)
    }

    /// Every tile centre (rows and U-turn tiles) in chain order.
    pub(crate) fn centres(&self, style: Style) -> Vec<Point> {
        let mut out = Vec::new();
        for (i, &(k, s, e)) in self.rows.iter().enumerate() {
            let step = if e >= s { 1 } else { -1 };
            let mut j = s;
            loop {
                out.push(self.centre(k, j));
                if j == e {
                    break;
                }
                j += step;
            }
            if i + 1 < self.rows.len() {
                let x = self.x0 + e as f64 + Serpentine::runs(k) * FRAC_1_SQRT_2;
                let y = self.y0 + k as f64 * self.pitch + FRAC_1_SQRT_2;
                out.push(Point::new(x, y));
                if style.turns == Turns::Loose {
                    out.push(Point::new(x, y + 1.0));
                }
            }
        }
        out
    }

    /// Appends the folds of its rows and U-turns: straight joints along a row, and each
    /// U-turn two L folds or two R folds (with a straight one between for loose turns).
    /// `ccw` says whether turning from +x towards +y is counter-clockwise (an L fold) in the
    /// physical frame.
    pub(crate) fn folds(&self, style: Style, ccw: bool, out: &mut Vec<Fold>) {
        for (i, &(k, s, e)) in self.rows.iter().enumerate() {
            out.extend(std::iter::repeat_n(
                Fold::S,
                (e - s).unsigned_abs() as usize,
            ));
            if i + 1 < self.rows.len() {
                // from a +x row the U-turn turns towards +y, from a -x row away from it
                let f = if (k % 2 == 0) == ccw {
                    Fold::L
                } else {
                    Fold::R
                };
                out.push(f);
                if style.turns == Turns::Loose {
                    out.push(Fold::S);
                }
                out.push(f);
            }
        }
    }
}
