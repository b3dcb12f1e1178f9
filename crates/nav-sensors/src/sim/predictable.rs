//! What of the unmodelled drift a model of the 50-Hz record can predict:
//! the least-squares estimate of its conditional expectation given the
//! vibration level and the interval-mean accelerations.
//!
//! Every channel's g- and g²-sensitive terms are, in the cluster frame, a
//! linear form `wᵀf` plus a quadratic form `fᵀCf` of the specific force f,
//! with w and C fixed by the channel's frame and true coefficients. So the
//! part of their unmodelled drift `Σ_k c_k·(mean(r_k) − r_k(x̄))` that comes
//! from the accelerations is, in every channel, the same combination of
//! nine **elementary** series of the record:
//!
//! ```text
//! e_i  = mean(f_i) − x̄_i                 (i = x, y, z)
//! Q_ij = mean(f_i·f_j) − x̄_i·x̄_j          (i ≤ j: xx, yy, zz, xy, xz, yz)
//! d    = Σ_i w_i·e_i + Σ_ij C_ij·Q_ij
//! ```
//!
//! (x̄ the interval means an error-free accelerometer of the same bandwidth
//! reports). Conditional expectation is linear, so `E[d | observed]` is the
//! same combination of the nine `E[· | observed]`: estimating those once
//! serves all six channels and all their terms (108 d_k series, six channel
//! sums) at the cost of nine fits — the cheapest exact route, and the one
//! whose features stay few.
//!
//! With v = f − g and u = x̄ − g the vibration parts (g the stationary
//! specific force), `Q_ij = g_i·e_j + g_j·e_i + V_ij` where
//! `V_ij = mean(v_i·v_j) − u_i·u_j` is a pure quadratic form of the
//! vibration (its within-interval covariance, plus the servo's share) and
//! `e_i` a pure linear one (the servo's lag). For a Gaussian vibration, the
//! conditional expectation of a linear form given linear observations is
//! linear in them, and that of a quadratic form is a constant plus a
//! quadratic form of them; with a level gain g it scales with g². So, by
//! least squares (Householder QR, [`super::lsq`]):
//!
//! - `e_i` on 1, g² and u_i[n+p] for lags p in −3..=3: 9 columns;
//! - `V_ii` on 1, g² and the 18 products u_i[n+p]·u_i[n+q], p ≤ q ≤ p + 2:
//!   20 columns;
//! - `V_ij` (i < j) on 1, g² and the 29 products u_i[n+p]·u_j[n+q],
//!   |p − q| ≤ 2: 31 columns;
//!
//! and `Q̂_ij = g_i·ê_j + g_j·ê_i + V̂_ij`. Products of other axes are left
//! out: they carry information only if the axes' motions are partially
//! correlated (independent drives carry none, fully correlated axes
//! duplicate the axes used).
//!
//! Why that set: on `triaxial_hidden` (3–20 Hz, where the neighbouring
//! samples reveal the within-interval motion) Y1's floor is 0.335 deg/h with
//! lags ±1 and all their products, 0.307 with ±2, 0.300 with ±3, 0.299 with
//! ±4 and |p − q| ≤ 3, and 0.302 with the set above — against 0.298 of
//! sensor noise, the limit; the other channels' floors agree within 0.001
//! from ±2 on. The band |p − q| ≤ 2 halves the cost of ±3 for a 0.7%
//! higher Y1 floor. On `paper_z_random` (20–2000 Hz, above the 25-Hz Nyquist
//! frequency) the features explain next to nothing: the floors move by
//! under 1%, most of it the in-sample bias below.
//!
//! The fit is in-sample: F columns over N samples lower the residual's
//! variance by about F/N of the *residual of the elementary series* (not of
//! the noise, which is not fitted) — 0.6% with 31 columns over 5000
//! samples, a few parts per thousand of a floor. Below
//! [`MIN_ROWS_PER_COLUMN`] rows per column of the largest basis (620 rows,
//! 12.4 s at 50 Hz) the features are not used and the level (1, g²) alone
//! is.

use super::lsq::fitted;

/// Lags −L..=L of the interval-mean accelerations used by the features.
pub(crate) const LAGS: usize = 3;

/// Largest lag difference |p − q| of a product feature.
pub(crate) const BAND: usize = 2;

/// Records shorter than this many rows per feature column (of the largest
/// basis) use the level-only basis: the in-sample fit would otherwise
/// explain a visible share of pure chance.
pub(crate) const MIN_ROWS_PER_COLUMN: usize = 20;

/// Pairs (i, j) of the six quadratic elementary series, in their order.
pub(crate) const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

/// One sample of the nine elementary series for specific force `f` (g):
/// f_x, f_y, f_z, then the products of [`PAIRS`]. The engine accumulates
/// these and [`weights`] acts on them, so both take the order from here.
pub(crate) fn elementary_moments(f: &nalgebra::Vector3<f64>) -> [f64; 9] {
    let mut out = [0.0; 9];
    out[..3].copy_from_slice(f.as_slice());
    for (o, &(i, j)) in out[3..].iter_mut().zip(&PAIRS) {
        *o = f[i] * f[j];
    }
    out
}

/// The nine elementary series (per sample: e_x, e_y, e_z, Q_xx, Q_yy, Q_zz,
/// Q_xy, Q_xz, Q_yz) and their least-squares predictions.
pub(crate) struct Elementary {
    /// The series themselves, `[k][n]`.
    pub actual: Vec<Vec<f64>>,
    /// Their estimated conditional expectation given the observed level
    /// and accelerations, `[k][n]`.
    pub predicted: Vec<Vec<f64>>,
}

/// A channel's g and g² terms as `wᵀf + fᵀCf` in the cluster frame, packed
/// to act on the elementary series: `d = Σ_k weights[k]·elementary[k]`.
pub(crate) fn weights(
    input: &nalgebra::Vector3<f64>,
    other: &nalgebra::Vector3<f64>,
    spin: &nalgebra::Vector3<f64>,
    c: &[f64; 18],
) -> [f64; 9] {
    use crate::dtg::DtgTerm as T;
    let u = [input, other, spin];
    let lin = [T::GI, T::GO, T::GS];
    // (term, a, b) with the regressor f_a·f_b.
    let quad = [
        (T::GgII, 0, 0),
        (T::GgOO, 1, 1),
        (T::GgSS, 2, 2),
        (T::GgIO, 0, 1),
        (T::GgIS, 0, 2),
        (T::GgOS, 1, 2),
    ];
    let mut w = [0.0; 9];
    for (a, t) in lin.iter().enumerate() {
        for i in 0..3 {
            w[i] += c[t.index()] * u[a][i];
        }
    }
    for &(t, a, b) in &quad {
        let ck = c[t.index()];
        // f_a·f_b = Σ_ij u_a,i·u_b,j·f_i·f_j; Q_ij with i < j stands for
        // both (i, j) and (j, i).
        for (k, &(i, j)) in PAIRS.iter().enumerate() {
            let m = if i == j {
                u[a][i] * u[b][i]
            } else {
                u[a][i] * u[b][j] + u[a][j] * u[b][i]
            };
            w[3 + k] += ck * m;
        }
    }
    w
}

/// Combines elementary series with a channel's weights.
pub(crate) fn combine(weights: &[f64; 9], series: &[Vec<f64>], n: usize) -> f64 {
    weights.iter().zip(series).map(|(w, s)| w * s[n]).sum()
}

/// Lagged copy: `out[n] = x[n + p]`, zero outside the record (the mean of
/// the vibration, which is what an unknown sample is expected to be).
fn lag(x: &[f64], p: isize) -> Vec<f64> {
    let n = x.len() as isize;
    (0..n)
        .map(|t| {
            let s = t + p;
            if (0..n).contains(&s) {
                x[s as usize]
            } else {
                0.0
            }
        })
        .collect()
}

/// What a fit's basis holds besides 1 and g².
#[derive(Clone, Copy)]
enum Features {
    /// The axis's samples at lags −L..=L.
    Linear,
    /// Products of two lagged samples at most [`BAND`] apart (one axis:
    /// p ≤ q; two axes: both orders).
    Quadratic,
}

/// The basis of one fit: 1, g² and the features of the axes involved.
fn basis(u: &[Vec<f64>; 3], g2: &[f64], axes: &[usize], features: Features) -> Vec<Vec<f64>> {
    let n = g2.len();
    let l = LAGS as isize;
    let lagged: Vec<Vec<Vec<f64>>> = axes
        .iter()
        .map(|&a| (-l..=l).map(|p| lag(&u[a], p)).collect())
        .collect();
    let mut cols = vec![vec![1.0; n], g2.to_vec()];
    let product = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).collect();
    match (features, lagged.as_slice()) {
        (Features::Linear, _) => {
            for per_axis in lagged {
                cols.extend(per_axis);
            }
        }
        (Features::Quadratic, [one]) => {
            for p in 0..one.len() {
                for q in p..=(p + BAND).min(one.len() - 1) {
                    cols.push(product(&one[p], &one[q]));
                }
            }
        }
        (Features::Quadratic, [first, second]) => {
            for (p, a) in first.iter().enumerate() {
                for (q, b) in second.iter().enumerate() {
                    if p.abs_diff(q) <= BAND {
                        cols.push(product(a, b));
                    }
                }
            }
        }
        _ => unreachable!("one or two axes"),
    }
    cols
}

/// Number of columns of the largest basis (a pair of axes): 1, g² and the
/// products within the band.
pub(crate) fn max_columns() -> usize {
    let w = 2 * LAGS + 1;
    let products = (0..w)
        .flat_map(|p| (0..w).map(move |q| (p, q)))
        .filter(|(p, q)| p.abs_diff(*q) <= BAND)
        .count();
    2 + products
}

/// The elementary series of a record and their predictions.
///
/// `moments[n]` are the interval's force moments (see
/// `HighRate::force_moments`), `xbar[n]` the error-free accelerometer's
/// interval means, `gravity[n]` the unit's specific force without the
/// vibration (g; constant at rest, the interval mean in motion), `g2[n]` the
/// squared level gain. With v = f − g and u = x̄ − g the vibration parts,
/// `Q_ij = g_i·e_j + g_j·e_i + V_ij` where `V_ij = mean(v_i·v_j) − u_i·u_j`
/// is a pure quadratic form of the vibration and `e_i` a pure linear one:
/// `e_i` is fitted on the lagged samples of axis i, `V_ij` on the lagged
/// products, and `Q̂_ij = g_i·ê_j + g_j·ê_i + V̂_ij`.
pub(crate) fn elementary(
    moments: &[[f64; 9]],
    xbar: &[[f64; 3]],
    gravity: &[[f64; 3]],
    g2: &[f64],
) -> Elementary {
    let n = g2.len();
    let g = gravity;
    let mut actual = vec![vec![0.0; n]; 9];
    for t in 0..n {
        let (m, x) = (&moments[t], &xbar[t]);
        for i in 0..3 {
            actual[i][t] = m[i] - x[i];
        }
        for (k, &(i, j)) in PAIRS.iter().enumerate() {
            actual[3 + k][t] = m[3 + k] - x[i] * x[j];
        }
    }
    let predicted = if uses_features(n) {
        let u: [Vec<f64>; 3] =
            std::array::from_fn(|i| xbar.iter().zip(g).map(|(x, g)| x[i] - g[i]).collect());
        let e_hat: Vec<Vec<f64>> = (0..3)
            .map(|i| {
                let (mut fit, _) = fitted(basis(&u, g2, &[i], Features::Linear), &[&actual[i]]);
                fit.pop().expect("one target")
            })
            .collect();
        let mut predicted = e_hat.clone();
        for (k, &(i, j)) in PAIRS.iter().enumerate() {
            let e = &actual;
            let v: Vec<f64> = (0..n)
                .map(|t| actual[3 + k][t] - g[t][i] * e[j][t] - g[t][j] * e[i][t])
                .collect();
            let axes: &[usize] = if i == j { &[i] } else { &[i, j] };
            let (mut fit, _) = fitted(basis(&u, g2, axes, Features::Quadratic), &[&v]);
            let v_hat = fit.pop().expect("one target");
            predicted.push(
                (0..n)
                    .map(|t| g[t][i] * e_hat[j][t] + g[t][j] * e_hat[i][t] + v_hat[t])
                    .collect(),
            );
        }
        predicted
    } else {
        let targets: Vec<&[f64]> = actual.iter().map(Vec::as_slice).collect();
        level_only(g2, &targets)
    };
    Elementary { actual, predicted }
}

/// Whether a record of `n` samples is long enough for the acceleration
/// features (else the level alone predicts).
pub(crate) fn uses_features(n: usize) -> bool {
    n >= MIN_ROWS_PER_COLUMN * max_columns()
}

/// Least-squares fit of each target on 1 and g² alone.
pub(crate) fn level_only(g2: &[f64], targets: &[&[f64]]) -> Vec<Vec<f64>> {
    fitted(vec![vec![1.0; g2.len()], g2.to_vec()], targets).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dtg::{DtgInput, DtgTerm};
    use crate::geometry::ChannelFrame;
    use nalgebra::Vector3;

    /// The g and g² regressors of every channel, summed with arbitrary
    /// coefficients, equal the packed linear and quadratic forms.
    #[test]
    fn weights_reproduce_every_channels_g_and_g2_terms() {
        let mut c = [0.0; 18];
        for (k, v) in c.iter_mut().enumerate() {
            *v = 0.1 * k as f64 - 0.7;
        }
        let accel_terms = DtgTerm::SPECIFIC_FORCE;
        for frame in ChannelFrame::all() {
            let w = weights(&frame.input, &frame.other, &frame.spin, &c);
            for f in [
                Vector3::new(0.3, -1.2, 2.5),
                Vector3::new(-4.0, 0.5, 1.0),
                Vector3::new(0.0, 0.0, 1.0),
            ] {
                let x = DtgInput {
                    specific_force_g: frame.resolve(&f),
                    ..DtgInput::default()
                };
                let direct: f64 = accel_terms
                    .iter()
                    .map(|t| c[t.index()] * t.regressor(&x))
                    .sum();
                let packed: f64 = w
                    .iter()
                    .zip(elementary_moments(&f))
                    .map(|(a, b)| a * b)
                    .sum();
                assert!(
                    (direct - packed).abs() < 1e-12,
                    "{:?}: {direct} vs {packed}",
                    frame.channel
                );
            }
        }
    }

    #[test]
    fn lags_pad_with_zero() {
        assert_eq!(lag(&[1.0, 2.0, 3.0], 1), [2.0, 3.0, 0.0]);
        assert_eq!(lag(&[1.0, 2.0, 3.0], -2), [0.0, 0.0, 1.0]);
    }

    #[test]
    fn basis_sizes_and_the_short_record_threshold() {
        let n = 1000;
        let u: [Vec<f64>; 3] =
            std::array::from_fn(|i| (0..n).map(|t| ((t * (i + 2)) as f64).sin()).collect());
        let g2 = vec![1.0; n];
        assert_eq!(basis(&u, &g2, &[1], Features::Linear).len(), 9);
        assert_eq!(basis(&u, &g2, &[0], Features::Quadratic).len(), 20);
        assert_eq!(basis(&u, &g2, &[0, 2], Features::Quadratic).len(), 31);
        assert_eq!(max_columns(), 31);
        assert!(!uses_features(619) && uses_features(620));
        // A short record is predicted by the level alone: constant here.
        let m = 100;
        let moments: Vec<[f64; 9]> = (0..m)
            .map(|t| {
                [
                    0.0,
                    0.0,
                    1.0,
                    0.0,
                    0.0,
                    1.0 + (t as f64).sin(),
                    0.0,
                    0.0,
                    0.0,
                ]
            })
            .collect();
        let e = elementary(
            &moments,
            &vec![[0.0, 0.0, 1.0]; m],
            &vec![[0.0, 0.0, 1.0]; m],
            &vec![1.0; m],
        );
        let mean = e.actual[5].iter().sum::<f64>() / m as f64;
        assert!(e.predicted[5].iter().all(|p| (p - mean).abs() < 1e-12));
    }
}
