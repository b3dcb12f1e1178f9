//! The stochastic part of a DTG channel: angle random walk and bias instability.

use serde::{Deserialize, Serialize};

/// Noise parameters of a DTG channel.
///
/// - Angle random walk N (deg/√h): white rate noise; averaged over an output
///   interval T (s) its standard deviation is `60·N/√T` deg/h.
/// - Bias instability B (deg/h) with correlation time τ (s): a first-order
///   Gauss–Markov drift of stationary standard deviation B.
///
/// ```
/// let n = nav_sensors::dtg::DtgNoise { arw_deg_per_rt_h: 0.001, ..Default::default() };
/// // 0.001 deg/√h at 50 Hz: 60·0.001/√0.02 ≈ 0.424 deg/h.
/// assert!((n.white_sigma_deg_h(0.02) - 0.42426).abs() < 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DtgNoise {
    /// Angle random walk, deg/√h.
    pub arw_deg_per_rt_h: f64,
    /// Bias instability (Gauss–Markov standard deviation), deg/h.
    pub bias_instability_deg_h: f64,
    /// Bias-instability correlation time, s.
    pub bias_instability_tau_s: f64,
}

impl DtgNoise {
    /// Standard deviation of the white (ARW) part of an output averaged over
    /// `interval_s`, deg/h.
    ///
    /// ```
    /// let n = nav_sensors::dtg::DtgNoise { arw_deg_per_rt_h: 0.01, ..Default::default() };
    /// assert!((n.white_sigma_deg_h(1.0) - 0.6).abs() < 1e-12);
    /// ```
    pub fn white_sigma_deg_h(&self, interval_s: f64) -> f64 {
        60.0 * self.arw_deg_per_rt_h / interval_s.sqrt()
    }
}
