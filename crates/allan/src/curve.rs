//! An Allan-deviation curve with, at every τ, the noise identified there,
//! its equivalent degrees of freedom and confidence interval.

use super::adev::{octave_factors, overlapping_adev};
use super::edf::{deviation_interval, edf_overlapping};
use super::error::AllanError;
use super::identify::{PowerLaw, identify_noise};
use serde::Serialize;

/// One τ of an [`AllanCurve`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AllanPoint {
    /// Averaging factor m (τ = m·τ₀).
    pub m: usize,
    /// τ, s.
    pub tau_s: f64,
    /// Overlapping Allan deviation, in the unit of the series (deg/h).
    pub adev: f64,
    /// Dominant power-law noise at this τ: identified by the lag-1
    /// autocorrelation where at least 30 averages remain, else carried from
    /// the longest τ where it could be.
    pub noise: PowerLaw,
    /// Whether `noise` was identified at this τ (false: carried over).
    pub noise_identified: bool,
    /// Equivalent degrees of freedom for that noise.
    pub edf: f64,
    /// Lower end of the confidence interval of `adev`.
    pub low: f64,
    /// Upper end of the confidence interval of `adev`.
    pub high: f64,
}

/// The overlapping Allan deviation of one rate series at several τ.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AllanCurve {
    /// Sample interval τ₀, s.
    pub tau0_s: f64,
    /// Number of rate samples.
    pub samples: usize,
    /// Two-sided confidence level of every interval (e.g. 0.683).
    pub confidence: f64,
    /// The points, τ increasing.
    pub points: Vec<AllanPoint>,
}

impl AllanCurve {
    /// The curve of `y` (rates, deg/h, one per τ₀ s) at the averaging
    /// factors `factors` (increasing), with intervals at `confidence`.
    ///
    /// ```
    /// use allan::{AllanCurve, PowerLaw};
    /// let y: Vec<f64> = (0..400).map(|k| ((k * 37) % 11) as f64).collect();
    /// let c = AllanCurve::new(&y, 1.0, &[1, 2, 4], 0.95).unwrap();
    /// assert_eq!(c.points.len(), 3);
    /// assert!(c.points.iter().all(|p| p.low <= p.adev && p.adev <= p.high));
    /// ```
    pub fn new(
        y: &[f64],
        tau0_s: f64,
        factors: &[usize],
        confidence: f64,
    ) -> Result<Self, AllanError> {
        if !(confidence > 0.0 && confidence < 1.0) {
            return Err(AllanError::BadConfidence(confidence));
        }
        let adev = overlapping_adev(y, tau0_s, factors)?;
        let mut carried = PowerLaw::WhiteRate;
        let mut points = Vec::with_capacity(factors.len());
        for (&m, &a) in factors.iter().zip(&adev) {
            let (noise, noise_identified) = match identify_noise(y, m) {
                Some(n) => (n, true),
                None => (carried, false),
            };
            carried = noise;
            let edf = edf_overlapping(y.len(), m, noise);
            let (low, high) = deviation_interval(a, edf, confidence)?;
            points.push(AllanPoint {
                m,
                tau_s: m as f64 * tau0_s,
                adev: a,
                noise,
                noise_identified,
                edf,
                low,
                high,
            });
        }
        Ok(Self {
            tau0_s,
            samples: y.len(),
            confidence,
            points,
        })
    }

    /// The curve at octave-spaced τ up to a tenth of the record
    /// ([`octave_factors`]).
    pub fn octaves(y: &[f64], tau0_s: f64, confidence: f64) -> Result<Self, AllanError> {
        let factors = octave_factors(y.len());
        if factors.is_empty() {
            return Err(AllanError::TooShort {
                samples: y.len(),
                m: 1,
                need: 3,
            });
        }
        Self::new(y, tau0_s, &factors, confidence)
    }

    /// τ of every point, s.
    pub fn tau_s(&self) -> Vec<f64> {
        self.points.iter().map(|p| p.tau_s).collect()
    }

    /// Allan deviation of every point.
    pub fn adev(&self) -> Vec<f64> {
        self.points.iter().map(|p| p.adev).collect()
    }
}
