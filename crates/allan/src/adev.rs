//! The overlapping Allan deviation (IEEE Std 952-1997 Annex C, IEEE Std
//! 1293-2018 Annex; NIST SP 1065 eq. 14) of a rate series.

use super::error::AllanError;

/// Overlapping Allan deviation of the rate samples `y` (each the mean rate
/// over one interval τ₀, any unit) at τ = m·τ₀ for each averaging factor in
/// `factors`, in the unit of `y`.
///
/// With the angle x_k = τ₀·Σ_{j<k} y_j (N + 1 points for N rates):
///
/// ```text
/// σ²(mτ₀) = Σ_{k=0}^{N−2m} (x_{k+2m} − 2x_{k+m} + x_k)² / (2 (N − 2m + 1) (mτ₀)²)
/// ```
///
/// that is, half the mean square difference of consecutive m-sample means,
/// taken at every start sample. The series' mean is removed first: the
/// result does not depend on it, and the running sums then stay small, so
/// a 15 deg/h Earth-rate offset does not cost digits.
///
/// ```
/// use allan::overlapping_adev;
/// // A ramp y_k = a·k·τ₀: consecutive m-means differ by a·mτ₀, so σ = a·τ/√2 exactly.
/// let a = 0.5; // deg/h per s
/// let y: Vec<f64> = (0..1000).map(|k| a * k as f64 * 0.02).collect();
/// let adev = overlapping_adev(&y, 0.02, &[1, 10, 100]).unwrap();
/// for (m, s) in [1.0, 10.0, 100.0].iter().zip(&adev) {
///     assert!((s - a * m * 0.02 / 2f64.sqrt()).abs() < 1e-12 * s);
/// }
/// ```
pub fn overlapping_adev(y: &[f64], tau0_s: f64, factors: &[usize]) -> Result<Vec<f64>, AllanError> {
    if !(tau0_s.is_finite() && tau0_s > 0.0) {
        return Err(AllanError::BadInterval { tau0_s });
    }
    if let Some((index, &value)) = y.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(AllanError::NonFinite { index, value });
    }
    for &m in factors {
        if m == 0 {
            return Err(AllanError::ZeroFactor);
        }
        if y.len() < 2 * m + 1 {
            return Err(AllanError::TooShort {
                samples: y.len(),
                m,
                need: 2 * m + 1,
            });
        }
    }
    let n = y.len();
    let mean = y.iter().sum::<f64>() / n as f64;
    // Angle in units of τ₀ (the τ₀ of the angle and of the 1/τ cancel).
    let mut x = Vec::with_capacity(n + 1);
    x.push(0.0);
    let mut acc = 0.0;
    for v in y {
        acc += v - mean;
        x.push(acc);
    }
    Ok(factors
        .iter()
        .map(|&m| {
            let terms = n + 1 - 2 * m;
            let s: f64 = (0..terms)
                .map(|k| {
                    let d = x[k + 2 * m] - 2.0 * x[k + m] + x[k];
                    d * d
                })
                .sum();
            (s / (2.0 * terms as f64)).sqrt() / m as f64
        })
        .collect())
}

/// Octave-spaced averaging factors 1, 2, 4, … up to `n / 10` (a tenth of
/// the record): beyond, fewer than about ten independent differences are
/// left and the estimate's confidence interval spans a factor of two.
/// Always at least `[1]` when `n ≥ 3`; empty below.
///
/// ```
/// use allan::octave_factors;
/// assert_eq!(octave_factors(5000), vec![1, 2, 4, 8, 16, 32, 64, 128, 256]);
/// assert_eq!(octave_factors(12), vec![1]);
/// assert!(octave_factors(2).is_empty());
/// ```
pub fn octave_factors(n: usize) -> Vec<usize> {
    if n < 3 {
        return Vec::new();
    }
    let max = (n / 10).max(1);
    std::iter::successors(Some(1usize), |m| m.checked_mul(2))
        .take_while(|&m| m <= max)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn white(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..n)
            .map(|_| {
                let z: f64 = StandardNormal.sample(&mut rng);
                sigma * z
            })
            .collect()
    }

    /// A direct transcription of the definition (means of m samples,
    /// every start), against the running-sum form.
    #[test]
    fn equals_the_definition_by_means() {
        let y: Vec<f64> = white(301, 1.0, 3).iter().map(|v| v + 15.0).collect();
        let factors = [1, 2, 3, 7, 50, 150];
        let fast = overlapping_adev(&y, 0.02, &factors).unwrap();
        for (&m, f) in factors.iter().zip(&fast) {
            let mean = |i: usize| y[i..i + m].iter().sum::<f64>() / m as f64;
            let terms = y.len() + 1 - 2 * m;
            let s: f64 = (0..terms).map(|k| (mean(k + m) - mean(k)).powi(2)).sum();
            let slow = (s / (2.0 * terms as f64)).sqrt();
            assert!((f - slow).abs() < 1e-12 * slow, "m={m}: {f} vs {slow}");
        }
    }

    /// White rate noise of standard deviation σ per sample: σ(mτ₀) = σ/√m,
    /// i.e. σ(τ) = σ·√(τ₀/τ). Over 200,000 samples the estimate at m ≤ 64
    /// has a relative standard deviation below 2.5% (EDF ≥ 800): 4σ bound 10%.
    #[test]
    fn white_noise_falls_as_one_over_root_tau() {
        let sigma = 0.3;
        let y = white(200_000, sigma, 7);
        let factors = [1, 4, 16, 64];
        let adev = overlapping_adev(&y, 0.02, &factors).unwrap();
        for (&m, s) in factors.iter().zip(&adev) {
            let expected = sigma / (m as f64).sqrt();
            assert!((s / expected - 1.0).abs() < 0.1, "m={m}: {s} vs {expected}");
        }
        // The shortest τ, where the estimate is tightest (EDF ≈ 89,000): 1.5%.
        assert!((adev[0] / sigma - 1.0).abs() < 0.015);
    }

    /// A random walk of the rate, b_{k+1} = b_k + q·w_k, sampled (not
    /// averaged) per interval: σ²(mτ₀) = q²·(2m² + 1)/(6m) (NIST SP 1065's
    /// discrete form), which tends to q²·m/3, the √(τ/3) slope.
    #[test]
    fn random_walk_rises_as_root_tau_over_three() {
        let q = 0.01;
        let mut b = 0.0;
        let y: Vec<f64> = white(400_000, q, 11)
            .into_iter()
            .map(|w| {
                b += w;
                b
            })
            .collect();
        let factors = [4, 16, 64];
        let adev = overlapping_adev(&y, 1.0, &factors).unwrap();
        for (&m, s) in factors.iter().zip(&adev) {
            let m = m as f64;
            let expected = q * ((2.0 * m * m + 1.0) / (6.0 * m)).sqrt();
            // EDF of a random walk at m = 64 over 400,000 samples ≈ 6,000.
            assert!((s / expected - 1.0).abs() < 0.1, "m={m}: {s} vs {expected}");
        }
        let slope = (adev[2] / adev[0]).ln() / (16f64).ln();
        assert!((slope - 0.5).abs() < 0.05, "slope {slope}");
    }

    #[test]
    fn a_constant_has_zero_deviation_and_the_mean_does_not_matter() {
        let y = white(500, 1.0, 5);
        let shifted: Vec<f64> = y.iter().map(|v| v + 1e6).collect();
        let a = overlapping_adev(&y, 0.1, &[1, 8, 32]).unwrap();
        let b = overlapping_adev(&shifted, 0.1, &[1, 8, 32]).unwrap();
        for (a, b) in a.iter().zip(&b) {
            assert!((a - b).abs() < 1e-9 * a);
        }
        assert_eq!(
            overlapping_adev(&[2.5; 20], 0.1, &[1, 5]).unwrap(),
            vec![0.0, 0.0]
        );
    }

    #[test]
    fn refusals_name_the_problem() {
        assert_eq!(
            overlapping_adev(&[1.0; 10], 0.02, &[5]).unwrap_err(),
            AllanError::TooShort {
                samples: 10,
                m: 5,
                need: 11
            }
        );
        assert!(overlapping_adev(&[1.0; 11], 0.02, &[5]).is_ok());
        assert_eq!(
            overlapping_adev(&[1.0; 10], 0.0, &[1]).unwrap_err(),
            AllanError::BadInterval { tau0_s: 0.0 }
        );
        assert_eq!(
            overlapping_adev(&[1.0; 10], 0.02, &[0]).unwrap_err(),
            AllanError::ZeroFactor
        );
        let err = overlapping_adev(&[1.0, f64::NAN, 1.0], 0.02, &[1]).unwrap_err();
        assert!(matches!(err, AllanError::NonFinite { index: 1, .. }));
    }
}
