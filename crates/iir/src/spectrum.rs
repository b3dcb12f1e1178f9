//! Welch's power spectral density estimate.

use rustfft::{FftPlanner, num_complex::Complex};

/// A single-sided power spectral density estimate.
///
/// ```
/// let x: Vec<f64> = (0..4096).map(|n| (n as f64 * 0.3).sin()).collect();
/// let s = iir::welch(&x, 1000.0, 256);
/// assert_eq!(s.frequency_hz.len(), s.density.len());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Bin frequencies, Hz (0 to fs/2).
    pub frequency_hz: Vec<f64>,
    /// Density in (unit of x)²/Hz, single-sided: ∑ density·Δf = variance.
    pub density: Vec<f64>,
}

impl Spectrum {
    /// Bin spacing, Hz.
    ///
    /// ```
    /// let s = iir::welch(&vec![0.0; 1024], 1000.0, 512);
    /// assert!((s.resolution_hz() - 1000.0 / 512.0).abs() < 1e-12);
    /// ```
    pub fn resolution_hz(&self) -> f64 {
        self.frequency_hz.get(1).copied().unwrap_or(0.0)
    }

    /// The variance within `[lo_hz, hi_hz]`: ∑ density·Δf over the bins in range.
    ///
    /// ```
    /// let fs = 100.0;
    /// let x: Vec<f64> = (0..10_000).map(|n| (2.0 * std::f64::consts::PI * 10.0 * n as f64 / fs).sin()).collect();
    /// let s = iir::welch(&x, fs, 1000);
    /// assert!((s.band_power(5.0, 15.0) - 0.5).abs() < 1e-3);
    /// ```
    pub fn band_power(&self, lo_hz: f64, hi_hz: f64) -> f64 {
        let df = self.resolution_hz();
        self.frequency_hz
            .iter()
            .zip(&self.density)
            .filter(|(f, _)| **f >= lo_hz && **f <= hi_hz)
            .map(|(_, d)| d * df)
            .sum()
    }
}

/// Welch's PSD: Hann-windowed segments of `segment_len` samples with 50%
/// overlap, each with its mean removed, periodograms averaged; single-sided
/// density (the bins between DC and Nyquist doubled), scaled so that a white
/// noise of variance σ² gives σ²/(fs/2) and `∑ density·Δf` is the variance.
///
/// Returns `segment_len/2 + 1` bins. Panics (programmer error) if
/// `segment_len < 2` or the signal is shorter than one segment.
///
/// ```
/// use iir::welch;
/// use rand::SeedableRng;
/// use rand_distr::{Distribution, StandardNormal};
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let x: Vec<f64> = (0..200_000).map(|_| StandardNormal.sample(&mut rng)).collect();
/// let s = welch(&x, 1000.0, 512);
/// let mean: f64 = s.density[10..250].iter().sum::<f64>() / 240.0;
/// assert!((mean / (1.0 / 500.0) - 1.0).abs() < 0.02); // σ² / (fs/2)
/// ```
#[track_caller]
pub fn welch(x: &[f64], fs: f64, segment_len: usize) -> Spectrum {
    assert!(segment_len >= 2, "segment length of at least 2");
    assert!(
        x.len() >= segment_len,
        "signal of {} samples is shorter than one segment of {segment_len}",
        x.len()
    );
    let n = segment_len;
    let window: Vec<f64> = (0..n)
        .map(|k| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos())
        .collect();
    let w2: f64 = window.iter().map(|w| w * w).sum();
    let fft = FftPlanner::<f64>::new().plan_fft_forward(n);
    let step = (n / 2).max(1);
    let bins = n / 2 + 1;
    let mut acc = vec![0.0; bins];
    let mut count = 0usize;
    let mut buf = vec![Complex::new(0.0, 0.0); n];
    let mut start = 0;
    while start + n <= x.len() {
        let seg = &x[start..start + n];
        let mean = seg.iter().sum::<f64>() / n as f64;
        for ((b, &v), &w) in buf.iter_mut().zip(seg).zip(&window) {
            *b = Complex::new((v - mean) * w, 0.0);
        }
        fft.process(&mut buf);
        for (k, a) in acc.iter_mut().enumerate() {
            *a += buf[k].norm_sqr();
        }
        count += 1;
        start += step;
    }
    let scale = 1.0 / (fs * w2 * count as f64);
    let density = acc
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let one_sided = if k == 0 || (n.is_multiple_of(2) && k == n / 2) {
                1.0
            } else {
                2.0
            };
            a * scale * one_sided
        })
        .collect();
    let frequency_hz = (0..bins).map(|k| k as f64 * fs / n as f64).collect();
    Spectrum {
        frequency_hz,
        density,
    }
}
