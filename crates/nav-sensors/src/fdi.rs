//! Fault detection and isolation on the parity vector, for any unit.
//!
//! Detection: `‖p‖ > threshold`, with `p = V·m` the parity vector (V the
//! unit's orthonormal parity matrix, [`crate::unit::Unit::parity_matrix`]).
//! With V orthonormal and independent channel noise of equal σ, ‖p‖²/σ² of
//! healthy sensors is χ² with n − 3 degrees of freedom, which sets the
//! threshold for a false-alarm probability ([`ParityFdi::for_false_alarm`]).
//! Isolation: a fault of size f on channel j gives `p = f·v_j` (column j of
//! V), so the failed channel is the one whose normalised column best explains
//! p, `argmax_j |v_jᵀp| / ‖v_j‖` (the generalised likelihood ratio for one
//! failed channel under equal white noise). Channels whose columns are
//! parallel cannot be told apart: with four gyros every column is (V has one
//! row), so four gyros detect and five isolate; two gyros on one input axis
//! (dual-triad's gz and gz2) are never told apart. The paper's six columns
//! are pairwise non-parallel (the six residue signatures of eq. 6 are
//! distinct), so every single failure of its unit is isolable.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};

use crate::geometry::{Channel, parity_matrix};
use crate::unit::Unit;

/// Two columns of V count as parallel (the faults they describe give the
/// same parity direction) when the cosine of their angle exceeds this.
const PARALLEL_COSINE: f64 = 1.0 - 1e-9;

/// Why a parity test cannot be built.
///
/// ```
/// use nav_sensors::fdi::{FdiError, ParityFdi};
/// let triad = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let err = ParityFdi::new(&triad, 1.0).unwrap_err();
/// assert!(matches!(err, FdiError::NotRedundant { gyros: 3 }));
/// assert_eq!(err.to_string(), "a unit of 3 gyros has no parity residue: fault detection needs at least 4 gyros, isolation 5");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FdiError {
    /// Three gyros: nothing is redundant.
    #[error(
        "a unit of {gyros} gyros has no parity residue: fault detection needs at least 4 gyros, isolation 5"
    )]
    NotRedundant {
        /// How many gyros the unit has.
        gyros: usize,
    },
    /// A threshold, noise level or probability out of range.
    #[error("{what} = {value}: {requirement}")]
    OutOfRange {
        /// The parameter.
        what: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
}

/// The outcome of one parity test on a unit of any size.
///
/// ```
/// use nav_sensors::fdi::{FdiOutcome, ParityFdi};
/// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let fdi = ParityFdi::new(&u, 1.0).unwrap();
/// let mut m = vec![0.0; 4];
/// assert_eq!(fdi.check(&m), FdiOutcome::Healthy);
/// m[1] = 5.0;
/// // Four gyros: detected, not isolated (every channel explains it).
/// assert!(matches!(fdi.check(&m), FdiOutcome::Detected { ref candidates, .. } if candidates.len() == 4));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FdiOutcome {
    /// The parity vector is within the threshold.
    Healthy,
    /// A fault is detected but the channels listed (gyro indices) explain it
    /// equally well.
    Detected {
        /// ‖p‖, same unit as the outputs.
        statistic: f64,
        /// The channels that cannot be told apart, in gyro order.
        candidates: Vec<usize>,
    },
    /// A fault is detected and isolated to one channel.
    Isolated {
        /// The gyro index judged failed.
        channel: usize,
        /// ‖p‖, same unit as the outputs.
        statistic: f64,
        /// Estimated fault size on that channel (same unit as the outputs).
        estimate: f64,
    },
}

impl FdiOutcome {
    /// Whether the test raised an alarm (detected or isolated).
    ///
    /// ```
    /// assert!(!nav_sensors::fdi::FdiOutcome::Healthy.is_alarm());
    /// ```
    pub fn is_alarm(&self) -> bool {
        !matches!(self, FdiOutcome::Healthy)
    }
}

/// Parity-vector fault detection and isolation with a fixed threshold, for
/// any unit of four or more gyros.
///
/// ```
/// use nav_sensors::fdi::{FdiOutcome, ParityFdi};
/// use nalgebra::Vector3;
/// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
/// let fdi = ParityFdi::for_false_alarm(&u, 0.3, 1e-3).unwrap();
/// let w = Vector3::new(10.0, 0.0, 5.0);
/// let mut m: Vec<f64> = u.gyros().iter().map(|g| g.input.dot(&w)).collect();
/// m[3] += 4.0; // gx2
/// assert!(matches!(fdi.check(&m), FdiOutcome::Isolated { channel: 3, .. }));
/// assert!(fdi.can_isolate(0) && !fdi.can_isolate(2)); // gz and gz2 share an axis
/// ```
#[derive(Debug, Clone)]
pub struct ParityFdi {
    threshold: f64,
    v: DMatrix<f64>,
    col_norms: Vec<f64>,
    /// For each channel, the channels whose columns are parallel to its own
    /// (itself included).
    twins: Vec<Vec<usize>>,
}

impl ParityFdi {
    /// A test on a unit's parity vector with a threshold on ‖p‖ (same unit as
    /// the outputs, e.g. deg/h).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert_eq!(nav_sensors::fdi::ParityFdi::new(&u, 2.0).unwrap().threshold(), 2.0);
    /// ```
    pub fn new(unit: &Unit, threshold: f64) -> Result<Self, FdiError> {
        let n = unit.gyros().len();
        if n < 4 {
            return Err(FdiError::NotRedundant { gyros: n });
        }
        Self::with_parity_matrix(unit.parity_matrix().clone(), threshold)
    }

    /// The threshold that healthy sensors with independent white noise of σ
    /// (same unit as the outputs) exceed with probability `probability` per
    /// sample: σ·√q with q the (1 − probability) quantile of χ²(n − 3).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// // One degree of freedom: the two-sided normal 1e-3 point, 3.29σ.
    /// let fdi = nav_sensors::fdi::ParityFdi::for_false_alarm(&u, 1.0, 1e-3).unwrap();
    /// assert!((fdi.threshold() - 3.2905).abs() < 1e-4);
    /// ```
    pub fn for_false_alarm(unit: &Unit, sigma: f64, probability: f64) -> Result<Self, FdiError> {
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(FdiError::OutOfRange {
                what: "sigma",
                value: sigma,
                requirement: "must be positive and finite",
            });
        }
        if !(probability > 0.0 && probability < 1.0) {
            return Err(FdiError::OutOfRange {
                what: "false-alarm probability",
                value: probability,
                requirement: "must be between 0 and 1",
            });
        }
        let n = unit.gyros().len();
        if n < 4 {
            return Err(FdiError::NotRedundant { gyros: n });
        }
        let chi2 = ChiSquared::new((n - 3) as f64).expect("positive degrees of freedom");
        Self::new(unit, sigma * chi2.inverse_cdf(1.0 - probability).sqrt())
    }

    fn with_parity_matrix(v: DMatrix<f64>, threshold: f64) -> Result<Self, FdiError> {
        if !(threshold.is_finite() && threshold > 0.0) {
            return Err(FdiError::OutOfRange {
                what: "threshold",
                value: threshold,
                requirement: "must be positive and finite",
            });
        }
        let n = v.ncols();
        let col_norms: Vec<f64> = (0..n).map(|j| v.column(j).norm()).collect();
        let twins = (0..n)
            .map(|j| {
                (0..n)
                    .filter(|&k| {
                        let c = v.column(j).dot(&v.column(k)) / (col_norms[j] * col_norms[k]);
                        c.abs() > PARALLEL_COSINE
                    })
                    .collect()
            })
            .collect();
        Ok(Self {
            threshold,
            v,
            col_norms,
            twins,
        })
    }

    /// The detection threshold on ‖p‖.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert_eq!(nav_sensors::fdi::ParityFdi::new(&u, 1.5).unwrap().threshold(), 1.5);
    /// ```
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// ‖v_j‖: the fraction of a fault on gyro j that reaches the parity vector
    /// (the rest is indistinguishable from a rate).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// // Symmetric layout: every gyro has ‖v_j‖ = √(1/4).
    /// let fdi = nav_sensors::fdi::ParityFdi::new(&u, 1.0).unwrap();
    /// assert!((fdi.sensitivity(2) - 0.5).abs() < 1e-12);
    /// ```
    pub fn sensitivity(&self, channel: usize) -> f64 {
        self.col_norms[channel]
    }

    /// The smallest fault on gyro j that always crosses the threshold without
    /// noise: `threshold / sensitivity`.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let fdi = nav_sensors::fdi::ParityFdi::new(&u, 1.0).unwrap();
    /// assert!((fdi.minimum_detectable(0) - 2.0).abs() < 1e-12);
    /// ```
    pub fn minimum_detectable(&self, channel: usize) -> f64 {
        self.threshold / self.col_norms[channel]
    }

    /// Whether a fault on gyro j can be isolated (no other gyro's column of V
    /// is parallel to its own).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// let fdi = nav_sensors::fdi::ParityFdi::new(&u, 1.0).unwrap();
    /// assert!((0..6).all(|j| fdi.can_isolate(j)));
    /// ```
    pub fn can_isolate(&self, channel: usize) -> bool {
        self.twins[channel].len() == 1
    }

    /// Tests one sample of gyro outputs (gyro order).
    ///
    /// ```
    /// use nav_sensors::fdi::{FdiOutcome, ParityFdi};
    /// let u = nav_sensors::unit::Unit::paper();
    /// assert_eq!(ParityFdi::new(&u, 1.0).unwrap().check(&[0.1; 6]), FdiOutcome::Healthy);
    /// ```
    #[track_caller]
    pub fn check(&self, m: &[f64]) -> FdiOutcome {
        assert_eq!(m.len(), self.v.ncols(), "one output per gyro");
        let p = &self.v * DVector::from_column_slice(m);
        let statistic = p.norm();
        if statistic <= self.threshold {
            return FdiOutcome::Healthy;
        }
        let (j, _) = (0..m.len())
            .map(|j| (j, (self.v.column(j).dot(&p) / self.col_norms[j]).abs()))
            .fold((0, f64::MIN), |b, c| if c.1 > b.1 { c } else { b });
        if !self.can_isolate(j) {
            return FdiOutcome::Detected {
                statistic,
                candidates: self.twins[j].clone(),
            };
        }
        FdiOutcome::Isolated {
            channel: j,
            statistic,
            estimate: self.v.column(j).dot(&p) / (self.col_norms[j] * self.col_norms[j]),
        }
    }

    /// The first sample index at which `persistence` consecutive tests give
    /// the same alarm (the same isolated channel, or the same candidate
    /// set), and that outcome. `None` when no fault is confirmed.
    ///
    /// ```
    /// use nav_sensors::fdi::{FdiOutcome, ParityFdi};
    /// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
    /// let mut samples = vec![vec![0.0; 6]; 10];
    /// for s in &mut samples[4..] { s[0] = 5.0; }
    /// let (at, outcome) = ParityFdi::new(&u, 1.0).unwrap().first_fault(samples, 3).unwrap();
    /// assert_eq!(at, 6);
    /// assert!(matches!(outcome, FdiOutcome::Isolated { channel: 0, .. }));
    /// ```
    #[track_caller]
    pub fn first_fault<S: AsRef<[f64]>>(
        &self,
        samples: impl IntoIterator<Item = S>,
        persistence: usize,
    ) -> Option<(usize, FdiOutcome)> {
        assert!(persistence >= 1, "persistence of at least one sample");
        let who = |o: &FdiOutcome| match o {
            FdiOutcome::Healthy => None,
            FdiOutcome::Detected { candidates, .. } => Some(candidates.clone()),
            FdiOutcome::Isolated { channel, .. } => Some(vec![*channel]),
        };
        let mut run: Option<(Vec<usize>, usize)> = None;
        for (i, m) in samples.into_iter().enumerate() {
            let outcome = self.check(m.as_ref());
            run = match (who(&outcome), run) {
                (Some(w), Some((c, n))) if c == w => Some((c, n + 1)),
                (Some(w), _) => Some((w, 1)),
                (None, _) => None,
            };
            if let Some((_, n)) = &run
                && *n >= persistence
            {
                return Some((i, outcome));
            }
        }
        None
    }
}

/// The outcome of one FDI test on the paper's unit.
///
/// ```
/// use nav_sensors::fdi::{Fdi, FdiDecision};
/// use nav_sensors::geometry::Channel;
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

/// Parity-vector fault detection and isolation on the paper's unit with a
/// fixed threshold ([`ParityFdi`] with the paper's parity matrix and
/// channel names).
///
/// ```
/// use nav_sensors::fdi::Fdi;
/// // Channel noise 0.5 deg/h at 50 Hz: threshold 6σ (false-alarm probability
/// // P(χ²₃ > 36) ≈ 7e-8 per sample).
/// let fdi = Fdi::for_noise(0.5, 6.0);
/// assert!((fdi.threshold() - 3.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct Fdi {
    inner: ParityFdi,
}

impl Fdi {
    /// A test with a threshold on ‖p‖ (same unit as the outputs, e.g. deg/h).
    ///
    /// ```
    /// let fdi = nav_sensors::fdi::Fdi::new(2.5);
    /// assert_eq!(fdi.threshold(), 2.5);
    /// ```
    #[track_caller]
    pub fn new(threshold: f64) -> Self {
        assert!(
            threshold.is_finite() && threshold > 0.0,
            "threshold must be positive"
        );
        let v = parity_matrix();
        let v = DMatrix::from_fn(3, 6, |i, j| v[(i, j)]);
        Self {
            inner: ParityFdi::with_parity_matrix(v, threshold).expect("threshold checked"),
        }
    }

    /// A threshold of `k_sigma`·σ for channel noise σ: with V orthonormal,
    /// ‖p‖²/σ² of healthy sensors is χ² with 3 degrees of freedom.
    ///
    /// ```
    /// assert_eq!(nav_sensors::fdi::Fdi::for_noise(0.1, 5.0).threshold(), 0.5);
    /// ```
    #[track_caller]
    pub fn for_noise(sigma: f64, k_sigma: f64) -> Self {
        Self::new(sigma * k_sigma)
    }

    /// The detection threshold on ‖p‖.
    ///
    /// ```
    /// assert_eq!(nav_sensors::fdi::Fdi::new(1.0).threshold(), 1.0);
    /// ```
    pub fn threshold(&self) -> f64 {
        self.inner.threshold()
    }

    /// ‖v_j‖: the fraction of a fault on this channel that reaches the parity
    /// vector (the rest is indistinguishable from a rate). The smallest
    /// detectable fault is `threshold / sensitivity`.
    ///
    /// ```
    /// use nav_sensors::fdi::Fdi;
    /// use nav_sensors::geometry::Channel;
    /// let s = Fdi::new(1.0).sensitivity(Channel::X);
    /// assert!(s > 0.5 && s < 1.0);
    /// ```
    pub fn sensitivity(&self, channel: Channel) -> f64 {
        self.inner.sensitivity(channel.index())
    }

    /// The smallest fault on a channel that always crosses the threshold
    /// without noise: `threshold / sensitivity` (same unit as the outputs).
    ///
    /// ```
    /// use nav_sensors::fdi::Fdi;
    /// use nav_sensors::geometry::Channel;
    /// let fdi = Fdi::new(2.0);
    /// assert!((fdi.minimum_detectable(Channel::Z) * fdi.sensitivity(Channel::Z) - 2.0).abs() < 1e-12);
    /// ```
    pub fn minimum_detectable(&self, channel: Channel) -> f64 {
        self.inner.minimum_detectable(channel.index())
    }

    /// Tests one set of six outputs (in [`Channel::ALL`] order).
    ///
    /// ```
    /// use nav_sensors::fdi::{Fdi, FdiDecision};
    /// assert_eq!(Fdi::new(1.0).check(&[0.1; 6]), FdiDecision::Healthy);
    /// ```
    pub fn check(&self, m: &[f64; 6]) -> FdiDecision {
        paper_decision(self.inner.check(m))
    }

    /// The first sample index at which `persistence` consecutive tests agree on
    /// the same failed channel, and that channel (a confirmation rule against
    /// isolated noise spikes). `None` when no fault is confirmed.
    ///
    /// ```
    /// use nav_sensors::fdi::Fdi;
    /// use nav_sensors::geometry::Channel;
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
        let (i, outcome) = self.inner.first_fault(samples, persistence)?;
        match paper_decision(outcome) {
            FdiDecision::Failed { channel, .. } => Some((i, channel)),
            FdiDecision::Healthy => None,
        }
    }
}

/// The paper's columns are pairwise non-parallel, so an alarm is always
/// isolated to one channel.
fn paper_decision(outcome: FdiOutcome) -> FdiDecision {
    match outcome {
        FdiOutcome::Healthy => FdiDecision::Healthy,
        FdiOutcome::Isolated {
            channel,
            statistic,
            estimate,
        } => FdiDecision::Failed {
            channel: Channel::ALL[channel],
            statistic,
            estimate,
        },
        FdiOutcome::Detected { .. } => {
            unreachable!("the paper's six parity columns are pairwise non-parallel")
        }
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

    /// Noisy outputs of a rotating unit with a step of `step` on gyro `bad`
    /// from sample ONSET.
    fn unit_run(unit: &Unit, bad: usize, step: f64, seed: u64) -> Vec<Vec<f64>> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..N)
            .map(|i| {
                let t = i as f64 * 0.02;
                let w = Vector3::new(15.0 * t.sin(), 30.0 * (0.3 * t).cos(), 100.0);
                let mut m: Vec<f64> = unit
                    .gyros()
                    .iter()
                    .map(|g| {
                        let n: f64 = StandardNormal.sample(&mut rng);
                        g.input.dot(&w) + SIGMA * n
                    })
                    .collect();
                if i >= ONSET {
                    m[bad] += step;
                }
                m
            })
            .collect()
    }

    #[test]
    fn any_unit_detects_from_four_gyros_and_isolates_from_five() {
        for name in ["tetra", "dual-triad", "paper"] {
            let unit = Unit::builtin(name).unwrap();
            let fdi = ParityFdi::for_false_alarm(&unit, SIGMA, 1e-6).unwrap();
            for bad in 0..unit.gyros().len() {
                let step = 2.0 * fdi.minimum_detectable(bad);
                let samples = unit_run(&unit, bad, step, 7 + bad as u64);
                assert!(
                    samples[..ONSET].iter().all(|m| !fdi.check(m).is_alarm()),
                    "{name}: false alarm before the step on {bad}"
                );
                let (at, outcome) = fdi.first_fault(samples.clone(), 3).expect("detected");
                assert!((ONSET..ONSET + 20).contains(&at), "{name}/{bad}: at {at}");
                match outcome {
                    FdiOutcome::Isolated { channel, .. } => {
                        assert!(fdi.can_isolate(bad));
                        assert_eq!(channel, bad, "{name}");
                    }
                    FdiOutcome::Detected { candidates, .. } => {
                        assert!(!fdi.can_isolate(bad), "{name}/{bad}");
                        assert!(candidates.contains(&bad));
                    }
                    FdiOutcome::Healthy => unreachable!(),
                }
            }
        }
        // Tetra: one residue, nothing isolable; dual-triad: all but gz, gz2.
        let tetra = ParityFdi::new(&Unit::builtin("tetra").unwrap(), 1.0).unwrap();
        assert!((0..4).all(|j| !tetra.can_isolate(j)));
        let dual = ParityFdi::new(&Unit::builtin("dual-triad").unwrap(), 1.0).unwrap();
        let isolable: Vec<bool> = (0..6).map(|j| dual.can_isolate(j)).collect();
        assert_eq!(isolable, [true, true, false, true, true, false]);
    }

    #[test]
    fn three_gyros_and_bad_parameters_are_refused() {
        let triad = Unit::builtin("triad").unwrap();
        assert!(matches!(
            ParityFdi::for_false_alarm(&triad, 1.0, 1e-3),
            Err(FdiError::NotRedundant { gyros: 3 })
        ));
        let tetra = Unit::builtin("tetra").unwrap();
        let err = ParityFdi::new(&tetra, f64::NAN).unwrap_err();
        assert_eq!(
            err.to_string(),
            "threshold = NaN: must be positive and finite"
        );
        assert!(ParityFdi::for_false_alarm(&tetra, 1.0, 1.5).is_err());
        assert!(ParityFdi::for_false_alarm(&tetra, 0.0, 1e-3).is_err());
    }

    /// The paper's unit takes the one parity basis of every unit (QR), not
    /// eq. 6's Gram–Schmidt rows; what fault detection and isolation
    /// report does not depend on the basis, so both give the same
    /// statistics, estimates, decisions and sensitivities to rounding, on
    /// healthy and faulty samples alike.
    #[test]
    fn the_paper_fdi_is_the_same_in_either_parity_basis() {
        let threshold = 2.0;
        let gram_schmidt = Fdi::new(threshold);
        let qr = ParityFdi::new(&Unit::paper(), threshold).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0);
        for c in Channel::ALL {
            let j = c.index();
            assert!(close(gram_schmidt.sensitivity(c), qr.sensitivity(j)), "{c}");
            assert!(close(
                gram_schmidt.minimum_detectable(c),
                qr.minimum_detectable(j)
            ));
        }
        let mut worst: f64 = 0.0;
        let (mut healthy, mut failed) = (0, 0);
        for (k, c) in Channel::ALL.into_iter().enumerate() {
            for m in run(
                c,
                |i| {
                    if i % 3 == 0 {
                        0.0
                    } else {
                        0.5 * i as f64 / N as f64 * 8.0
                    }
                },
                900 + k as u64,
            ) {
                match (gram_schmidt.check(&m), qr.check(&m)) {
                    (FdiDecision::Healthy, FdiOutcome::Healthy) => healthy += 1,
                    (
                        FdiDecision::Failed {
                            channel,
                            statistic,
                            estimate,
                        },
                        FdiOutcome::Isolated {
                            channel: j,
                            statistic: s,
                            estimate: e,
                        },
                    ) => {
                        assert_eq!(channel.index(), j);
                        assert!(close(statistic, s) && close(estimate, e));
                        worst = worst.max((statistic - s).abs() / s);
                        failed += 1;
                    }
                    (a, b) => panic!("{c}: {a:?} against {b:?}"),
                }
            }
        }
        assert!(healthy > 1000 && failed > 1000, "{healthy} {failed}");
        println!("largest relative difference of ‖p‖ between the bases: {worst:e}");
    }
}
