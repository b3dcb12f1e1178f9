//! Equivalent degrees of freedom of the overlapping Allan variance and the
//! chi-square confidence interval they give.
//!
//! The EDF are the simple approximations of Howe, Allan & Barnes
//! ("Properties of signal sources and measurement methods", 1981), as
//! tabulated in NIST SP 1065 Table 5 and used by IEEE Std 952 Annex C, per
//! power-law noise. N there is the number of angle (phase) points: one more
//! than the number of rate samples.

use super::error::AllanError;
use super::identify::PowerLaw;
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// EDF of the overlapping Allan variance at averaging factor `m` on
/// `samples` rate samples, for the noise `noise`, at least 1 and at most
/// the number of squared differences summed (N − 2m).
///
/// ```
/// use allan::{edf_overlapping, PowerLaw};
/// // White rate noise, 5000 samples: ≈ 3332 at m = 1, ≈ 27.3 at m = 256.
/// assert!((edf_overlapping(5000, 1, PowerLaw::WhiteRate) - 3332.4).abs() < 0.1);
/// assert!((edf_overlapping(5000, 256, PowerLaw::WhiteRate) - 27.3).abs() < 0.1);
/// ```
pub fn edf_overlapping(samples: usize, m: usize, noise: PowerLaw) -> f64 {
    let n = samples as f64 + 1.0; // phase points
    let m_f = m.max(1) as f64;
    let edf = match noise {
        PowerLaw::WhiteAngle => (n + 1.0) * (n - 2.0 * m_f) / (2.0 * (n - m_f)),
        PowerLaw::FlickerAngle => {
            let a = (n - 1.0) / (2.0 * m_f);
            let b = (2.0 * m_f + 1.0) * (n - 1.0) / 4.0;
            if a > 1.0 && b > 1.0 {
                (a.ln() * b.ln()).sqrt().exp()
            } else {
                1.0
            }
        }
        PowerLaw::WhiteRate => {
            (3.0 * (n - 1.0) / (2.0 * m_f) - 2.0 * (n - 2.0) / n) * (4.0 * m_f * m_f)
                / (4.0 * m_f * m_f + 5.0)
        }
        PowerLaw::FlickerRate => {
            if m == 1 {
                2.0 * (n - 2.0) / (2.3 * n - 4.9)
            } else {
                5.0 * n * n / (4.0 * m_f * (n + 3.0 * m_f))
            }
        }
        PowerLaw::RandomWalkRate => {
            (n - 2.0) / (m_f * (n - 3.0).powi(2))
                * ((n - 1.0).powi(2) - 3.0 * m_f * (n - 1.0) + 4.0 * m_f * m_f)
        }
    };
    let terms = (n - 2.0 * m_f).max(1.0);
    if edf.is_finite() {
        edf.clamp(1.0, terms)
    } else {
        1.0
    }
}

/// Two-sided chi-square confidence interval of a deviation σ̂ estimated
/// with `edf` degrees of freedom, at `confidence` (e.g. 0.683):
/// `[σ̂·√(edf/χ²_{(1+c)/2}), σ̂·√(edf/χ²_{(1−c)/2})]`.
///
/// ```
/// use allan::deviation_interval;
/// let (lo, hi) = deviation_interval(1.0, 100.0, 0.683).unwrap();
/// // Relative half-width ≈ 1/√(2·edf) = 7%.
/// assert!(lo < 1.0 && hi > 1.0 && (lo - 0.93).abs() < 0.01 && (hi - 1.08).abs() < 0.01, "{lo} {hi}");
/// ```
pub fn deviation_interval(sigma: f64, edf: f64, confidence: f64) -> Result<(f64, f64), AllanError> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(AllanError::BadConfidence(confidence));
    }
    let chi = ChiSquared::new(edf.max(f64::MIN_POSITIVE))
        .expect("a positive finite EDF is a valid chi-square parameter");
    let upper = chi.inverse_cdf(0.5 + confidence / 2.0);
    let lower = chi.inverse_cdf(0.5 - confidence / 2.0);
    Ok((sigma * (edf / upper).sqrt(), sigma * (edf / lower).sqrt()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// NIST SP 1065 Table 5's formulas at a few hand-computed points.
    #[test]
    fn matches_the_tabulated_formulas() {
        // N = 1001 phase points, m = 10.
        let n = 1001.0_f64;
        let cases = [
            (
                PowerLaw::WhiteAngle,
                (n + 1.0) * (n - 20.0) / (2.0 * (n - 10.0)),
            ),
            (
                PowerLaw::FlickerAngle,
                (((n - 1.0) / 20.0).ln() * (21.0 * (n - 1.0) / 4.0).ln())
                    .sqrt()
                    .exp(),
            ),
            (
                PowerLaw::WhiteRate,
                (3.0 * (n - 1.0) / 20.0 - 2.0 * (n - 2.0) / n) * 400.0 / 405.0,
            ),
            (PowerLaw::FlickerRate, 5.0 * n * n / (40.0 * (n + 30.0))),
            (
                PowerLaw::RandomWalkRate,
                (n - 2.0) / (10.0 * (n - 3.0).powi(2))
                    * ((n - 1.0).powi(2) - 30.0 * (n - 1.0) + 400.0),
            ),
        ];
        for (noise, expected) in cases {
            let e = edf_overlapping(1000, 10, noise);
            assert!(
                (e - expected).abs() < 1e-9 * expected,
                "{noise:?}: {e} vs {expected}"
            );
        }
    }

    #[test]
    fn more_samples_more_freedom_longer_tau_less() {
        for noise in [
            PowerLaw::WhiteAngle,
            PowerLaw::FlickerAngle,
            PowerLaw::WhiteRate,
            PowerLaw::FlickerRate,
            PowerLaw::RandomWalkRate,
        ] {
            assert!(edf_overlapping(10_000, 8, noise) > edf_overlapping(1_000, 8, noise));
            assert!(edf_overlapping(10_000, 8, noise) > edf_overlapping(10_000, 64, noise));
            let e = edf_overlapping(100, 10, noise);
            assert!((1.0..=81.0).contains(&e), "{noise:?}: {e}");
        }
    }

    #[test]
    fn interval_brackets_the_estimate_and_narrows_with_freedom() {
        let (l1, h1) = deviation_interval(2.0, 10.0, 0.9).unwrap();
        let (l2, h2) = deviation_interval(2.0, 1000.0, 0.9).unwrap();
        assert!(l1 < l2 && l2 < 2.0 && 2.0 < h2 && h2 < h1);
        assert!(deviation_interval(1.0, 10.0, 1.0).is_err());
    }
}
