//! Tile centres bucketed by unit cell (unit tiles), for "which tiles are near this point":
//! the fit measures ask it for every sample point, the cell router for every new tile.

use kurbo::Point;

/// Sample points farther than this (tile widths) from every tile centre are empty: tight
/// rows sqrt2 apart leave no point of the band between them farther than 0.71 from a
/// centre, and a row of tiles 1 apart none farther than 0.5 along it, so 0.95 flags only
/// what no row reaches (issue 26's measure).
pub(crate) const NEAR: f64 = 0.95;

/// Tile centres bucketed by unit cell (compressed rows).
pub(crate) struct CentreGrid {
    x0: i64,
    y0: i64,
    nx: i64,
    ny: i64,
    /// `start[c]..start[c + 1]` indexes `ids` for cell `c`.
    start: Vec<usize>,
    ids: Vec<usize>,
}

/// `x.floor() as i64`, without a call into libm (the build's baseline x86-64 has no rounding
/// instruction): the same value for every `x`, NaN and infinities included.
#[inline]
pub(crate) fn floor_i64(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) > x {
        t.saturating_sub(1)
    } else {
        t
    }
}

/// `x.ceil() as i64`, as [`floor_i64`].
#[inline]
pub(crate) fn ceil_i64(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) < x {
        t.saturating_add(1)
    } else {
        t
    }
}

/// The unit cell holding `p`.
fn cell_of(p: Point) -> (i64, i64) {
    (floor_i64(p.x), floor_i64(p.y))
}

impl CentreGrid {
    /// The grid of `centres` (their indices are the tile ids).
    pub(crate) fn new(centres: &[Point]) -> CentreGrid {
        let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
        for c in centres.iter().map(|&p| cell_of(p)) {
            (x0, y0, x1, y1) = (x0.min(c.0), y0.min(c.1), x1.max(c.0), y1.max(c.1));
        }
        let (nx, ny) = if centres.is_empty() {
            (0, 0)
        } else {
            (x1 - x0 + 1, y1 - y0 + 1)
        };
        let index = |(cx, cy): (i64, i64)| ((cy - y0) * nx + (cx - x0)) as usize;
        let mut start = vec![0usize; (nx * ny) as usize + 1];
        for c in centres.iter().map(|&p| cell_of(p)) {
            start[index(c) + 1] += 1;
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let mut fill = start.clone();
        let mut ids = vec![0usize; centres.len()];
        for (i, c) in centres.iter().map(|&p| cell_of(p)).enumerate() {
            let k = index(c);
            ids[fill[k]] = i;
            fill[k] += 1;
        }
        CentreGrid {
            x0,
            y0,
            nx,
            ny,
            start,
            ids,
        }
    }

    /// The tiles whose centre lies in the cell `(cx, cy)`.
    fn in_cell(&self, cx: i64, cy: i64) -> &[usize] {
        let (i, j) = (cx - self.x0, cy - self.y0);
        if i < 0 || j < 0 || i >= self.nx || j >= self.ny {
            return &[];
        }
        let k = (j * self.nx + i) as usize;
        &self.ids[self.start[k]..self.start[k + 1]]
    }

    /// True if `hit` holds for some tile whose centre lies in the cell of `p` or one of its
    /// eight neighbours (every centre within one tile width of `p`, and some further).
    pub(crate) fn any_near(&self, p: Point, mut hit: impl FnMut(usize) -> bool) -> bool {
        let (cx, cy) = cell_of(p);
        // a point more than a cell beyond the grid has no neighbours in it (the cell router
        // asks for every tile laid before, most far from the new leg)
        if cx < self.x0.saturating_sub(1)
            || cy < self.y0.saturating_sub(1)
            || cx > self.x0.saturating_add(self.nx)
            || cy > self.y0.saturating_add(self.ny)
        {
            return false;
        }
        (-1..=1).any(|i| (-1..=1).any(|j| self.in_cell(cx + i, cy + j).iter().any(|&t| hit(t))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The integer floor and ceiling agree with libm's on values around integers, halves,
    /// the ends of `i64` and the non-finite.
    #[test]
    fn integer_floor_and_ceiling_match_libm() {
        let mut xs = vec![
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            9.3e18,
            -9.3e18,
            i64::MAX as f64,
            i64::MIN as f64,
            f64::EPSILON,
            -f64::EPSILON,
        ];
        for i in -40..40 {
            let x = i as f64 * 0.25;
            xs.extend([x, x.next_up(), x.next_down(), x * 1e15 + 0.5]);
        }
        for x in xs {
            assert_eq!(floor_i64(x), x.floor() as i64, "{x}");
            assert_eq!(ceil_i64(x), x.ceil() as i64, "{x}");
        }
    }

    #[test]
    fn finds_exactly_the_centres_within_a_unit() {
        let centres: Vec<Point> = (0..40)
            .map(|i| Point::new(0.37 * i as f64, (i % 7) as f64 * 0.9 - 2.0))
            .collect();
        let grid = CentreGrid::new(&centres);
        for probe in [
            Point::new(3.1, 0.2),
            Point::new(-5.0, 9.0),
            Point::new(10.0, -1.6),
        ] {
            let mut near = Vec::new();
            grid.any_near(probe, |t| {
                near.push(t);
                false
            });
            for (t, c) in centres.iter().enumerate() {
                if c.distance(probe) <= 1.0 {
                    assert!(near.contains(&t), "{t} missed near {probe:?}");
                }
            }
        }
    }
}
