//! The overlapping Allan deviation of a rate series, with at every τ the
//! dominant power-law noise, its equivalent degrees of freedom and the
//! chi-square confidence interval they give: the generic estimator that
//! `nav_sensors::noise` (IEEE Std 952 noise terms) and `sysid`'s
//! noise-aware model choice share, so both read the same curve.
//!
//! - [`overlapping_adev`]: σ(τ) at τ = m·τ₀, [`octave_factors`] the usual m;
//! - [`identify_noise`]: the dominant power-law noise at each τ, [`PowerLaw`];
//! - [`edf_overlapping`], [`deviation_interval`]: equivalent degrees of
//!   freedom and the confidence interval of each point;
//! - [`AllanCurve`]: all of it for one series.
//!
//! ```
//! // White noise: σ(τ) falls as 1/√τ, and every interval brackets its point.
//! let y: Vec<f64> = (0..4000).map(|k| (((k * 7919) % 1009) as f64 / 1009.0 - 0.5)).collect();
//! let c = allan::AllanCurve::octaves(&y, 0.02, 0.683).unwrap();
//! assert!(c.points.iter().all(|p| p.low <= p.adev && p.adev <= p.high));
//! assert!(c.points[4].adev < 0.3 * c.points[0].adev);
//! ```

mod adev;
mod curve;
mod edf;
mod error;
mod identify;

pub use adev::{octave_factors, overlapping_adev};
pub use curve::{AllanCurve, AllanPoint};
pub use edf::{deviation_interval, edf_overlapping};
pub use error::AllanError;
pub use identify::{MIN_IDENTIFY_SAMPLES, PowerLaw, identify_noise};
