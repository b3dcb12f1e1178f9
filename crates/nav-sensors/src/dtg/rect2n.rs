//! Rectification of angular vibration at twice the spin frequency (2N).
//!
//! A DTG's rotor, seen from the case, responds to angular vibration about an
//! axis normal to the spin axis at twice the spin frequency with a rectified
//! (DC) drift (Craig 1972). We model the channel's sensitivity as a narrow
//! resonance: the angular rate about I is passed through a unit-peak-gain
//! band-pass centred at 2N with quality factor Q, and the drift is
//!
//! ```text
//! drift_2N = rect_2n · ω_bp²      (deg/h; rect_2n in deg/h/(deg/s)², ω_bp in deg/s)
//! ```
//!
//! so a sine of amplitude W deg/s exactly at 2N drifts by `rect_2n·W²/2` on
//! average, and random angular vibration by `rect_2n` times its mean-square
//! rate within about `2N/Q` of 2N.

use crate::signal::Biquad;

/// The 2N band-pass of one channel, run at the simulator's internal rate.
///
/// ```
/// use nav_sensors::dtg::Rect2nDetector;
/// let (spin, fs) = (200.0, 4000.0);
/// let mut d = Rect2nDetector::new(spin, 8.0, fs);
/// let w = 0.5; // deg/s at 400 Hz
/// let n = 40_000;
/// let mut mean = 0.0;
/// for k in 0..n {
///     let r = d.step(w * (2.0 * std::f64::consts::PI * 2.0 * spin * k as f64 / fs).sin());
///     if k >= n / 2 { mean += r / (n / 2) as f64; }
/// }
/// assert!((mean - w * w / 2.0).abs() < 1e-3 * w * w);
/// ```
#[derive(Debug, Clone)]
pub struct Rect2nDetector {
    filter: Biquad,
}

impl Rect2nDetector {
    /// A detector for a rotor spinning at `spin_hz`, resonance quality `q`,
    /// at `sample_rate_hz`. Panics when 2·spin is not below Nyquist.
    ///
    /// ```
    /// let d = nav_sensors::dtg::Rect2nDetector::new(200.0, 10.0, 4000.0);
    /// let _ = d;
    /// ```
    #[track_caller]
    pub fn new(spin_hz: f64, q: f64, sample_rate_hz: f64) -> Self {
        Self {
            filter: Biquad::band_pass(2.0 * spin_hz, q, sample_rate_hz),
        }
    }

    /// Takes the rate about I (deg/s) and returns the instantaneous regressor
    /// ω_bp² in (deg/s)²; its mean over an interval is the `rect_2n` regressor.
    ///
    /// ```
    /// let mut d = nav_sensors::dtg::Rect2nDetector::new(200.0, 10.0, 4000.0);
    /// assert_eq!(d.step(0.0), 0.0);
    /// assert!(d.step(1.0) >= 0.0);
    /// ```
    #[inline]
    pub fn step(&mut self, rate_about_i_deg_s: f64) -> f64 {
        let y = self.filter.step(rate_about_i_deg_s);
        y * y
    }
}
