//! The shape of a window's vibration: where in frequency its power lies, as
//! the training windows spanned it per operating signal, and how far a new
//! window's shape lies outside.
//!
//! A window's mean and level ([`super::range`]) do not see its spectrum: a
//! flight whose vibration has another spectrum than the shaker's, at the
//! same rms, is inside by level. A network that reads the window's level
//! (its statistics input) maps that level to the drift the shaker's
//! spectrum gave at it, and a network that reads the raw window saw only
//! windows of the shaker's spectrum; at another spectrum both extrapolate.
//!
//! The shape of a window of one signal is the rms of its sample-to-sample
//! change over √2 times its rms about the mean,
//! `ρ = √(Σᵢ₌₁ᴸ⁻¹ (vᵢ − vᵢ₋₁)² / (2(L − 1)) / (Σ (v − m)² / L))`:
//! one for white vibration up to the sampling rate's Nyquist frequency,
//! toward 0 as the power moves below it (`√2·sin(π f Δt)` for a sine at
//! `f`), at most 2. It is `√(1 − r₁)` of the window's lag-one
//! autocorrelation `r₁`: a one-number band-power ratio (the power above a
//! first difference's corner against the whole), which a flight computer
//! sums over the window it already rings, with no filter state.
//!
//! The range keeps each signal's smallest and largest shape over the
//! fitted windows (training and validation) that vibrate on that signal (level above the range's
//! [`scale`](super::range::TrainingRange::scale): below it the window is
//! noise and resolved motion, whose shape is not the vibration's). A new
//! window's shape counts in its distance as its excess beyond that interval
//! divided by [`SHAPE_SCALE`], gated by its own level: nothing at one scale
//! of level or less, in full from two scales up (a linear ramp between, so
//! the distance is continuous). A signal that never vibrated in training has
//! the interval `[0, 2]` (every shape): its level's excess already counts.

use serde::{Deserialize, Serialize};

/// Divisor of a shape's excess beyond the training interval: 0.1, a tenth
/// of white vibration's shape. A training record's windows of one spectrum
/// spread over about 0.3 of shape (the campaign's z run 1.05–1.35) and a
/// validation window lies within a few hundredths of the training
/// interval; another spectrum lies tenths beyond (the 2–12 Hz z run of
/// tests/dtg_vib_fade_shape.rs 0.33–0.79). At the fade's width of 2
/// scales the network is gone 0.2 of shape beyond what it saw.
pub const SHAPE_SCALE: f64 = 0.1;

/// The largest shape a window can have (`ρ² ≤ 2L/(L − 1)`): the interval of
/// a signal that never vibrated in training is `[0, SHAPE_MAX]`.
pub const SHAPE_MAX: f64 = 2.0;

/// A window's shape given its variance about the mean `var` (population,
/// divided by `L`): the samples' sum of squared successive differences
/// over `2(L − 1)`, over `var`, rooted; 0 for a window of one sample or of
/// no variance. The onboard evaluator sums in the same order.
///
/// ```
/// use sysid::operating::shape::shape;
/// // Alternating ±1: changes of 2, ρ² = 12/(2·3)/1.
/// let a = [1.0, -1.0, 1.0, -1.0];
/// assert!((shape(&a, 1.0) - 2f64.sqrt()).abs() < 1e-12);
/// // A slow ramp: little change from sample to sample.
/// let r: Vec<f64> = (0..50).map(|i| i as f64).collect();
/// let m = 24.5;
/// let var = r.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / 50.0;
/// assert!(shape(&r, var) < 0.1);
/// ```
pub fn shape(a: &[f64], var: f64) -> f64 {
    if a.len() < 2 || var <= 0.0 {
        return 0.0;
    }
    let mut dd = 0.0;
    for i in 1..a.len() {
        let d = a[i] - a[i - 1];
        dd += d * d;
    }
    (dd / (2.0 * (a.len() - 1) as f64) / var).sqrt()
}

/// How much of a window's shape excess counts at level `level`, with the
/// range's level scale `scale`: 0 up to one scale, 1 from two.
///
/// ```
/// use sysid::operating::shape::gate;
/// assert_eq!(gate(0.04, 0.05), 0.0);
/// assert!((gate(0.075, 0.05) - 0.5).abs() < 1e-12);
/// assert_eq!(gate(0.3, 0.05), 1.0);
/// ```
#[inline]
pub fn gate(level: f64, scale: f64) -> f64 {
    ((level - scale) / scale).clamp(0.0, 1.0)
}

/// Each operating signal's shape interval over the training windows that
/// vibrate on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShapeRange {
    /// Smallest shape of each signal (0 for one that never vibrated).
    pub min: Vec<f64>,
    /// Largest shape of each signal ([`SHAPE_MAX`] for one that never
    /// vibrated).
    pub max: Vec<f64>,
    /// Divisor of a shape's excess ([`SHAPE_SCALE`]).
    pub scale: f64,
}

impl ShapeRange {
    /// The interval of each of `k` signals over the fitted windows'
    /// statistics `stats` (means, levels, shapes: [`super::range::statistics`];
    /// training and validation alike, so a fitted record is inside),
    /// counting a window on a signal when its level there exceeds `scale`.
    pub fn from_training(stats: &[&[f64]], k: usize, scale: f64) -> Self {
        let (mut min, mut max) = (vec![f64::INFINITY; k], vec![f64::NEG_INFINITY; k]);
        for p in stats {
            for j in 0..k {
                if gate(p[k + j], scale) > 0.0 {
                    min[j] = min[j].min(p[2 * k + j]);
                    max[j] = max[j].max(p[2 * k + j]);
                }
            }
        }
        for j in 0..k {
            if min[j] > max[j] {
                (min[j], max[j]) = (0.0, SHAPE_MAX);
            }
        }
        Self {
            min,
            max,
            scale: SHAPE_SCALE,
        }
    }

    /// Signal `j`'s term of a window's distance (in shape scales): its
    /// shape's excess beyond the interval, gated by its level.
    #[inline]
    pub fn term(&self, j: usize, level: f64, shape: f64, level_scale: f64) -> f64 {
        gate(level, level_scale) * super::range::excess(shape, self.min[j], self.max[j])
            / self.scale
    }

    /// Whether the range fits `k` signals: the reason if not.
    pub fn check(&self, k: usize) -> Result<(), String> {
        if self.min.len() != k || self.max.len() != k {
            return Err(format!(
                "{} and {} shape bounds for {k} signals",
                self.min.len(),
                self.max.len()
            ));
        }
        if !(self.scale.is_finite() && self.scale > 0.0) {
            return Err(format!("shape scale {}: need a positive one", self.scale));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sine's shape is √2·sin(π f Δt): 1 near a quarter of the sampling
    /// rate, small well below it.
    #[test]
    fn a_sines_shape_follows_its_frequency() {
        for f in [1.0, 5.0, 12.5] {
            let a: Vec<f64> = (0..1000)
                .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 * 0.02).sin())
                .collect();
            let m = a.iter().sum::<f64>() / 1000.0;
            let var = a.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / 1000.0;
            let want = 2f64.sqrt() * (std::f64::consts::PI * f * 0.02).sin();
            assert!((shape(&a, var) - want).abs() < 0.01, "{f} Hz");
        }
    }

    #[test]
    fn quiet_windows_do_not_set_the_interval_and_an_unseen_signal_takes_every_shape() {
        // Two signals: the first vibrates at shapes 1.1 and 1.3, once quiet
        // at 0.2; the second never vibrates.
        let stats: [&[f64]; 3] = [
            &[0.0, 0.0, 0.3, 0.01, 1.1, 0.5],
            &[0.0, 0.0, 0.2, 0.01, 1.3, 0.4],
            &[0.0, 0.0, 0.02, 0.01, 0.2, 0.6],
        ];
        let r = ShapeRange::from_training(&stats, 2, 0.05);
        assert_eq!((r.min, r.max), (vec![1.1, 0.0], vec![1.3, SHAPE_MAX]));
    }

    #[test]
    fn a_shape_counts_in_proportion_to_its_level_up_to_two_scales() {
        let r = ShapeRange {
            min: vec![1.0],
            max: vec![1.3],
            scale: SHAPE_SCALE,
        };
        // 0.5 below the interval: 5 shape scales at full level.
        assert!((r.term(0, 0.3, 0.5, 0.05) - 5.0).abs() < 1e-12);
        assert!((r.term(0, 0.075, 0.5, 0.05) - 2.5).abs() < 1e-12);
        assert_eq!(r.term(0, 0.05, 0.5, 0.05), 0.0);
        assert_eq!(r.term(0, 0.3, 1.2, 0.05), 0.0);
    }
}
