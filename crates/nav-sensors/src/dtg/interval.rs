//! What a product of interval means misses.
//!
//! A DTG's 50-Hz output is the mean of its drift over each 20-ms interval, and
//! an anisoelastic drift `D·f_I·f_S` then holds the interval mean of the
//! product, `mean(f_I)·mean(f_S) + cov(f_I, f_S)`. Ground-calibration
//! compensation and effect regressors see only the accelerometers' interval
//! means, so without the covariance they leave `D·cov` behind — the
//! rectification of vibration that moves within an interval.
//!
//! For vibration slower than the output rate the covariance is predictable
//! from the neighbouring means: a quadratic through three consecutive interval
//! means (matching each interval's mean exactly) gives, over the central
//! interval of length T with τ = (t − t_n)/T,
//! `f(τ) = c0 + c1·τ + c2·τ²`, `c1 = (m₊ − m₋)/2`, `c2 = (m₊ + m₋ − 2m)/2`,
//! and `mean(f_a·f_b) = m_a·m_b + c1_a·c1_b/12 + c2_a·c2_b/180`.
//! For vibration far above the output rate the means are aliased and the
//! estimate is small and uninformative, never harmful by construction (it is
//! a product of differences of means, of the order of the means' own
//! fluctuation squared).

use nalgebra::{Matrix3, Vector3};

use super::input::DtgInput;
use crate::geometry::{ChannelFrame, DtgAxes};

/// Within-interval covariance of a vector signal (cluster frame) at every
/// interval, from the interval means; zero at the first and last interval,
/// which have one neighbour only.
///
/// Exact for a signal that is a quadratic in time over three intervals:
///
/// ```
/// use nalgebra::Vector3;
/// // f(t) = (t, 0, t²) sampled as means over unit intervals centred on 0, 1, 2.
/// let mean_over = |n: f64| Vector3::new(n, 0.0, n * n + 1.0 / 12.0);
/// let m = [mean_over(0.0), mean_over(1.0), mean_over(2.0)];
/// let c = nav_sensors::dtg::within_interval_covariance(&m);
/// // Over [0.5, 1.5]: mean(t·t²) − mean(t)·mean(t²) = 1.25 − 1·(13/12) = 1/6.
/// assert!((c[1][(0, 2)] - 1.0 / 6.0).abs() < 1e-12);
/// assert_eq!(c[0], nalgebra::Matrix3::zeros());
/// ```
pub fn within_interval_covariance(means: &[Vector3<f64>]) -> Vec<Matrix3<f64>> {
    let n = means.len();
    (0..n)
        .map(|i| {
            if i == 0 || i + 1 >= n {
                return Matrix3::zeros();
            }
            let c1 = (means[i + 1] - means[i - 1]) / 2.0;
            let c2 = (means[i + 1] + means[i - 1] - 2.0 * means[i]) / 2.0;
            c1 * c1.transpose() / 12.0 + c2 * c2.transpose() / 180.0
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

    /// Interval means of a sampled signal, against the truth computed from
    /// the fine samples: the estimate recovers most of the covariance of a
    /// slow sine (measured: 96% at 0.05 cycles per interval, 72% at 0.15 —
    /// the central difference of means underestimates a faster slope), and
    /// adds almost nothing for one far above the output rate.
    #[test]
    fn recovers_slow_vibration_and_ignores_fast() {
        let fine = 80; // samples per interval
        let intervals = 400;
        for (freq_per_interval, min_share, max_abs) in [
            (0.05, 0.9, f64::INFINITY),
            (0.15, 0.65, f64::INFINITY),
            (7.3, -1.0, 0.02),
        ] {
            let f = |t: f64| {
                Vector3::new(
                    (2.0 * std::f64::consts::PI * freq_per_interval * t).sin(),
                    0.0,
                    0.0,
                )
            };
            let mut means = Vec::new();
            let mut true_cov = Vec::new();
            for n in 0..intervals {
                let ts: Vec<f64> = (0..fine)
                    .map(|k| n as f64 + (k as f64 + 0.5) / fine as f64)
                    .collect();
                let m = ts.iter().map(|&t| f(t)).sum::<Vector3<f64>>() / fine as f64;
                let msq = ts.iter().map(|&t| f(t).x * f(t).x).sum::<f64>() / fine as f64;
                means.push(m);
                true_cov.push(msq - m.x * m.x);
            }
            let est = within_interval_covariance(&means);
            let (mut t_sum, mut e_sum) = (0.0, 0.0);
            for n in 1..intervals - 1 {
                t_sum += true_cov[n];
                e_sum += est[n][(0, 0)];
            }
            let share = e_sum / t_sum;
            if min_share > 0.0 {
                assert!(
                    share > min_share && share < 1.05,
                    "slow sine: estimated {share} of the covariance"
                );
            } else {
                assert!(
                    e_sum / (intervals as f64) < max_abs,
                    "fast sine: mean estimate {}",
                    e_sum / intervals as f64
                );
            }
        }
    }
}
