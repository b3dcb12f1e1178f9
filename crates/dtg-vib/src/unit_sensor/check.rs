//! Does a model hold on a record it was not fitted on? Per channel rms
//! before and after compensation, the parity residues, and how much of the
//! record lies outside the operating range the model was trained on
//! ([`sysid::operating`]).

use super::apply::Applied;
use super::model::UnitModel;
use super::parity::{ResidueSeries, ResidueStats};
use crate::error::DtgVibError;
use serde::Serialize;

/// Standard deviation of the unit's rate (deg/s, any axis) above which a
/// record is taken as moving: the anisoinertia candidates' threshold, the
/// rate a vibration table does not reach.
pub const MOVING_RATE_DEG_S: f64 = super::ANISOINERTIA_MIN_RATE_DEG_S;

/// Share of windows outside the training range above which `check` warns.
pub use sysid::check::DEFAULT_OUTSIDE_THRESHOLD;

/// One channel on the new record, deg/h.
pub type ChannelTransfer = sysid::check::ChannelTransfer<String>;

/// A model checked on another record.
#[derive(Debug, Clone, Serialize)]
pub struct TransferCheck {
    /// Every channel, in the unit's order.
    pub channels: Vec<ChannelTransfer>,
    /// Parity residues before and after compensation, every row (none for
    /// a unit of three gyros).
    pub residues: Vec<ResidueStats>,
    /// Share of windows outside the training range (null for a model file
    /// without operating points).
    pub outside_fraction: Option<f64>,
    /// Median relative distance of the windows to the training points (1 is
    /// the training points' own 99th-percentile spacing).
    pub median_relative_distance: Option<f64>,
    /// The share that triggers the warning.
    pub threshold: f64,
    /// Why the comparison should not be trusted as is, if it should not.
    pub warning: Option<String>,
    /// Largest standard deviation of the unit's least-squares rate over the
    /// record (any axis), deg/s: above [`MOVING_RATE_DEG_S`] the unit moves.
    pub rate_std_deg_s: f64,
    /// What the figures mean on this record, if they need saying: on a
    /// moving unit each channel's rms holds the motion itself.
    pub note: Option<String>,
    /// Windows compared.
    pub windows: usize,
    /// Share of windows outside the per-axis training range alone (each
    /// axis's mean specific force and vibration level; null for a model
    /// without one).
    pub outside_range_fraction: Option<f64>,
    /// Mean weight of the network part over the windows (1: never faded).
    pub fade_weight_mean: Option<f64>,
    /// What the record has that the model did not see, in words.
    pub lacks: Vec<String>,
    /// Parity residues after the model as fitted, its network part not
    /// faded (null for a model without a training range: `residues` is it).
    pub residues_unfaded: Option<Vec<ResidueStats>>,
}

/// Measures how well `model`, applied to records it was not fitted on,
/// holds, warning when more than `threshold` of the windows lie outside
/// the training range.
pub fn check(
    model: &UnitModel,
    applied: &Applied,
    threshold: f64,
) -> Result<TransferCheck, DtgVibError> {
    let p = &applied.prepared;
    let t = sysid::check::transfer(model.inner(), p, &applied.predicted, threshold)?;
    // A gyro channel reads the unit's own rate as well as its errors; only a
    // fixed rate reference is removed, so on a moving unit (a flight) the
    // channel rms is mostly motion, while the parity residues cancel any rate.
    let calibrated = p.calibrated();
    let all: Vec<usize> = (0..calibrated.len()).collect();
    let rate_std_deg_s = p.sensor().rate_variation_deg_s(calibrated, &all);
    let parity = p.sensor().rate_reference == super::RateReference::Parity;
    // A unit of three gyros has no residue to point at.
    let redundant = !p.sensor().unit.residue_names().is_empty();
    let note = (rate_std_deg_s > MOVING_RATE_DEG_S).then(|| match parity {
        false if redundant => format!(
            "the unit moves on this record (its rate varies by {rate_std_deg_s:.2} deg/s rms): each channel's rms before and after holds that motion, which no fixed rate reference removes; the parity residues cancel any rate, judge the model on this record by them"
        ),
        false => format!(
            "the unit moves on this record (its rate varies by {rate_std_deg_s:.2} deg/s rms): each channel's rms before and after holds that motion, which no fixed rate reference removes, and with {} gyros no parity residue cancels it: judge the model on a still record, or on a rate table with its rate reference",
            p.sensor().unit.gyros().len()
        ),
        true => format!(
            "the unit moves on this record (its rate varies by {rate_std_deg_s:.2} deg/s rms): the model was fitted in parity, so each channel's rms before and after is of its parity-projected output (the motion removed); the pooled parity residue says how much the model transfers"
        ),
    });
    let residues = applied.residues();
    let every: Vec<usize> = (0..p.rows()).collect();
    Ok(TransferCheck {
        channels: t.channels,
        residues: residues.stats(&every),
        outside_fraction: t.outside_fraction,
        median_relative_distance: t.median_relative_distance,
        threshold: t.threshold,
        warning: t.warning,
        rate_std_deg_s,
        note,
        windows: t.windows,
        residues_unfaded: unfaded_residues(model, applied, &residues)?,
        outside_range_fraction: t.outside_range_fraction,
        fade_weight_mean: t.fade_weight_mean,
        lacks: t.lacks,
    })
}

/// The residues after the model as fitted (not faded), every row; `None`
/// for a model without a training range, which never fades.
fn unfaded_residues(
    model: &UnitModel,
    applied: &Applied,
    faded: &ResidueSeries,
) -> Result<Option<Vec<ResidueStats>>, DtgVibError> {
    let inner = model.inner();
    if inner
        .operating_points()
        .and_then(|o| o.range.as_ref())
        .is_none()
    {
        return Ok(None);
    }
    let p = &applied.prepared;
    let predicted = inner.predict(p)?;
    let first = p.first_sample();
    let outputs: Vec<Vec<f64>> = (0..predicted.len())
        .map(|k| p.target_full(k)[first..].to_vec())
        .collect();
    let series = ResidueSeries::new(&p.sensor().unit, faded.t.clone(), &outputs, &predicted);
    let all: Vec<usize> = (0..series.t.len()).collect();
    Ok(Some(series.stats(&all)))
}
