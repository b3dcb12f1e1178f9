//! Does a model hold on a record it was not fitted on? Per channel rms
//! before and after compensation, the parity residues, and how much of the
//! record lies outside the operating range the model was trained on
//! ([`crate::operating`]).

use crate::apply::Applied;
use crate::error::DtgVibError;
use crate::model::CompensationModel;
use crate::operating;
use crate::parity::ResidueStats;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use serde::Serialize;

/// Standard deviation of the unit's rate (deg/s, any axis) above which a
/// record is taken as moving: the anisoinertia candidates' threshold, the
/// rate a vibration table does not reach.
pub const MOVING_RATE_DEG_S: f64 = crate::effects::ANISOINERTIA_MIN_RATE_DEG_S;

/// Share of windows outside the training range above which `check` warns.
pub const DEFAULT_OUTSIDE_THRESHOLD: f64 = 0.05;

/// One channel on the new record, deg/h.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelTransfer {
    /// The channel.
    pub channel: Channel,
    /// Rms of the pre-processed output about its mean: what the best
    /// constant (bias-only) correction leaves.
    pub rms_before: f64,
    /// Rms of output − model about zero: everything the model leaves,
    /// a bias that moved since the fit included.
    pub rms_after: f64,
    /// Mean of output − model (a bias shift, or a rectified error the model
    /// does not know at this vibration level).
    pub mean_after: f64,
    /// 100·(1 − ‖y − ŷ‖/‖y − ȳ‖), as MATLAB's `compare`.
    pub fit_percent: f64,
    /// Rms of output − model on windows inside the training range (null if none).
    pub rms_inside: Option<f64>,
    /// Rms of output − model on windows outside it (null if none).
    pub rms_outside: Option<f64>,
}

/// A model checked on another record.
#[derive(Debug, Clone, Serialize)]
pub struct TransferCheck {
    /// The six channels.
    pub channels: Vec<ChannelTransfer>,
    /// Parity residues before and after compensation, every row.
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
}

/// Applies `model` to `record` (never fitted on it) and measures how well it
/// holds, warning when more than `threshold` of the windows lie outside the
/// training range.
///
/// ```no_run
/// let model = dtg_vib::model::CompensationModel::load("model.json")?;
/// let other = nav_sensors::record::Record::read_csv("x-axis.csv")?;
/// let c = dtg_vib::check::check(&model, &other, dtg_vib::check::DEFAULT_OUTSIDE_THRESHOLD)?;
/// if let Some(w) = &c.warning { eprintln!("{w}"); }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check(
    model: &CompensationModel,
    record: &Record,
    threshold: f64,
) -> Result<TransferCheck, DtgVibError> {
    check_applied(model, &Applied::unsplit(model, record)?, threshold)
}

/// [`check`] of a model already applied to the record (a report of the same
/// record needs the application too: predict once).
pub fn check_applied(
    model: &CompensationModel,
    applied: &Applied,
    threshold: f64,
) -> Result<TransferCheck, DtgVibError> {
    if !(0.0..=1.0).contains(&threshold) {
        return Err(DtgVibError::InvalidOption {
            name: "outside threshold",
            value: threshold.to_string(),
            reason: "a share of windows, between 0 and 1",
        });
    }
    let prepared = &applied.prepared;
    let n = prepared.rows();
    let rows: Vec<usize> = (0..n).collect();
    let distances = match model.operating_points() {
        Some(op) => {
            let length = model.preprocess().window.length();
            Some(op.relative_distances(&operating::points(prepared, length, &rows))?)
        }
        None => None,
    };
    let outside: Option<Vec<bool>> = distances
        .as_ref()
        .map(|d| d.iter().map(|&v| v > operating::OUTSIDE_FACTOR).collect());
    let median_relative_distance = distances.map(|mut d| {
        d.sort_by(f64::total_cmp);
        d[d.len() / 2]
    });
    let channels = Channel::ALL
        .iter()
        .map(|&ch| {
            let y = prepared.target(ch);
            let e: Vec<f64> = y
                .iter()
                .zip(&applied.predicted[ch.index()])
                .map(|(a, b)| a - b)
                .collect();
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
                channel: ch,
                rms_before: before,
                rms_after: after,
                mean_after: e.iter().sum::<f64>() / n as f64,
                fit_percent: 100.0 * (1.0 - after / before),
                rms_inside: pick(false),
                rms_outside: pick(true),
            }
        })
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
    // A gyro channel reads the unit's own rate as well as its errors; only a
    // fixed rate reference is removed, so on a moving unit (a flight) the
    // channel rms is mostly motion, while the parity residues cancel any rate.
    let rec = prepared.calibrated();
    let rate_std_deg_s = crate::effects::rate_variation_deg_s(rec, 0..rec.len());
    let note = (rate_std_deg_s > MOVING_RATE_DEG_S).then(|| {
        format!(
            "the unit moves on this record (its rate varies by {rate_std_deg_s:.2} deg/s rms): each channel's rms before and after holds that motion, which no fixed rate reference removes; the parity residues cancel any rate, judge the model on this record by them"
        )
    });
    Ok(TransferCheck {
        channels,
        residues: applied.all_residues(),
        outside_fraction,
        median_relative_distance,
        threshold,
        warning,
        rate_std_deg_s,
        note,
        windows: n,
    })
}
