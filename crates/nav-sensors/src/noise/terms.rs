//! The IEEE Std 952 noise terms read from an Allan-deviation curve: angle
//! random walk on the τ^−½ region, bias instability at the flat minimum,
//! rate random walk on the τ^+½ region.
//!
//! A region is a run of at least two consecutive octaves (three points)
//! whose log-log slope is within ±0.25 of the term's slope (halfway to the
//! neighbouring power laws): one octave alone may be a bend between two
//! regions. What
//! the curve does not show is not extrapolated: the term is then
//! [`NoiseTerm::Unresolved`] with the reason and the upper bound every
//! point still gives (independent noises add in Allan variance, so no term
//! can exceed what the curve's upper confidence limits allow at any τ).

use allan::{AllanCurve, AllanPoint, PowerLaw, deviation_interval, edf_overlapping};
use serde::Serialize;

/// σ(τ) = 60·N/√τ: N (deg/√h) from σ (deg/h) at τ (s).
fn arw_at(p: &AllanPoint, sigma: f64) -> f64 {
    sigma * p.tau_s.sqrt() / 60.0
}

/// σ(τ) = K·√(τ_h/3) = K·√(τ/10800): K (deg/h/√h) from σ (deg/h) at τ (s).
fn rrw_at(p: &AllanPoint, sigma: f64) -> f64 {
    sigma * (10_800.0 / p.tau_s).sqrt()
}

/// Flicker rate noise of coefficient B has a flat Allan deviation
/// √(2 ln 2/π)·B = 0.664·B (IEEE Std 952 Annex C).
pub const FLICKER_FLOOR: f64 = 0.664_282_4;

/// A fitted noise term with its confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The term's value (deg/√h, deg/h or deg/h/√h).
    pub value: f64,
    /// Lower confidence limit.
    pub low: f64,
    /// Upper confidence limit.
    pub high: f64,
    /// Shortest τ of the region it was read on, s.
    pub tau_from_s: f64,
    /// Longest τ of that region, s.
    pub tau_to_s: f64,
    /// Equivalent degrees of freedom behind the interval.
    pub edf: f64,
}

/// A noise term: fitted, or why not and the bound that remains.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum NoiseTerm {
    /// Read on its region of the curve.
    Resolved(Estimate),
    /// The curve does not show it.
    Unresolved {
        /// What the curve shows instead.
        reason: String,
        /// The largest value compatible with every point's upper confidence
        /// limit (None for an empty curve).
        upper_bound: Option<f64>,
    },
}

impl NoiseTerm {
    /// The estimate, if resolved.
    pub fn estimate(&self) -> Option<&Estimate> {
        match self {
            Self::Resolved(e) => Some(e),
            Self::Unresolved { .. } => None,
        }
    }
}

/// Angle random walk (deg/√h), bias instability (deg/h) and rate random
/// walk (deg/h/√h) of one curve (rates in deg/h, τ in s).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseTerms {
    /// Angle random walk N, deg/√h: σ(τ) = 60·N/√τ on the τ^−½ region; the
    /// EDF-weighted geometric mean of the region's readings, with the
    /// interval of its most precise point (white-rate EDF) — conservative,
    /// since neighbouring octaves share most of their data.
    pub arw: NoiseTerm,
    /// Bias instability B, deg/h: the curve's minimum / 0.664, read where the
    /// curve has flattened or turns up significantly after it; interval from
    /// the flicker-rate EDF at that τ.
    pub bias_instability: NoiseTerm,
    /// Rate random walk K, deg/h/√h: σ(τ) = K·√(τ/10800) on a τ^+½ region
    /// after the minimum; interval from the random-walk-rate EDF.
    pub rrw: NoiseTerm,
}

/// Slope of log σ against log τ between consecutive points.
fn slopes(points: &[AllanPoint]) -> Vec<f64> {
    points
        .windows(2)
        .map(|w| (w[1].adev / w[0].adev).ln() / (w[1].tau_s / w[0].tau_s).ln())
        .collect()
}

/// The longest run of at least [`MIN_REGION_OCTAVES`] consecutive segments
/// (from index `from` on) whose slope is within 0.25 of `target`, as an
/// inclusive point range; the earliest on ties.
fn region(slopes: &[f64], from: usize, target: f64) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for (k, s) in slopes.iter().enumerate().skip(from) {
        if (s - target).abs() <= 0.25 {
            let a = *start.get_or_insert(k);
            if best.is_none_or(|(b0, b1)| k + 1 - a > b1 - b0) {
                best = Some((a, k + 1));
            }
        } else {
            start = None;
        }
    }
    best.filter(|(a, b)| b - a >= MIN_REGION_OCTAVES)
}

/// Fewest octaves a power-law region spans.
const MIN_REGION_OCTAVES: usize = 2;

/// Reads a term on points `a..=b`: EDF-weighted geometric mean of
/// `read(point, σ)`, interval of the point with the largest EDF for `noise`.
fn read_region(
    curve: &AllanCurve,
    (a, b): (usize, usize),
    noise: PowerLaw,
    read: fn(&AllanPoint, f64) -> f64,
) -> Estimate {
    let pts = &curve.points[a..=b];
    let edf: Vec<f64> = pts
        .iter()
        .map(|p| edf_overlapping(curve.samples, p.m, noise))
        .collect();
    let w: f64 = edf.iter().sum();
    let log_mean = pts
        .iter()
        .zip(&edf)
        .map(|(p, e)| e * read(p, p.adev).ln())
        .sum::<f64>()
        / w;
    let value = log_mean.exp();
    let best_edf = edf.iter().copied().fold(0.0, f64::max);
    let (lo, hi) = deviation_interval(1.0, best_edf, curve.confidence)
        .expect("the curve's confidence was checked when it was built");
    Estimate {
        value,
        low: value * lo,
        high: value * hi,
        tau_from_s: pts[0].tau_s,
        tau_to_s: pts[pts.len() - 1].tau_s,
        edf: best_edf,
    }
}

/// The smallest upper bound any point gives, and its τ.
fn bound(curve: &AllanCurve, read: impl Fn(&AllanPoint, f64) -> f64) -> Option<f64> {
    curve
        .points
        .iter()
        .map(|p| read(p, p.high))
        .min_by(f64::total_cmp)
}

impl NoiseTerms {
    /// Reads the three terms on `curve` (rates in deg/h, τ in s).
    ///
    /// ```
    /// use nav_sensors::noise::{AllanCurve, NoiseTerms};
    /// // A short curve: nothing to read but bounds.
    /// let c = AllanCurve::new(&[0.0, 1.0, 0.0, 1.0, 0.0], 1.0, &[1], 0.683).unwrap();
    /// let t = NoiseTerms::fit(&c);
    /// assert!(t.arw.estimate().is_none());
    /// ```
    pub fn fit(curve: &AllanCurve) -> Self {
        let pts = &curve.points;
        let s = slopes(pts);
        let tau_range = || match (pts.first(), pts.last()) {
            (Some(a), Some(b)) => format!("{} to {} s", a.tau_s, b.tau_s),
            _ => "no τ".into(),
        };
        let slope_list = || {
            s.iter()
                .map(|v| format!("{v:+.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        };

        let arw = match region(&s, 0, -0.5) {
            Some(r) => NoiseTerm::Resolved(read_region(curve, r, PowerLaw::WhiteRate, arw_at)),
            None => NoiseTerm::Unresolved {
                reason: format!(
                    "no τ^−½ region from {}: octave slopes {}",
                    tau_range(),
                    slope_list()
                ),
                upper_bound: bound(curve, arw_at),
            },
        };

        let min = pts
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.adev.total_cmp(&b.1.adev))
            .map(|(k, _)| k);
        let bi_bound = bound(curve, |_, sigma| sigma / FLICKER_FLOOR);
        let bias_instability = match min {
            None => NoiseTerm::Unresolved {
                reason: "empty curve".into(),
                upper_bound: None,
            },
            Some(k) if k + 1 == pts.len() => NoiseTerm::Unresolved {
                reason: format!(
                    "the curve still falls at its longest τ ({} s, slope {}): its flat region lies beyond a tenth of this record",
                    pts[k].tau_s,
                    s.last().map_or("—".into(), |v| format!("{v:+.2}"))
                ),
                upper_bound: bi_bound,
            },
            Some(k) => {
                let p = &pts[k];
                let rises = pts[k + 1..].iter().any(|q| q.low > p.high);
                let above_white = match &arw {
                    NoiseTerm::Resolved(e) => p.low > 60.0 * e.high / p.tau_s.sqrt(),
                    NoiseTerm::Unresolved { .. } => true,
                };
                let flattened = k > 0 && s[k - 1] >= -0.25 && above_white;
                if rises || flattened {
                    let edf = edf_overlapping(curve.samples, p.m, PowerLaw::FlickerRate);
                    let (lo, hi) = deviation_interval(p.adev, edf, curve.confidence)
                        .expect("the curve's confidence was checked when it was built");
                    NoiseTerm::Resolved(Estimate {
                        value: p.adev / FLICKER_FLOOR,
                        low: lo / FLICKER_FLOOR,
                        high: hi / FLICKER_FLOOR,
                        tau_from_s: p.tau_s,
                        tau_to_s: p.tau_s,
                        edf,
                    })
                } else {
                    NoiseTerm::Unresolved {
                        reason: format!(
                            "the minimum at τ = {} s is neither followed by a significant rise nor reached on a flattened curve: the flat region is not resolved",
                            p.tau_s
                        ),
                        upper_bound: bi_bound,
                    }
                }
            }
        };

        let after_min = min.unwrap_or(0);
        let rrw = match region(&s, after_min, 0.5) {
            Some(r) => NoiseTerm::Resolved(read_region(curve, r, PowerLaw::RandomWalkRate, rrw_at)),
            None => NoiseTerm::Unresolved {
                reason: format!(
                    "no τ^+½ region after the minimum, up to τ = {} s (a longer record would be needed)",
                    pts.last().map_or(0.0, |p| p.tau_s)
                ),
                upper_bound: bound(curve, rrw_at),
            },
        };
        Self {
            arw,
            bias_instability,
            rrw,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn normals(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
    }

    /// White rate noise of ARW N plus a rate random walk of RRW K, both
    /// exactly as interval means (the RW's within-interval mean drawn with
    /// its covariance with the end point): the curve is
    /// σ²(τ) = 3600·N²/τ + K²·τ/10800, and both terms must be recovered.
    #[test]
    fn recovers_arw_and_rrw_and_the_minimum_between() {
        let (n_arw, k_rrw, dt): (f64, f64, f64) = (0.001, 0.5, 0.02); // deg/√h, deg/h/√h, s
        let samples = 500_000; // 10,000 s
        let w = normals(samples, 1);
        let z = normals(2 * samples, 2);
        let white = 60.0 * n_arw / dt.sqrt();
        let step = k_rrw * (dt / 3600.0).sqrt(); // deg/h per √interval
        let mut b = 0.0;
        let y: Vec<f64> = (0..samples)
            .map(|i| {
                let (z1, z2) = (z[2 * i], z[2 * i + 1]);
                let mean = b + step * (0.5 * z1 + z2 / 12f64.sqrt());
                b += step * z1;
                white * w[i] + mean
            })
            .collect();
        let curve = AllanCurve::octaves(&y, dt, 0.683).unwrap();
        let t = NoiseTerms::fit(&curve);
        let arw = t.arw.estimate().expect("ARW region");
        assert!((arw.value / n_arw - 1.0).abs() < 0.05, "{arw:?}");
        assert!(arw.low < n_arw && n_arw < arw.high * 1.05, "{arw:?}");
        let rrw = t.rrw.estimate().expect("RRW region");
        assert!((rrw.value / k_rrw - 1.0).abs() < 0.3, "{rrw:?}");
        // White and random walk cross at τ* = 3600·√3·N/K ≈ 12.5 s, where
        // σ = √2·σ_white(τ*) ≈ 1.02 deg/h: the reading minimum / 0.664 is
        // the bias instability IEEE Std 952 reads off such a curve.
        let bi = t
            .bias_instability
            .estimate()
            .expect("a minimum that turns up");
        let tau_star = 3600.0 * 3f64.sqrt() * n_arw / k_rrw;
        let sigma_min = 2f64.sqrt() * 60.0 * n_arw / tau_star.sqrt();
        assert!(
            (bi.value * FLICKER_FLOOR / sigma_min - 1.0).abs() < 0.2,
            "{bi:?}"
        );
    }

    #[test]
    fn white_noise_alone_resolves_arw_and_bounds_the_rest() {
        let y: Vec<f64> = normals(20_000, 3).iter().map(|v| 0.3 * v).collect();
        let curve = AllanCurve::octaves(&y, 0.02, 0.683).unwrap();
        let t = NoiseTerms::fit(&curve);
        let n_true = 0.3 * 0.02f64.sqrt() / 60.0;
        let arw = t.arw.estimate().unwrap();
        assert!((arw.value / n_true - 1.0).abs() < 0.03, "{arw:?}");
        assert_eq!(arw.tau_from_s, 0.02);
        match &t.bias_instability {
            NoiseTerm::Unresolved { upper_bound, .. } => {
                assert!(upper_bound.unwrap() > 0.0);
            }
            other => panic!("{other:?}"),
        }
        match &t.rrw {
            NoiseTerm::Unresolved {
                upper_bound: Some(k),
                ..
            } => assert!(*k > 0.0),
            other => panic!("{other:?}"),
        }
    }

    /// A constant rate ramp (σ = Rτ/√2, slope +1) is no white noise.
    #[test]
    fn a_ramp_has_no_random_walk_regions() {
        let y: Vec<f64> = (0..10_000).map(|k| 1e-3 * k as f64).collect();
        let curve = AllanCurve::octaves(&y, 0.02, 0.683).unwrap();
        let t = NoiseTerms::fit(&curve);
        assert!(t.arw.estimate().is_none());
        assert!(t.rrw.estimate().is_none());
    }

    #[test]
    fn regions_are_the_longest_runs_within_a_quarter() {
        let s = [-1.0, -0.5, -0.6, 0.0, -0.45, -0.5, -0.55, 0.5, 0.3];
        assert_eq!(region(&s, 0, -0.5), Some((4, 7)));
        assert_eq!(region(&s, 5, -0.5), Some((5, 7)));
        assert_eq!(region(&s, 0, 0.5), Some((7, 9)));
        // One octave is not a region.
        assert_eq!(region(&s[..8], 0, 0.5), None);
        assert_eq!(region(&s, 0, 1.5), None);
    }
}
