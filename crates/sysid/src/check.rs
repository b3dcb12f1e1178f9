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
    /// Rms of target − model about its own mean, √(rms_after² −
    /// mean_after²): what the model leaves varying, to compare with
    /// `rms_before` (about the record's mean too).
    pub spread_after: f64,
    /// `rms_after` of the model as fitted, its network part not faded
    /// outside the training range (null for a model without a range: it
    /// never fades).
    pub rms_after_unfaded: Option<f64>,
    /// `mean_after` of the model not faded.
    pub mean_after_unfaded: Option<f64>,
    /// `spread_after` of the model not faded.
    pub spread_after_unfaded: Option<f64>,
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
    /// Share of windows outside the per-signal training range alone (each
    /// operating signal's mean and vibration level, [`crate::operating::range`];
    /// null for a model without one). `outside_fraction` counts a window
    /// outside either measure.
    pub outside_range_fraction: Option<f64>,
    /// Mean weight of the network part over the windows (1: never faded;
    /// null for a model without a range).
    pub fade_weight_mean: Option<f64>,
    /// What the record has that the model did not see, in words (which
    /// signal, which level or mean; empty when nothing).
    pub lacks: Vec<String>,
}

/// Measures how well `model` holds on a record it was not fitted on,
/// `prepared` by [`Model::prepare`] and `predicted` what compensation
/// subtracts ([`crate::Model::predict_faded`], or an on-line run
/// of the model), warning when more than `threshold` of the windows lie
/// outside the training range or a channel keeps an offset the model cannot
/// know. The figures without the fade come from [`Model::predict`].
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let model = sysid::fit(&Line, &line_record(3000, 2.0, 1), &options, &|_| {})?;
/// let other = model.prepare(&line_record(2000, 2.0, 2))?;
/// let faded = model.predict_faded(&other)?;
/// let c = sysid::check::transfer(&model, &other, &faded.predicted, 0.05)?;
/// assert!(c.channels[0].rms_after < c.channels[0].rms_before);
/// assert!(c.channels[0].spread_after <= c.channels[0].rms_after);
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
    let range = RangeView::of(model, prepared)?;
    let outside: Option<Vec<bool>> = distances.as_ref().map(|d| {
        d.iter()
            .enumerate()
            .map(|(i, &v)| v > OUTSIDE_FACTOR || range.as_ref().is_some_and(|r| r.outside[i]))
            .collect()
    });
    let median_relative_distance = distances.map(|mut d| {
        d.sort_by(f64::total_cmp);
        d[d.len() / 2]
    });
    let unfaded = match &range {
        Some(_) => Some(model.predict(prepared)?),
        None => None,
    };
    let channels: Vec<ChannelTransfer<S::Channel>> = model
        .channels()
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let y = prepared.target(k);
            let mut t = channel_transfer(c.channel(), y, &predicted[k], &outside);
            if let Some(u) = &unfaded {
                let (rms, mean) = rms_and_mean(y, &u[k]);
                t.rms_after_unfaded = Some(rms);
                t.mean_after_unfaded = Some(mean);
                t.spread_after_unfaded = Some(spread(rms, mean));
            }
            t
        })
        .collect();
    let share = |o: &[bool]| o.iter().filter(|v| **v).count() as f64 / n as f64;
    let outside_fraction = outside.as_deref().map(share);
    let lacks = range.as_ref().map_or_else(Vec::new, |r| r.lacks.clone());
    let wording = model.sensor().wording();
    let warning = match outside_fraction {
        None => Some(
            "the model file has no training operating points (fitted by an older version): refit it to measure extrapolation".to_string(),
        ),
        Some(f) if f > threshold => Some(outside_warning(f, threshold, &lacks, model)),
        Some(_) => offset_warning(&channels, &wording.target_unit),
    };
    Ok(Transfer {
        channels,
        outside_fraction,
        median_relative_distance,
        threshold,
        warning,
        windows: n,
        outside_range_fraction: range.as_ref().map(|r| share(&r.outside)),
        fade_weight_mean: range
            .as_ref()
            .map(|r| r.weight.iter().sum::<f64>() / n.max(1) as f64),
        lacks,
    })
}

/// The per-signal range's view of a record: which windows lie outside it,
/// the fade weights, and what the record lacks in words.
struct RangeView {
    outside: Vec<bool>,
    weight: Vec<f64>,
    lacks: Vec<String>,
}

impl RangeView {
    fn of<S: Sensor>(model: &Model<S>, prepared: &Prepared<S>) -> Result<Option<Self>, SysidError> {
        let Some(range) = model.operating_points().and_then(|o| o.range.as_ref()) else {
            return Ok(None);
        };
        let Some(w) = model.fade_weights(prepared)? else {
            return Ok(None);
        };
        let rows: Vec<usize> = (0..prepared.rows()).collect();
        let stats = crate::operating::range::statistics(prepared, range.window, &rows)?;
        let wording = model.sensor().wording();
        Ok(Some(Self {
            outside: w.distance.iter().map(|&d| range.is_outside(d)).collect(),
            weight: w.weight,
            lacks: range.lacks(&stats, &wording.operating_unit, &wording.spread),
        }))
    }
}

/// The warning of a record mostly outside: the share, what it lacks, and
/// what that means for the network part.
fn outside_warning<S: Sensor>(
    f: f64,
    threshold: f64,
    lacks: &[String],
    model: &Model<S>,
) -> String {
    let head = format!(
        "{:.1}% of the windows lie outside the operating range the model was trained on (threshold {:.1}%)",
        100.0 * f,
        100.0 * threshold
    );
    if lacks.is_empty() {
        // Outside only by the joint operating points (mean and summed level
        // together), or a model without a per-signal range.
        let advice = if model.records().is_empty() {
            "fit on a record that covers them (several --data)"
        } else {
            "the records it was fitted on do not hold these conditions together: add one that does"
        };
        return format!("{head}: its errors there are extrapolation; {advice}");
    }
    format!(
        "{head}: {}; its network part fades out there (the effects stay), and the mean offset it leaves is not one the model can know: to compensate there, fit with a record that has those conditions",
        lacks.join("; ")
    )
}

/// A channel whose mean offset after compensation is larger than what it
/// leaves varying holds a bias the model does not know (a bias shift since
/// the fit, or conditions the operating point does not see).
fn offset_warning<C: std::fmt::Display>(
    channels: &[ChannelTransfer<C>],
    unit: &str,
) -> Option<String> {
    let big: Vec<String> = channels
        .iter()
        .filter(|c| c.mean_after.abs() > c.spread_after.max(c.rms_before))
        .map(|c| format!("{} ({:+.4} {unit})", c.channel, c.mean_after))
        .collect();
    (!big.is_empty()).then(|| {
        format!(
            "mean offset after compensation larger than the variation before on {}: a bias the model does not know (it moved since the fit, or the record holds conditions the operating point does not see); the record counts as outside what the model knows",
            big.join(", ")
        )
    })
}

/// Rms about zero and mean of `y − predicted`.
fn rms_and_mean(y: &[f64], predicted: &[f64]) -> (f64, f64) {
    let e: Vec<f64> = y.iter().zip(predicted).map(|(a, b)| a - b).collect();
    (
        stats::rms(&e),
        e.iter().sum::<f64>() / e.len().max(1) as f64,
    )
}

/// The rms about the mean from the rms about zero and the mean (rms² =
/// mean² + spread²).
pub fn spread(rms: f64, mean: f64) -> f64 {
    (rms * rms - mean * mean).max(0.0).sqrt()
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
    let mean_after = e.iter().sum::<f64>() / n as f64;
    ChannelTransfer {
        channel,
        rms_before: before,
        rms_after: after,
        mean_after,
        fit_percent: 100.0 * (1.0 - after / before),
        rms_inside: pick(false),
        rms_outside: pick(true),
        spread_after: spread(after, mean_after),
        rms_after_unfaded: None,
        mean_after_unfaded: None,
        spread_after_unfaded: None,
    }
}
