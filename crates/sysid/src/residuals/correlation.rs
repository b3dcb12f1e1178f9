//! Sample auto- and cross-correlation, and Bartlett's variance of a sample
//! correlation between two autocorrelated series.
//!
//! Bartlett's formula is why the bands here are honest on filtered data: the
//! usual ±1.96/√N band assumes at least one of the two series is white. After
//! a low-pass both residual and input are coloured, and the plain band would
//! flag "dependence" that is only shared smoothness.

/// Subtracts the mean; `None` when the series has zero variance.
fn centred(x: &[f64]) -> Option<(Vec<f64>, f64)> {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let c: Vec<f64> = x.iter().map(|v| v - mean).collect();
    let ss = c.iter().map(|v| v * v).sum::<f64>();
    (ss > 0.0 && ss.is_finite()).then_some((c, ss))
}

/// Normalised sample autocorrelation ρ(τ) for τ = 0..=max_lag (biased
/// estimator, ρ(0) = 1). A constant series gives all zeros but ρ(0) = 1.
///
/// ```
/// use sysid::residuals::autocorrelation;
/// let x: Vec<f64> = (0..100).map(|i| if i % 2 == 0 { 1.0 } else { -1.0 }).collect();
/// let r = autocorrelation(&x, 2);
/// assert_eq!(r[0], 1.0);
/// assert!((r[1] + 0.99).abs() < 1e-12 && (r[2] - 0.98).abs() < 1e-12);
/// ```
#[track_caller]
pub fn autocorrelation(x: &[f64], max_lag: usize) -> Vec<f64> {
    assert!(
        max_lag < x.len(),
        "max_lag {max_lag} must be below the series length {}",
        x.len()
    );
    let mut r = vec![0.0; max_lag + 1];
    r[0] = 1.0;
    let Some((c, ss)) = centred(x) else {
        return r;
    };
    let mut sums = vec![0.0; max_lag + 1];
    super::lag_sums::lag_sums_into(&c, &mut sums);
    for (rt, s) in r.iter_mut().zip(&sums).skip(1) {
        *rt = s / ss;
    }
    r
}

/// Normalised sample cross-correlation r_ab(τ) = Σ a(t)·b(t+τ) / (N σ_a σ_b)
/// for τ = −max_lag..=max_lag, returned in that order (index `max_lag` is
/// lag 0). A positive lag pairs `a` now with `b` later.
///
/// ```
/// use sysid::residuals::cross_correlation;
/// let a: Vec<f64> = (0..200).map(|i| ((i * 7919) % 13) as f64).collect();
/// let mut b = vec![0.0; 200];
/// b[3..].copy_from_slice(&a[..197]); // b lags a by 3 samples
/// let r = cross_correlation(&a, &b, 5);
/// let best = (0..r.len()).max_by(|&i, &j| r[i].total_cmp(&r[j])).unwrap();
/// assert_eq!(best as i64 - 5, 3);
/// ```
#[track_caller]
pub fn cross_correlation(a: &[f64], b: &[f64], max_lag: usize) -> Vec<f64> {
    assert_eq!(a.len(), b.len(), "series lengths differ");
    assert!(
        max_lag < a.len(),
        "max_lag {max_lag} must be below the series length {}",
        a.len()
    );
    let mut r = vec![0.0; 2 * max_lag + 1];
    let (Some((ca, sa)), Some((cb, sb))) = (centred(a), centred(b)) else {
        return r;
    };
    let norm = (sa * sb).sqrt();
    let n = a.len();
    for (k, rk) in r.iter_mut().enumerate() {
        let tau = k as i64 - max_lag as i64;
        let s: f64 = if tau >= 0 {
            let t = tau as usize;
            ca[..n - t].iter().zip(&cb[t..]).map(|(x, y)| x * y).sum()
        } else {
            let t = (-tau) as usize;
            ca[t..].iter().zip(&cb[..n - t]).map(|(x, y)| x * y).sum()
        };
        *rk = s / norm;
    }
    r
}

/// How many lags of each autocorrelation enter Bartlett's sums: enough to
/// cover the memory of a low-pass filtered series, few enough that the
/// sample autocorrelation's own noise does not dominate.
pub fn bartlett_truncation(n: usize) -> usize {
    (n / 4).clamp(1, 500).min(n.saturating_sub(1))
}

/// Bartlett's variance of the sample cross-correlation of two independent
/// stationary series, given their autocorrelations ρ_a, ρ_b (lags 0..):
/// var ≈ (1/N) Σ_{k=−K..K} ρ_a(k) ρ_b(k), with a triangular taper so the
/// estimate stays positive. For white `a` it reduces to 1/N.
///
/// `N / (N · var)` is the effective number of independent samples.
///
/// ```
/// use sysid::residuals::bartlett_cross_variance;
/// let white = [1.0, 0.0, 0.0, 0.0];
/// let smooth = [1.0, 0.9, 0.8, 0.7];
/// assert!((bartlett_cross_variance(&white, &smooth, 100) - 0.01).abs() < 1e-15);
/// assert!(bartlett_cross_variance(&smooth, &smooth, 100) > 0.01);
/// ```
#[track_caller]
pub fn bartlett_cross_variance(rho_a: &[f64], rho_b: &[f64], n: usize) -> f64 {
    assert!(
        !rho_a.is_empty() && !rho_b.is_empty(),
        "autocorrelations must hold lag 0"
    );
    let k = rho_a.len().min(rho_b.len());
    let mut s = rho_a[0] * rho_b[0];
    for j in 1..k {
        let taper = 1.0 - j as f64 / k as f64;
        s += 2.0 * taper * rho_a[j] * rho_b[j];
    }
    // Between one effective sample and N: never claim more independent
    // samples than there are.
    s.clamp(1.0, n as f64) / n as f64
}

/// Bartlett's variance of the sample autocorrelation at lag `tau` of a
/// series whose true autocorrelation is `rho` (lags 0..):
/// var ≈ (1/N) Σ_k [ρ(k)² + ρ(k+τ)ρ(k−τ) − 4ρ(τ)ρ(k)ρ(k−τ) + 2ρ(k)²ρ(τ)²].
///
/// ```
/// use sysid::residuals::bartlett_auto_variance;
/// let white = [1.0, 0.0, 0.0];
/// assert!((bartlett_auto_variance(&white, 1, 400) - 1.0 / 400.0).abs() < 1e-15);
/// ```
#[track_caller]
pub fn bartlett_auto_variance(rho: &[f64], tau: usize, n: usize) -> f64 {
    assert!(!rho.is_empty(), "autocorrelation must hold lag 0");
    let at = |k: i64| -> f64 { rho.get(k.unsigned_abs() as usize).copied().unwrap_or(0.0) };
    let (t, kmax) = (tau as i64, rho.len() as i64 + tau as i64);
    let rt = at(t);
    let s: f64 = (-kmax..=kmax)
        .map(|k| {
            let rk = at(k);
            rk * rk + at(k + t) * at(k - t) - 4.0 * rt * rk * at(k - t) + 2.0 * rk * rk * rt * rt
        })
        .sum();
    s.max(0.0) / n as f64
}

/// Variance of the Billings–Voon correlation ρ_e(eu)(τ) = corr(e·u, e(t+τ))
/// under its null hypothesis, the residual `e` independent of the input `u`
/// (both centred, equal lengths, τ ≥ 0).
///
/// Bartlett's formula for two independent series does not apply: e·u and e
/// share e. With p(t) = e(t)·e(t+τ) the correlation's numerator is Σ u(t)·p(t),
/// and under the null u is independent of p, so its variance is
/// (N−τ) Σ_k (1 − |k|/K) γ_u(k) M_p(k), with γ_u u's autocovariance and M_p
/// p's *uncentred* second moment at lag k (K as in [`bartlett_truncation`]).
/// Bartlett's formula misses M_p's mean part, γ_e(τ)²·Σγ_u(k), which
/// dominates at the lags where the residual is correlated with itself.
///
/// ```
/// use sysid::residuals::residual_times_input_variance;
/// // White, independent ±1 series: about 1/N at every lag.
/// let mut s = 9u64;
/// let mut sign = move || { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); if s >> 63 == 0 { -1.0 } else { 1.0 } };
/// let e: Vec<f64> = (0..4000).map(|_| sign()).collect();
/// let u: Vec<f64> = (0..4000).map(|_| sign()).collect();
/// let v = residual_times_input_variance(&e, &u, 1);
/// assert!((v * 4000.0 - 1.0).abs() < 0.1, "{v}");
/// ```
#[track_caller]
pub fn residual_times_input_variance(e: &[f64], u: &[f64], tau: usize) -> f64 {
    assert_eq!(e.len(), u.len(), "series lengths differ");
    let n = e.len();
    assert!(tau < n, "lag {tau} must be below the series length {n}");
    residual_times_input_variance_with(e, u, &InputAutocovariance::new(u), tau)
}

/// u's lagged mean products `Σ u_t u_{t+k} / N` for every lag the Bartlett
/// sum of [`residual_times_input_variance`] reads: they do not depend on
/// τ, so a test over many lags works them out once.
pub(crate) struct InputAutocovariance(Vec<f64>);

impl InputAutocovariance {
    pub(crate) fn new(u: &[f64]) -> Self {
        let n = u.len();
        let k_max = bartlett_truncation(n).min(n);
        let mut sums = vec![0.0; k_max.max(1)];
        super::lag_sums::lag_sums_into(u, &mut sums);
        Self(sums.into_iter().map(|s| s / n as f64).collect())
    }
}

/// [`residual_times_input_variance`] with u's lagged products worked out.
pub(crate) fn residual_times_input_variance_with(
    e: &[f64],
    u: &[f64],
    u_acov: &InputAutocovariance,
    tau: usize,
) -> f64 {
    let n = e.len();
    let p: Vec<f64> = e[..n - tau]
        .iter()
        .zip(&e[tau..])
        .map(|(a, b)| a * b)
        .collect();
    let m = p.len();
    let k_max = bartlett_truncation(n).min(m);
    let mut sums = vec![0.0; k_max.max(1)];
    super::lag_sums::lag_sums_into(&p, &mut sums);
    let lagged = |k: usize| sums[k] / m as f64;
    let mut s = u_acov.0[0] * lagged(0);
    for k in 1..k_max {
        let taper = 1.0 - k as f64 / k_max as f64;
        s += 2.0 * taper * u_acov.0[k] * lagged(k);
    }
    let eu = e.iter().zip(u).map(|(a, b)| a * b);
    let mean_eu = eu.clone().sum::<f64>() / n as f64;
    let ss_eu: f64 = eu.map(|v| (v - mean_eu).powi(2)).sum();
    let ss_e: f64 = e.iter().map(|v| v * v).sum();
    let denom = ss_eu * ss_e;
    if !(denom > 0.0 && denom.is_finite()) {
        return 0.0;
    }
    (m as f64 * s).max(0.0) / denom
}
