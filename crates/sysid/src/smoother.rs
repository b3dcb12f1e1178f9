//! The prediction smoother: a 2nd-order Butterworth low-pass on the network
//! part of a prediction (the effects, which carry units and intervals, are
//! not smoothed), forward–backward (zero-phase) offline and one causal pass
//! started in the steady state of its first value in causal mode, as the
//! onboard evaluator runs it.
//!
//! Why: the network reads a vibration level estimated over one window, and
//! a 50-sample window's level of near-white vibration has ~20% relative
//! noise, correlated over the window; the error it predicts (a rectified
//! error following the test's schedule) is slow. Unsmoothed, that
//! estimation noise is added to the gyro and raises its Allan deviation at
//! τ of a fraction of a second to a second; smoothed, it is removed and the
//! validation rms falls as well (docs/dtg-vib.md, "The model's input and
//! smoother").

use crate::error::SysidError;
use iir::LowPass;
use serde::{Deserialize, Serialize};

/// Order of the smoother's Butterworth low-pass.
pub const SMOOTHER_ORDER: usize = 2;

/// The cut-offs a fit tries, Hz, besides no smoother.
pub const SMOOTHER_LADDER_HZ: [f64; 4] = [0.5, 0.2, 0.1, 0.05];

/// A low-pass on the network part of each prediction.
///
/// ```
/// let s = sysid::Smoother { cutoff_hz: 0.2 };
/// // A step through the causal pass settles on the step; zero-phase, it
/// // starts before it.
/// let x: Vec<f64> = (0..2000).map(|i| if i < 1000 { 0.0 } else { 1.0 }).collect();
/// let causal = s.apply(&x, 0.02, true).unwrap();
/// let zero_phase = s.apply(&x, 0.02, false).unwrap();
/// assert_eq!(causal[999], 0.0);
/// assert!(zero_phase[999] > 0.4 && zero_phase[999] < 0.6);
/// assert!((causal[1999] - 1.0).abs() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Smoother {
    /// −3 dB cut-off of one pass, Hz.
    pub cutoff_hz: f64,
}

impl Smoother {
    /// The filter at the sample interval `dt_s`.
    pub fn design(&self, dt_s: f64) -> Result<LowPass, SysidError> {
        Ok(LowPass::butterworth(
            SMOOTHER_ORDER,
            self.cutoff_hz,
            1.0 / dt_s,
        )?)
    }

    /// `x` (one record's network part, one value per sample) smoothed:
    /// one causal pass from the steady state of `x[0]`, or forward–backward.
    pub fn apply(&self, x: &[f64], dt_s: f64, causal: bool) -> Result<Vec<f64>, SysidError> {
        let f = self.design(dt_s)?;
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return Err(iir::FilterError::NotFinite { index: i }.into());
        }
        if causal {
            Ok(f.filter_causal(x))
        } else {
            Ok(f.filtfilt(x)?)
        }
    }

    /// Its name in reports: the cut-off in Hz.
    pub fn label(smoother: Option<Smoother>) -> String {
        match smoother {
            None => "none".into(),
            Some(s) => format!("{} Hz", s.cutoff_hz),
        }
    }
}

/// A channel's predictions `y` (one per row, the rows of `records`, each
/// record's range; with the effects' regressors `z`, bias `bias` and effect
/// coefficients `theta`) with their network part smoothed by `smoother`, if
/// any (`causal`: one forward pass, else zero-phase): bias and effects as
/// they are.
#[allow(clippy::too_many_arguments)]
pub(crate) fn smoothed(
    smoother: Option<&Smoother>,
    causal: bool,
    dt_s: f64,
    records: &[std::ops::Range<usize>],
    (bias, theta): (f64, &[f64]),
    z: &faer::Mat<f64>,
    y: Vec<f64>,
) -> Result<Vec<f64>, SysidError> {
    let Some(s) = smoother else {
        return Ok(y);
    };
    let linear: Vec<f64> = (0..y.len())
        .map(|i| {
            bias + theta
                .iter()
                .enumerate()
                .map(|(j, t)| z[(i, j)] * t)
                .sum::<f64>()
        })
        .collect();
    let net: Vec<f64> = y.iter().zip(&linear).map(|(y, l)| y - l).collect();
    let smooth = smooth_by_record(s, &net, records, dt_s, causal)?;
    Ok(linear.iter().zip(&smooth).map(|(l, n)| l + n).collect())
}

/// The network parts `net` (one value per row) smoothed record by record
/// (`records`: each record's rows), so nothing is smoothed across a
/// boundary.
pub(crate) fn smooth_by_record(
    smoother: &Smoother,
    net: &[f64],
    records: &[std::ops::Range<usize>],
    dt_s: f64,
    causal: bool,
) -> Result<Vec<f64>, SysidError> {
    let mut out = Vec::with_capacity(net.len());
    for r in records {
        out.extend(smoother.apply(&net[r.clone()], dt_s, causal)?);
    }
    Ok(out)
}
