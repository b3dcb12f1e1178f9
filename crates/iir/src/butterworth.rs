//! Butterworth low-pass design as a cascade of second-order sections.
//!
//! Second-order sections (not one high-order polynomial) because the
//! polynomial coefficients of a narrow low-pass lose most of their digits:
//! a 6th-order filter at 1 Hz on 50 Hz data has poles within 1e-1 of z = 1,
//! and expanding them into a single denominator puts the response at the
//! mercy of rounding. Each section here is exact to rounding on its own.

//!
//! Written here rather than taken from a crate: `sci-rs` (0.4, scipy's
//! `butter`/`sosfilt`/`sosfiltfilt`) pulls a second nalgebra (0.33 beside
//! the workspace's 0.35) with kalmanfilt, lstsq and gaussfilt, asserts
//! (panics) on a record shorter than the edge extension instead of
//! returning an error, and keeps the overall gain in the first section as
//! scipy does, so the sections saved in a model's JSON would change in
//! their last digits; `iir_filters` (0.1) designs the sections but has no
//! zero-phase filtering and no steady-state initial conditions. The
//! outputs here agree with scipy's to rounding (tests below).

use crate::{Biquad, FilterError};
use serde::{Deserialize, Serialize};

/// A digital Butterworth low-pass filter: maximally flat pass band, −3 dB at
/// the cut-off, roll-off of `20·order` dB/decade.
///
/// ```
/// use iir::LowPass;
/// let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap(); // 4th order, 5 Hz, 50 Hz sampling
/// assert_eq!(lp.sections().len(), 2);
/// assert!((lp.gain_at(0.0) - 1.0).abs() < 1e-12);
/// assert!((lp.gain_at(5.0) - 0.5_f64.sqrt()).abs() < 1e-12); // −3 dB at the cut-off
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LowPass {
    order: usize,
    cutoff_hz: f64,
    sample_rate_hz: f64,
    sections: Vec<Biquad>,
}

/// Highest order accepted: beyond this a low-pass of 50-Hz data gains nothing
/// and its transients outgrow short records.
pub const MAX_ORDER: usize = 12;

/// The lowest cut-off, as a fraction of the sample rate (0.005 Hz at 50 Hz).
pub const MIN_CUTOFF_PER_RATE: f64 = 1e-4;

impl LowPass {
    /// Designs an `order`-th Butterworth low-pass with −3 dB at `cutoff_hz`
    /// for data sampled at `sample_rate_hz`, by the bilinear transform with
    /// frequency pre-warping (so the cut-off lands exactly where asked).
    pub fn butterworth(
        order: usize,
        cutoff_hz: f64,
        sample_rate_hz: f64,
    ) -> Result<Self, FilterError> {
        if order == 0 || order > MAX_ORDER {
            return Err(FilterError::Order {
                order,
                max: MAX_ORDER,
            });
        }
        if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
            return Err(FilterError::SampleRate { sample_rate_hz });
        }
        let nyquist = sample_rate_hz / 2.0;
        if !(cutoff_hz.is_finite() && cutoff_hz > 0.0 && cutoff_hz < nyquist) {
            return Err(FilterError::Cutoff {
                cutoff_hz,
                nyquist_hz: nyquist,
            });
        }
        let min_hz = sample_rate_hz * MIN_CUTOFF_PER_RATE;
        if cutoff_hz < min_hz {
            return Err(FilterError::CutoffTooLow { cutoff_hz, min_hz });
        }
        let fs2 = 2.0 * sample_rate_hz;
        // Pre-warped analog cut-off (rad/s).
        let wc = fs2 * (std::f64::consts::PI * cutoff_hz / sample_rate_hz).tan();
        let n = order as f64;
        let mut sections = Vec::with_capacity(order.div_ceil(2));
        // Analog prototype poles in the upper half of the left half-plane;
        // each, with its conjugate, makes one section with a double zero at z = −1.
        for k in 0..order / 2 {
            let theta = std::f64::consts::PI * (2.0 * k as f64 + n + 1.0) / (2.0 * n);
            let (pr, pi) = (wc * theta.cos(), wc * theta.sin());
            // z = (fs2 + p) / (fs2 − p)
            let (nr, ni) = (fs2 + pr, pi);
            let (dr, di) = (fs2 - pr, -pi);
            let d2 = dr * dr + di * di;
            let (zr, zi) = ((nr * dr + ni * di) / d2, (ni * dr - nr * di) / d2);
            let a = [-2.0 * zr, zr * zr + zi * zi];
            let g = (1.0 + a[0] + a[1]) / 4.0;
            sections.push(Biquad::new([g, 2.0 * g, g], a));
        }
        if order % 2 == 1 {
            // The real pole p = −wc.
            let z = (fs2 - wc) / (fs2 + wc);
            let a = [-z, 0.0];
            let g = (1.0 + a[0]) / 2.0;
            sections.push(Biquad::new([g, g, 0.0], a));
        }
        Ok(Self {
            order,
            cutoff_hz,
            sample_rate_hz,
            sections,
        })
    }

    /// The filter order.
    pub fn order(&self) -> usize {
        self.order
    }

    /// The −3 dB frequency (Hz) of one pass; a zero-phase (forward–backward)
    /// pass is −6 dB there.
    pub fn cutoff_hz(&self) -> f64 {
        self.cutoff_hz
    }

    /// The sample rate (Hz) the filter was designed for.
    pub fn sample_rate_hz(&self) -> f64 {
        self.sample_rate_hz
    }

    /// The second-order sections, applied in order.
    pub fn sections(&self) -> &[Biquad] {
        &self.sections
    }

    /// Magnitude of one pass at `f_hz`.
    pub fn gain_at(&self, f_hz: f64) -> f64 {
        let omega = 2.0 * std::f64::consts::PI * f_hz / self.sample_rate_hz;
        self.sections
            .iter()
            .map(|s| {
                let (re, im) = s.response(omega);
                (re * re + im * im).sqrt()
            })
            .product()
    }

    /// Number of samples of odd extension added at each end by
    /// [`LowPass::filtfilt`]: scipy's `sosfiltfilt` default, so results agree.
    pub fn pad_len(&self) -> usize {
        let zero_b2 = self.sections.iter().filter(|s| s.b[2] == 0.0).count();
        let zero_a2 = self.sections.iter().filter(|s| s.a[1] == 0.0).count();
        3 * (2 * self.sections.len() + 1 - zero_b2.min(zero_a2))
    }
}
