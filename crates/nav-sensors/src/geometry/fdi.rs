//! Fault detection and isolation on the parity vector.
//!
//! Detection: `‖p‖ > threshold`, with `p = V·m` the parity vector (see
//! [`parity_matrix`]). Isolation: a fault of size f on channel j gives
//! `p = f·v_j` (column j of V), so the failed channel is the one whose
//! normalised column best explains p, `argmax_j |v_jᵀp| / ‖v_j‖` (the
//! generalised likelihood ratio for one failed channel under equal white
//! noise). The six columns are pairwise non-parallel (the six residue
//! signatures of eq. 6 are distinct), so every single failure is isolable.

use nalgebra::{SMatrix, SVector};
use serde::{Deserialize, Serialize};

use super::channel::Channel;
use super::parity::parity_matrix;

/// The outcome of one FDI test.
///
/// ```
/// use nav_sensors::geometry::{Channel, Fdi, FdiDecision};
/// let fdi = Fdi::new(1.0);
/// let mut m = nav_sensors::geometry::ideal_outputs(&nalgebra::Vector3::new(10.0, 0.0, 5.0));
/// assert_eq!(fdi.check(&m), FdiDecision::Healthy);
/// m[Channel::Y1.index()] += 3.0;
/// match fdi.check(&m) {
///     FdiDecision::Failed { channel, estimate, .. } => {
///         assert_eq!(channel, Channel::Y1);
///         assert!((estimate - 3.0).abs() < 1e-9);
///     }
///     other => panic!("{other:?}"),
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum FdiDecision {
    /// The parity vector is within the threshold.
    Healthy,
    /// A failure was detected and isolated.
    Failed {
        /// The channel judged failed.
        channel: Channel,
        /// ‖p‖, same unit as the outputs.
        statistic: f64,
        /// Estimated fault size on that channel (same unit as the outputs).
        estimate: f64,
    },
}

/// Parity-vector fault detection and isolation with a fixed threshold.
///
/// ```
/// use nav_sensors::geometry::Fdi;
/// // Channel noise 0.5 deg/h at 50 Hz: threshold 6σ (false-alarm probability
/// // P(χ²₃ > 36) ≈ 7e-8 per sample).
/// let fdi = Fdi::for_noise(0.5, 6.0);
/// assert!((fdi.threshold() - 3.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Fdi {
    threshold: f64,
    v: SMatrix<f64, 3, 6>,
    col_norms: [f64; 6],
}

impl Fdi {
    /// A test with a threshold on ‖p‖ (same unit as the outputs, e.g. deg/h).
    ///
    /// ```
    /// let fdi = nav_sensors::geometry::Fdi::new(2.5);
    /// assert_eq!(fdi.threshold(), 2.5);
    /// ```
    #[track_caller]
    pub fn new(threshold: f64) -> Self {
        assert!(
            threshold.is_finite() && threshold > 0.0,
            "threshold must be positive"
        );
        let v = parity_matrix();
        let col_norms = std::array::from_fn(|j| v.column(j).norm());
        Self {
            threshold,
            v,
            col_norms,
        }
    }

    /// A threshold of `k_sigma`·σ for channel noise σ: with V orthonormal,
    /// ‖p‖²/σ² of healthy sensors is χ² with 3 degrees of freedom.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Fdi::for_noise(0.1, 5.0).threshold(), 0.5);
    /// ```
    #[track_caller]
    pub fn for_noise(sigma: f64, k_sigma: f64) -> Self {
        Self::new(sigma * k_sigma)
    }

    /// The detection threshold on ‖p‖.
    ///
    /// ```
    /// assert_eq!(nav_sensors::geometry::Fdi::new(1.0).threshold(), 1.0);
    /// ```
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// ‖v_j‖: the fraction of a fault on this channel that reaches the parity
    /// vector (the rest is indistinguishable from a rate). The smallest
    /// detectable fault is `threshold / sensitivity`.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Fdi};
    /// let s = Fdi::new(1.0).sensitivity(Channel::X);
    /// assert!(s > 0.5 && s < 1.0);
    /// ```
    pub fn sensitivity(&self, channel: Channel) -> f64 {
        self.col_norms[channel.index()]
    }

    /// The smallest fault on a channel that always crosses the threshold
    /// without noise: `threshold / sensitivity` (same unit as the outputs).
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Fdi};
    /// let fdi = Fdi::new(2.0);
    /// assert!((fdi.minimum_detectable(Channel::Z) * fdi.sensitivity(Channel::Z) - 2.0).abs() < 1e-12);
    /// ```
    pub fn minimum_detectable(&self, channel: Channel) -> f64 {
        self.threshold / self.sensitivity(channel)
    }

    /// Tests one set of six outputs (in [`Channel::ALL`] order).
    ///
    /// ```
    /// use nav_sensors::geometry::{Fdi, FdiDecision};
    /// assert_eq!(Fdi::new(1.0).check(&[0.1; 6]), FdiDecision::Healthy);
    /// ```
    pub fn check(&self, m: &[f64; 6]) -> FdiDecision {
        let p = self.v * SVector::<f64, 6>::from_column_slice(m);
        let statistic = p.norm();
        if statistic <= self.threshold {
            return FdiDecision::Healthy;
        }
        let (j, _) = (0..6)
            .map(|j| (j, (self.v.column(j).dot(&p) / self.col_norms[j]).abs()))
            .fold((0, f64::MIN), |b, c| if c.1 > b.1 { c } else { b });
        FdiDecision::Failed {
            channel: Channel::ALL[j],
            statistic,
            estimate: self.v.column(j).dot(&p) / (self.col_norms[j] * self.col_norms[j]),
        }
    }

    /// The first sample index at which `persistence` consecutive tests agree on
    /// the same failed channel, and that channel (a confirmation rule against
    /// isolated noise spikes). `None` when no fault is confirmed.
    ///
    /// ```
    /// use nav_sensors::geometry::{Channel, Fdi};
    /// let mut samples = vec![[0.0; 6]; 10];
    /// for s in &mut samples[4..] { s[Channel::Z.index()] = 5.0; }
    /// assert_eq!(Fdi::new(1.0).first_fault(samples, 3), Some((6, Channel::Z)));
    /// ```
    #[track_caller]
    pub fn first_fault(
        &self,
        samples: impl IntoIterator<Item = [f64; 6]>,
        persistence: usize,
    ) -> Option<(usize, Channel)> {
        assert!(persistence >= 1, "persistence of at least one sample");
        let mut run: Option<(Channel, usize)> = None;
        for (i, m) in samples.into_iter().enumerate() {
            run = match (self.check(&m), run) {
                (FdiDecision::Failed { channel, .. }, Some((c, n))) if c == channel => {
                    Some((c, n + 1))
                }
                (FdiDecision::Failed { channel, .. }, _) => Some((channel, 1)),
                (FdiDecision::Healthy, _) => None,
            };
            if let Some((c, n)) = run
                && n >= persistence
            {
                return Some((i, c));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ideal_outputs;
    use nalgebra::Vector3;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    use rand_xoshiro::Xoshiro256PlusPlus;

    const SIGMA: f64 = 0.4; // deg/h, about a DTG's 50-Hz noise
    const N: usize = 2000;
    const ONSET: usize = 1000;

    /// Six noisy outputs of a rotating cluster with `fault(i)` added to `bad`.
    fn run(bad: Channel, fault: impl Fn(usize) -> f64, seed: u64) -> Vec<[f64; 6]> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..N)
            .map(|i| {
                let t = i as f64 * 0.02;
                let w = Vector3::new(15.0 * t.sin(), 30.0 * (0.3 * t).cos(), 100.0);
                let mut m = ideal_outputs(&w);
                for v in &mut m {
                    let n: f64 = StandardNormal.sample(&mut rng);
                    *v += SIGMA * n;
                }
                m[bad.index()] += fault(i);
                m
            })
            .collect()
    }

    #[test]
    fn step_on_each_channel_is_detected_and_named() {
        let fdi = Fdi::for_noise(SIGMA, 6.0);
        for (k, c) in Channel::ALL.into_iter().enumerate() {
            // Twice the minimum detectable fault: the parity signal is then 12σ
            // against a 6σ threshold. Small against the rates (100 deg/h).
            let step = 2.0 * fdi.minimum_detectable(c);
            assert!(step < 10.0);
            let samples = run(c, |i| if i >= ONSET { step } else { 0.0 }, k as u64);
            let before = samples[..ONSET]
                .iter()
                .filter(|m| fdi.check(m) != FdiDecision::Healthy)
                .count();
            assert_eq!(before, 0, "false alarm before the step on {c}");
            let (at, named) = fdi.first_fault(samples.clone(), 3).expect("detected");
            assert_eq!(named, c);
            assert!((ONSET..ONSET + 20).contains(&at), "{c}: confirmed at {at}");
            let right = samples[ONSET..]
                .iter()
                .filter(
                    |m| matches!(fdi.check(m), FdiDecision::Failed { channel, .. } if channel == c),
                )
                .count();
            assert!(right as f64 > 0.95 * (N - ONSET) as f64, "{c}: {right}");
        }
    }

    #[test]
    fn ramp_on_each_channel_is_detected_and_named() {
        let fdi = Fdi::for_noise(SIGMA, 6.0);
        for (k, c) in Channel::ALL.into_iter().enumerate() {
            // 0.02 deg/h per sample (1 deg/h/s): crosses the minimum detectable
            // fault (< 4 deg/h) within 200 samples.
            assert!(fdi.minimum_detectable(c) < 4.0);
            let samples = run(
                c,
                |i| 0.02 * (i.saturating_sub(ONSET)) as f64,
                100 + k as u64,
            );
            let (at, named) = fdi.first_fault(samples.clone(), 5).expect("detected");
            assert_eq!(named, c, "ramp on {c}");
            assert!(at > ONSET && at < ONSET + 400, "{c}: confirmed at {at}");
            // Once the ramp is large (last quarter), every test names it.
            for m in &samples[N - N / 4..] {
                match fdi.check(m) {
                    FdiDecision::Failed { channel, .. } => assert_eq!(channel, c),
                    FdiDecision::Healthy => panic!("missed ramp on {c}"),
                }
            }
        }
    }
}
