//! Causal and zero-phase application of a second-order-section cascade.
//!
//! Zero phase matters here: the RBF maps a window of acceleration to the rate
//! error at the same instant, and a causal filter would delay the rate and
//! the acceleration by the same group delay only if both went through it —
//! filtering forward and backward removes the question.

use crate::{FilterError, LowPass};

impl LowPass {
    /// One causal pass from rest (zero initial state).
    ///
    /// ```
    /// use iir::LowPass;
    /// let lp = LowPass::butterworth(2, 1.0, 50.0).unwrap();
    /// let y = lp.filter(&vec![1.0; 500]);
    /// assert!((y[499] - 1.0).abs() < 1e-9); // a step settles at the DC gain
    /// assert!(y[0] < 0.01);                 // after starting from rest
    /// ```
    pub fn filter(&self, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        for s in self.sections() {
            s.run_from(&mut y, [0.0, 0.0]);
        }
        y
    }

    /// One causal pass started in the steady state of the first sample (as if
    /// the signal had held that value forever): what an on-line filter does
    /// from its first sample, without the start-up transient of
    /// [`LowPass::filter`] on a signal far from zero (a 1-g acceleration, a
    /// 15-deg/h Earth rate). Sample `n` of the result depends on samples
    /// `≤ n` only.
    ///
    /// ```
    /// use iir::LowPass;
    /// let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
    /// let y = lp.filter_causal(&vec![3.0; 50]);
    /// assert!(y.iter().all(|v| (v - 3.0).abs() < 1e-12)); // no transient
    /// let mut x = vec![0.0; 50];
    /// x[20] = 1.0;
    /// assert!(lp.filter_causal(&x)[..20].iter().all(|&v| v == 0.0)); // nothing before the impulse
    /// ```
    pub fn filter_causal(&self, x: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        if !y.is_empty() {
            self.run_with_state(&mut y, &self.steady_state());
        }
        y
    }

    /// Zero-phase filtering: forward then backward, with odd extension of
    /// [`LowPass::pad_len`] samples at both ends and steady-state initial
    /// conditions, as scipy's `sosfiltfilt` does (results agree with it to
    /// rounding). The magnitude response is the square of one pass
    /// (−6 dB at the cut-off); the phase is zero.
    ///
    /// ```
    /// use iir::LowPass;
    /// let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
    /// // A 0.5 Hz sine passes with no delay.
    /// let x: Vec<f64> = (0..1000).map(|i| (2.0 * std::f64::consts::PI * 0.5 * i as f64 / 50.0).sin()).collect();
    /// let y = lp.filtfilt(&x).unwrap();
    /// let worst = x.iter().zip(&y).skip(100).take(800).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    /// assert!(worst < 1e-3);
    /// // Too short a record is an error, not a silent garbage answer.
    /// assert!(lp.filtfilt(&x[..10]).is_err());
    /// ```
    pub fn filtfilt(&self, x: &[f64]) -> Result<Vec<f64>, FilterError> {
        let pad = self.pad_len();
        let n = x.len();
        if n <= pad {
            return Err(FilterError::TooShort {
                len: n,
                min: pad + 1,
            });
        }
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return Err(FilterError::NotFinite { index: i });
        }
        // Odd extension: reflect about the end values so the extension
        // continues the local slope instead of introducing a step.
        let mut ext = Vec::with_capacity(n + 2 * pad);
        ext.extend((1..=pad).rev().map(|i| 2.0 * x[0] - x[i]));
        ext.extend_from_slice(x);
        ext.extend((1..=pad).map(|i| 2.0 * x[n - 1] - x[n - 1 - i]));

        let zi = self.steady_state();
        self.run_with_state(&mut ext, &zi);
        ext.reverse();
        self.run_with_state(&mut ext, &zi);
        ext.reverse();
        Ok(ext[pad..pad + n].to_vec())
    }

    /// Autocorrelation of white noise after [`LowPass::filtfilt`], at lags
    /// 0, `step`, 2·`step`, … (`count` of them): the reference a whiteness
    /// test compares a filtered residual with.
    ///
    /// ```
    /// use iir::LowPass;
    /// let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
    /// let rho = lp.white_noise_acf(1, 30);
    /// assert_eq!(rho[0], 1.0);
    /// assert!(rho[1] > 0.9 && rho[29].abs() < 0.01); // smooth at lag 1, gone by lag 29
    /// ```
    pub fn white_noise_acf(&self, step: usize, count: usize) -> Vec<f64> {
        // The zero-phase impulse response, long enough for any sensible filter
        // and lag range.
        let half = 2000.max(2 * step * count);
        let mut impulse = vec![0.0; 2 * half + 1];
        impulse[half] = 1.0;
        let h = self
            .filtfilt(&impulse)
            .expect("an impulse is finite and long enough");
        let energy: f64 = h.iter().map(|v| v * v).sum();
        (0..count)
            .map(|i| i * step)
            .map(|k| {
                h[..h.len() - k]
                    .iter()
                    .zip(&h[k..])
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
                    / energy
            })
            .collect()
    }

    /// Runs the cascade with each section's state set to its steady state for
    /// a constant input equal to the first sample.
    fn run_with_state(&self, y: &mut [f64], zi: &[[f64; 2]]) {
        let x0 = y[0];
        for (s, z) in self.sections().iter().zip(zi) {
            s.run_from(y, [z[0] * x0, z[1] * x0]);
        }
    }

    /// Per-section states (transposed direct form II, `[z1, z2]`) that make
    /// a unit step a steady state of the cascade (scipy's `sosfilt_zi`): each
    /// section sees the DC gain of the sections before it. Scaled by the
    /// first sample, they start [`LowPass::filter_causal`].
    pub fn steady_state(&self) -> Vec<[f64; 2]> {
        let mut scale = 1.0;
        self.sections()
            .iter()
            .map(|s| {
                let g = s.dc_gain();
                // Transposed direct form II at rest under input 1, output g.
                let z2 = s.b[2] - s.a[1] * g;
                let z1 = s.b[1] - s.a[0] * g + z2;
                let z = [scale * z1, scale * z2];
                scale *= g;
                z
            })
            .collect()
    }
}
