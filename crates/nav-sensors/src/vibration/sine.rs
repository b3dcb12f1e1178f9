//! Sine and logarithmic sine-sweep vibration.

use super::synth::{Motion, STANDARD_GRAVITY_M_S2};

/// A sine of `amplitude_g` (peak) at `frequency_hz`, with phase in degrees.
///
/// ```
/// let m = nav_sensors::vibration::sine(100.0, 2.0, 0.0, 400, 4000.0);
/// let ms = m.accel_g.iter().map(|a| a * a).sum::<f64>() / 400.0;
/// assert!((ms - 2.0).abs() < 1e-12); // A²/2
/// ```
pub fn sine(frequency_hz: f64, amplitude_g: f64, phase_deg: f64, n: usize, fs: f64) -> Motion {
    let w = std::f64::consts::TAU * frequency_hz;
    let p = phase_deg.to_radians();
    let (accel_g, velocity_m_s) = (0..n)
        .map(|k| {
            let t = k as f64 / fs;
            let arg = w * t + p;
            (
                amplitude_g * arg.sin(),
                -amplitude_g * STANDARD_GRAVITY_M_S2 / w * arg.cos(),
            )
        })
        .unzip();
    Motion {
        accel_g,
        velocity_m_s,
    }
}

/// A logarithmic sweep from `start_hz` to `end_hz` over the `n` samples, of
/// constant peak `amplitude_g`. Instantaneous frequency
/// `f(t) = f0·(f1/f0)^(t/T)`; the velocity uses the instantaneous frequency
/// (exact for slow sweeps).
///
/// ```
/// let m = nav_sensors::vibration::sweep(20.0, 2000.0, 1.0, 40_000, 4000.0);
/// assert_eq!(m.accel_g.len(), 40_000);
/// assert!(m.accel_g.iter().all(|a| a.abs() <= 1.0));
/// ```
pub fn sweep(start_hz: f64, end_hz: f64, amplitude_g: f64, n: usize, fs: f64) -> Motion {
    let duration = n as f64 / fs;
    let ratio = end_hz / start_hz;
    let ln_r = ratio.ln();
    let (accel_g, velocity_m_s) = (0..n)
        .map(|k| {
            let t = k as f64 / fs;
            let (phase, f) = if ln_r.abs() < 1e-12 {
                (std::f64::consts::TAU * start_hz * t, start_hz)
            } else {
                let x = ratio.powf(t / duration);
                (
                    std::f64::consts::TAU * start_hz * duration / ln_r * (x - 1.0),
                    start_hz * x,
                )
            };
            let w = std::f64::consts::TAU * f;
            (
                amplitude_g * phase.sin(),
                -amplitude_g * STANDARD_GRAVITY_M_S2 / w * phase.cos(),
            )
        })
        .unzip();
    Motion {
        accel_g,
        velocity_m_s,
    }
}
