//! IIR filters, one type for the workspace: the second-order section
//! [`Biquad`] (a sensor model's servo loop and detector run single
//! sections) and the Butterworth [`LowPass`], a cascade of them, applied
//! causally or with zero phase (forward–backward, as scipy's `sosfiltfilt`)
//! to sensor records before identification; and [`welch`]'s spectrum, which
//! judges what such filters leave.
//!
//! Its own crate because both the sensor models (`nav-sensors`) and the
//! identification loop (`sysid`) filter and take spectra, and neither
//! depends on the other.
//!
//! ```
//! let lp = iir::LowPass::butterworth(4, 5.0, 50.0)?;
//! assert!((lp.gain_at(5.0) - 0.5_f64.sqrt()).abs() < 1e-12);
//! let y = lp.filtfilt(&vec![1.0; 200])?;
//! assert!((y[100] - 1.0).abs() < 1e-9);
//! # Ok::<(), iir::FilterError>(())
//! ```

mod biquad;
mod butterworth;
mod error;
mod filtfilt;
mod spectrum;

pub use biquad::Biquad;
pub use butterworth::{LowPass, MAX_ORDER, MIN_CUTOFF_PER_RATE};
pub use error::FilterError;
pub use spectrum::{Spectrum, welch};

/// A number as a reader would type it: plain in the usual range, in
/// exponent form beyond (1e308 printed plainly is 309 digits).
///
/// ```
/// # use iir::num;
/// assert_eq!(num(5.0), "5");
/// assert_eq!(num(1e308), "1e308");
/// assert_eq!(num(1e-9), "1e-9");
/// ```
pub fn num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference values from scipy 1.17.1:
    //   signal.butter(4, 5.0, fs=50.0, output='sos'); signal.butter(3, 2.0, fs=50.0, output='sos')
    //   signal.sosfiltfilt(sos3, np.sin(np.arange(40)*0.3) + 0.1*np.arange(40))
    // scipy keeps the overall gain in the first section and we spread it, so
    // compare the poles (denominators) and the end-to-end outputs.
    #[test]
    fn denominators_match_scipy() {
        let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
        let mut den: Vec<[f64; 2]> = lp.sections().iter().map(|s| s.a).collect();
        den.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let want = [
            [-1.3209134308194264, 0.6327387928852766],
            [-1.0485995763626117, 0.2961403575616696],
        ];
        for (g, w) in den.iter().zip(&want) {
            assert!(
                (g[0] - w[0]).abs() < 1e-13 && (g[1] - w[1]).abs() < 1e-13,
                "{g:?} vs {w:?}"
            );
        }
        let gain: f64 = lp.sections().iter().map(|s| s.b[0]).product();
        assert!((gain - 0.00482434335771623).abs() < 1e-16);
    }

    #[test]
    fn odd_order_filtfilt_matches_scipy() {
        let lp = LowPass::butterworth(3, 2.0, 50.0).unwrap();
        assert_eq!(lp.pad_len(), 3 * (2 * 2 + 1 - 1));
        let x: Vec<f64> = (0..40)
            .map(|i| (i as f64 * 0.3).sin() + 0.1 * i as f64)
            .collect();
        let y = lp.filtfilt(&x).unwrap();
        let want = [
            -0.0131486222079035,
            0.17759165040956063,
            0.3581455793962438,
            0.5223668723522613,
            0.6654365229352506,
            0.7842595276920205,
            0.877724981141838,
            0.9468040103856513,
            0.9944743216630325,
            1.0254755933872832,
            1.045915136903651,
            1.0627567582351223,
            1.083236346791006,
            1.1142544136838688,
            1.161797982755261,
            1.2304416943000587,
            1.322970939149376,
            1.4401589350829298,
            1.5807158784538757,
            1.74141290597755,
            1.9173679904087426,
            2.1024664983005663,
            2.2898772805246637,
            2.4726169413555885,
            2.6441111054668758,
            2.798702438970286,
            2.932060807892492,
            3.041460767198081,
            3.1259046635440555,
            3.186084785875749,
            3.2241937783137744,
            3.243607421436832,
            3.2484764204258205,
            3.2432727198961295,
            3.232340100067309,
            3.2194977907150077,
            3.207739411060385,
            3.199058020219117,
            3.1944122131454544,
            3.193829187812936,
        ];
        for (i, (g, w)) in y.iter().zip(&want).enumerate() {
            assert!((g - w).abs() < 1e-11, "sample {i}: {g} vs {w}");
        }
    }

    #[test]
    fn magnitude_is_maximally_flat_and_minus_3db_at_cutoff_for_all_orders() {
        for order in 1..=MAX_ORDER {
            let lp = LowPass::butterworth(order, 3.0, 50.0).unwrap();
            assert!((lp.gain_at(0.0) - 1.0).abs() < 1e-12, "order {order}");
            assert!(
                (lp.gain_at(3.0) - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-10,
                "order {order}"
            );
            // Monotone decreasing magnitude.
            let g: Vec<f64> = (0..=250).map(|i| lp.gain_at(i as f64 * 0.1)).collect();
            assert!(g.windows(2).all(|w| w[1] <= w[0] + 1e-12), "order {order}");
        }
    }

    #[test]
    fn filtfilt_has_zero_phase_and_squared_magnitude() {
        let fs = 50.0;
        let lp = LowPass::butterworth(4, 5.0, fs).unwrap();
        for &f in &[1.0, 3.0, 5.0, 8.0] {
            let x: Vec<f64> = (0..5000)
                .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 / fs).sin())
                .collect();
            let y = lp.filtfilt(&x).unwrap();
            let g = lp.gain_at(f).powi(2);
            // In the middle, y is x scaled by |H|² with no shift.
            let err = x
                .iter()
                .zip(&y)
                .skip(1000)
                .take(3000)
                .map(|(a, b)| (g * a - b).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-6, "f = {f} Hz: {err}");
        }
    }

    #[test]
    fn each_validation_rule_has_its_error() {
        assert!(matches!(
            LowPass::butterworth(0, 1.0, 50.0),
            Err(FilterError::Order { .. })
        ));
        assert!(matches!(
            LowPass::butterworth(13, 1.0, 50.0),
            Err(FilterError::Order { .. })
        ));
        assert!(matches!(
            LowPass::butterworth(2, 25.0, 50.0),
            Err(FilterError::Cutoff { .. })
        ));
        assert!(matches!(
            LowPass::butterworth(2, -1.0, 50.0),
            Err(FilterError::Cutoff { .. })
        ));
        assert!(matches!(
            LowPass::butterworth(2, f64::NAN, 50.0),
            Err(FilterError::Cutoff { .. })
        ));
        assert!(matches!(
            LowPass::butterworth(2, 1.0, 0.0),
            Err(FilterError::SampleRate { .. })
        ));
        let lp = LowPass::butterworth(2, 1.0, 50.0).unwrap();
        assert!(matches!(
            lp.filtfilt(&[1.0; 9]),
            Err(FilterError::TooShort { len: 9, min: 10 })
        ));
        let mut x = vec![0.0; 100];
        x[42] = f64::NAN;
        assert_eq!(lp.filtfilt(&x), Err(FilterError::NotFinite { index: 42 }));
    }
}
