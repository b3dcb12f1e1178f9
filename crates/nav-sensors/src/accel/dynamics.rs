//! The accelerometer's servo loop and noise.

use serde::{Deserialize, Serialize};

use crate::signal::Biquad;

/// Closed-loop dynamics of the servo accelerometer: second-order low-pass
/// `ωn²/(s² + 2ζωn s + ωn²)`, discretised by the pre-warped bilinear
/// transform at the simulator's internal rate (stable for any ζ > 0).
///
/// ```
/// use nav_sensors::accel::ServoLoop;
/// let lp = ServoLoop { natural_hz: 800.0, damping: 0.7 };
/// let mut f = lp.filter(4000.0);
/// f.settle(1.0);
/// assert!((f.step(1.0) - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServoLoop {
    /// Natural frequency, Hz.
    pub natural_hz: f64,
    /// Damping ratio ζ.
    pub damping: f64,
}

impl Default for ServoLoop {
    /// 800 Hz, ζ = 0.7: a navigation servo accelerometer's loop is typically
    /// a few hundred Hz to ~1 kHz wide, flat over the 20–2000 Hz vibration
    /// band's low end and rolling off above.
    fn default() -> Self {
        Self {
            natural_hz: 800.0,
            damping: 0.7,
        }
    }
}

impl ServoLoop {
    /// The discrete filter at `sample_rate_hz`. Panics if the natural
    /// frequency is not below Nyquist (scenarios validate this first).
    ///
    /// ```
    /// let f = nav_sensors::accel::ServoLoop::default().filter(4000.0);
    /// let _ = f;
    /// ```
    #[track_caller]
    pub fn filter(&self, sample_rate_hz: f64) -> Biquad {
        Biquad::low_pass(self.natural_hz, self.damping, sample_rate_hz)
    }
}

/// Accelerometer noise: white, single-sided density in µg/√Hz.
///
/// ```
/// let n = nav_sensors::accel::AccelNoise { density_ug_per_rt_hz: 10.0 };
/// // Averaged over 20 ms: σ = 10 µg/√Hz · √(1/(2·0.02 s)) = 50 µg.
/// assert!((n.averaged_sigma_g(0.02) - 50e-6).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AccelNoise {
    /// Noise density, µg/√Hz (single-sided).
    pub density_ug_per_rt_hz: f64,
}

impl AccelNoise {
    /// Standard deviation of the noise averaged over `interval_s`, in g: a
    /// white single-sided density n gives `n/√(2T)`.
    ///
    /// ```
    /// let n = nav_sensors::accel::AccelNoise { density_ug_per_rt_hz: 20.0 };
    /// assert!((n.averaged_sigma_g(0.02) - 100e-6).abs() < 1e-12);
    /// ```
    pub fn averaged_sigma_g(&self, interval_s: f64) -> f64 {
        1e-6 * self.density_ug_per_rt_hz / (2.0 * interval_s).sqrt()
    }
}
