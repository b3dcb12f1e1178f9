//! Does a model hold on a record it was not fitted on? Per channel rms
//! before and after compensation, and how much of the record lies outside
//! the operating range the model was trained on ([`crate::operating`]).

use crate::error::SysidError;
use crate::model::Model;
use crate::operating::{OUTSIDE_FACTOR, points};
use crate::prepared::Prepared;
use crate::sensor::Sensor;
use serde::Serialize;

/// Share of windows outside the training range above which the check warns.
pub const DEFAULT_OUTSIDE_THRESHOLD: f64 = 0.05;

/// One channel on the new record, in the target's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelTransfer<C> {
    /// The channel.
    pub channel: C,
    /// Rms of the pre-processed target about its mean: what the best
    /// constant (bias-only) correction leaves.
    pub rms_before: f64,
    /// Rms of target − model about zero: everything the model leaves,
    /// a bias that moved since the fit included.
    pub rms_after: f64,
    /// Mean of target − model (a bias shift, or a rectified error the model
    /// does not know at this level).
    pub mean_after: f64,
    /// 100·(1 − ‖y − ŷ‖/‖y − ȳ‖), as MATLAB's `compare`.
    pub fit_percent: f64,
    /// Rms of target − model on windows inside the training range (null if none).
    pub rms_inside: Option<f64>,
    /// Rms of target − model on windows outside it (null if none).
    pub rms_outside: Option<f64>,
}

/// A model checked on another record: what every sensor's check says.
#[derive(Debug, Clone, Serialize)]
pub struct Transfer<C> {
    /// Every channel.
    pub channels: Vec<ChannelTransfer<C>>,
    /// Share of windows outside the training range (null for a model
    /// without operating points).
    pub outside_fraction: Option<f64>,
    /// Median relative distance of the windows to the training points (1 is
    /// the training points' own 99th-percentile spacing).
    pub median_relative_distance: Option<f64>,
    /// The share that triggers the warning.
    pub threshold: f64,
    /// Why the comparison should not be trusted as is, if it should not.
    pub warning: Option<String>,
    /// Windows compared.
    pub windows: usize,
}

/// Measures how well `model` holds on a record it was not fitted on,
/// `prepared` by [`Model::prepare`] and `predicted` by [`Model::predict`]
/// (or an on-line run of the model), warning when more than `threshold` of
/// the windows lie outside the training range.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let model = sysid::fit(&Line, &line_record(3000, 2.0, 1), &options, &|_| {})?;
/// let other = model.prepare(&line_record(2000, 2.0, 2))?;
/// let c = sysid::check::transfer(&model, &other, &model.predict(&other)?, 0.05)?;
/// assert!(c.channels[0].rms_after < c.channels[0].rms_before);
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn transfer<S: Sensor>(
    model: &Model<S>,
    prepared: &Prepared<S>,
    predicted: &[Vec<f64>],
    threshold: f64,
) -> Result<Transfer<S::Channel>, SysidError> {
    if !(0.0..=1.0).contains(&threshold) {
        return Err(SysidError::InvalidOption {
            name: "outside threshold",
            value: threshold.to_string(),
            reason: "a share of windows, between 0 and 1",
        });
    }
    let n = prepared.rows();
    let rows: Vec<usize> = (0..n).collect();
    let distances = match model.operating_points() {
        Some(op) => {
            let length = model.preprocess().window.length();
            Some(op.relative_distances(&points(prepared, length, &rows)?)?)
        }
        None => None,
    };
    let outside: Option<Vec<bool>> = distances
        .as_ref()
        .map(|d| d.iter().map(|&v| v > OUTSIDE_FACTOR).collect());
    let median_relative_distance = distances.map(|mut d| {
        d.sort_by(f64::total_cmp);
        d[d.len() / 2]
    });
    let channels = model
        .channels()
        .iter()
        .enumerate()
        .map(|(k, c)| channel_transfer(c.channel(), prepared.target(k), &predicted[k], &outside))
        .collect();
    let outside_fraction = outside.map(|o| o.iter().filter(|v| **v).count() as f64 / n as f64);
    let warning = match outside_fraction {
        None => Some(
            "the model file has no training operating points (fitted by an older version): refit it to measure extrapolation".to_string(),
        ),
        Some(f) if f > threshold => Some(format!(
            "{:.1}% of the windows lie outside the operating range the model was trained on (threshold {:.1}%): its errors there are extrapolation; fit on a record that covers them (several --data)",
            100.0 * f,
            100.0 * threshold
        )),
        Some(_) => None,
    };
    Ok(Transfer {
        channels,
        outside_fraction,
        median_relative_distance,
        threshold,
        warning,
        windows: n,
    })
}

/// One channel's figures: the target `y`, the prediction, and which rows
/// lie outside the training range (if known).
fn channel_transfer<C>(
    channel: C,
    y: &[f64],
    predicted: &[f64],
    outside: &Option<Vec<bool>>,
) -> ChannelTransfer<C> {
    let n = y.len();
    let e: Vec<f64> = y.iter().zip(predicted).map(|(a, b)| a - b).collect();
    let mean_y = y.iter().sum::<f64>() / n as f64;
    let dev: Vec<f64> = y.iter().map(|v| v - mean_y).collect();
    let (before, after) = (stats::rms(&dev), stats::rms(&e));
    let pick = |want: bool| -> Option<f64> {
        let o = outside.as_ref()?;
        let sel: Vec<f64> = e
            .iter()
            .zip(o)
            .filter(|(_, out)| **out == want)
            .map(|(v, _)| *v)
            .collect();
        (!sel.is_empty()).then(|| stats::rms(&sel))
    };
    ChannelTransfer {
        channel,
        rms_before: before,
        rms_after: after,
        mean_after: e.iter().sum::<f64>() / n as f64,
        fit_percent: 100.0 * (1.0 - after / before),
        rms_inside: pick(false),
        rms_outside: pick(true),
    }
}
