//! Dormand-Prince 5(4) (Dormand and Prince 1980; Hairer, Norsett and Wanner, *Solving ODEs
//! I*, II.5 and `dopri5.f`): the tableau, and the six stages of one step, written once for
//! the reference's whole-chain states and the event engine's small unit states alike
//! ([`stages`]). Seven stages, first same as last; the embedded fourth-order solution gives
//! the error ([`E`]); the free continuous extension of order 4 ([`D`]) gives the dense output
//! ([`crate::ode::Dense`]). Its stability region bounds the step by about `3.3 / |lambda|`
//! whatever the tolerance, so it pays for stiffness in steps.

/// The stage coefficients `a_ij`, row by row (row 6 is the fifth-order solution's weights
/// `b`: the method is first same as last).
pub(crate) const A: [[f64; 6]; 6] = [
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// The error weights: `b - b*` (fifth-order less fourth-order weights), stage by stage.
pub(crate) const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// The stage times `c_2..c_7` (fractions of the step).
pub(crate) const C: [f64; 6] = [1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];

/// Dormand-Prince's dense-output weights of stages 1, 3, 4, 5, 6 and 7 (stage 2 has none).
pub(crate) const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The six stages of one step of `h` from `y0` with `k[0] = f(y0)` given: `k[1..=6]`, and
/// the fifth-order solution into `y` (the state of the last stage). `f(c, y, out)` evaluates
/// the rates at state `y`, `c` the stage's time as a fraction of the step. `stage6`, when
/// given, receives the sixth stage's state (the second-last, which Hairer's stiffness test
/// compares with the last). Every component is computed as `y0 + h * sum_j a_ij k_j`, the
/// same operations in the same order whatever holds the vectors.
pub(crate) fn stages<K: AsRef<[f64]> + AsMut<[f64]>>(
    y0: &[f64],
    h: f64,
    k: &mut [K; 7],
    y: &mut [f64],
    mut stage6: Option<&mut [f64]>,
    mut f: impl FnMut(f64, &[f64], &mut [f64]),
) {
    let n = y0.len();
    for (s, row) in A.iter().enumerate() {
        {
            let (done, _) = k.split_at(s + 1);
            for i in 0..n {
                let mut acc = 0.0;
                for (j, a) in row.iter().enumerate().take(s + 1) {
                    acc += a * done[j].as_ref()[i];
                }
                y[i] = y0[i] + h * acc;
            }
        }
        if s == 4 {
            if let Some(out) = stage6.as_deref_mut() {
                out.copy_from_slice(&y[..n]);
            }
        }
        f(C[s], &y[..n], &mut k[s + 1].as_mut()[..n]);
    }
}

/// Component `i`'s error rate `sum_j e_j k_j[i]` (times `h`, the local error estimate).
pub(crate) fn error_rate<K: AsRef<[f64]>>(k: &[K; 7], i: usize) -> f64 {
    let mut e = 0.0;
    for (j, c) in E.iter().enumerate() {
        e += c * k[j].as_ref()[i];
    }
    e
}
