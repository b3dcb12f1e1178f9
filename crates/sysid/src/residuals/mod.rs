//! Residual analysis as system identification does it: sample correlations
//! with honest (Bartlett) bands, and the correlation-based validity tests
//! (whiteness, independence, Billings–Voon) with named verdicts.

mod correlation;
mod lag_sums;
mod validity;

pub use correlation::{
    autocorrelation, bartlett_auto_variance, bartlett_cross_variance, bartlett_truncation,
    cross_correlation, residual_times_input_variance,
};
pub use validity::{
    CorrelationCheck, CorrelationKind, billings_voon, independence, whiteness, whiteness_beyond,
};

#[cfg(test)]
mod tests {
    use super::*;
    use iir::LowPass;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    fn noise(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
    }

    /// Under the null hypothesis the Bonferroni-corrected tests should pass
    /// in about `confidence` of the records: check the false-alarm rate over
    /// many independent records stays near 1 − confidence (here at most 4
    /// of 100 at 99%, a generous binomial bound: P(X ≥ 5 | p = 0.01) ≈ 0.003).
    #[test]
    fn false_alarm_rate_of_independence_on_filtered_noise_is_controlled() {
        let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
        let mut alarms = 0;
        for seed in 0..100 {
            let e = lp.filtfilt(&noise(2000, 2 * seed)).unwrap();
            let u = lp.filtfilt(&noise(2000, 2 * seed + 1)).unwrap();
            if !independence(&e, &u, 25, 0.99).passed {
                alarms += 1;
            }
        }
        assert!(alarms <= 4, "{alarms} false alarms in 100 filtered records");
    }

    /// The same filtered series with the naive ±z/√N band would alarm far
    /// more often: this is the case for Bartlett's band.
    #[test]
    fn naive_band_would_alarm_on_filtered_noise() {
        let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
        let mut naive_alarms = 0;
        for seed in 0..30 {
            let e = lp.filtfilt(&noise(2000, 1000 + 2 * seed)).unwrap();
            let u = lp.filtfilt(&noise(2000, 1001 + 2 * seed)).unwrap();
            let r = cross_correlation(&u, &e, 25);
            let naive = 2.576 / (2000f64).sqrt();
            if r.iter().any(|v| v.abs() > naive) {
                naive_alarms += 1;
            }
        }
        assert!(naive_alarms >= 10, "only {naive_alarms} naive alarms");
    }

    #[test]
    fn whiteness_with_filter_reference_accepts_filtered_noise_and_rejects_unfiltered_drift() {
        let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
        // Reference: autocorrelation of white noise through the same
        // zero-phase filter, decimated to twice the cut-off: Bartlett's
        // first-order variance is poor at lags where ρ is near 1, and those
        // lags carry no information.
        let q = 5;
        let reference = lp.white_noise_acf(q, 60);
        let mut passes = 0;
        for seed in 0..50 {
            let e = lp.filtfilt(&noise(10000, 500 + seed)).unwrap();
            let d: Vec<f64> = e.iter().step_by(q).copied().collect();
            if whiteness(&d, 25, Some(&reference), 0.99).passed {
                passes += 1;
            }
        }
        // Binomial bound at p = 0.01: P(X ≥ 4 of 50) ≈ 0.002.
        assert!(passes >= 47, "{passes}/50 filtered-noise records passed");
        // Filtered noise plus a slow sinusoidal drift (an unmodelled low-frequency effect) fails.
        let mut e = lp.filtfilt(&noise(10000, 77)).unwrap();
        let sd = (e.iter().map(|v| v * v).sum::<f64>() / 10000.0).sqrt();
        for (i, v) in e.iter_mut().enumerate() {
            *v += sd * (i as f64 * 0.005).sin();
        }
        let e: Vec<f64> = e.iter().step_by(q).copied().collect();
        let w = whiteness(&e, 25, Some(&reference), 0.99);
        assert!(
            !w.passed,
            "{:?} {:?} {:?}",
            &w.values[..5],
            &w.expected[..5],
            &w.band[..5]
        );
    }

    #[test]
    fn billings_voon_pass_on_independent_noise_and_catch_a_cross_term() {
        let u = noise(3000, 11);
        let w = noise(3000, 12);
        let ok = billings_voon(&w, &u, 10, 0.99);
        assert!(
            ok.iter().all(|t| t.passed),
            "{:?}",
            ok.iter().map(|t| (t.kind, t.statistic)).collect::<Vec<_>>()
        );
        // e(t) = w(t) + 0.5·w(t−1)·u(t−1): a missing residual×input term.
        let e: Vec<f64> = (0..3000)
            .map(|t| {
                if t == 0 {
                    w[0]
                } else {
                    w[t] + 0.5 * w[t - 1] * u[t - 1]
                }
            })
            .collect();
        let bad = billings_voon(&e, &u, 10, 0.99);
        let eu = bad
            .iter()
            .find(|t| t.kind == CorrelationKind::ResidualTimesInput)
            .unwrap();
        assert!(!eu.passed && eu.worst_lag == 1, "{eu:?}");
    }

    #[test]
    fn squared_residual_test_catches_level_dependent_noise() {
        let u = noise(3000, 21);
        let w = noise(3000, 22);
        let e: Vec<f64> = w.iter().zip(&u).map(|(a, b)| a * (0.2 + b.abs())).collect();
        let t = billings_voon(&e, &u, 10, 0.99);
        let sq2 = t
            .iter()
            .find(|t| t.kind == CorrelationKind::SquaredInputSquaredResidual)
            .unwrap();
        assert!(!sq2.passed && sq2.worst_lag == 0);
    }

    /// A multiplicative error e = (1 + k·u²)·ε, the residual's scale rising
    /// by 10% per unit u² (40% at two standard deviations of u), is caught
    /// by ρ_u²'e² at lag 0; the same ε without it passes.
    #[test]
    fn squared_residual_test_catches_a_multiplicative_error() {
        let u = noise(3000, 31);
        let w = noise(3000, 32);
        let find = |e: &[f64]| {
            billings_voon(e, &u, 10, 0.99)
                .into_iter()
                .find(|t| t.kind == CorrelationKind::SquaredInputSquaredResidual)
                .unwrap()
        };
        assert!(find(&w).passed);
        let e: Vec<f64> = w
            .iter()
            .zip(&u)
            .map(|(a, b)| (1.0 + 0.1 * b * b) * a)
            .collect();
        let t = find(&e);
        assert!(!t.passed && t.worst_lag == 0, "{t:?}");
    }

    /// ρ_e(eu) on a residual and an input that are independent but both
    /// low-pass filtered (so e is correlated with itself over the filter's
    /// memory): the long-run variance of the products keeps the false-alarm
    /// rate at its level. Bartlett's formula for independent series (e·u and
    /// e are not) misses the term ρ_e(τ)²·Σρ_u: over 400 such records its
    /// standardised values spread 1.33 at lag 1 instead of 1.
    #[test]
    fn false_alarm_rate_of_residual_times_input_on_filtered_noise_is_controlled() {
        let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
        let mut alarms = 0;
        for seed in 0..100 {
            let e = lp.filtfilt(&noise(2000, 4000 + 2 * seed)).unwrap();
            let u = lp.filtfilt(&noise(2000, 4001 + 2 * seed)).unwrap();
            let t = billings_voon(&e, &u, 10, 0.99);
            alarms += t
                .iter()
                .filter(|t| t.kind == CorrelationKind::ResidualTimesInput && !t.passed)
                .count();
        }
        // P(X ≥ 5 of 100 | p = 0.01) ≈ 0.003.
        assert!(alarms <= 4, "{alarms} false alarms in 100 filtered records");
    }

    #[test]
    fn constant_series_give_zero_correlation_not_nan() {
        let r = cross_correlation(&[1.0; 10], &[2.0; 10], 3);
        assert!(r.iter().all(|v| *v == 0.0));
        let a = autocorrelation(&[5.0; 10], 3);
        assert_eq!(a, vec![1.0, 0.0, 0.0, 0.0]);
    }
}
