//! Allan variance of rate sensors and the IEEE Std 952 noise terms read
//! from it.
//!
//! - [`overlapping_adev`]: the overlapping Allan deviation of a rate series
//!   at τ = m·τ₀, [`octave_factors`] the usual octave-spaced m;
//! - [`identify_noise`]: the dominant power-law noise at each τ (lag-1
//!   autocorrelation), [`PowerLaw`];
//! - [`edf_overlapping`], [`deviation_interval`]: equivalent degrees of
//!   freedom and the chi-square confidence interval of each point;
//! - [`AllanCurve`]: all of it for one series;
//! - [`NoiseTerms`]: angle random walk (deg/√h), bias instability (deg/h) and
//!   rate random walk (deg/h/√h) fitted on the curve's τ^−½, flat and τ^+½
//!   regions, each with its interval, or the reason it is not resolved and
//!   the upper bound the curve still gives.
//!
//! Rates are in deg/h and τ in s throughout; the noise terms convert with
//! σ(τ) = 60·N/√τ (N in deg/√h), σ = 0.664·B at the flat minimum (flicker
//! rate noise), σ(τ) = K·√(τ/10800) (K in deg/h/√h).
//!
//! ```
//! use nav_sensors::noise::{AllanCurve, NoiseTerms};
//! use rand::SeedableRng;
//! use rand_distr::{Distribution, StandardNormal};
//! // 100 s of white rate noise at 50 Hz with N = 0.001 deg/√h: 0.424 deg/h per sample.
//! let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
//! let sigma = 60.0 * 0.001 / 0.02f64.sqrt();
//! let y: Vec<f64> = (0..5000)
//!     .map(|_| { let z: f64 = StandardNormal.sample(&mut rng); sigma * z })
//!     .collect();
//! let curve = AllanCurve::octaves(&y, 0.02, 0.683).unwrap();
//! let terms = NoiseTerms::fit(&curve);
//! let arw = terms.arw.estimate().unwrap();
//! assert!((arw.value / 0.001 - 1.0).abs() < 0.05);
//! assert!(arw.low < arw.value && arw.value < arw.high);
//! // 100 s of white noise cannot show where a bias instability would flatten the curve.
//! assert!(terms.bias_instability.estimate().is_none());
//! ```

mod terms;

// The generic estimator lives in the `allan` crate (sysid's model choice
// reads it too); its items are re-exported here, where they always were.
pub use allan::{
    AllanCurve, AllanError, AllanPoint, MIN_IDENTIFY_SAMPLES, PowerLaw, deviation_interval,
    edf_overlapping, identify_noise, octave_factors, overlapping_adev,
};
pub use terms::{Estimate, FLICKER_FLOOR, NoiseTerm, NoiseTerms};
