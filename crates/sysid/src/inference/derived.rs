//! Quantities derived from several coefficients of one fit, with 95%
//! intervals from the fit's joint covariance: a linear combination exactly
//! (its variance wᵀΣw), a smooth function by the delta method (gᵀΣg, g its
//! gradient at the estimate), and the magnitude of a complex linear
//! combination (a FIR's response over a band) by projecting the 2-D 95%
//! region of its real and imaginary parts, which stays valid where the
//! magnitude is zero and the delta method is not.
//!
//! The FIR helpers read a family of taps (`index` in the fit, `lag` in
//! samples) of one stimulus: its mean response over a band, and its delay
//! (the phase delay of that mean response over the lowest band).
//!
//! Intervals use the fit's own Student-t quantile (read back from any of
//! its coefficients, whose intervals are value ± t·se), so a derived
//! quantity of one tap has exactly that tap's interval.

use super::Coefficient;

/// 95% quantile of χ² with two degrees of freedom: −2 ln 0.05.
const CHI2_2_95: f64 = 5.991_464_547_107_979;

/// The normal 97.5% quantile (the t quantile's limit).
const Z975: f64 = 1.959_963_984_540_054;

/// Why derived intervals cannot be given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DerivedError {
    /// The fit kept no joint covariance (a model file written before it did).
    #[error(
        "the fit kept no joint covariance of its coefficients (a model written before it did): fit again for derived intervals"
    )]
    NoCovariance,
    /// No coefficient has a standard error, so no interval quantile.
    #[error("no coefficient has a positive standard error")]
    NoInterval,
}

/// The coefficients of one fit, for derived quantities.
///
/// ```
/// use sysid::inference::{Coefficient, Derived};
/// // Two taps, se 0.1 and 0.2, covariance −0.01, t = 2 (ci = value ± 2 se).
/// let a = Coefficient::new(1.0, 0.1, [0.8, 1.2], "u").with_covariance(vec![0.01, -0.01]);
/// let b = Coefficient::new(2.0, 0.2, [1.6, 2.4], "u").with_covariance(vec![-0.01, 0.04]);
/// let coefs = [a.clone(), b];
/// let d = Derived::new(&coefs).unwrap();
/// let sum = d.linear(&[(0, 1.0), (1, 1.0)], "u");
/// assert!((sum.value - 3.0).abs() < 1e-12 && (sum.se - 0.03f64.sqrt()).abs() < 1e-12);
/// assert!((sum.ci95[1] - 3.0 - 2.0 * 0.03f64.sqrt()).abs() < 1e-12);
/// // One tap alone: its own interval.
/// assert_eq!(d.linear(&[(0, 1.0)], "u").ci95, a.ci95);
/// ```
#[derive(Debug, Clone)]
pub struct Derived<'a> {
    coefs: &'a [Coefficient],
    t: f64,
}

impl<'a> Derived<'a> {
    /// The fit's coefficients, each with its row of the joint covariance.
    ///
    /// # Errors
    /// [`DerivedError::NoCovariance`] when a coefficient lacks its row,
    /// [`DerivedError::NoInterval`] when none has a standard error.
    pub fn new(coefs: &'a [Coefficient]) -> Result<Self, DerivedError> {
        if coefs.is_empty() || coefs.iter().any(|c| c.cov.len() != coefs.len()) {
            return Err(DerivedError::NoCovariance);
        }
        let t = coefs
            .iter()
            .find(|c| c.se > 0.0 && c.se.is_finite())
            .map(|c| (c.ci95[1] - c.value) / c.se)
            .filter(|t| t.is_finite() && *t > 0.0)
            .ok_or(DerivedError::NoInterval)?;
        Ok(Self { coefs, t })
    }

    /// The Student-t quantile the fit's 95% intervals use.
    pub fn t_quantile(&self) -> f64 {
        self.t
    }

    /// The estimate Σ w_i θ_i of sparse weights `(index, w)`.
    pub fn value(&self, w: &[(usize, f64)]) -> f64 {
        w.iter().map(|&(i, x)| x * self.coefs[i].value).sum()
    }

    /// The covariance aᵀ Σ b of two sparse weight vectors.
    pub fn covariance(&self, a: &[(usize, f64)], b: &[(usize, f64)]) -> f64 {
        a.iter()
            .map(|&(i, x)| {
                x * b
                    .iter()
                    .map(|&(j, y)| y * self.coefs[i].cov[j])
                    .sum::<f64>()
            })
            .sum()
    }

    /// A linear combination Σ w_i θ_i with its exact interval.
    pub fn linear(&self, w: &[(usize, f64)], unit: &str) -> Coefficient {
        self.delta(self.value(w), w, unit)
    }

    /// A smooth function of the coefficients, `value` at the estimate and
    /// `gradient` there (sparse), by the delta method.
    pub fn delta(&self, value: f64, gradient: &[(usize, f64)], unit: &str) -> Coefficient {
        let se = self.covariance(gradient, gradient).max(0.0).sqrt();
        let h = self.t * se;
        Coefficient::new(value, se, [value - h, value + h], unit)
    }

    /// The magnitude and phase (degrees) of the complex combination
    /// Σ (re_i + j·im_i) θ_i. The magnitude's interval is the range of
    /// |v| over the 95% ellipse of v = (Re, Im) (χ²₂, widened by the fit's
    /// t over the normal quantile): at least 95%, and valid at zero, where
    /// its lower end is 0. Its `se` is the delta method's. The phase (delta
    /// method) is given only where the ellipse excludes zero.
    pub fn magnitude(
        &self,
        re: &[(usize, f64)],
        im: &[(usize, f64)],
        unit: &str,
    ) -> (Coefficient, Option<Coefficient>) {
        let v = [self.value(re), self.value(im)];
        let s = [
            [self.covariance(re, re), self.covariance(re, im)],
            [self.covariance(re, im), self.covariance(im, im)],
        ];
        let m = v[0].hypot(v[1]);
        let c = CHI2_2_95 * (self.t / Z975).powi(2);
        let [lo, hi] = ellipse_range(v, s, c);
        let grad = |a: f64, b: f64| -> Vec<(usize, f64)> {
            re.iter()
                .map(|&(i, x)| (i, a * x))
                .chain(im.iter().map(|&(i, y)| (i, b * y)))
                .collect()
        };
        let se = match m > 0.0 {
            true => self
                .covariance(&grad(v[0] / m, v[1] / m), &grad(v[0] / m, v[1] / m))
                .max(0.0)
                .sqrt(),
            false => s[0][0].max(s[1][1]).max(0.0).sqrt(),
        };
        let gain = Coefficient::new(m, se, [lo, hi], unit);
        let phase = (lo > 0.0).then(|| {
            let g = grad(-v[1] / (m * m), v[0] / (m * m));
            let deg = 180.0 / std::f64::consts::PI;
            let p = self.delta(v[1].atan2(v[0]) * deg, &g, "deg");
            let h = p.se * deg;
            Coefficient::new(
                p.value,
                h,
                [p.value - self.t * h, p.value + self.t * h],
                "deg",
            )
        });
        (gain, phase)
    }
}

/// The range of |v| over the ellipse {v̂ + u : uᵀ S⁻¹ u ≤ c}: its boundary
/// traced at 1440 points through S's eigenvectors (so a singular S, a line
/// segment, is handled); 0 at the low end when the origin lies inside.
fn ellipse_range(v: [f64; 2], s: [[f64; 2]; 2], c: f64) -> [f64; 2] {
    let (a, b, d) = (s[0][0], s[0][1], s[1][1]);
    let mid = 0.5 * (a + d);
    let rad = (0.25 * (a - d).powi(2) + b * b).sqrt();
    let l = [(mid + rad).max(0.0), (mid - rad).max(0.0)];
    let e0 = match b.abs() > 0.0 {
        true => {
            let (x, y) = (l[0] - d, b);
            let n = x.hypot(y);
            [x / n, y / n]
        }
        false if a >= d => [1.0, 0.0],
        false => [0.0, 1.0],
    };
    let e1 = [-e0[1], e0[0]];
    let r = [(c * l[0]).sqrt(), (c * l[1]).sqrt()];
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for k in 0..1440 {
        let phi = k as f64 * std::f64::consts::TAU / 1440.0;
        let (p, q) = (r[0] * phi.cos(), r[1] * phi.sin());
        let m = (v[0] + p * e0[0] + q * e1[0]).hypot(v[1] + p * e0[1] + q * e1[1]);
        lo = lo.min(m);
        hi = hi.max(m);
    }
    // The origin inside: Mahalanobis distance of −v̂ within c.
    let along = [v[0] * e0[0] + v[1] * e0[1], v[0] * e1[0] + v[1] * e1[1]];
    let maha = along
        .iter()
        .zip(l)
        .map(|(x, l)| match l > 0.0 {
            true => x * x / l,
            false if x.abs() <= 1e-300 => 0.0,
            false => f64::INFINITY,
        })
        .sum::<f64>();
    if maha <= c {
        lo = 0.0;
    }
    [lo, hi]
}

/// A family of FIR taps of one stimulus: each tap's index among the fit's
/// coefficients and its lag, samples.
pub type Taps = [(usize, usize)];

/// `n` equal frequency bands from 0 to the Nyquist frequency of the
/// sampling interval `dt_s`, Hz.
///
/// ```
/// assert_eq!(sysid::inference::derived::bands(1.0 / 120.0, 4), vec![[0.0, 15.0], [15.0, 30.0], [30.0, 45.0], [45.0, 60.0]]);
/// ```
pub fn bands(dt_s: f64, n: usize) -> Vec<[f64; 2]> {
    let nyq = 0.5 / dt_s;
    (0..n)
        .map(|k| [nyq * k as f64 / n as f64, nyq * (k + 1) as f64 / n as f64])
        .collect()
}

/// Points a band's mean response is averaged over.
const BAND_POINTS: usize = 64;

/// The weights of the FIR's mean response over `band` (Hz), H̄ = mean over
/// f of Σ_k h_k e^{−i2πf k Δt}, as (real, imaginary) sparse weights: its
/// magnitude is the band's gain, its angle the band's phase.
pub fn band_weights(taps: &Taps, dt_s: f64, band: [f64; 2]) -> [Vec<(usize, f64)>; 2] {
    let f = |p: usize| band[0] + (band[1] - band[0]) * (p as f64 + 0.5) / BAND_POINTS as f64;
    let mean = |trig: fn(f64) -> f64, k: usize| {
        (0..BAND_POINTS)
            .map(|p| trig(std::f64::consts::TAU * f(p) * k as f64 * dt_s))
            .sum::<f64>()
            / BAND_POINTS as f64
    };
    [
        taps.iter().map(|&(i, k)| (i, mean(f64::cos, k))).collect(),
        taps.iter().map(|&(i, k)| (i, -mean(f64::sin, k))).collect(),
    ]
}

/// The delay of a FIR's whole response `unity` + Σ h_k e^{−iωkΔt}, ms:
/// the phase delay of its mean response over `band` (Hz),
/// −arg(Ḡ)/(2π f_c) with f_c the band's centre, with its delta-method
/// interval. `unity` is the nominal response the taps are errors of (1e6
/// for taps in ppm of the rate). For a pure delay τ the band's mean
/// response is e^{−i2πf_cτ} times a real factor, so this is τ exactly;
/// over the lowest band it is the low-frequency (group) delay. The taps'
/// centroid Σ k g_k / Σ g_k, the group delay at 0 Hz, is not used: a short
/// FIR fitted to a fractional delay matches it where the motion has its
/// power, and its slope at 0 Hz is off by 1% on a quadrotor's rates.
///
/// `None` where the phase no longer tells the delay: the band's mean
/// response has no positive real part (the phase has passed ±90°), or the
/// phase delay and the taps' centroid disagree by more than a sample. The
/// second catches a long delay whose band-mean phase has wrapped while the
/// band's real factor changed sign (a pure 10-sample delay reads as 2
/// samples over the lowest of four bands).
pub fn phase_delay(
    d: &Derived<'_>,
    taps: &Taps,
    dt_s: f64,
    unity: f64,
    band: [f64; 2],
) -> Option<Coefficient> {
    let [re, im] = band_weights(taps, dt_s, band);
    let (x, y) = (unity + d.value(&re), d.value(&im));
    let sum: Vec<(usize, f64)> = taps.iter().map(|&(i, _)| (i, 1.0)).collect();
    let moment: Vec<(usize, f64)> = taps.iter().map(|&(i, k)| (i, k as f64)).collect();
    let centroid_samples = d.value(&moment) / (unity + d.value(&sum));
    if x <= 0.0 {
        return None;
    }
    let m2 = x * x + y * y;
    let scale = -1e3 / (std::f64::consts::TAU * 0.5 * (band[0] + band[1]));
    let grad: Vec<(usize, f64)> = re
        .iter()
        .zip(&im)
        .map(|(&(i, r), &(_, m))| (i, scale * (x * m - y * r) / m2))
        .collect();
    let delay = d.delta(scale * y.atan2(x), &grad, "ms");
    let agree = (delay.value / (1e3 * dt_s) - centroid_samples).abs() <= 1.0;
    agree.then_some(delay)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inference::hac_regression;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    fn stored(y: &[f64], x: &[&[f64]]) -> Vec<Coefficient> {
        let f = hac_regression(y, x).unwrap();
        (0..x.len())
            .map(|j| {
                let [lo, hi] = f.interval(j, 0.95);
                Coefficient::new(f.coef[j], f.se[j], [lo, hi], "u")
                    .with_covariance(f.cov[j].clone())
            })
            .collect()
    }

    /// y on two correlated taps of AR(1) noise, `n` rows.
    fn taps(seed: u64, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut g = move || -> f64 { StandardNormal.sample(&mut rng) };
        let s: Vec<f64> = (0..n + 1).map(|_| g()).collect();
        let x0: Vec<f64> = s[1..].to_vec();
        let x1: Vec<f64> = (0..n).map(|i| 0.6 * s[i] + 0.8 * s[i + 1]).collect();
        let mut e = 0.0;
        let y = (0..n)
            .map(|i| {
                e = 0.5 * e + g();
                1.0 * x0[i] - 0.5 * x1[i] + e
            })
            .collect();
        (y, x0, x1)
    }

    /// One tap alone has exactly its stored interval (no regression against
    /// the per-tap intervals), and a derived interval of a fit with white
    /// residuals matches the textbook σ² wᵀ(XᵀX)⁻¹w within sampling error.
    #[test]
    fn one_tap_is_its_own_interval_and_a_sum_matches_the_textbook() {
        let (y, x0, x1) = taps(1, 4000);
        let c = stored(&y, &[&x0, &x1]);
        let d = Derived::new(&c).unwrap();
        for (j, cj) in c.iter().enumerate() {
            let one = d.linear(&[(j, 1.0)], "u");
            for (a, b) in one.ci95.iter().zip(cj.ci95) {
                assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{one:?} {cj:?}");
            }
        }
        // White noise: regress y on x0, x1 directly; Var(b0 + b1) =
        // σ² (1, 1)(XᵀX)⁻¹(1, 1)ᵀ with the 2×2 inverse written out.
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(2);
        let yw: Vec<f64> = x0
            .iter()
            .zip(&x1)
            .map(|(a, b)| {
                let e: f64 = StandardNormal.sample(&mut rng);
                a - 0.5 * b + e
            })
            .collect();
        let f = hac_regression(&yw, &[&x0, &x1]).unwrap();
        let c = stored(&yw, &[&x0, &x1]);
        let sum = Derived::new(&c).unwrap().linear(&[(0, 1.0), (1, 1.0)], "u");
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let (a, b, dd) = (dot(&x0, &x0), dot(&x0, &x1), dot(&x1, &x1));
        let det = a * dd - b * b;
        let s2 = f.rss / (x0.len() - 2) as f64;
        let textbook = (s2 * (dd - 2.0 * b + a) / det).sqrt();
        assert!(
            (sum.se / textbook - 1.0).abs() < 0.1,
            "{} {textbook}",
            sum.se
        );
    }

    /// Monte Carlo: over 200 seeds the derived 95% interval of b0 + b1 (the
    /// taps negatively correlated, AR(1) residuals) covers the truth 0.5 in
    /// 180–198 of them (the binomial 99.9% range around 95%), and its mean
    /// standard error is within 15% of the estimates' spread.
    #[test]
    fn a_sum_of_taps_covers_over_seeds() {
        let (mut covered, mut sum, mut sum2, mut se) = (0, 0.0, 0.0, 0.0);
        let runs = 200;
        for seed in 0..runs {
            let (y, x0, x1) = taps(100 + seed, 1500);
            let c = stored(&y, &[&x0, &x1]);
            let s = Derived::new(&c).unwrap().linear(&[(0, 1.0), (1, 1.0)], "u");
            covered += usize::from(s.covers(0.5));
            sum += s.value;
            sum2 += s.value * s.value;
            se += s.se;
        }
        let n = runs as f64;
        let sd = (sum2 / n - (sum / n).powi(2)).sqrt();
        assert!((180..=198).contains(&covered), "covered {covered}/200");
        assert!(((se / n) / sd - 1.0).abs() < 0.15, "se {} sd {sd}", se / n);
    }

    /// The band response of known taps: a single tap at lag 0 is flat with
    /// zero phase; a one-sample delay's mean response over the lowest of
    /// four bands has the phase of its centre frequency, −(Nyquist/8)/fs·360°.
    #[test]
    fn band_weights_of_known_taps() {
        let dt = 1.0 / 120.0;
        let [re, im] = band_weights(&[(0, 0)], dt, [30.0, 45.0]);
        assert_eq!((re[0].1, im[0].1), (1.0, 0.0));
        let [re, im] = band_weights(&[(0, 1)], dt, [0.0, 15.0]);
        let phase = im[0].1.atan2(re[0].1).to_degrees();
        assert!((phase + 7.5 / 120.0 * 360.0).abs() < 1e-9, "{phase}");
    }

    /// The magnitude's interval at a zero response: it starts at 0 and the
    /// phase is not given; well away from zero it is the delta method's
    /// width or wider.
    #[test]
    fn a_magnitude_interval_holds_at_zero() {
        let c = |v: f64, row: Vec<f64>| Coefficient::new(v, row[0].sqrt(), [v - 0.2, v + 0.2], "u");
        let a = c(0.01, vec![0.01, 0.0]).with_covariance(vec![0.01, 0.0]);
        let b = Coefficient::new(-0.02, 0.1, [-0.22, 0.18], "u").with_covariance(vec![0.0, 0.01]);
        let coefs = [a, b];
        let d = Derived::new(&coefs).unwrap();
        let (g, p) = d.magnitude(&[(0, 1.0)], &[(1, 1.0)], "u");
        assert_eq!(g.ci95[0], 0.0);
        assert!(p.is_none());
        let a = c(3.0, vec![0.01]).with_covariance(vec![0.01, 0.0]);
        let b = Coefficient::new(4.0, 0.1, [3.8, 4.2], "u").with_covariance(vec![0.0, 0.01]);
        let coefs = [a, b];
        let d = Derived::new(&coefs).unwrap();
        let (g, p) = d.magnitude(&[(0, 1.0)], &[(1, 1.0)], "u");
        assert!(
            (g.value - 5.0).abs() < 1e-12 && g.ci95[0] > 4.5 && g.ci95[1] < 5.5,
            "{g:?}"
        );
        assert!(g.ci95[1] - g.value >= 2.0 * g.se * 0.999, "{g:?}");
        let p = p.unwrap();
        assert!(
            (p.value - 4f64.atan2(3.0).to_degrees()).abs() < 1e-9,
            "{p:?}"
        );
    }

    /// A pure one-sample delay (one tap at lag 1, no unity) is Δt exactly;
    /// a quarter-sample delay by linear interpolation, as the error taps
    /// h = (−¼, ¼)·1e6 ppm of a unit response, is Δt/4 within 3% (linear
    /// interpolation's phase delay falls with frequency: 0.243 samples
    /// over the lowest of four bands), with a small interval.
    #[test]
    fn the_phase_delay_of_known_taps() {
        let coefs = [
            Coefficient::new(-0.25e6, 1.0, [-0.25e6 - 2.0, -0.25e6 + 2.0], "ppm")
                .with_covariance(vec![1.0, 0.0]),
            Coefficient::new(0.25e6, 1.0, [0.25e6 - 2.0, 0.25e6 + 2.0], "ppm")
                .with_covariance(vec![0.0, 1.0]),
        ];
        let d = Derived::new(&coefs).unwrap();
        let dt = 0.008;
        let band = bands(dt, 4)[0];
        let pure = phase_delay(&d, &[(1, 1)], dt, 0.0, band).unwrap();
        assert!((pure.value - 8.0).abs() < 1e-9, "{pure:?}");
        // Ten samples late is past a quarter period of the band's centre
        // (16 samples): the phase has wrapped, so no delay is given.
        assert_eq!(phase_delay(&d, &[(1, 10)], dt, 0.0, band), None);
        let t = phase_delay(&d, &[(0, 0), (1, 1)], dt, 1e6, band).unwrap();
        assert!((t.value / 2.0 - 1.0).abs() < 0.03, "{t:?}");
        assert!(t.se > 0.0 && t.se < 1e-4, "{t:?}");
    }
}
