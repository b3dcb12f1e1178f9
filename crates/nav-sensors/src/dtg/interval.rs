//! What a product of interval means misses.
//!
//! A DTG's 50-Hz output is the mean of its drift over each 20-ms interval, and
//! an anisoelastic drift `D·f_I·f_S` then holds the interval mean of the
//! product, `mean(f_I)·mean(f_S) + cov(f_I, f_S)`. Ground-calibration
//! compensation and effect regressors see only the accelerometers' interval
//! means, so without the covariance they leave `D·cov` behind — the
//! rectification of vibration that moves within an interval.
//!
//! The covariance is estimated from the seven means around the interval,
//! n − 3 … n + 3, by a band-limited reconstruction of the signal within it:
//! `f(τ) = Σⱼ hⱼ(τ)·m[n+j]`, τ ∈ [0, 1] across interval n, with `h(τ)` the
//! minimum-mean-square-error estimate of `f(τ)` from the seven means for a
//! signal of flat spectrum up to 0.4 cycles per interval (20 Hz at 50 Hz,
//! 0.8 × the output's Nyquist), constrained to be exact for constants and
//! linear trends. Its integral is then exactly the own mean's selector (the
//! estimate of an interval's mean from the means is that mean), so
//! `mean(f_a·f_b) = Σⱼₖ Mⱼₖ·m_a[n+j]·m_b[n+k]` with `M = ∫₀¹ h·hᵀ dτ`, and
//! the covariance is `Σⱼₖ Wⱼₖ·m_a[n+j]·m_b[n+k]`, `W = M − e₀e₀ᵀ`: the
//! spread of `h(τ)` about `e₀`, positive semi-definite, zero on constants.
//! `W` is stored as its four leading factors ([`WITHIN_INTERVAL_FACTORS`],
//! `W ≈ FᵀF`), so a covariance is four outer products, `Σᵣ eᵣeᵣᵀ` with
//! `eᵣ = Σⱼ Fᵣⱼ·m[n+j]`; the onboard compensator (`dtg-onboard`) takes the
//! same factors. Being the minimum-mean-square-error estimate, its error is
//! uncorrelated with it: a drift regressed on it has slope 1 for vibration
//! spread over 0–20 Hz, where a quadratic through three means gave 1.09.
//! For one sinusoid its phase-averaged estimate is 0.77–1.19 × the truth
//! between 0.01 and 0.38 cycles per interval (0.5–19 Hz at 50 Hz). For
//! vibration far above the output rate the means are aliased and the
//! estimate is small (a few percent of the truth at 0.7 cycles per
//! interval and above), never harmful by construction.

use nalgebra::{Matrix3, Vector3};

use super::input::DtgInput;
use crate::geometry::{ChannelFrame, DtgAxes};

/// Means on each side of an interval that its covariance reads: the
/// estimate at interval n needs means n − 3 … n + 3 (so an onboard
/// compensator outputs a sample 3 periods late, 60 ms at 50 Hz).
pub const WITHIN_INTERVAL_REACH: usize = dtg_onboard::LOOKAHEAD;

/// The four leading factors `F` of the within-interval covariance's
/// weights `W` (see the module's documentation), `W ≈ FᵀF`, over the seven
/// means n − 3 … n + 3.
///
/// Derived (the test `the_factors_are_their_derivation` repeats it) by
/// Gauss–Legendre quadrature: the means' covariances `Rⱼₖ = ∫ sinc²(ν)
/// cos(2πν(j − k)) dν` and `rⱼ(τ) = ∫ sinc(ν) cos(2πν(j + ½ − τ)) dν` over
/// |ν| ≤ 0.4 cycles per interval (400 nodes), `h(τ)` the minimiser of
/// `E[(f(τ) − hᵀm)²]` subject to `Σⱼ hⱼ = 1` and `Σⱼ j·hⱼ = τ − ½`
/// (constants and linear trends exact), `M = ∫₀¹ h hᵀ dτ` (40 nodes),
/// `W = M − e₀e₀ᵀ`; then its eigenvectors, scaled by the root of their
/// eigenvalues (0.189, 0.0307, 6.9·10⁻⁵, 1.5·10⁻⁶), made exactly
/// (anti)symmetric in time, the symmetric ones' middle weight set so that
/// each row sums to zero (a constant has no covariance). The three smaller
/// eigenvalues (below 4·10⁻¹⁰) are left out, and the first row is scaled
/// by 1 + 5.3·10⁻⁸ so that the four factors keep a linear trend's variance
/// (slope²/12) exact: `FᵀF` is within 10⁻⁸ of `W`.
///
/// The numbers are `dtg_onboard`'s (no_std), which the onboard compensator
/// and the exported C read: one table for the desktop and onboard.
pub const WITHIN_INTERVAL_FACTORS: [[f64; 2 * WITHIN_INTERVAL_REACH + 1]; 4] =
    dtg_onboard::WITHIN_INTERVAL_FACTORS;

/// The factors `eᵣ = Σⱼ Fᵣⱼ·m[n+j]` of one interval's within-interval
/// covariance (`C = Σᵣ eᵣeᵣᵀ`) from the seven means around it (`window`:
/// n − 3 … n + 3), each a sum in the order of `j`: the onboard compensator
/// forms the same sums in the same order.
pub fn within_interval_factors(window: &[Vector3<f64>]) -> [Vector3<f64>; 4] {
    WITHIN_INTERVAL_FACTORS.map(|row| {
        row.iter()
            .zip(window)
            .fold(Vector3::zeros(), |e, (w, m)| e + *w * m)
    })
}

/// Within-interval covariance of a vector signal (cluster frame, g²) at
/// every interval, from the interval means by the band-limited
/// reconstruction of the module's documentation; zero at the first and
/// last [`WITHIN_INTERVAL_REACH`] intervals of `means` (a record or a
/// segment), which lack the neighbours it reads.
///
/// Exact for a linear trend, whose within-interval variance is slope²/12:
///
/// ```
/// use nalgebra::Vector3;
/// // f(t) = (t, 0, 2t) as means over unit intervals: n + ½.
/// let m: Vec<Vector3<f64>> = (0..9).map(|n| Vector3::new(n as f64 + 0.5, 0.0, 2.0 * n as f64 + 1.0)).collect();
/// let c = nav_sensors::dtg::within_interval_covariance(&m);
/// assert!((c[4][(0, 0)] - 1.0 / 12.0).abs() < 1e-12);
/// assert!((c[4][(0, 2)] - 2.0 / 12.0).abs() < 1e-12);
/// assert_eq!(c[4][(1, 1)], 0.0);
/// // The first and last three intervals lack neighbours: zero.
/// assert_eq!(c[2], nalgebra::Matrix3::zeros());
/// assert_eq!(c[6], nalgebra::Matrix3::zeros());
/// ```
pub fn within_interval_covariance(means: &[Vector3<f64>]) -> Vec<Matrix3<f64>> {
    let (n, reach) = (means.len(), WITHIN_INTERVAL_REACH);
    (0..n)
        .map(|i| {
            if i < reach || i + reach >= n {
                return Matrix3::zeros();
            }
            within_interval_factors(&means[i - reach..=i + reach])
                .iter()
                .fold(Matrix3::zeros(), |c, e| c + e * e.transpose())
        })
        .collect()
}

impl DtgInput {
    /// Sets the within-interval covariance of the specific force, resolving a
    /// cluster-frame covariance (g²) into the channel's frame.
    ///
    /// ```
    /// use nav_sensors::dtg::{DtgInput, DtgTerm};
    /// use nav_sensors::geometry::{Channel, ChannelFrame};
    /// let frame = ChannelFrame::of(Channel::Z);
    /// let cov = nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 0.0, 0.5));
    /// let x = DtgInput::resolved(&frame, &nalgebra::Vector3::zeros(), &nalgebra::Vector3::new(0.0, 0.0, 2.0))
    ///     .with_covariance(&frame, &cov);
    /// // Channel Z's input axis is cluster z: f_I² holds 2² plus the covariance.
    /// assert_eq!(DtgTerm::GgII.regressor(&x), 4.5);
    /// ```
    pub fn with_covariance(mut self, frame: &ChannelFrame, cov: &Matrix3<f64>) -> Self {
        self.specific_force_cov_g2 = resolve_covariance(&frame.axes(), cov);
        self
    }
}

/// A unit-frame covariance of the specific force (g²) resolved into a DTG
/// channel's axes: (II, OO, SS, IO, IS, OS), the order of
/// [`DtgInput::specific_force_cov_g2`].
///
/// ```
/// use nav_sensors::geometry::{Channel, ChannelFrame};
/// let cov = nalgebra::Matrix3::from_diagonal(&nalgebra::Vector3::new(0.0, 0.0, 0.5));
/// let c = nav_sensors::dtg::resolve_covariance(&ChannelFrame::of(Channel::Z).axes(), &cov);
/// assert_eq!(c[0], 0.5);
/// ```
pub fn resolve_covariance(axes: &DtgAxes, cov: &Matrix3<f64>) -> [f64; 6] {
    let (i, o, s) = (axes.input, axes.output, axes.spin);
    let q = |a: &Vector3<f64>, b: &Vector3<f64>| (a.transpose() * cov * b)[(0, 0)];
    [
        q(&i, &i),
        q(&o, &o),
        q(&s, &s),
        q(&i, &o),
        q(&i, &s),
        q(&o, &s),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use std::f64::consts::PI;

    /// Gauss–Legendre nodes and weights on [a, b] (Newton on Pₙ from
    /// Chebyshev's guesses).
    fn gauss_legendre(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
        (0..n)
            .map(|i| {
                let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                let mut dp = 0.0;
                for _ in 0..100 {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 2..=n {
                        let k = k as f64;
                        (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                    }
                    dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    let step = p1 / dp;
                    x -= step;
                    if step.abs() < 1e-16 {
                        break;
                    }
                }
                let w = 2.0 / ((1.0 - x * x) * dp * dp);
                ((a + b) / 2.0 + (b - a) / 2.0 * x, (b - a) / 2.0 * w)
            })
            .collect()
    }

    fn sinc(x: f64) -> f64 {
        if x == 0.0 {
            1.0
        } else {
            (PI * x).sin() / (PI * x)
        }
    }

    /// `W` by the derivation [`WITHIN_INTERVAL_FACTORS`] states.
    fn derived_weights() -> DMatrix<f64> {
        let band = gauss_legendre(400, 0.0, 0.4);
        let j = |k: usize| k as f64 - 3.0;
        // Both integrands are even in ν: twice the integral over [0, 0.4].
        let integral =
            |g: &dyn Fn(f64) -> f64| band.iter().map(|&(v, w)| 2.0 * w * g(v)).sum::<f64>();
        let mut kkt = DMatrix::zeros(9, 9);
        for a in 0..7 {
            for b in 0..7 {
                kkt[(a, b)] = integral(&|v| sinc(v).powi(2) * (2.0 * PI * v * (j(a) - j(b))).cos());
            }
            (kkt[(a, 7)], kkt[(7, a)]) = (1.0, 1.0);
            (kkt[(a, 8)], kkt[(8, a)]) = (j(a), j(a));
        }
        let qr = kkt.qr();
        let mut m = DMatrix::zeros(7, 7);
        for (tau, wt) in gauss_legendre(40, 0.0, 1.0) {
            let mut rhs = DVector::zeros(9);
            for a in 0..7 {
                rhs[a] = integral(&|v| sinc(v) * (2.0 * PI * v * (j(a) + 0.5 - tau)).cos());
            }
            (rhs[7], rhs[8]) = (1.0, tau - 0.5);
            let h = qr.solve(&rhs).unwrap().rows(0, 7).into_owned();
            m += wt * &h * h.transpose();
        }
        m[(3, 3)] -= 1.0;
        m
    }

    #[test]
    fn the_factors_are_their_derivation() {
        let w = derived_weights();
        let f = DMatrix::from_fn(4, 7, |r, c| WITHIN_INTERVAL_FACTORS[r][c]);
        let diff = (f.transpose() * &f - &w).abs().max();
        assert!(diff < 1e-8, "FᵀF is {diff} from W");
        // A linear trend's variance, 1/12 for a unit slope, exact.
        let slope: f64 = WITHIN_INTERVAL_FACTORS
            .iter()
            .map(|row| {
                (0..7)
                    .map(|j| row[j] * (j as f64 - 3.0))
                    .sum::<f64>()
                    .powi(2)
            })
            .sum();
        assert!((slope - 1.0 / 12.0).abs() < 1e-16, "{slope}");
        // W itself: the spread of h(τ) about e₀, zero on constants.
        assert!((&w * DVector::from_element(7, 1.0)).abs().max() < 1e-12);
        for row in WITHIN_INTERVAL_FACTORS {
            assert!(row.iter().sum::<f64>().abs() < 1e-16, "{row:?}");
        }
    }

    /// Interval means and true within-interval variances of `f` over
    /// `intervals` unit intervals, from 200 midpoint samples each.
    fn means_and_truth(f: &dyn Fn(f64) -> f64, intervals: usize) -> (Vec<Vector3<f64>>, Vec<f64>) {
        let fine = 200;
        (0..intervals)
            .map(|n| {
                let v: Vec<f64> = (0..fine)
                    .map(|k| f(n as f64 + (k as f64 + 0.5) / fine as f64))
                    .collect();
                let m = v.iter().sum::<f64>() / fine as f64;
                let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / fine as f64;
                (Vector3::new(m, 0.0, 0.0), var)
            })
            .unzip()
    }

    /// One sinusoid, averaged over its phase: the estimate is 0.77–1.19 ×
    /// the truth from 0.01 to 0.38 cycles per interval (as the module
    /// states; measured 0.777 at 0.14–0.15, 1.184 at 0.30, 0.814 at 0.38),
    /// and under 7 % of it at 0.7 cycles per interval and above (aliased).
    #[test]
    fn a_sinusoid_within_the_band_and_above() {
        for (cycles, low, high) in [
            (0.01, 0.77, 1.19),
            (0.05, 0.77, 1.19),
            (0.1, 0.77, 1.19),
            (0.145, 0.77, 1.19),
            (0.2, 0.77, 1.19),
            (0.3, 0.77, 1.19),
            (0.35, 0.77, 1.19),
            (0.38, 0.77, 1.19),
            (0.7, 0.0, 0.07),
            (1.3, 0.0, 0.07),
            (7.3, 0.0, 0.07),
        ] {
            let (mut est, mut truth) = (0.0, 0.0);
            for p in 0..24 {
                let phase = 2.0 * PI * p as f64 / 24.0;
                let (m, t) = means_and_truth(&|x| (2.0 * PI * cycles * x + phase).sin(), 7);
                est += within_interval_covariance(&m)[3][(0, 0)];
                truth += t[3];
            }
            let ratio = est / truth;
            assert!(
                (low..=high).contains(&ratio),
                "{cycles} cycles per interval: {ratio}"
            );
        }
    }

    /// Vibration spread over the design's band (60 tones, uniform in 0.01–0.4
    /// cycles per interval, fixed pseudo-random phases and amplitudes):
    /// the true within-interval variance regressed on the estimate has slope
    /// 1 within 0.02 — the property a regressor needs, where the quadratic
    /// through three means, whose estimate is that of the middle one, had
    /// about 1.09 on the shaker's records.
    #[test]
    fn broadband_vibration_regresses_with_slope_one() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let tones: Vec<(f64, f64, f64)> = (0..60)
            .map(|_| {
                (
                    0.01 + 0.39 * uniform(),
                    2.0 * PI * uniform(),
                    0.5 + uniform(),
                )
            })
            .collect();
        let f = |x: f64| {
            tones
                .iter()
                .map(|&(c, p, a)| a * (2.0 * PI * c * x + p).sin())
                .sum::<f64>()
        };
        let (m, truth) = means_and_truth(&f, 3000);
        let est = within_interval_covariance(&m);
        let (mut te, mut ee) = (0.0, 0.0);
        let e_mean = est[3..2997].iter().map(|c| c[(0, 0)]).sum::<f64>() / 2994.0;
        let t_mean = truth[3..2997].iter().sum::<f64>() / 2994.0;
        for (c, t) in est.iter().zip(&truth).take(2997).skip(3) {
            let e = c[(0, 0)] - e_mean;
            te += (t - t_mean) * e;
            ee += e * e;
        }
        let slope = te / ee;
        assert!((slope - 1.0).abs() < 0.02, "slope {slope}");
        assert!(
            (e_mean / t_mean - 1.0).abs() < 0.05,
            "mean {e_mean} against {t_mean}"
        );
    }
}
