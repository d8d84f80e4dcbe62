//! Banded matrices for the stiff integrator: a Jacobian estimated by finite differences with
//! column grouping (Curtis, Powell and Reid: columns `2 bw + 1` apart touch disjoint rows,
//! so `2 bw + 1` right-hand sides give all of it), and an LU factorisation with partial
//! pivoting that keeps the band (LINPACK `gbfa`/`gbsl`: the upper band grows by the lower
//! bandwidth). Work and memory are linear in the number of unknowns at a fixed bandwidth, so
//! the sparsity pattern is given, never probed.

/// A square band matrix with `lower` sub- and `upper` super-diagonals (storage keeps room
/// for `lower` more above, the pivoting fill-in).
#[derive(Clone, Debug)]
pub(crate) struct Band {
    n: usize,
    lower: usize,
    upper: usize,
    width: usize,
    data: Vec<f64>,
    pivots: Vec<usize>,
}

/// A zero pivot: the matrix is singular (the caller shrinks the step).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("singular band matrix: zero pivot in column {column}")]
pub(crate) struct Singular {
    /// The column.
    pub(crate) column: usize,
}

impl Band {
    /// A zero `n x n` band matrix.
    pub(crate) fn zeros(n: usize, lower: usize, upper: usize) -> Band {
        let width = 2 * lower + upper + 1;
        Band {
            n,
            lower,
            upper,
            width,
            data: vec![0.0; n * width],
            pivots: vec![0; n],
        }
    }

    /// Whether `(i, j)` lies in the stored band (including fill-in room).
    fn slot(&self, i: usize, j: usize) -> Option<usize> {
        if j + self.lower < i || j > i + self.upper + self.lower || i >= self.n || j >= self.n {
            return None;
        }
        Some(i * self.width + (j + self.lower - i))
    }

    /// Entry `(i, j)` (zero outside the band).
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        self.slot(i, j).map_or(0.0, |s| self.data[s])
    }

    /// Sets entry `(i, j)` inside the original band (`j - upper <= i <= j + lower`).
    pub(crate) fn set(&mut self, i: usize, j: usize, v: f64) {
        if j > i + self.upper {
            return;
        }
        if let Some(s) = self.slot(i, j) {
            self.data[s] = v;
        }
    }

    /// Sets every entry to zero.
    pub(crate) fn clear(&mut self) {
        self.data.iter_mut().for_each(|x| *x = 0.0);
    }

    /// Factorises in place (partial pivoting).
    pub(crate) fn factor(&mut self) -> Result<(), Singular> {
        let n = self.n;
        let fill = self.upper + self.lower;
        for k in 0..n {
            let last = (k + self.lower).min(n - 1);
            let mut p = k;
            let mut best = self.get(k, k).abs();
            for i in k + 1..=last {
                let v = self.get(i, k).abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            self.pivots[k] = p;
            if best == 0.0 || !best.is_finite() {
                return Err(Singular { column: k });
            }
            let jmax = (k + fill).min(n - 1);
            if p != k {
                for j in k..=jmax {
                    let (a, b) = (self.get(k, j), self.get(p, j));
                    self.put(k, j, b);
                    self.put(p, j, a);
                }
            }
            let pivot = self.get(k, k);
            for i in k + 1..=last {
                let l = self.get(i, k) / pivot;
                self.put(i, k, l);
                if l != 0.0 {
                    for j in k + 1..=jmax {
                        let v = self.get(i, j) - l * self.get(k, j);
                        self.put(i, j, v);
                    }
                }
            }
        }
        Ok(())
    }

    fn put(&mut self, i: usize, j: usize, v: f64) {
        if let Some(s) = self.slot(i, j) {
            self.data[s] = v;
        }
    }

    /// Solves `A x = b` in place after [`Band::factor`].
    pub(crate) fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        let fill = self.upper + self.lower;
        for k in 0..n {
            let p = self.pivots[k];
            if p != k {
                b.swap(k, p);
            }
            let last = (k + self.lower).min(n - 1);
            for i in k + 1..=last {
                b[i] -= self.get(i, k) * b[k];
            }
        }
        for k in (0..n).rev() {
            let jmax = (k + fill).min(n - 1);
            let mut s = b[k];
            for (j, bj) in b.iter().enumerate().take(jmax + 1).skip(k + 1) {
                s -= self.get(k, j) * bj;
            }
            b[k] = s / self.get(k, k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[allow(clippy::needless_range_loop)] // matrix indices read clearer here
    fn solves_a_band_system_that_needs_pivoting() {
        // tridiagonal plus a wider lower band, with small diagonal entries
        let n = 40;
        let (kl, ku) = (2, 1);
        let mut a = Band::zeros(n, kl, ku);
        let mut dense = vec![vec![0.0; n]; n];
        let mut seed = 12345u64;
        for i in 0..n {
            for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                let v = next(&mut seed);
                let v = if i == j { 1e-3 * v } else { v };
                a.set(i, j, v);
                dense[i][j] = v;
            }
        }
        let x: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| dense[i][j] * x[j]).sum())
            .collect();
        match a.factor() {
            Ok(()) => {}
            Err(e) => panic!("{e}"),
        }
        a.solve(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-9, "{i}: {} {}", b[i], x[i]);
        }
    }

    /// A pseudo-random number in [-0.5, 0.5) (a linear congruential generator).
    fn next(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    /// Solves `a x = b` densely: Gaussian elimination with partial pivoting.
    #[allow(clippy::needless_range_loop)] // matrix indices read clearer here
    fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
        let n = b.len();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
                .unwrap();
            a.swap(k, p);
            b.swap(k, p);
            for i in k + 1..n {
                let l = a[i][k] / a[k][k];
                for j in k..n {
                    a[i][j] -= l * a[k][j];
                }
                b[i] -= l * b[k];
            }
        }
        let mut x = vec![0.0; n];
        for k in (0..n).rev() {
            let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
            x[k] = (b[k] - s) / a[k][k];
        }
        x
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // matrix indices read clearer here
    fn agrees_with_a_dense_solve_on_random_band_matrices() {
        let mut seed = 2024u64;
        for (n, kl, ku) in [
            (1, 0, 0),
            (5, 1, 1),
            (12, 2, 3),
            (30, 3, 1),
            (40, 4, 4),
            (7, 6, 6),
        ] {
            for _ in 0..20 {
                let mut a = Band::zeros(n, kl, ku);
                let mut dense = vec![vec![0.0; n]; n];
                for i in 0..n {
                    for j in i.saturating_sub(kl)..=(i + ku).min(n - 1) {
                        // small diagonals now and then, so pivoting is needed
                        let v = next(&mut seed)
                            * if i == j && next(&mut seed) > 0.0 {
                                1e-3
                            } else {
                                1.0
                            };
                        a.set(i, j, v);
                        dense[i][j] = v;
                    }
                }
                let b: Vec<f64> = (0..n).map(|_| next(&mut seed)).collect();
                let want = dense_solve(dense, b.clone());
                let mut x = b;
                a.factor().unwrap();
                a.solve(&mut x);
                let scale = want.iter().fold(1.0f64, |m, v| m.max(v.abs()));
                for (i, (p, q)) in x.iter().zip(&want).enumerate() {
                    assert!(
                        (p - q).abs() < 1e-9 * scale,
                        "n {n} kl {kl} ku {ku} x[{i}]: {p} {q}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_zero_column_is_singular() {
        let mut a = Band::zeros(4, 1, 1);
        for i in 0..4 {
            a.set(i, i, 1.0);
        }
        for i in 1..3 {
            a.set(i, 2, 0.0);
        }
        a.set(2, 2, 0.0);
        a.set(3, 2, 0.0);
        assert_eq!(a.factor(), Err(Singular { column: 2 }));
    }
}
