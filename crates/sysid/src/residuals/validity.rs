//! Correlation-based model validity tests: whiteness, independence from an
//! input, and the Billings–Voon nonlinear tests, each with per-lag
//! confidence bands and a named pass/fail decision.
//!
//! The decision is a max-statistic with a Bonferroni correction over the lags
//! tested: a test with 50 lags at 99% would otherwise "fail" by chance on one
//! lag in two records. Bands come from Bartlett's formula, so filtered
//! (coloured) series are judged fairly; ρ_e(eu)'s band is its own variance
//! under the null, because e·u and e are not two independent series.

use super::correlation::{
    InputAutocovariance, autocorrelation, bartlett_auto_variance, bartlett_cross_variance,
    bartlett_truncation, cross_correlation, residual_times_input_variance_with,
};
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, Normal};

/// Which null hypothesis a correlation test examines (residual e, input u,
/// u²' = u² − mean(u²)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CorrelationKind {
    /// ρ_ee(τ) equals the reference autocorrelation (δ(τ) for white noise, or
    /// that of white noise through the pre-filter).
    Whiteness,
    /// ρ_ue(τ) = 0 for all τ: nothing linear in u is left in e.
    Independence,
    /// Billings–Voon ρ_e(eu)(τ) = 0, τ ≥ 0: no product of past residual and
    /// input is left (a missing cross term). Its band is the correlation's
    /// variance under the null that e is independent of u, not Bartlett's
    /// formula for two independent series: e·u and e share e, and a residual
    /// correlated over the model's memory makes the spread at short lags
    /// larger than Bartlett's formula says.
    ResidualTimesInput,
    /// Billings–Voon ρ_u²'e(τ) = 0: no even (squared) function of u is left in e.
    SquaredInput,
    /// Billings–Voon ρ_u²'e²(τ) = 0: the residual's variance does not follow u²
    /// (a multiplicative or level-dependent error). Bartlett's band, whose
    /// null is e independent of u: a band from the products' own spread
    /// would widen with the very error it looks for and lose most of its
    /// power.
    SquaredInputSquaredResidual,
}

impl CorrelationKind {
    /// A short name for tables and plots.
    pub fn name(self) -> &'static str {
        match self {
            Self::Whiteness => "whiteness",
            Self::Independence => "independence",
            Self::ResidualTimesInput => "billings_voon_e_eu",
            Self::SquaredInput => "billings_voon_u2_e",
            Self::SquaredInputSquaredResidual => "billings_voon_u2_e2",
        }
    }
}

/// One correlation test's curve, bands and verdict.
#[derive(Debug, Clone, Serialize)]
pub struct CorrelationCheck {
    /// The hypothesis examined.
    pub kind: CorrelationKind,
    /// Lags in samples, in the order of `values`.
    pub lags: Vec<i64>,
    /// Sample correlation at each lag.
    pub values: Vec<f64>,
    /// What the correlation should be under the null hypothesis.
    pub expected: Vec<f64>,
    /// Half-width of the per-lag band at `confidence` (Bartlett's formula;
    /// for `billings_voon_e_eu` the variance under e independent of u, see
    /// [`residual_times_input_variance`](super::residual_times_input_variance)).
    pub band: Vec<f64>,
    /// Per-lag confidence of `band`, e.g. 0.99.
    pub confidence: f64,
    /// Largest standardised deviation max |value − expected| / σ.
    pub statistic: f64,
    /// The lag where it occurs.
    pub worst_lag: i64,
    /// Bonferroni threshold on `statistic` for the family of lags.
    pub threshold: f64,
    /// `statistic ≤ threshold`.
    pub passed: bool,
}

/// Two-sided standard-normal quantile for confidence `c`.
fn z_two_sided(c: f64) -> f64 {
    Normal::new(0.0, 1.0)
        .expect("unit normal")
        .inverse_cdf(0.5 + c / 2.0)
}

#[track_caller]
fn check_confidence(confidence: f64) {
    assert!(
        confidence > 0.0 && confidence < 1.0,
        "confidence {confidence} must be in (0, 1)"
    );
}

fn verdict(
    kind: CorrelationKind,
    lags: Vec<i64>,
    values: Vec<f64>,
    expected: Vec<f64>,
    sigma: Vec<f64>,
    confidence: f64,
) -> CorrelationCheck {
    let z = z_two_sided(confidence);
    let m = lags.len().max(1) as f64;
    let threshold = z_two_sided(1.0 - (1.0 - confidence) / m);
    let (mut statistic, mut worst_lag) = (0.0, lags.first().copied().unwrap_or(0));
    for ((&lag, (v, e)), s) in lags.iter().zip(values.iter().zip(&expected)).zip(&sigma) {
        let d = (v - e).abs() / s.max(f64::MIN_POSITIVE);
        if d > statistic {
            statistic = d;
            worst_lag = lag;
        }
    }
    CorrelationCheck {
        kind,
        band: sigma.iter().map(|s| z * s).collect(),
        lags,
        values,
        expected,
        confidence,
        statistic,
        worst_lag,
        threshold,
        passed: statistic <= threshold,
    }
}

/// Whiteness test on lags 1..=max_lag. `reference` is the autocorrelation the
/// residual should have under the null hypothesis (lag 0 first): `None` means
/// white noise; pass the autocorrelation of white noise through the
/// pre-processing filter when the data were filtered. Bartlett's
/// first-order variance understates the spread at lags where ρ is near 1, so
/// decimate a low-passed residual to about twice its cut-off first (those
/// lags carry no information anyway).
///
/// ```
/// use sysid::residuals::whiteness;
/// // A deterministic pseudo-random sequence (LCG) is white; its running sum is not.
/// let mut s = 12345u64;
/// let e: Vec<f64> = (0..2000).map(|_| { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5 }).collect();
/// assert!(whiteness(&e, 25, None, 0.99).passed);
/// let walk: Vec<f64> = e.iter().scan(0.0, |a, v| { *a += v; Some(*a) }).collect();
/// assert!(!whiteness(&walk, 25, None, 0.99).passed);
/// ```
#[track_caller]
pub fn whiteness(
    e: &[f64],
    max_lag: usize,
    reference: Option<&[f64]>,
    confidence: f64,
) -> CorrelationCheck {
    check_confidence(confidence);
    assert!(max_lag >= 1, "whiteness needs at least lag 1");
    let n = e.len();
    let r = autocorrelation(e, max_lag);
    let white = [1.0];
    let rho = reference.unwrap_or(&white);
    let lags: Vec<i64> = (1..=max_lag as i64).collect();
    let expected: Vec<f64> = (1..=max_lag)
        .map(|k| rho.get(k).copied().unwrap_or(0.0))
        .collect();
    let sigma: Vec<f64> = (1..=max_lag)
        .map(|k| bartlett_auto_variance(rho, k, n).sqrt())
        .collect();
    verdict(
        CorrelationKind::Whiteness,
        lags,
        r[1..].to_vec(),
        expected,
        sigma,
        confidence,
    )
}

/// Whiteness beyond the model's memory: the residual may be correlated over
/// `memory` lags (a network on a one-second window errs alike on
/// overlapping windows, and the pre-filter smears each error), but not
/// beyond. Tests ρ(k) = 0 on lags memory+1..=memory+max_lag with Bartlett's
/// variance for a series correlated up to `memory` lags, (1 + 2Σ_{j≤memory} ρ̂(j)²)/N.
///
/// This is the question a user asks of a residual ("is something slow left
/// that the model could not explain?") without the null hypothesis that the
/// residual is the sensor's noise alone, which no finite model meets.
///
/// ```
/// use sysid::residuals::whiteness_beyond;
/// let mut s = 99u64;
/// let mut next = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5 };
/// let w: Vec<f64> = (0..3000).map(|_| next()).collect();
/// // A moving sum over 10 samples is correlated over 9 lags only …
/// let ma: Vec<f64> = w.windows(10).map(|x| x.iter().sum()).collect();
/// assert!(whiteness_beyond(&ma, 9, 20, 0.99).passed);
/// // … a slow drift added to it is not.
/// let drift: Vec<f64> = ma.iter().enumerate().map(|(i, v)| v + (i as f64 / 400.0).sin()).collect();
/// assert!(!whiteness_beyond(&drift, 9, 20, 0.99).passed);
/// ```
#[track_caller]
pub fn whiteness_beyond(
    e: &[f64],
    memory: usize,
    max_lag: usize,
    confidence: f64,
) -> CorrelationCheck {
    check_confidence(confidence);
    assert!(max_lag >= 1, "whiteness needs at least one lag");
    let n = e.len();
    let top = (memory + max_lag).min(n.saturating_sub(1));
    let r = autocorrelation(e, top);
    let within: f64 = r[1..=memory.min(top)].iter().map(|v| v * v).sum();
    let sigma = ((1.0 + 2.0 * within) / n as f64).sqrt();
    let lags: Vec<i64> = (memory + 1..=top).map(|k| k as i64).collect();
    let m = lags.len();
    verdict(
        CorrelationKind::Whiteness,
        lags,
        r[memory + 1..=top].to_vec(),
        vec![0.0; m],
        vec![sigma; m],
        confidence,
    )
}

/// Cross-correlation test of `a` against `b` on the given lags (positive lag
/// pairs `a` now with `b` later), with Bartlett bands from both series'
/// sample autocorrelations.
fn cross_test(
    kind: CorrelationKind,
    a: &[f64],
    b: &[f64],
    lags: std::ops::RangeInclusive<i64>,
    confidence: f64,
) -> CorrelationCheck {
    check_confidence(confidence);
    let n = a.len();
    let max_lag = lags.start().unsigned_abs().max(lags.end().unsigned_abs()) as usize;
    let r = cross_correlation(a, b, max_lag);
    let k = bartlett_truncation(n);
    let var = bartlett_cross_variance(&autocorrelation(a, k), &autocorrelation(b, k), n);
    let lags: Vec<i64> = lags.collect();
    let values: Vec<f64> = lags
        .iter()
        .map(|&l| r[(l + max_lag as i64) as usize])
        .collect();
    let m = lags.len();
    verdict(
        kind,
        lags,
        values,
        vec![0.0; m],
        vec![var.sqrt(); m],
        confidence,
    )
}

/// Billings–Voon ρ_e(eu)(τ) on τ = 0..=max_lag, reported as lags
/// 1..=max_lag+1 of e·u against e (as before), with the variance under the
/// null that e is independent of u
/// ([`residual_times_input_variance`](super::residual_times_input_variance)), not
/// Bartlett's formula for two independent series: e·u and e share e.
fn residual_times_input_test(
    ec: &[f64],
    uc: &[f64],
    max_lag: usize,
    confidence: f64,
) -> CorrelationCheck {
    check_confidence(confidence);
    let top = (max_lag + 1).min(ec.len().saturating_sub(1));
    let eu: Vec<f64> = ec.iter().zip(uc).map(|(a, b)| a * b).collect();
    let r = cross_correlation(&eu, ec, top);
    let lags: Vec<i64> = (1..=top as i64).collect();
    let values: Vec<f64> = lags.iter().map(|&l| r[top + l as usize]).collect();
    // u's lagged products are the same at every τ: worked out once.
    let u_acov = InputAutocovariance::new(uc);
    let sigma: Vec<f64> = lags
        .iter()
        .map(|&l| residual_times_input_variance_with(ec, uc, &u_acov, l as usize).sqrt())
        .collect();
    let m = lags.len();
    verdict(
        CorrelationKind::ResidualTimesInput,
        lags,
        values,
        vec![0.0; m],
        sigma,
        confidence,
    )
}

/// Independence test: the residual `e` is uncorrelated with the input `u` at
/// every lag in −max_lag..=max_lag.
///
/// ```
/// use sysid::residuals::independence;
/// let mut s = 3u64;
/// let mut next = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5 };
/// let u: Vec<f64> = (0..1000).map(|_| next()).collect();
/// let clean: Vec<f64> = (0..1000).map(|_| next()).collect();
/// assert!(independence(&clean, &u, 20, 0.99).passed);
/// // A residual that still holds part of the input fails.
/// let leak: Vec<f64> = u.iter().zip(&clean).map(|(a, b)| 0.5 * a + b).collect();
/// assert!(!independence(&leak, &u, 20, 0.99).passed);
/// ```
#[track_caller]
pub fn independence(e: &[f64], u: &[f64], max_lag: usize, confidence: f64) -> CorrelationCheck {
    let l = max_lag as i64;
    cross_test(CorrelationKind::Independence, u, e, -l..=l, confidence)
}

/// The Billings–Voon nonlinear correlation tests (Billings & Voon 1986) of a
/// residual `e` against an input `u`: ρ_e(eu)(τ) on τ = 0..max_lag (as lags
/// 1..=max_lag+1 of e·u against e), ρ_u²'e(τ) and ρ_u²'e²(τ) on
/// −max_lag..=max_lag.
///
/// The null of all three is e independent of u. ρ_u²'e and ρ_u²'e² have
/// Bartlett's band (u² against e or e², independent series under the
/// null); ρ_e(eu) has the variance of its own statistic under that null,
/// [`residual_times_input_variance`](super::residual_times_input_variance),
/// since e·u and e are never independent.
///
/// ```
/// use sysid::residuals::{billings_voon, CorrelationKind};
/// // Uniform pseudo-random numbers from a 64-bit LCG.
/// let mut s = 7u64;
/// let mut next = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5 };
/// // A residual that still holds u² fails the squared-input test.
/// let u: Vec<f64> = (0..2000).map(|_| next()).collect();
/// let e: Vec<f64> = u.iter().map(|v| v * v + 0.05 * next()).collect();
/// let tests = billings_voon(&e, &u, 10, 0.99);
/// let sq = tests.iter().find(|t| t.kind == CorrelationKind::SquaredInput).unwrap();
/// assert!(!sq.passed);
/// ```
#[track_caller]
pub fn billings_voon(
    e: &[f64],
    u: &[f64],
    max_lag: usize,
    confidence: f64,
) -> Vec<CorrelationCheck> {
    assert_eq!(e.len(), u.len(), "residual and input lengths differ");
    let l = max_lag as i64;
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
    let (me, mu) = (mean(e), mean(u));
    let ec: Vec<f64> = e.iter().map(|v| v - me).collect();
    let uc: Vec<f64> = u.iter().map(|v| v - mu).collect();
    let u2: Vec<f64> = uc.iter().map(|v| v * v).collect();
    let e2: Vec<f64> = ec.iter().map(|v| v * v).collect();
    vec![
        residual_times_input_test(&ec, &uc, max_lag, confidence),
        cross_test(CorrelationKind::SquaredInput, &u2, &ec, -l..=l, confidence),
        cross_test(
            CorrelationKind::SquaredInputSquaredResidual,
            &u2,
            &e2,
            -l..=l,
            confidence,
        ),
    ]
}
