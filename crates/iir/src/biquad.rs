//! The second-order IIR section (biquad): the one filter building block of
//! the workspace. The sensor dynamics run single sections (the accelerometer
//! servo loop as a low-pass, the DTG 2N detector as a band-pass); the
//! Butterworth [`LowPass`](super::LowPass) is a cascade of them.

use serde::{Deserialize, Serialize};

/// One second-order section `H(z) = (b0 + b1 z⁻¹ + b2 z⁻²) / (1 + a1 z⁻¹ + a2 z⁻²)`,
/// run in transposed direct form II; it carries its own state, so a
/// section is also a running filter ([`Biquad::step`]). The state is not
/// part of a saved filter: serialisation writes the coefficients `b`, `a`
/// only, and reading gives a section at rest.
///
/// ```
/// use iir::Biquad;
/// // A 800-Hz, ζ = 0.7 low-pass at 4 kHz passes DC unchanged.
/// let mut f = Biquad::low_pass(800.0, 0.7, 4000.0);
/// let mut y = 0.0;
/// for _ in 0..2000 { y = f.step(1.0); }
/// assert!((y - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Biquad {
    /// Numerator `b0, b1, b2`.
    pub b: [f64; 3],
    /// Denominator `a1, a2` (a0 is 1).
    pub a: [f64; 2],
    /// State `[z1, z2]` of transposed direct form II.
    #[serde(skip)]
    z: [f64; 2],
}

impl Biquad {
    /// A section at rest from its coefficients: numerator `b0, b1, b2`,
    /// denominator `a1, a2` (a0 = 1).
    ///
    /// ```
    /// use iir::Biquad;
    /// let s = Biquad::new([0.25, 0.5, 0.25], [0.0, 0.0]);
    /// assert!((s.dc_gain() - 1.0).abs() < 1e-15);
    /// ```
    pub fn new(b: [f64; 3], a: [f64; 2]) -> Self {
        Self { b, a, z: [0.0; 2] }
    }

    /// The gain at zero frequency, `H(1)`.
    ///
    /// ```
    /// let f = iir::Biquad::low_pass(100.0, 0.7, 4000.0);
    /// assert!((f.dc_gain() - 1.0).abs() < 1e-12);
    /// ```
    pub fn dc_gain(&self) -> f64 {
        (self.b[0] + self.b[1] + self.b[2]) / (1.0 + self.a[0] + self.a[1])
    }

    /// The complex response at `z = exp(iω)`, as `(re, im)`.
    pub(crate) fn response(&self, omega: f64) -> (f64, f64) {
        // Evaluate both polynomials in z⁻¹ = cos ω − i sin ω.
        let (c1, s1) = (omega.cos(), -omega.sin());
        let (c2, s2) = ((2.0 * omega).cos(), -(2.0 * omega).sin());
        let num = (
            self.b[0] + self.b[1] * c1 + self.b[2] * c2,
            self.b[1] * s1 + self.b[2] * s2,
        );
        let den = (
            1.0 + self.a[0] * c1 + self.a[1] * c2,
            self.a[0] * s1 + self.a[1] * s2,
        );
        let d2 = den.0 * den.0 + den.1 * den.1;
        (
            (num.0 * den.0 + num.1 * den.1) / d2,
            (num.1 * den.0 - num.0 * den.1) / d2,
        )
    }

    /// Runs the section over `y` in place, starting from state `z`.
    pub(crate) fn run_from(&self, y: &mut [f64], z: [f64; 2]) {
        let mut s = Self { z, ..*self };
        for v in y.iter_mut() {
            *v = s.step(*v);
        }
    }

    /// Discretises `ωn² / (s² + 2ζωn s + ωn²)` by the bilinear transform
    /// pre-warped at the natural frequency. The bilinear transform maps the
    /// stable left half-plane into the unit disc, so the filter is stable for
    /// every ζ > 0 and every rate; the DC gain is exactly 1.
    ///
    /// ```
    /// let mut f = iir::Biquad::low_pass(100.0, 0.7, 4000.0);
    /// // A 1-kHz tone, a decade above the corner, is attenuated by ~40 dB.
    /// let mut peak: f64 = 0.0;
    /// for n in 0..4000 {
    ///     let y = f.step((2.0 * std::f64::consts::PI * 1000.0 * n as f64 / 4000.0).sin());
    ///     if n > 2000 { peak = peak.max(y.abs()); }
    /// }
    /// assert!(peak < 0.02);
    /// ```
    #[track_caller]
    pub fn low_pass(natural_hz: f64, damping: f64, sample_rate_hz: f64) -> Self {
        assert!(
            natural_hz > 0.0 && natural_hz < 0.5 * sample_rate_hz,
            "natural frequency {natural_hz} Hz must be below Nyquist ({} Hz)",
            0.5 * sample_rate_hz
        );
        assert!(damping > 0.0, "damping must be positive");
        let w = (std::f64::consts::PI * natural_hz / sample_rate_hz).tan();
        let a0 = 1.0 + 2.0 * damping * w + w * w;
        Self {
            b: [w * w / a0, 2.0 * w * w / a0, w * w / a0],
            a: [
                (2.0 * w * w - 2.0) / a0,
                (1.0 - 2.0 * damping * w + w * w) / a0,
            ],
            z: [0.0; 2],
        }
    }

    /// A band-pass of unit gain at `centre_hz` with quality factor `q`
    /// (RBJ cookbook, constant 0 dB peak gain).
    ///
    /// ```
    /// use iir::Biquad;
    /// let (fs, f0) = (4000.0, 400.0);
    /// let mut bp = Biquad::band_pass(f0, 10.0, fs);
    /// let mut ms = 0.0;
    /// for n in 0..40_000 {
    ///     let y = bp.step((2.0 * std::f64::consts::PI * f0 * n as f64 / fs).sin());
    ///     if n >= 20_000 { ms += y * y / 20_000.0; }
    /// }
    /// assert!((ms - 0.5).abs() < 1e-3);
    /// ```
    #[track_caller]
    pub fn band_pass(centre_hz: f64, q: f64, sample_rate_hz: f64) -> Self {
        assert!(
            centre_hz > 0.0 && centre_hz < 0.5 * sample_rate_hz,
            "centre frequency {centre_hz} Hz must be below Nyquist ({} Hz)",
            0.5 * sample_rate_hz
        );
        assert!(q > 0.0, "quality factor must be positive");
        let w0 = 2.0 * std::f64::consts::PI * centre_hz / sample_rate_hz;
        let alpha = w0.sin() / (2.0 * q);
        let a0 = 1.0 + alpha;
        Self {
            b: [alpha / a0, 0.0, -alpha / a0],
            a: [-2.0 * w0.cos() / a0, (1.0 - alpha) / a0],
            z: [0.0; 2],
        }
    }

    /// Filters one sample.
    ///
    /// ```
    /// let mut f = iir::Biquad::band_pass(400.0, 10.0, 4000.0);
    /// assert_eq!(f.step(0.0), 0.0);
    /// ```
    #[inline]
    pub fn step(&mut self, x: f64) -> f64 {
        let y = self.b[0] * x + self.z[0];
        self.z[0] = self.b[1] * x - self.a[0] * y + self.z[1];
        self.z[1] = self.b[2] * x - self.a[1] * y;
        y
    }

    /// Sets the state to the steady state of a constant input `x` (for a
    /// low-pass this avoids a start-up transient).
    ///
    /// ```
    /// let mut f = iir::Biquad::low_pass(100.0, 0.7, 4000.0);
    /// f.settle(1.0);
    /// assert!((f.step(1.0) - 1.0).abs() < 1e-12);
    /// ```
    pub fn settle(&mut self, x: f64) {
        let y = self.dc_gain() * x;
        self.z[1] = self.b[2] * x - self.a[1] * y;
        self.z[0] = self.b[1] * x - self.a[0] * y + self.z[1];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn low_pass_is_stable_and_has_unit_gain_at_low_frequency_even_near_nyquist() {
        for &(fnat, zeta) in &[(800.0, 0.7), (1900.0, 0.05), (10.0, 2.0)] {
            let mut f = Biquad::low_pass(fnat, zeta, 4000.0);
            let mut peak: f64 = 0.0;
            for n in 0..20_000 {
                let y = f.step(if n == 0 { 1.0 } else { 0.0 });
                if n > 15_000 {
                    peak = peak.max(y.abs());
                }
            }
            assert!(
                peak < 1e-6,
                "impulse response decays ({fnat} Hz, ζ {zeta}): {peak}"
            );
        }
    }
}
