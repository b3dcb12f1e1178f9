//! The vibration environment: PSD tables (with the NAVMAT P-9492 profile),
//! FFT synthesis of random vibration, sine and sweep, level schedules,
//! shaker drives with cross-axis motion and rocking, and Welch's PSD (from
//! the `iir` crate, which the identification loop shares).

mod environment;
mod psd;
mod schedule;
mod sine;
mod synth;

pub use environment::{Drive, Rocking, VibrationConfig, VibrationError, VibrationHistory};
pub use iir::{Spectrum, welch};
pub use psd::{PsdError, PsdTable};
pub use schedule::{LevelSchedule, Segment};
pub use sine::{sine, sweep};
pub use synth::{Motion, STANDARD_GRAVITY_M_S2, synthesize_random};

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// A 100-s NAVMAT history at 4 kHz, Welch with 4096-sample segments
    /// (0.98 Hz bins, ~195 averages): every bin inside the band, away from the
    /// band edges by two resolution widths (where the table's corner smears
    /// over the Hann main lobe), is within ±1.5 dB of the table.
    #[test]
    fn synthesised_navmat_matches_its_table_within_1_5_db_and_2_percent_rms() {
        let psd = PsdTable::navmat_p9492();
        let fs = 4000.0;
        let n = 400_000;
        let m = synthesize_random(&psd, n, fs, &mut Xoshiro256PlusPlus::seed_from_u64(42));
        let rms = (m.accel_g.iter().map(|a| a * a).sum::<f64>() / n as f64).sqrt();
        assert!(
            (rms / psd.grms() - 1.0).abs() < 0.02,
            "rms {rms} vs {}",
            psd.grms()
        );
        let s = welch(&m.accel_g, fs, 4096);
        let edge = 2.0 * s.resolution_hz();
        let mut worst: f64 = 0.0;
        let mut checked = 0;
        for (f, d) in s.frequency_hz.iter().zip(&s.density) {
            if *f >= 20.0 + edge && *f <= 2000.0 - edge {
                let db = 10.0 * (d / psd.density(*f)).log10();
                worst = worst.max(db.abs());
                checked += 1;
            }
        }
        eprintln!(
            "NAVMAT synthesis: rms {rms:.4} g (table {:.4} g), worst Welch deviation {worst:.3} dB over {checked} bins",
            psd.grms()
        );
        assert!(checked > 1900, "{checked} bins checked");
        assert!(worst < 1.5, "worst deviation {worst} dB");
    }

    #[test]
    fn velocity_is_the_integral_of_acceleration() {
        let psd = PsdTable::new(vec![[20.0, 0.1], [200.0, 0.1]]).unwrap();
        let fs = 4000.0;
        let m = synthesize_random(&psd, 40_000, fs, &mut Xoshiro256PlusPlus::seed_from_u64(5));
        // Trapezoidal integral over 2000 samples against the velocity change.
        let mut v = m.velocity_m_s[0];
        let mut worst: f64 = 0.0;
        for k in 1..2000 {
            v += 0.5 * (m.accel_g[k - 1] + m.accel_g[k]) * STANDARD_GRAVITY_M_S2 / fs;
            worst = worst.max((v - m.velocity_m_s[k]).abs());
        }
        let v_rms = (m.velocity_m_s.iter().map(|x| x * x).sum::<f64>() / 40_000.0).sqrt();
        assert!(worst < 0.01 * v_rms, "{worst} vs rms {v_rms}");
    }

    #[test]
    fn sine_and_sweep_stay_below_nyquist_or_error() {
        let cfg = VibrationConfig {
            drives: vec![Drive::Sine {
                axis: crate::geometry::Axis::Z,
                frequency_hz: 2500.0,
                amplitude_g: 1.0,
                phase_deg: 0.0,
                transverse: Default::default(),
            }],
            ..Default::default()
        };
        let err = cfg
            .generate(10, 4000.0, &mut Xoshiro256PlusPlus::seed_from_u64(0))
            .unwrap_err();
        assert!(
            matches!(err, VibrationError::AboveNyquist { index: 0, .. }),
            "{err}"
        );
    }

    /// The log sweep's instantaneous frequency goes from f0 to f1: count
    /// zero crossings over the first and last 0.5 s.
    #[test]
    fn log_sweep_starts_at_f0_and_ends_at_f1() {
        let fs = 4000.0;
        let n = 80_000; // 20 s
        let m = sweep(20.0, 200.0, 1.0, n, fs);
        let crossings = |x: &[f64]| x.windows(2).filter(|w| w[0] * w[1] < 0.0).count() as f64;
        let half = 2000; // 0.5 s
        let f_start = crossings(&m.accel_g[..half]) / 2.0 / 0.5;
        let f_end = crossings(&m.accel_g[n - half..]) / 2.0 / 0.5;
        // Mean frequency over the first/last 0.5 s of a 20-s decade sweep:
        // within 6% of the end points.
        assert!((f_start / 20.0 - 1.0).abs() < 0.1, "{f_start}");
        assert!((f_end / 200.0 - 1.0).abs() < 0.06, "{f_end}");
    }
}
