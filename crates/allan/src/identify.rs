//! Power-law noise identification by the lag-1 autocorrelation (Riley &
//! Greenhall, "Power law noise identification using the lag 1
//! autocorrelation", EFTF 2004; NIST SP 1065 §5.6).
//!
//! A rate (frequency) series whose spectrum is S_y(f) ∝ f^α has, once
//! averaged over m samples and differenced d times until it is stationary,
//! a lag-1 autocorrelation r₁ with δ = r₁/(1 + r₁) ≈ −(α/2 + d) — so
//! α = −2(δ + d), rounded to the nearest integer.

use serde::Serialize;

/// The five power-law noises of IEEE Std 952 / NIST SP 1065, named by the
/// exponent α of the rate's spectrum S_y(f) ∝ f^α and by the slope of the
/// Allan deviation σ(τ) ∝ τ^μ they give.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PowerLaw {
    /// α = +2 (white angle noise: quantisation), σ ∝ τ⁻¹.
    WhiteAngle,
    /// α = +1 (flicker angle noise), σ ∝ τ⁻¹ (with a log factor).
    FlickerAngle,
    /// α = 0 (white rate noise: angle random walk), σ ∝ τ^−½.
    WhiteRate,
    /// α = −1 (flicker rate noise: bias instability), σ flat.
    FlickerRate,
    /// α = −2 (random-walk rate noise: rate random walk), σ ∝ τ^+½.
    RandomWalkRate,
}

impl PowerLaw {
    /// The exponent α of S_y(f) ∝ f^α.
    pub fn alpha(self) -> i32 {
        match self {
            Self::WhiteAngle => 2,
            Self::FlickerAngle => 1,
            Self::WhiteRate => 0,
            Self::FlickerRate => -1,
            Self::RandomWalkRate => -2,
        }
    }

    /// The noise of exponent `alpha`, clamped to [−2, 2].
    ///
    /// ```
    /// use allan::PowerLaw;
    /// assert_eq!(PowerLaw::from_alpha(0), PowerLaw::WhiteRate);
    /// assert_eq!(PowerLaw::from_alpha(-3), PowerLaw::RandomWalkRate);
    /// ```
    pub fn from_alpha(alpha: i32) -> Self {
        match alpha.clamp(-2, 2) {
            2 => Self::WhiteAngle,
            1 => Self::FlickerAngle,
            0 => Self::WhiteRate,
            -1 => Self::FlickerRate,
            _ => Self::RandomWalkRate,
        }
    }
}

/// Fewest averaged samples the lag-1 method is trusted on (Riley &
/// Greenhall recommend at least 30).
pub const MIN_IDENTIFY_SAMPLES: usize = 30;

/// Identifies the dominant power-law noise of the rate series `y` at
/// averaging factor `m`: averages non-overlapping groups of m samples,
/// differences (at most twice) until δ = r₁/(1 + r₁) < 0.25, and returns
/// the noise of α = −round(2δ) − 2d. `None` when fewer than
/// [`MIN_IDENTIFY_SAMPLES`] averages remain.
///
/// ```
/// use allan::{identify_noise, PowerLaw};
/// use rand::SeedableRng;
/// use rand_distr::{Distribution, StandardNormal};
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let y: Vec<f64> = (0..3000).map(|_| StandardNormal.sample(&mut rng)).collect();
/// assert_eq!(identify_noise(&y, 1), Some(PowerLaw::WhiteRate));
/// // Its running sum is a random walk of the rate.
/// let rw: Vec<f64> = y.iter().scan(0.0, |s, v| { *s += v; Some(*s) }).collect();
/// assert_eq!(identify_noise(&rw, 10), Some(PowerLaw::RandomWalkRate));
/// assert_eq!(identify_noise(&y, 200), None); // 15 averages: too few
/// ```
pub fn identify_noise(y: &[f64], m: usize) -> Option<PowerLaw> {
    let m = m.max(1);
    let groups = y.len() / m;
    if groups < MIN_IDENTIFY_SAMPLES {
        return None;
    }
    let mut z: Vec<f64> = (0..groups)
        .map(|g| y[g * m..(g + 1) * m].iter().sum::<f64>() / m as f64)
        .collect();
    const DMAX: i32 = 2;
    let mut d = 0;
    loop {
        let r1 = lag1_autocorrelation(&z)?;
        let delta = r1 / (1.0 + r1);
        if delta < 0.25 || d >= DMAX {
            let alpha = -(2.0 * delta).round() as i32 - 2 * d;
            return Some(PowerLaw::from_alpha(alpha));
        }
        z = z.windows(2).map(|w| w[1] - w[0]).collect();
        d += 1;
    }
}

/// Lag-1 autocorrelation about the mean; `None` for a constant series.
fn lag1_autocorrelation(z: &[f64]) -> Option<f64> {
    let n = z.len();
    if n < 3 {
        return None;
    }
    let mean = z.iter().sum::<f64>() / n as f64;
    let var: f64 = z.iter().map(|v| (v - mean).powi(2)).sum();
    if var <= 0.0 || !var.is_finite() {
        return None;
    }
    let cov: f64 = z.windows(2).map(|w| (w[0] - mean) * (w[1] - mean)).sum();
    Some(cov / var)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn white(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
    }

    #[test]
    fn identifies_white_random_walk_and_white_angle_noise() {
        let w = white(20_000, 1);
        // White rate noise, at every averaging factor.
        for m in [1, 4, 16, 64] {
            assert_eq!(identify_noise(&w, m), Some(PowerLaw::WhiteRate), "m={m}");
        }
        // Random-walk rate: the running sum of white noise.
        let rw: Vec<f64> = w
            .iter()
            .scan(0.0, |s, v| {
                *s += v;
                Some(*s)
            })
            .collect();
        for m in [1, 8, 64] {
            assert_eq!(
                identify_noise(&rw, m),
                Some(PowerLaw::RandomWalkRate),
                "m={m}"
            );
        }
        // White angle noise seen as rate: first differences of white noise.
        let wa: Vec<f64> = w.windows(2).map(|p| p[1] - p[0]).collect();
        assert_eq!(identify_noise(&wa, 1), Some(PowerLaw::WhiteAngle));
    }

    #[test]
    fn a_constant_or_short_series_is_not_identified() {
        assert_eq!(identify_noise(&[1.0; 100], 1), None);
        assert_eq!(identify_noise(&white(29, 2), 1), None);
    }
}
