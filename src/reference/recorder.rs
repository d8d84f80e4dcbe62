//! The states a reference run keeps for pictures ([`Recording::Grid`]): on an evenly spaced
//! time grid, each interpolated inside the integrator step that holds it (cubic Hermite on
//! the step's end values and rates; for a step cut short at an event, quadratic on the start
//! rate), clamped to `[0, 1]`. When the states would exceed the budget, the spacing doubles
//! and every other state is dropped, so the grid stays even and the memory bounded.

use crate::reference::options::Recording;

/// The states of [`Recording::Grid`]: grid index `i` is time `i * dt`.
pub(crate) struct Recorder {
    /// Grid states kept at most (one place is left for the final state).
    max: usize,
    dt: f64,
    /// Grid index of the next state to record.
    next: u64,
    index: Vec<u64>,
    states: Vec<(f64, Vec<f64>)>,
}

impl Recorder {
    /// At most `max_states` states (the final one included), spaced `dt` to begin with,
    /// the first `y0` at time 0.
    pub(crate) fn new(max_states: usize, dt: f64, y0: &[f64]) -> Recorder {
        Recorder {
            max: max_states.max(3) - 1,
            dt,
            next: 1,
            index: vec![0],
            states: vec![(0.0, y0.to_vec())],
        }
    }

    /// The recorder `record` asks for (none for [`Recording::Off`]), spaced `dt` to begin
    /// with, the first state `y0` at time 0.
    pub(crate) fn of(record: Recording, dt: f64, y0: &[f64]) -> Option<Recorder> {
        match record {
            Recording::Off => None,
            Recording::Grid { max_states } => Some(Recorder::new(max_states, dt, y0)),
        }
    }

    /// The time of the next state to record.
    pub(crate) fn next_time(&self) -> f64 {
        self.next as f64 * self.dt
    }

    /// Doubles the spacing, keeping the states on the coarser grid (index 0 always stays).
    fn thin(&mut self) {
        let mut keep = self.index.iter().map(|i| i % 2 == 0);
        self.states.retain(|_| keep.next().unwrap_or(false));
        self.index.retain(|i| i % 2 == 0);
        for i in &mut self.index {
            *i /= 2;
        }
        self.dt *= 2.0;
        self.next = self.next.div_ceil(2);
    }

    /// Records the grid times in `(t0, t1]` of a step from `(t0, y0)`, rates `f0`, to
    /// `(t1, y1)`, rates `f1` if known: cubic Hermite, or quadratic on `f0` without `f1`.
    pub(crate) fn cover(
        &mut self,
        t0: f64,
        y0: &[f64],
        f0: &[f64],
        t1: f64,
        y1: &[f64],
        f1: Option<&[f64]>,
    ) {
        let h = t1 - t0;
        if h.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return;
        }
        loop {
            let t = self.next_time();
            if t > t1 {
                break;
            }
            if self.states.len() >= self.max {
                self.thin();
                continue;
            }
            let s = ((t - t0) / h).clamp(0.0, 1.0);
            let (s2, s3) = (s * s, s * s * s);
            let y: Vec<f64> = (0..y0.len())
                .map(|i| {
                    let v = match f1 {
                        Some(f1) => {
                            y0[i] * (2.0 * s3 - 3.0 * s2 + 1.0)
                                + h * f0[i] * (s3 - 2.0 * s2 + s)
                                + y1[i] * (3.0 * s2 - 2.0 * s3)
                                + h * f1[i] * (s3 - s2)
                        }
                        None => y0[i] + f0[i] * h * s + (y1[i] - y0[i] - f0[i] * h) * s2,
                    };
                    v.clamp(0.0, 1.0)
                })
                .collect();
            self.states.push((t, y));
            self.index.push(self.next);
            self.next += 1;
        }
    }

    /// The recorded states with the final one `(t, y)` last.
    pub(crate) fn finish(mut self, t: f64, y: &[f64]) -> Vec<(f64, Vec<f64>)> {
        if self.states.last().is_some_and(|(last, _)| *last >= t) {
            self.states.pop();
        }
        self.states.push((t, y.to_vec()));
        self.states
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_stays_even_bounded_and_exact_on_a_line() {
        // y = t / 20 stepped in 0.37 s steps to 10 s: Hermite is exact on a line
        let mut r = Recorder::new(6, 0.5, &[0.0]);
        let mut t = 0.0;
        while t < 10.0 {
            let t1 = t + 0.37;
            r.cover(t, &[t / 20.0], &[0.05], t1, &[t1 / 20.0], Some(&[0.05]));
            t = t1;
        }
        let states = r.finish(t, &[t / 20.0]);
        assert!(states.len() <= 6 && states.len() >= 3, "{}", states.len());
        let dt = states[1].0;
        // 0.5 doubled until five grid states cover 10 s
        assert_eq!(dt, 4.0);
        for (i, (ti, y)) in states[..states.len() - 1].iter().enumerate() {
            assert_eq!(*ti, i as f64 * dt);
            assert!((y[0] - ti / 20.0).abs() < 1e-12, "{ti}: {}", y[0]);
        }
        assert_eq!(states.last().unwrap().0, t);
    }
}
