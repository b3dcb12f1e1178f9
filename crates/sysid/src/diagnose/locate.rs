//! Where a model fails: the validation residual broken down by time segment,
//! by frequency band against a white-noise floor, and by operating regime
//! (bins of each operating signal: an inertial unit's accelerations).

use serde::Serialize;

/// Residual statistics over one stretch of time.
#[derive(Debug, Clone, Serialize)]
pub struct Segment {
    /// Start, s.
    pub t_start: f64,
    /// End, s.
    pub t_end: f64,
    /// RMS of the (pre-processed, so low-passed) operating signals' deviation
    /// from their record means over the segment, summed over the signals
    /// (an inertial unit's vibration level, g; named so in JSON).
    #[serde(rename = "vibration_rms_g")]
    pub operating_rms: f64,
    /// Mean of the residual, in the target's unit.
    pub residual_mean: f64,
    /// RMS of the residual, in the target's unit.
    pub residual_rms: f64,
}

/// Residual power in one frequency band.
#[derive(Debug, Clone, Serialize)]
pub struct Band {
    /// Lower edge, Hz.
    pub f_lo_hz: f64,
    /// Upper edge, Hz.
    pub f_hi_hz: f64,
    /// Share of the residual variance in the band.
    pub share: f64,
    /// Band power over what a white residual of the same pass-band level would
    /// have there (through the pre-processing filter): ≫ 1 means structure.
    pub ratio_to_floor: f64,
}

/// Residual statistics in one bin of one operating signal.
#[derive(Debug, Clone, Serialize)]
pub struct RegimeBin {
    /// Lower edge of the bin, in the signal's unit (g for an inertial
    /// unit's acceleration; named so in JSON).
    #[serde(rename = "lo_g")]
    pub lo: f64,
    /// Upper edge.
    #[serde(rename = "hi_g")]
    pub hi: f64,
    /// Rows in the bin.
    pub count: usize,
    /// Mean of the residual, in the target's unit.
    pub residual_mean: f64,
    /// RMS of the residual, in the target's unit.
    pub residual_rms: f64,
}

/// The residual binned by one operating signal.
#[derive(Debug, Clone, Serialize)]
pub struct Regime {
    /// The signal (`ax`, `ay`, `az` for an inertial unit).
    pub axis: String,
    /// Quantile bins of the (filtered) signal.
    pub bins: Vec<RegimeBin>,
    /// Spread of the bin means, in units of their standard error: a residual
    /// that depends on this signal (a missing g or g² term of an
    /// acceleration) gives ≫ 3. 0 for a signal that does not vary (one bin).
    pub mean_spread_sigma: f64,
}

/// [`stats::mean`] of an iterator's values (0 for none).
fn mean(x: impl Iterator<Item = f64> + Clone) -> f64 {
    let v: Vec<f64> = x.collect();
    if v.is_empty() { 0.0 } else { stats::mean(&v) }
}

/// [`stats::rms`] of an iterator's values (0 for none).
fn rms(x: impl Iterator<Item = f64> + Clone) -> f64 {
    let v: Vec<f64> = x.collect();
    if v.is_empty() { 0.0 } else { stats::rms(&v) }
}

/// Splits rows into `count` contiguous segments of (nearly) equal length.
///
/// ```
/// use sysid::diagnose::segments;
/// let t: Vec<f64> = (0..100).map(|i| i as f64).collect();
/// let r: Vec<f64> = (0..100).map(|i| if i < 50 { 1.0 } else { 3.0 }).collect();
/// let acc = vec![vec![0.0; 100], vec![0.0; 100], vec![0.0; 100]];
/// let s = segments(&t, &r, &acc, 2);
/// assert_eq!((s[0].residual_rms, s[1].residual_rms), (1.0, 3.0));
/// ```
#[track_caller]
pub fn segments(t: &[f64], residual: &[f64], operating: &[Vec<f64>], count: usize) -> Vec<Segment> {
    let n = residual.len();
    assert!(
        t.len() == n && operating.iter().all(|a| a.len() == n),
        "series lengths differ"
    );
    let count = count.clamp(1, n.max(1));
    let means: Vec<f64> = operating.iter().map(|a| mean(a.iter().copied())).collect();
    (0..count)
        .filter_map(|s| {
            let (lo, hi) = (s * n / count, (s + 1) * n / count);
            (hi > lo).then(|| {
                let r = residual[lo..hi].iter().copied();
                let vib = (0..operating.len())
                    .map(|k| mean(operating[k][lo..hi].iter().map(|v| (v - means[k]).powi(2))))
                    .sum::<f64>()
                    .sqrt();
                Segment {
                    t_start: t[lo],
                    t_end: t[hi - 1],
                    operating_rms: vib,
                    residual_mean: mean(r.clone()),
                    residual_rms: rms(r),
                }
            })
        })
        .collect()
}

/// A residual's power spectral density (Welch) and the floor a white
/// residual of the same pass-band level would have after the pre-processing.
#[derive(Debug, Clone, Default)]
pub struct ResidualSpectrum {
    /// Bin frequencies, Hz.
    pub frequency_hz: Vec<f64>,
    /// Residual PSD, (target unit)²/Hz.
    pub density: Vec<f64>,
    /// White floor through the pre-filter at each bin, (target unit)²/Hz.
    pub floor: Vec<f64>,
}

impl ResidualSpectrum {
    /// The spectrum of `residual` sampled at `fs` Hz. `white_shape(f)` is the
    /// power transfer of the pre-processing at f (|H(f)|⁴ of a zero-phase
    /// filter, 1 without one): the floor is a white level, the median of
    /// density / shape over the bins where the shape is above 0.5, times the
    /// shape. `None` for a residual shorter than 16 samples.
    ///
    /// ```
    /// use sysid::diagnose::ResidualSpectrum;
    /// let x: Vec<f64> = (0..4096).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
    /// let s = ResidualSpectrum::new(&x, 50.0, &|_| 1.0).unwrap();
    /// assert_eq!(s.frequency_hz.len(), s.floor.len());
    /// assert!(s.floor.windows(2).all(|w| w[0] == w[1])); // white: a flat floor
    /// ```
    pub fn new(residual: &[f64], fs: f64, white_shape: &dyn Fn(f64) -> f64) -> Option<Self> {
        let seg = 512.min(residual.len().next_power_of_two() / 2);
        if seg < 8 || residual.len() < seg {
            return None;
        }
        let s = iir::welch(residual, fs, seg);
        let mut levels: Vec<f64> = s
            .frequency_hz
            .iter()
            .zip(&s.density)
            .filter(|(f, _)| **f > 0.0 && white_shape(**f) > 0.5)
            .map(|(f, d)| d / white_shape(*f))
            .collect();
        levels.sort_by(f64::total_cmp);
        let white = levels.get(levels.len() / 2).copied().unwrap_or(0.0);
        let floor = s
            .frequency_hz
            .iter()
            .map(|&f| white * white_shape(f))
            .collect();
        Some(Self {
            frequency_hz: s.frequency_hz,
            density: s.density,
            floor,
        })
    }

    /// Breaks the power into bands: `edges_hz` are the band edges
    /// (ascending, the last at most Nyquist), each band with its share of
    /// the variance and its ratio to the floor.
    ///
    /// ```
    /// use sysid::diagnose::ResidualSpectrum;
    /// // A white residual: every band is at its floor.
    /// let mut s = 9u64;
    /// let x: Vec<f64> = (0..20000).map(|_| { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5 }).collect();
    /// let b = ResidualSpectrum::new(&x, 50.0, &|_| 1.0).unwrap().bands(&[0.0, 1.0, 5.0, 25.0]);
    /// assert!(b.iter().all(|b| (b.ratio_to_floor - 1.0).abs() < 0.25), "{b:?}");
    /// ```
    #[track_caller]
    pub fn bands(&self, edges_hz: &[f64]) -> Vec<Band> {
        assert!(edges_hz.len() >= 2, "need at least one band");
        let df = self.frequency_hz.get(1).copied().unwrap_or(0.0);
        let nyquist = self.frequency_hz.last().copied().unwrap_or(0.0);
        let total: f64 = self
            .density
            .iter()
            .map(|d| d * df)
            .sum::<f64>()
            .max(f64::MIN_POSITIVE);
        edges_hz
            .windows(2)
            .map(|w| {
                let in_band = |f: f64| f >= w[0] && (f < w[1] || (w[1] >= nyquist && f <= w[1]));
                let (mut p, mut floor) = (0.0, 0.0);
                for ((f, d), fl) in self.frequency_hz.iter().zip(&self.density).zip(&self.floor) {
                    if in_band(*f) {
                        p += d * df;
                        floor += fl * df;
                    }
                }
                Band {
                    f_lo_hz: w[0],
                    f_hi_hz: w[1],
                    share: p / total,
                    ratio_to_floor: if floor > 0.0 {
                        p / floor
                    } else {
                        f64::INFINITY
                    },
                }
            })
            .collect()
    }
}

/// Bins the residual by quantiles of one operating signal (an acceleration).
///
/// ```
/// use sysid::diagnose::regime;
/// // A residual proportional to the acceleration: the bin means spread far.
/// let a: Vec<f64> = (0..1000).map(|i| ((i * 37) % 100) as f64 / 100.0).collect();
/// let r: Vec<f64> = a.iter().enumerate().map(|(i, v)| 2.0 * v + 0.01 * ((i % 7) as f64 - 3.0)).collect();
/// let g = regime("az", &a, &r, 5, 1000.0);
/// assert_eq!(g.bins.len(), 5);
/// assert!(g.mean_spread_sigma > 10.0);
/// ```
#[track_caller]
pub fn regime(
    axis: &str,
    signal: &[f64],
    residual: &[f64],
    bins: usize,
    effective_samples: f64,
) -> Regime {
    assert_eq!(signal.len(), residual.len(), "series lengths differ");
    let n = signal.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| signal[a].total_cmp(&signal[b]));
    // An axis that does not move has one regime: quantile bins of tied
    // values would split the rows by time and call a drift a dependence.
    let (lo, hi) = match (order.first(), order.last()) {
        (Some(&a), Some(&b)) => (signal[a], signal[b]),
        _ => (0.0, 0.0),
    };
    let bins = if hi - lo <= 1e-12 * lo.abs().max(hi.abs()) {
        1
    } else {
        bins.clamp(1, n.max(1))
    };
    let out: Vec<RegimeBin> = (0..bins)
        .filter_map(|b| {
            let idx = &order[b * n / bins..(b + 1) * n / bins];
            (!idx.is_empty()).then(|| {
                let r = idx.iter().map(|&i| residual[i]);
                RegimeBin {
                    lo: signal[idx[0]],
                    hi: signal[idx[idx.len() - 1]],
                    count: idx.len(),
                    residual_mean: mean(r.clone()),
                    residual_rms: rms(r),
                }
            })
        })
        .collect();
    // Standard error of a bin mean with the residual's effective samples
    // shared out over the bins.
    let sd = {
        let m = mean(residual.iter().copied());
        rms(residual.iter().map(|v| v - m))
    };
    let per_bin = (effective_samples / bins as f64).max(1.0);
    let se = sd / per_bin.sqrt();
    let means: Vec<f64> = out.iter().map(|b| b.residual_mean).collect();
    let spread = means.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - means.iter().copied().fold(f64::INFINITY, f64::min);
    Regime {
        axis: axis.to_string(),
        bins: out,
        mean_spread_sigma: if se > 0.0 { spread / se } else { 0.0 },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_axis_has_no_regimes_to_compare() {
        // An axis that does not move (a column of zeros, or a constant after
        // filtering's rounding) must not be binned by row order: that would
        // turn a drift in time into a "dependence" on the axis.
        let n = 1000;
        let drift: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
        for accel in [
            vec![0.0; n],
            (0..n).map(|i| 1.0 + 1e-16 * (i % 3) as f64).collect(),
        ] {
            let g = regime("ax", &accel, &drift, 5, n as f64);
            assert_eq!(g.mean_spread_sigma, 0.0, "{g:?}");
            assert_eq!(g.bins.len(), 1);
            assert_eq!(g.bins[0].count, n);
        }
    }
}
