//! The network's input: the raw window of the windowed signals (the DTG
//! paper's 50 samples of `az`), or a few statistics of it per signal.
//!
//! A rectified (level-dependent) error follows the vibration *level*, which
//! a window carries in its energy, not in the order of its samples: per
//! signal the current sample, the window's mean and its rms about that mean
//! say as much as the whole window to such an error, in 3 numbers instead
//! of `length` (9 instead of 150 for 50 samples of ax, ay, az), and the
//! kernel's distances, nearly all the cost of an onboard step, shrink with
//! them. The current sample keeps what a low-frequency (resolved)
//! vibration does sample by sample.
//!
//! The statistics stay in the signal's unit (g for accelerations), not
//! divided by their spread: standardised, a quiet axis's noise would weigh
//! as much in a distance as a vibrating axis's level.
//!
//! The mean and rms come from running sums over the window, updated by one
//! sample in and one sample out in exactly this order (the `dtg-onboard`
//! evaluator and the exported C do the same arithmetic):
//! `s₁ ← (s₁ + v) − v_old`, `s₂ ← (s₂ + v·v) − v_old·v_old` (`v_old = 0`
//! while the window fills), mean `s₁/L`, rms `√max(s₂/L − mean², 0)`.

use crate::window::{WindowError, WindowSpec, Windows};
use serde::{Deserialize, Serialize};

/// What the network reads of the windowed signals.
///
/// ```
/// use sysid::{ModelInput, WindowSpec};
/// let w = WindowSpec::new(vec!["ax".into(), "ay".into(), "az".into()], 50).unwrap();
/// assert_eq!(ModelInput::Raw.dim(&w), 150);
/// assert_eq!(ModelInput::Statistics.dim(&w), 9);
/// assert_eq!("statistics".parse::<ModelInput>().unwrap(), ModelInput::Statistics);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelInput {
    /// The window itself: `length` samples of each signal, oldest first.
    #[default]
    Raw,
    /// Per signal: the current sample, the window mean and the window rms
    /// about its mean, in the signal's unit.
    Statistics,
}

/// Statistics per signal of [`ModelInput::Statistics`].
pub const STATISTICS_PER_SIGNAL: usize = 3;

impl ModelInput {
    /// Both inputs, in the order a choice lists them.
    pub const ALL: [ModelInput; 2] = [ModelInput::Raw, ModelInput::Statistics];

    /// True for [`ModelInput::Raw`] (what files written before the choice
    /// hold: the field is left out of them).
    pub fn is_raw(&self) -> bool {
        *self == ModelInput::Raw
    }

    /// The network's input dimension for windows `window`.
    pub fn dim(self, window: &WindowSpec) -> usize {
        match self {
            ModelInput::Raw => window.dim(),
            ModelInput::Statistics => STATISTICS_PER_SIGNAL * window.signals().len(),
        }
    }

    /// Its name in files, flags and reports.
    pub fn name(self) -> &'static str {
        match self {
            ModelInput::Raw => "raw",
            ModelInput::Statistics => "statistics",
        }
    }

    /// The inputs of every full window of `signals` (one slice per name of
    /// `window`, all of one length): rows as [`WindowSpec::build`]'s.
    pub fn build(self, window: &WindowSpec, signals: &[&[f64]]) -> Result<Windows, WindowError> {
        let raw = window.build(signals)?;
        match self {
            ModelInput::Raw => Ok(raw),
            ModelInput::Statistics => {
                let per: Vec<Vec<[f64; 3]>> = signals
                    .iter()
                    .map(|s| running_statistics(s, window.length()))
                    .collect();
                let dim = self.dim(window);
                let mut data = Vec::with_capacity(raw.len() * dim);
                for r in 0..raw.len() {
                    for p in &per {
                        data.extend_from_slice(&p[r]);
                    }
                }
                Ok(Windows::written(data, dim, raw.first_sample(), raw.len()))
            }
        }
    }
}

impl std::fmt::Display for ModelInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for ModelInput {
    type Err = crate::error::SysidError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "raw" => Ok(ModelInput::Raw),
            "statistics" => Ok(ModelInput::Statistics),
            other => Err(crate::error::SysidError::InvalidOption {
                name: "input",
                value: other.to_string(),
                reason: "use raw or statistics",
            }),
        }
    }
}

/// `[current, mean, rms about the mean]` of every full window of `length`
/// samples of `x` (row `i` ends at sample `length − 1 + i`), from running
/// sums in the order the module documents.
///
/// ```
/// let s = sysid::input::running_statistics(&[1.0, 3.0, 1.0, 3.0], 2);
/// assert_eq!(s, vec![[3.0, 2.0, 1.0], [1.0, 2.0, 1.0], [3.0, 2.0, 1.0]]);
/// ```
pub fn running_statistics(x: &[f64], length: usize) -> Vec<[f64; 3]> {
    let l = length as f64;
    let (mut s1, mut s2) = (0.0f64, 0.0f64);
    let mut out = Vec::with_capacity(x.len().saturating_sub(length - 1));
    for (t, &v) in x.iter().enumerate() {
        let old = if t >= length { x[t - length] } else { 0.0 };
        s1 = (s1 + v) - old;
        s2 = (s2 + v * v) - old * old;
        if t + 1 >= length {
            let mean = s1 / l;
            let var = s2 / l - mean * mean;
            out.push([v, mean, if var > 0.0 { var.sqrt() } else { 0.0 }]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The running sums agree with each window's direct mean and rms about
    /// its mean, over a long record with a 1 g offset (where a running sum
    /// of squares could lose digits).
    #[test]
    fn running_sums_equal_each_windows_direct_statistics() {
        let x: Vec<f64> = (0..20_000)
            .map(|i| 1.0 + 0.05 * ((i as f64) * 0.37).sin() + 0.01 * ((i * 7919) % 101) as f64)
            .collect();
        let l = 50;
        let s = running_statistics(&x, l);
        assert_eq!(s.len(), x.len() - l + 1);
        for (i, r) in s.iter().enumerate() {
            let w = &x[i..i + l];
            assert_eq!(r[0], w[l - 1]);
            assert!((r[1] - stats::mean(w)).abs() < 1e-12);
            assert!((r[2] - stats::std_dev(w)).abs() < 1e-9, "{i}: {r:?}");
        }
    }

    #[test]
    fn statistics_rows_are_per_signal_triples() {
        let w = WindowSpec::new(vec!["a".into(), "b".into()], 2).unwrap();
        let a = [1.0, 3.0, 5.0];
        let b = [0.0, 0.0, 2.0];
        let s = ModelInput::Statistics.build(&w, &[&a, &b]).unwrap();
        assert_eq!((s.len(), s.dim(), s.first_sample()), (2, 6, 1));
        assert_eq!(s.row(1), &[5.0, 4.0, 1.0, 2.0, 1.0, 1.0]);
    }
}
