//! A solved unknown over time: the states of a local solve's accepted steps, joined by cubic
//! Hermite pieces (value and rate at both ends of every step), so that a later solve can ask
//! where an upstream magnet is at any instant (the dense output).
//!
//! A [`Shape`] is stored once and placed in time by a [`Track`] (its offset): a run of tiles
//! that repeat the same local solution shares one shape, shifted.

use std::sync::Arc;

pub(crate) use crate::ode::hermite;

/// One unknown over time, from its own time origin (`t[0] = 0`).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Shape {
    /// Node times, s, increasing from 0.
    pub(crate) t: Vec<f64>,
    /// Values at the nodes.
    pub(crate) y: Vec<f64>,
    /// Rates at the nodes, per s.
    pub(crate) dy: Vec<f64>,
}

impl Shape {
    /// The value at `t` (before the first node: the first value; after the last: the last).
    pub(crate) fn at(&self, t: f64) -> f64 {
        // no hint: the search of at_hinted, after two failed guesses
        self.at_hinted(t, &mut 0)
    }

    /// The first and second derivatives by time at `t` of the Hermite piece holding it
    /// (0 outside the nodes).
    pub(crate) fn rates_at(&self, t: f64) -> (f64, f64) {
        let n = self.t.len();
        if n < 2 || t <= self.t[0] || t >= self.t[n - 1] {
            return (0.0, 0.0);
        }
        let i = self.t.partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        let h = self.t[i + 1] - self.t[i];
        if h <= 0.0 {
            return (self.dy[i], 0.0);
        }
        let s = (t - self.t[i]) / h;
        let (y0, m0, y1, m1) = (self.y[i], self.dy[i], self.y[i + 1], self.dy[i + 1]);
        let d1 = (6.0 * s * s - 6.0 * s) * (y0 - y1) / h
            + (3.0 * s * s - 4.0 * s + 1.0) * m0
            + (3.0 * s * s - 2.0 * s) * m1;
        let d2 = (12.0 * s - 6.0) * (y0 - y1) / (h * h)
            + ((6.0 * s - 4.0) * m0 + (6.0 * s - 2.0) * m1) / h;
        (d1, d2)
    }

    /// [`Shape::at`], starting the search for `t`'s interval at `hint` (the interval found
    /// last, kept up to date): the same value, in constant time while `t` moves by no more
    /// than an interval between calls.
    pub(crate) fn at_hinted(&self, t: f64, hint: &mut usize) -> f64 {
        let n = self.t.len();
        if n == 0 {
            return 0.0;
        }
        if t <= self.t[0] {
            return self.y[0];
        }
        if t >= self.t[n - 1] {
            return self.y[n - 1];
        }
        // the interval `at` finds: the last node at or before `t` (n >= 2 here)
        let fits = |i: usize| i + 1 < n && self.t[i] <= t && t < self.t[i + 1];
        let i = if fits(*hint) {
            *hint
        } else if fits(*hint + 1) {
            *hint + 1
        } else {
            self.t.partition_point(|&x| x <= t).clamp(1, n - 1) - 1
        };
        *hint = i;
        hermite(
            self.t[i],
            self.t[i + 1],
            (self.y[i], self.dy[i]),
            (self.y[i + 1], self.dy[i + 1]),
            t,
        )
    }

    /// When the shape first reaches `x` (bisection on its interpolant), if it does.
    pub(crate) fn crossing(&self, x: f64) -> Option<f64> {
        let i = self.y.iter().position(|&y| y >= x)?;
        if i == 0 {
            return Some(self.t[0]);
        }
        let (mut lo, mut hi) = (self.t[i - 1], self.t[i]);
        let (a, b) = ((self.y[i - 1], self.dy[i - 1]), (self.y[i], self.dy[i]));
        let (t0, t1) = (lo, hi);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if hermite(t0, t1, a, b, mid) >= x {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        Some(hi)
    }

    /// The time of the last node (the shape is constant after it).
    pub(crate) fn end(&self) -> f64 {
        self.t.last().copied().unwrap_or(0.0)
    }

    /// The first node after `t`, if any.
    #[cfg(test)]
    pub(crate) fn next_node_after(&self, t: f64) -> Option<f64> {
        let i = self.t.partition_point(|&x| x <= t);
        self.t.get(i).copied()
    }

    /// [`Shape::next_node_after`], starting the search at `hint` (the node found last, kept
    /// up to date): the same node, in constant time while `t` moves forwards by few nodes
    /// between calls.
    pub(crate) fn next_node_after_hinted(&self, t: f64, hint: &mut usize) -> Option<f64> {
        let n = self.t.len();
        let mut i = (*hint).min(n);
        if i > 0 && self.t[i - 1] > t {
            // t went back: search
            i = self.t.partition_point(|&x| x <= t);
        } else {
            let mut steps = 0;
            while i < n && self.t[i] <= t {
                i += 1;
                steps += 1;
                if steps == 8 {
                    i = self.t.partition_point(|&x| x <= t);
                    break;
                }
            }
        }
        *hint = i;
        self.t.get(i).copied()
    }

    /// Whether `other`, placed `lag` later than this shape, agrees with it within `tol` at
    /// every node of either, and ends within `dt` of it.
    pub(crate) fn close_shifted(&self, other: &Shape, lag: f64, tol: f64, dt: f64) -> bool {
        if (self.end() - (lag + other.end())).abs() > dt {
            return false;
        }
        self.t
            .iter()
            .all(|&t| (self.at(t) - other.at(t - lag)).abs() <= tol)
            && other
                .t
                .iter()
                .all(|&t| (self.at(t + lag) - other.at(t)).abs() <= tol)
    }
}

/// Id of the shape that is 0 at all times (a magnet at rest, a straight joint).
pub(crate) const REST: u32 = 0;

/// A shape id's bits above this one number the sweep that made it (0: [`REST`]), those
/// below number it among that sweep's shapes, in the order the sweep made them: ids that
/// do not depend on how the sweeps are spread over threads. 2^26 (67 million) shapes a
/// sweep, and [`MAX_STORED_SWEEPS`] sweeps.
const SWEEP_SHIFT: u32 = 26;

/// The most sweeps whose shapes [`Shapes`] tells apart: 63 (the relaxation stops at
/// [`MAX_SWEEPS`](crate::engine::local::relaxation::MAX_SWEEPS), or
/// [`COUPLED_MAX_SWEEPS`](crate::engine::local::relaxation::COUPLED_MAX_SWEEPS) with
/// coupled folds).
pub(crate) const MAX_STORED_SWEEPS: usize = (1 << (32 - SWEEP_SHIFT)) - 1;

/// A shape placed in time: the unknown's value at `t` is `shape.at(t - offset)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Track {
    /// The shape's id in [`Shapes`].
    pub(crate) shape: u32,
    /// When the shape's time origin falls, s.
    pub(crate) offset: f64,
}

impl Track {
    /// At rest for ever.
    pub(crate) const REST: Track = Track {
        shape: REST,
        offset: 0.0,
    };
}

/// Shapes by id ([`REST`] first), each sweep's in its own list: a sweep's view of the
/// shapes it may read (those of the sweeps before it and its own). The shapes themselves
/// are shared between views.
#[derive(Clone, Debug)]
pub(crate) struct Shapes {
    by_sweep: Vec<Vec<Arc<Shape>>>,
}

impl Default for Shapes {
    fn default() -> Shapes {
        Shapes {
            by_sweep: vec![vec![Arc::new(Shape {
                t: vec![0.0],
                y: vec![0.0],
                dy: vec![0.0],
            })]],
        }
    }
}

impl Shapes {
    /// Stores `shape` as the next shape of sweep `sweep` (from 1); its id.
    pub(crate) fn add(&mut self, sweep: usize, shape: Arc<Shape>) -> u32 {
        debug_assert!((1..=MAX_STORED_SWEEPS).contains(&sweep));
        if self.by_sweep.len() <= sweep {
            self.by_sweep.resize_with(sweep + 1, Vec::new);
        }
        let list = &mut self.by_sweep[sweep];
        debug_assert!(list.len() < 1 << SWEEP_SHIFT);
        list.push(shape);
        ((sweep as u32) << SWEEP_SHIFT) | (list.len() - 1) as u32
    }

    /// How many shapes are stored.
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.by_sweep.iter().map(Vec::len).sum()
    }

    /// The shape of id `id`.
    pub(crate) fn get(&self, id: u32) -> &Shape {
        &self.by_sweep[(id >> SWEEP_SHIFT) as usize][(id & ((1 << SWEEP_SHIFT) - 1)) as usize]
    }

    /// The value of `track` at `t`.
    pub(crate) fn value(&self, track: Track, t: f64) -> f64 {
        if track.shape == REST {
            return 0.0;
        }
        self.get(track.shape).at(t - track.offset)
    }

    /// [`Shapes::value`] by [`Shape::at_hinted`].
    pub(crate) fn value_hinted(&self, track: Track, t: f64, hint: &mut usize) -> f64 {
        if track.shape == REST {
            return 0.0;
        }
        self.get(track.shape).at_hinted(t - track.offset, hint)
    }

    /// The value of `track` at `t` and its first and second derivatives by time.
    pub(crate) fn motion(&self, track: Track, t: f64) -> (f64, f64, f64) {
        if track.shape == REST {
            return (0.0, 0.0, 0.0);
        }
        let shape = self.get(track.shape);
        let (d1, d2) = shape.rates_at(t - track.offset);
        (shape.at(t - track.offset), d1, d2)
    }

    /// When `track` starts changing (`None` for the rest track).
    pub(crate) fn first_move(&self, track: Track) -> Option<f64> {
        (track.shape != REST).then_some(track.offset)
    }

    /// When `track` stops changing (`None` for the rest track).
    pub(crate) fn last_move(&self, track: Track) -> Option<f64> {
        (track.shape != REST).then(|| track.offset + self.get(track.shape).end())
    }

    /// The first node of `track` after `t`, if any, by [`Shape::next_node_after_hinted`].
    pub(crate) fn next_node_hinted(&self, track: Track, t: f64, hint: &mut usize) -> Option<f64> {
        if track.shape == REST {
            return None;
        }
        self.get(track.shape)
            .next_node_after_hinted(t - track.offset, hint)
            .map(|x| x + track.offset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_reproduces_a_cubic() {
        let f = |t: f64| 1.0 + 2.0 * t - t * t + 0.5 * t * t * t;
        let df = |t: f64| 2.0 - 2.0 * t + 1.5 * t * t;
        let s = Shape {
            t: vec![0.0, 1.0, 3.0],
            y: vec![f(0.0), f(1.0), f(3.0)],
            dy: vec![df(0.0), df(1.0), df(3.0)],
        };
        for t in [0.2, 0.7, 1.5, 2.9] {
            assert!((s.at(t) - f(t)).abs() < 1e-12, "{t}");
        }
        assert_eq!(s.at(-1.0), f(0.0));
        assert_eq!(s.at(5.0), f(3.0));
        assert_eq!(s.next_node_after(1.0), Some(3.0));
        let mut hint = 0;
        for t in [0.2, 0.7, 1.5, 2.9, 0.1, 2.0, 1.0] {
            assert_eq!(s.at_hinted(t, &mut hint), s.at(t), "{t}");
        }
        assert!(s.close_shifted(&s.clone(), 0.0, 0.0, 0.0));
        let mut hint = 0;
        for t in [-1.0, 0.0, 0.5, 1.0, 2.0, 3.0, 4.0, 0.2, 1.0, -3.0, 2.5] {
            assert_eq!(
                s.next_node_after_hinted(t, &mut hint),
                s.next_node_after(t),
                "{t}"
            );
        }
        let mut shapes = Shapes::default();
        let id = shapes.add(1, Arc::new(s));
        let tr = Track {
            shape: id,
            offset: 10.0,
        };
        assert!((shapes.value(tr, 10.7) - f(0.7)).abs() < 1e-12);
        assert_eq!(shapes.value(Track::REST, 3.0), 0.0);
        assert_eq!(shapes.last_move(tr), Some(13.0));
    }

    #[test]
    fn every_sweeps_shapes_are_told_apart() {
        // (a sweep past the 15th once wrapped its id onto sweep 0's: Shapes::get panicked)
        let mut shapes = Shapes::default();
        let mut ids = Vec::new();
        for sweep in 1..=MAX_STORED_SWEEPS {
            for i in 0..3 {
                let y = (100 * sweep + i) as f64;
                let shape = Shape {
                    t: vec![0.0, 1.0],
                    y: vec![0.0, y],
                    dy: vec![0.0, 0.0],
                };
                ids.push((shapes.add(sweep, Arc::new(shape)), y));
            }
        }
        assert_eq!(shapes.len(), 1 + 3 * MAX_STORED_SWEEPS);
        for &(id, y) in &ids {
            assert_eq!(shapes.get(id).y[1], y, "{id:x}");
        }
        let distinct: std::collections::HashSet<u32> = ids.iter().map(|p| p.0).collect();
        assert_eq!(distinct.len(), ids.len());
        assert!(!distinct.contains(&REST));
    }
}
