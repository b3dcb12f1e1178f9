//! Random vibration by FFT synthesis from a PSD table.

use rand::Rng;
use rustfft::{FftPlanner, num_complex::Complex};

use super::psd::PsdTable;

/// Standard gravity, m/s² per g.
///
/// ```
/// assert_eq!(nav_sensors::vibration::STANDARD_GRAVITY_M_S2, 9.80665);
/// ```
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;

/// A synthesised vibration time history on one axis.
///
/// ```
/// let m = nav_sensors::vibration::sine(10.0, 1.0, 0.0, 400, 4000.0);
/// assert_eq!(m.accel_g.len(), m.velocity_m_s.len());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Acceleration, g.
    pub accel_g: Vec<f64>,
    /// Velocity, m/s (the exact integral of the acceleration, zero mean).
    pub velocity_m_s: Vec<f64>,
}

/// Synthesises `n` samples at `fs` Hz of stationary random vibration with the
/// single-sided PSD `psd` (g²/Hz).
///
/// Random-phase multisine: every FFT bin k (spacing Δf = fs/n) inside the
/// table gets the amplitude `√(2·S(f_k)·Δf)` and a uniform random phase, and
/// one inverse FFT makes the time history (periodic over n samples). The
/// spectrum is then exactly the table at every bin, the amplitudes are
/// Gaussian by the central limit theorem, and the velocity comes from the
/// same spectrum divided by i·2πf (no integration drift). This is how shaker
/// controllers drive random tests. Bins at 0 Hz and Nyquist are left empty.
///
/// ```
/// use nav_sensors::vibration::{synthesize_random, PsdTable};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
/// let m = synthesize_random(&PsdTable::navmat_p9492(), 40_000, 4000.0, &mut rng);
/// let rms = (m.accel_g.iter().map(|a| a * a).sum::<f64>() / 40_000.0).sqrt();
/// assert!((rms / PsdTable::navmat_p9492().grms() - 1.0).abs() < 0.01);
/// ```
#[track_caller]
pub fn synthesize_random(psd: &PsdTable, n: usize, fs: f64, rng: &mut impl Rng) -> Motion {
    assert!(n >= 4, "at least 4 samples");
    let df = fs / n as f64;
    let mut spec = vec![Complex::new(0.0, 0.0); n];
    // Acceleration X_k in the real part's spectrum, velocity V_k = X_k/(iω)
    // in the imaginary part's: the inverse FFT of X + iV is x + i·v.
    for k in 1..n.div_ceil(2) {
        let f = k as f64 * df;
        // Draw the phase for every bin, in or out of band, so a change of
        // table does not shift the random sequence of the other bins.
        let phase: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
        let s = psd.density(f);
        if s <= 0.0 {
            continue;
        }
        let half_amp = 0.5 * (2.0 * s * df).sqrt();
        let x = Complex::from_polar(half_amp, phase);
        let omega = std::f64::consts::TAU * f;
        let v = x * Complex::new(0.0, -STANDARD_GRAVITY_M_S2 / omega); // X/(iω)·g0
        let i = Complex::new(0.0, 1.0);
        spec[k] += x + i * v;
        spec[n - k] += x.conj() + i * v.conj();
    }
    FftPlanner::<f64>::new()
        .plan_fft_inverse(n)
        .process(&mut spec);
    Motion {
        accel_g: spec.iter().map(|c| c.re).collect(),
        velocity_m_s: spec.iter().map(|c| c.im).collect(),
    }
}
