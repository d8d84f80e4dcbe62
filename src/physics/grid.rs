//! Pairs of points closer than a distance, found on a uniform grid of cells of that size:
//! each point is compared only with the points of its own and the eight neighbouring cells,
//! so the work grows with the points and their crowding, not with their square. The
//! reference's distance cutoff ([`crate::model::ModelOptions::distance_cutoff`]) uses it
//! to keep the pairs that are far apart in chain index but near in space (a ring's first
//! and last tiles).

use std::collections::HashMap;

use kurbo::Point;

/// Every pair `(i, j)`, `i < j`, of `points` less than `radius` apart (any units), sorted.
/// Empty for a radius that is not a positive finite number.
pub fn pairs_within(points: &[Point], radius: f64) -> Vec<(usize, usize)> {
    if !(radius.is_finite() && radius > 0.0) {
        return Vec::new();
    }
    let cell = |p: Point| ((p.x / radius).floor() as i64, (p.y / radius).floor() as i64);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for (i, p) in points.iter().enumerate() {
        grid.entry(cell(*p)).or_default().push(i);
    }
    let r2 = radius * radius;
    let mut out = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let (cx, cy) = cell(*p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                let Some(bucket) = grid.get(&(cx + dx, cy + dy)) else {
                    continue;
                };
                for &j in bucket {
                    if j > i && (points[j] - *p).hypot2() < r2 {
                        out.push((i, j));
                    }
                }
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_exactly_the_close_pairs() {
        // a pseudo-random cloud against all pairs
        let mut rng = crate::rng::SplitMix64::new(12345);
        let mut next = || (rng.next_u64() % 10_000) as f64 / 100.0 - 50.0;
        let pts: Vec<Point> = (0..300).map(|_| Point::new(next(), next())).collect();
        for r in [0.5, 3.0, 17.0] {
            let mut want = Vec::new();
            for i in 0..pts.len() {
                for j in i + 1..pts.len() {
                    if pts[i].distance(pts[j]) < r {
                        want.push((i, j));
                    }
                }
            }
            assert_eq!(pairs_within(&pts, r), want, "r {r}");
        }
        assert!(pairs_within(&pts, 0.0).is_empty());
        assert!(pairs_within(&pts, f64::NAN).is_empty());
    }
}
