//! How long the relative motion of two blocks of a timed schedule stays as it is: the next
//! breakpoint of any track inside the run of tiles they span.
//!
//! The schedule check ([`super::advancement`]) walks the segments between every track's
//! breakpoints, but two blocks move relative to each other only by the joints between them:
//! while no joint inside their span reaches a breakpoint (a knot, a start, an end or a pass
//! through straight, where its hinge changes side), every moving joint there keeps its rate
//! and every other stands still, so the pair can be advanced past the segment's end, up to
//! that breakpoint, and skipped in the segments until then. A long chain folding at many
//! places at once has many segments, and a pair of rows lying face to face at a U-turn then
//! costs what its own two joints' breakpoints cost, not every track's.
//!
//! The next breakpoint of each joint's track is kept in a tree of minima over the joints, so
//! a span's next breakpoint costs O(log n) and a track passing one of its breakpoints updates
//! one path.

use super::JointTrack;

/// The next breakpoint after the walk's current time of every joint, and its range minima.
pub(super) struct Windows {
    /// Each track's breakpoints (its times and its passes through straight), sorted.
    breakpoints: Vec<Vec<f64>>,
    /// Each track's first breakpoint after the current time.
    cursor: Vec<usize>,
    /// Leaves (a power of two) of the minimum tree; joint `k` is node `leaves + k`.
    leaves: usize,
    min: Vec<f64>,
}

impl Windows {
    /// The breakpoints of `tracks` on a chain of `joints` joints, before the first one.
    pub fn new(tracks: &[JointTrack], joints: usize) -> Windows {
        let leaves = joints.max(1).next_power_of_two();
        let mut w = Windows {
            breakpoints: tracks.iter().map(track_breakpoints).collect(),
            cursor: vec![0; tracks.len()],
            leaves,
            min: vec![f64::INFINITY; 2 * leaves],
        };
        for (i, tr) in tracks.iter().enumerate() {
            let first = w.breakpoints[i].first().copied().unwrap_or(f64::INFINITY);
            w.set(tr.joint, first);
        }
        w
    }

    fn set(&mut self, joint: usize, value: f64) {
        let mut p = self.leaves + joint;
        if p >= self.min.len() {
            return;
        }
        self.min[p] = value;
        while p > 1 {
            p /= 2;
            self.min[p] = self.min[2 * p].min(self.min[2 * p + 1]);
        }
    }

    /// Moves track `i` (of `tracks`) past every breakpoint at or before `t`.
    pub fn pass(&mut self, tracks: &[JointTrack], i: usize, t: f64) {
        let bps = &self.breakpoints[i];
        let mut c = self.cursor[i];
        if c >= bps.len() || bps[c] > t {
            return;
        }
        while c < bps.len() && bps[c] <= t {
            c += 1;
        }
        self.cursor[i] = c;
        let next = bps.get(c).copied().unwrap_or(f64::INFINITY);
        self.set(tracks[i].joint, next);
    }

    /// The earliest next breakpoint of the joints `lo..hi` (after the time every track inside
    /// has been passed to); infinity for an empty range or no breakpoint left.
    pub fn until(&self, lo: usize, hi: usize) -> f64 {
        let (mut l, mut r) = (
            lo.min(self.leaves) + self.leaves,
            hi.min(self.leaves) + self.leaves,
        );
        let mut m = f64::INFINITY;
        while l < r {
            if l & 1 == 1 {
                m = m.min(self.min[l]);
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                m = m.min(self.min[r]);
            }
            l /= 2;
            r /= 2;
        }
        m
    }
}

/// A track's breakpoints: its times and the moments it passes through straight, sorted.
pub(super) fn track_breakpoints(tr: &JointTrack) -> Vec<f64> {
    let mut out = tr.times.clone();
    for i in 1..tr.times.len() {
        let (a0, a1) = (tr.angles[i - 1], tr.angles[i]);
        if a0 * a1 < 0.0 {
            let (t0, t1) = (tr.times[i - 1], tr.times[i]);
            out.push(t0 + (t1 - t0) * a0 / (a0 - a1));
        }
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_breakpoint_of_a_span() {
        let tracks = vec![
            JointTrack {
                joint: 2,
                times: vec![1.0, 2.0, 4.0],
                angles: vec![0.0, 0.5, 1.0],
                ended: None,
            },
            JointTrack {
                joint: 7,
                times: vec![0.0, 3.0],
                angles: vec![0.2, -0.4], // straight at t = 1
                ended: None,
            },
        ];
        let mut w = Windows::new(&tracks, 10);
        assert_eq!(w.until(0, 10), 0.0);
        assert_eq!(w.until(0, 7), 1.0);
        assert_eq!(w.until(3, 7), f64::INFINITY);
        w.pass(&tracks, 1, 0.0);
        assert_eq!(w.until(7, 8), 1.0);
        w.pass(&tracks, 0, 1.0);
        w.pass(&tracks, 1, 1.0);
        assert_eq!(w.until(0, 10), 2.0);
        assert_eq!(w.until(5, 10), 3.0);
        w.pass(&tracks, 0, 3.5);
        w.pass(&tracks, 1, 3.5);
        assert_eq!(w.until(0, 10), 4.0);
        w.pass(&tracks, 0, 4.0);
        assert_eq!(w.until(0, 10), f64::INFINITY);
    }
}
