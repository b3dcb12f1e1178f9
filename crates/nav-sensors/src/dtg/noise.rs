//! The stochastic part of a DTG channel: the IEEE Std 952 angle random
//! walk, bias instability (as a Gauss–Markov drift) and rate random walk.

use serde::{Deserialize, Serialize};

/// Noise parameters of a DTG channel.
///
/// - Angle random walk N (deg/√h): white rate noise; averaged over an output
///   interval T (s) its standard deviation is `60·N/√T` deg/h.
/// - Bias instability B (deg/h) with correlation time τ (s): a first-order
///   Gauss–Markov drift of stationary standard deviation B. Its Allan
///   deviation peaks at about 0.62·B near τ_avg ≈ 1.9·τ and falls as
///   τ^−½ beyond; it stands in for flicker rate noise over a decade or so.
/// - Rate random walk K (deg/h/√h): the rate's integral of white noise,
///   σ(τ) = K·√(τ/3) with τ in h; the output is its exact interval mean.
///   Zero (the default) draws nothing, so records without it are unchanged.
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
    /// Rate random walk, deg/h/√h (absent from a file when zero).
    #[serde(skip_serializing_if = "is_zero")]
    pub rrw_deg_h_per_rt_h: f64,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
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

    /// Standard deviation of the rate random walk's increment over
    /// `interval_s`, deg/h: K·√(interval in h).
    ///
    /// ```
    /// let n = nav_sensors::dtg::DtgNoise { rrw_deg_h_per_rt_h: 0.6, ..Default::default() };
    /// assert!((n.rrw_step_deg_h(3600.0) - 0.6).abs() < 1e-12);
    /// ```
    pub fn rrw_step_deg_h(&self, interval_s: f64) -> f64 {
        self.rrw_deg_h_per_rt_h * (interval_s / 3600.0).sqrt()
    }
}
