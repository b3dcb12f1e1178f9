//! From a test record to model inputs: ground-calibration compensation, the
//! optional rate reference, low-pass (zero-phase, or causal in
//! [`Preprocess::causal`] mode), windows and effect columns.
//!
//! The same [`Preprocess`] is stored in a fitted model, so compensation and
//! diagnosis see data prepared exactly as the training data were.

use crate::effects::{Effect, EffectColumns};
use crate::error::DtgVibError;
use crate::signal::LowPass;
use crate::window::{WindowSpec, Windows};
use faer::{Mat, MatRef};
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::{Axis, Channel, ideal_outputs};
use nav_sensors::record::Record;
use nav_sensors::sim::Site;
use serde::{Deserialize, Serialize};

/// A zero-phase Butterworth low-pass: `order` and −3 dB `cutoff_hz` of one
/// pass (the forward–backward pass is −6 dB there).
///
/// ```
/// let f = dtg_vib::pipeline::FilterSpec::default();
/// assert_eq!((f.order, f.cutoff_hz), (4, 5.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilterSpec {
    /// Filter order (1 to 12).
    pub order: usize,
    /// Cut-off, Hz.
    pub cutoff_hz: f64,
}

impl Default for FilterSpec {
    /// 4th order at 5 Hz on 50-Hz data. The paper names a low-pass but not
    /// its corner; 5 Hz keeps the level-dependent (rectified) error, which
    /// moves on the scale of seconds, and the part of the
    /// vibration-proportional error below 5 Hz, and removes four fifths of
    /// the band of the white sensor noise. docs/dtg-vib.md has the cut-off
    /// sweep that chose it.
    fn default() -> Self {
        Self {
            order: 4,
            cutoff_hz: 5.0,
        }
    }
}

/// The true angular rate the unit saw, if known; subtracted from every
/// channel (eq. 4) so the model learns errors only. Without one, the constant
/// rate of a stationary test is absorbed by each channel's bias.
///
/// ```
/// use dtg_vib::pipeline::RateReference;
/// let r = RateReference::Table { rate_deg_s: [0.0, 0.0, 10.0] };
/// assert_eq!(r.rate_deg_h().unwrap().z, 36000.0);
/// assert!(RateReference::None.rate_deg_h().is_none());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum RateReference {
    /// No reference.
    #[default]
    None,
    /// Earth rate at a site (latitude, cluster orientation).
    Earth {
        /// The site.
        site: Site,
    },
    /// A known constant table rate in the cluster frame, deg/s.
    Table {
        /// Rate about cluster x, y, z, deg/s.
        rate_deg_s: [f64; 3],
    },
}

impl RateReference {
    /// Checks the reference can be a rate: a latitude in [−90°, 90°] with
    /// perpendicular x and z axes, or three finite table rates.
    pub fn check(&self) -> Result<(), DtgVibError> {
        let bad = |name, value: String, reason| {
            Err(DtgVibError::InvalidOption {
                name,
                value,
                reason,
            })
        };
        match self {
            RateReference::None => Ok(()),
            RateReference::Earth { site } => {
                if !(-90.0..=90.0).contains(&site.latitude_deg) {
                    return bad(
                        "latitude",
                        site.latitude_deg.to_string(),
                        "must be a number of degrees in [-90, 90]",
                    );
                }
                if site.orientation.axes_enu().is_none() {
                    return bad(
                        "orientation",
                        format!("{:?}", site.orientation),
                        "the cluster's x and z axes must be perpendicular",
                    );
                }
                Ok(())
            }
            RateReference::Table { rate_deg_s } => {
                if rate_deg_s.iter().all(|w| w.is_finite()) {
                    Ok(())
                } else {
                    bad(
                        "table rate",
                        format!("{rate_deg_s:?}"),
                        "must be three finite rates, deg/s",
                    )
                }
            }
        }
    }

    /// The reference rate in the cluster frame, deg/h.
    pub fn rate_deg_h(&self) -> Option<nalgebra::Vector3<f64>> {
        match self {
            RateReference::None => None,
            RateReference::Earth { site } => site.earth_rate_cluster_deg_h(),
            RateReference::Table { rate_deg_s } => {
                Some(nalgebra::Vector3::from(*rate_deg_s) * 3600.0)
            }
        }
    }
}

/// How a record is prepared for the models.
///
/// ```
/// let p = dtg_vib::pipeline::Preprocess::default();
/// assert_eq!(p.window.length(), 50);
/// assert_eq!(p.window.signals(), ["az"]);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Preprocess {
    /// Zero-phase low-pass of the gyro outputs and effect columns, or none.
    pub filter: Option<FilterSpec>,
    /// Zero-phase low-pass of the windowed input signals, or none. None by
    /// default: the vibration level the rectified error follows is carried
    /// by the acceleration's energy across the whole 0–25 Hz band, and a
    /// low-pass on the window throws most of it away (measured: residue
    /// reduction 3.7× with a 5-Hz input filter against 4.2× without).
    pub input_filter: Option<FilterSpec>,
    /// Input windows of the RBF.
    pub window: WindowSpec,
    /// Known true rate.
    pub rate_reference: RateReference,
    /// Causal mode: the model runs on-line with one output period of
    /// latency (the `dtg-onboard` evaluator, the exported C): the correction
    /// of sample n uses samples up to n + 1. The low-passes are one forward
    /// pass started in the steady state of the first sample instead of
    /// forward–backward; the g² terms' within-interval covariance (ground
    /// calibration and effects) keeps its centred estimate from samples
    /// n − 1, n, n + 1, hence the latency (a causal estimate from n − 2,
    /// n − 1, n cost 33–40% in residual error on the triaxial test,
    /// docs/dtg-vib.md). Absent in model files written before it:
    /// zero-phase.
    #[serde(default)]
    pub causal: bool,
}

impl Default for Preprocess {
    /// Low-pass of the outputs, unfiltered 50-sample windows of `az` (the
    /// paper's input), no rate reference.
    fn default() -> Self {
        Self {
            filter: Some(FilterSpec::default()),
            input_filter: None,
            window: WindowSpec::paper(),
            rate_reference: RateReference::None,
            causal: false,
        }
    }
}

/// A record prepared for fitting, compensation or diagnosis, with the
/// calibration and pre-processing it was prepared with (a fit on it keeps
/// them: nothing prepared one way is fitted as if it were another).
///
/// Row `r` of the windows (and of every per-row quantity) is record sample
/// `first_sample() + r`.
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The ground calibration compensated, if any.
    calibration: Option<Calibration>,
    /// How the record was prepared.
    preprocess: Preprocess,
    calibrated: Record,
    /// The records of a multi-record preparation, each calibrated and
    /// untrimmed, with their rows; empty for one record.
    parts: Vec<Part>,
    filter: Option<LowPass>,
    /// Filtered gyro outputs minus the rate reference, deg/h, full length.
    targets: [Vec<f64>; 6],
    windows: Windows,
}

impl Prepared {
    /// Compensates with `calibration` (if any), removes the rate reference,
    /// filters and forms windows.
    pub fn new(
        record: &Record,
        calibration: Option<&Calibration>,
        pre: &Preprocess,
    ) -> Result<Self, DtgVibError> {
        pre.rate_reference.check()?;
        let causal = pre.causal;
        let calibrated = match calibration {
            Some(c) => {
                let calibrated = c.compensate(record);
                check_calibrated(&calibrated)?;
                calibrated
            }
            None => record.clone(),
        };
        let filter = pre
            .filter
            .map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / calibrated.dt()))
            .transpose()?;
        let reference = pre.rate_reference.rate_deg_h().map(|w| ideal_outputs(&w));
        let mut targets: [Vec<f64>; 6] = Default::default();
        for (k, ch) in Channel::ALL.into_iter().enumerate() {
            let mut y = calibrated.gyro(ch).to_vec();
            if let Some(r) = reference {
                y.iter_mut().for_each(|v| *v -= r[k]);
            }
            targets[k] = apply(&filter, causal, &y)?;
        }
        let input_filter = pre
            .input_filter
            .map(|f| LowPass::butterworth(f.order, f.cutoff_hz, 1.0 / calibrated.dt()))
            .transpose()?;
        let mut signals = Vec::with_capacity(pre.window.signals().len());
        for name in pre.window.signals() {
            signals.push(apply(&input_filter, causal, signal(&calibrated, name)?)?);
        }
        let refs: Vec<&[f64]> = signals.iter().map(Vec::as_slice).collect();
        let windows = pre.window.build(&refs)?;
        Ok(Self {
            calibration: calibration.cloned(),
            preprocess: pre.clone(),
            calibrated,
            parts: Vec::new(),
            filter,
            targets,
            windows,
        })
    }

    /// Several records prepared one by one (calibration, filter and windows
    /// never cross from one record to the next) and laid end to end, named
    /// (by their file, say) for errors and per-record scores.
    ///
    /// Row `r` is still sample `first_sample() + r` of [`Prepared::calibrated`],
    /// which holds the records one after another with each later record's
    /// warm-up (the samples before its first full window) left out and its
    /// time restamped to continue the first record's. The records must share
    /// their sampling interval and their extra columns. One record gives
    /// exactly [`Prepared::new`].
    pub fn new_many(
        records: &[(String, &Record)],
        calibration: Option<&Calibration>,
        pre: &Preprocess,
    ) -> Result<Self, DtgVibError> {
        let Some(((first_name, first_record), rest)) = records.split_first() else {
            return Err(DtgVibError::NoRecords);
        };
        if rest.is_empty() {
            return Self::new(first_record, calibration, pre);
        }
        let mut names: Vec<&str> = first_record.extra_names();
        names.sort_unstable();
        for (name, r) in rest {
            let dt = (first_record.dt(), r.dt());
            if (dt.0 - dt.1).abs() > 1e-9 * dt.0 {
                return Err(DtgVibError::RecordsDiffer {
                    first: first_name.clone(),
                    other: name.clone(),
                    what: format!("sampling interval {} s against {} s", dt.0, dt.1),
                });
            }
            let mut other: Vec<&str> = r.extra_names();
            other.sort_unstable();
            if other != names {
                return Err(DtgVibError::RecordsDiffer {
                    first: first_name.clone(),
                    other: name.clone(),
                    what: format!(
                        "extra columns [{}] against [{}]",
                        names.join(", "),
                        other.join(", ")
                    ),
                });
            }
        }
        let prepared = records
            .iter()
            .map(|(name, r)| {
                Self::new(r, calibration, pre).map_err(|e| DtgVibError::InRecord {
                    record: name.clone(),
                    source: Box::new(e),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let first = prepared[0].first_sample();
        let trim = |k: usize| if k == 0 { 0 } else { first };
        let mut parts = Vec::with_capacity(prepared.len());
        let mut row = 0;
        for (p, (name, _)) in prepared.iter().zip(records) {
            let rows = p.rows();
            parts.push(Part {
                name: name.clone(),
                calibrated: p.calibrated.clone(),
                rows: row..row + rows,
            });
            row += rows;
        }
        let cat = |f: &dyn Fn(&Prepared) -> &[f64]| -> Vec<f64> {
            prepared
                .iter()
                .enumerate()
                .flat_map(|(k, p)| f(p)[trim(k)..].iter().copied())
                .collect()
        };
        let targets: [Vec<f64>; 6] = std::array::from_fn(|k| cat(&|p| &p.targets[k]));
        let calibrated = concat_records(&prepared, first)?;
        let windows = Windows::concat(
            &prepared
                .iter()
                .map(|p| p.windows.clone())
                .collect::<Vec<_>>(),
        );
        let head = prepared.into_iter().next().expect("two or more records");
        Ok(Self {
            calibration: head.calibration,
            preprocess: head.preprocess,
            calibrated,
            parts,
            filter: head.filter,
            targets,
            windows,
        })
    }

    /// The records and their rows: one entry per record of
    /// [`Prepared::new_many`], and one named `""` for [`Prepared::new`].
    pub fn record_rows(&self) -> Vec<(&str, std::ops::Range<usize>)> {
        if self.parts.is_empty() {
            return vec![("", 0..self.rows())];
        }
        self.parts
            .iter()
            .map(|p| (p.name.as_str(), p.rows.clone()))
            .collect()
    }

    /// The record (calibrated, whole) a row belongs to, and the sample of
    /// that record its window ends at: a window's span `sample + 1 −
    /// length ..= sample` then lies inside one record.
    pub fn locate(&self, row: usize) -> (&Record, usize) {
        let first = self.first_sample();
        match self.parts.iter().find(|p| p.rows.contains(&row)) {
            Some(p) => (&p.calibrated, first + row - p.rows.start),
            None => (&self.calibrated, first + row),
        }
    }

    /// A per-record series over the full (concatenated) sample range:
    /// computed on each record alone, filtered on it alone, warm-up of each
    /// later record left out.
    fn per_record(
        &self,
        f: impl Fn(&Record) -> Result<Vec<f64>, DtgVibError>,
    ) -> Result<Vec<f64>, DtgVibError> {
        let first = self.first_sample();
        let mut out = Vec::with_capacity(self.calibrated.len());
        for (k, p) in self.parts.iter().enumerate() {
            let v = f(&p.calibrated).map_err(|e| DtgVibError::InRecord {
                record: p.name.clone(),
                source: Box::new(e),
            })?;
            out.extend(v.into_iter().skip(if k == 0 { 0 } else { first }));
        }
        Ok(out)
    }

    /// The ground calibration the record was compensated with, if any.
    pub fn calibration(&self) -> Option<&Calibration> {
        self.calibration.as_ref()
    }

    /// How the record was prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The calibrated (not filtered) record.
    pub fn calibrated(&self) -> &Record {
        &self.calibrated
    }

    /// Number of rows (windows).
    pub fn rows(&self) -> usize {
        self.windows.len()
    }

    /// Record sample of row 0.
    pub fn first_sample(&self) -> usize {
        self.windows.first_sample()
    }

    /// The windows as an `rows × dim` matrix.
    pub fn window_matrix(&self) -> Mat<f64> {
        let w = &self.windows;
        Mat::from_fn(w.len(), w.dim(), |i, j| w.row(i)[j])
    }

    /// The windows as an `rows × dim` matrix view of the prepared windows
    /// themselves ([`Windows::matrix`]; nothing is copied): what
    /// [`Prepared::window_matrix`] holds, without its copy (400 MB for a
    /// 1M-row record of 50-sample windows).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new((1..=60).map(|i| i as f64 * 0.02).collect(),
    ///     std::array::from_fn(|_| vec![0.0; 60]), [vec![0.0; 60], vec![0.0; 60], (0..60).map(f64::from).collect()],
    ///     vec![]).unwrap();
    /// let pre = dtg_vib::pipeline::Preprocess { filter: None, ..Default::default() };
    /// let p = dtg_vib::pipeline::Prepared::new(&rec, None, &pre).unwrap();
    /// assert_eq!(p.window_view(), p.window_matrix().as_ref());
    /// ```
    pub fn window_view(&self) -> MatRef<'_, f64> {
        self.windows.matrix()
    }

    /// The windows.
    pub fn windows(&self) -> &Windows {
        &self.windows
    }

    /// A channel's filtered, reference-removed output over the whole record, deg/h.
    pub fn target_full(&self, channel: Channel) -> &[f64] {
        &self.targets[channel.index()]
    }

    /// A channel's target on the rows, deg/h.
    pub fn target(&self, channel: Channel) -> &[f64] {
        &self.targets[channel.index()][self.first_sample()..]
    }

    /// The filtered effect columns of a channel over the whole record.
    pub fn effect_columns_full(
        &self,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Vec<Vec<f64>>, DtgVibError> {
        if self.parts.is_empty() {
            return self.effect_columns_on(&self.calibrated, channel, effects);
        }
        let first = self.first_sample();
        let mut out = vec![Vec::with_capacity(self.calibrated.len()); effects.len()];
        for (k, p) in self.parts.iter().enumerate() {
            let cols = self
                .effect_columns_on(&p.calibrated, channel, effects)
                .map_err(|e| DtgVibError::InRecord {
                    record: p.name.clone(),
                    source: Box::new(e),
                })?;
            for (o, c) in out.iter_mut().zip(cols) {
                o.extend(c.into_iter().skip(if k == 0 { 0 } else { first }));
            }
        }
        Ok(out)
    }

    /// The filtered effect columns of one record.
    fn effect_columns_on(
        &self,
        record: &Record,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Vec<Vec<f64>>, DtgVibError> {
        // No effects, no columns: the record's rates and covariances (0.5 GB
        // for a 1M-sample record) are not worked out for nothing.
        if effects.is_empty() {
            return Ok(Vec::new());
        }
        // Regressors first, filter second: the gyro saw D·a_I·a_S, and the
        // filtered output holds the filtered product, not the product of
        // filtered accelerations.
        let cols = EffectColumns::new(record).evaluate(channel, effects)?;
        for (e, c) in effects.iter().zip(&cols) {
            check_range(
                || format!("channel {channel}'s effect {}", e.id()),
                c,
                record.t(),
                "the record's accelerations (g) or rates are too large for this effect's products: check their units, or drop the effect",
            )?;
        }
        cols.iter()
            .map(|c| apply(&self.filter, self.preprocess.causal, c))
            .collect()
    }

    /// The effect columns of a channel on the rows, as an `rows × effects` matrix.
    pub fn effect_matrix(
        &self,
        channel: Channel,
        effects: &[Effect],
    ) -> Result<Mat<f64>, DtgVibError> {
        let cols = self.effect_columns_full(channel, effects)?;
        let first = self.first_sample();
        Ok(Mat::from_fn(self.rows(), cols.len(), |i, j| {
            cols[j][first + i]
        }))
    }

    /// A record signal (accelerometer axis or extra column), filtered, over the whole record.
    pub fn signal_full(&self, name: &str) -> Result<Vec<f64>, DtgVibError> {
        if !self.parts.is_empty() {
            return self
                .per_record(|r| apply(&self.filter, self.preprocess.causal, signal(r, name)?));
        }
        apply(
            &self.filter,
            self.preprocess.causal,
            signal(&self.calibrated, name)?,
        )
    }

    /// A series over the whole record (one sample per record sample)
    /// through the filter the targets went through, zero-phase or causal:
    /// e.g. a simulator's per-sample noise floor as the model's target sees
    /// it. For a preparation of one record (a series over several would be
    /// filtered across their boundaries).
    pub fn filter_like_targets(&self, x: &[f64]) -> Result<Vec<f64>, DtgVibError> {
        apply(&self.filter, self.preprocess.causal, x)
    }

    /// True when prepared in causal mode ([`Preprocess::causal`]).
    pub fn causal(&self) -> bool {
        self.preprocess.causal
    }

    /// The designed filter, if any.
    pub fn filter(&self) -> Option<&LowPass> {
        self.filter.as_ref()
    }

    /// Samples over which one sample influences its filtered neighbours on
    /// each side (where the impulse response, zero-phase or causal, exceeds
    /// 10⁻³ of its peak); 0 without a filter. Train and validation rows are
    /// kept this far apart, plus a window length, so nothing leaks across.
    pub fn filter_memory(&self) -> usize {
        let Some(f) = &self.filter else { return 0 };
        if self.preprocess.causal {
            let mut impulse = vec![0.0; 4000];
            impulse[0] = 1.0;
            let h = f.filter(&impulse);
            let peak = h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            return (1..h.len())
                .rev()
                .find(|&k| h[k].abs() > 1e-3 * peak)
                .unwrap_or(0);
        }
        let half = 2000;
        let mut impulse = vec![0.0; 2 * half + 1];
        impulse[half] = 1.0;
        let Ok(h) = f.filtfilt(&impulse) else {
            return 0;
        };
        let peak = h[half].abs();
        (1..half)
            .rev()
            .find(|&k| h[half + k].abs() > 1e-3 * peak)
            .unwrap_or(0)
    }
}

/// One record of a multi-record preparation.
#[derive(Debug, Clone)]
struct Part {
    name: String,
    calibrated: Record,
    rows: std::ops::Range<usize>,
}

/// The calibrated records laid end to end, each later one without its first
/// `first` samples, time restamped on the first record's grid.
fn concat_records(prepared: &[Prepared], first: usize) -> Result<Record, DtgVibError> {
    let recs: Vec<&Record> = prepared.iter().map(|p| &p.calibrated).collect();
    let skip = |k: usize| if k == 0 { 0 } else { first };
    let cat = |f: &dyn Fn(&Record) -> &[f64]| -> Vec<f64> {
        recs.iter()
            .enumerate()
            .flat_map(|(k, r)| f(r)[skip(k)..].iter().copied())
            .collect()
    };
    let (t0, dt) = (recs[0].t()[0], recs[0].dt());
    let n: usize = recs
        .iter()
        .enumerate()
        .map(|(k, r)| r.len() - skip(k))
        .sum();
    let t: Vec<f64> = (0..n).map(|i| t0 + i as f64 * dt).collect();
    let gyro = std::array::from_fn(|k| cat(&|r| r.gyro(Channel::ALL[k])));
    let accel = std::array::from_fn(|k| cat(&|r| r.accel(Axis::ALL[k])));
    let extra = recs[0]
        .extra_names()
        .into_iter()
        .map(|name| {
            (
                name.to_string(),
                cat(&|r| r.extra(name).expect("names checked")),
            )
        })
        .collect();
    Ok(Record::new(t, gyro, accel, extra)?)
}

/// The record's values are within ±1e150 (the reader refuses more), but a
/// calibration's polynomial terms (an accelerometer's k3·a³, a gyro's g²
/// sensitivities) can carry them past what the filter and the fit can square.
fn check_calibrated(calibrated: &Record) -> Result<(), DtgVibError> {
    let hint = "the calibration's coefficients or the record's values are out of range: check the units of both";
    let t = calibrated.t();
    for ch in Channel::ALL {
        check_range(
            || format!("column '{}' after calibration", ch.name()),
            calibrated.gyro(ch),
            t,
            hint,
        )?;
    }
    for axis in Axis::ALL {
        check_range(
            || format!("column '{}' after calibration", axis.column()),
            calibrated.accel(axis),
            t,
            hint,
        )?;
    }
    Ok(())
}

/// The first value of `x` that is non-finite or beyond ±1e150, as an error
/// naming `what` and the record time.
fn check_range(
    what: impl FnOnce() -> String,
    x: &[f64],
    t: &[f64],
    hint: &'static str,
) -> Result<(), DtgVibError> {
    match x
        .iter()
        .position(|v| !(v.is_finite() && v.abs() <= tabular::MAX_MAGNITUDE))
    {
        None => Ok(()),
        Some(i) => Err(DtgVibError::OutOfRange {
            what: what(),
            value: x[i],
            t: t[i],
            row: i + 1,
            hint,
        }),
    }
}

fn apply(filter: &Option<LowPass>, causal: bool, x: &[f64]) -> Result<Vec<f64>, DtgVibError> {
    Ok(match filter {
        Some(f) if causal => {
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(crate::signal::FilterError::NotFinite { index: i }.into());
            }
            f.filter_causal(x)
        }
        Some(f) => f.filtfilt(x)?,
        None => x.to_vec(),
    })
}

/// An accelerometer axis (`ax`, `ay`, `az`) or an extra column of a record.
pub fn signal<'r>(record: &'r Record, name: &str) -> Result<&'r [f64], DtgVibError> {
    if let Some(axis) = Axis::ALL.into_iter().find(|a| a.column() == name) {
        return Ok(record.accel(axis));
    }
    record.extra(name).ok_or_else(|| DtgVibError::WindowSignal {
        name: name.to_string(),
        available: record.extra_names().iter().map(|s| s.to_string()).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(n: usize) -> Record {
        let t: Vec<f64> = (1..=n).map(|i| i as f64 * 0.02).collect();
        let az: Vec<f64> = (0..n).map(|i| 1.0 + (i as f64 * 0.7).sin()).collect();
        let gyro = std::array::from_fn(|k| (0..n).map(|i| k as f64 + 0.1 * az[i]).collect());
        Record::new(
            t,
            gyro,
            [vec![0.0; n], vec![0.0; n], az],
            vec![("temp".into(), vec![20.0; n])],
        )
        .unwrap()
    }

    #[test]
    fn rows_align_windows_targets_and_effects() {
        let rec = record(300);
        let pre = Preprocess {
            filter: None,
            ..Preprocess::default()
        };
        let p = Prepared::new(&rec, None, &pre).unwrap();
        assert_eq!(p.rows(), 251);
        assert_eq!(p.first_sample(), 49);
        let z = p
            .effect_matrix(Channel::Z, &["g_I".parse().unwrap()])
            .unwrap();
        // Channel Z: g_I is az; row r is sample 49 + r, the last element of its window.
        for r in [0, 100, 250] {
            assert_eq!(z[(r, 0)], rec.accel(Axis::Z)[49 + r]);
            assert_eq!(p.windows().row(r)[49], rec.accel(Axis::Z)[49 + r]);
            assert_eq!(p.target(Channel::Z)[r], rec.gyro(Channel::Z)[49 + r]);
        }
    }

    #[test]
    fn a_preprocess_written_before_causal_mode_reads_as_zero_phase() {
        let old = r#"{"filter": {"order": 4, "cutoff_hz": 5.0}, "input_filter": null,
            "window": {"signals": ["az"], "length": 50}, "rate_reference": {"kind": "none"}}"#;
        let p: Preprocess = serde_json::from_str(old).unwrap();
        assert!(!p.causal);
        assert_eq!(p, Preprocess::default());
    }

    #[test]
    fn causal_preparation_never_looks_ahead() {
        let rec = record(400);
        let pre = Preprocess {
            causal: true,
            ..Preprocess::default()
        };
        let mut az = rec.accel(Axis::Z).to_vec();
        az[300..].iter_mut().for_each(|v| *v += 1.0);
        let changed = rec.with_accel([vec![0.0; 400], vec![0.0; 400], az]);
        let (a, b) = (
            Prepared::new(&rec, None, &pre).unwrap(),
            Prepared::new(&changed, None, &pre).unwrap(),
        );
        let e: Vec<Effect> = vec!["gg_II".parse().unwrap()];
        let (ea, eb) = (
            a.effect_columns_full(Channel::Z, &e).unwrap(),
            b.effect_columns_full(Channel::Z, &e).unwrap(),
        );
        // One sample of look-ahead: the covariance of sample 299 uses 300.
        assert_eq!(ea[0][..299], eb[0][..299]);
        assert_ne!(ea[0][299], eb[0][299]);
        assert_ne!(ea[0][301], eb[0][301]);
        // Zero-phase, the same change reaches further back.
        let zp = Preprocess::default();
        let (za, zb) = (
            Prepared::new(&rec, None, &zp).unwrap(),
            Prepared::new(&changed, None, &zp).unwrap(),
        );
        assert_ne!(
            za.effect_columns_full(Channel::Z, &e).unwrap()[0][295],
            zb.effect_columns_full(Channel::Z, &e).unwrap()[0][295]
        );
    }

    #[test]
    fn rate_reference_is_removed_from_every_channel() {
        let rec = record(200);
        let pre = Preprocess {
            filter: None,
            rate_reference: RateReference::Table {
                rate_deg_s: [0.0, 0.0, 1.0],
            },
            ..Preprocess::default()
        };
        let p = Prepared::new(&rec, None, &pre).unwrap();
        let m = ideal_outputs(&nalgebra::Vector3::new(0.0, 0.0, 3600.0));
        for ch in Channel::ALL {
            assert!((p.target_full(ch)[7] - (rec.gyro(ch)[7] - m[ch.index()])).abs() < 1e-9);
        }
    }

    #[test]
    fn an_impossible_rate_reference_is_refused_with_its_reason() {
        let rec = record(200);
        let with = |r| Preprocess {
            filter: None,
            rate_reference: r,
            ..Preprocess::default()
        };
        for (r, want) in [
            (
                RateReference::Earth {
                    site: Site {
                        latitude_deg: 95.0,
                        ..Site::default()
                    },
                },
                "latitude = 95",
            ),
            (
                RateReference::Earth {
                    site: Site {
                        latitude_deg: f64::NAN,
                        ..Site::default()
                    },
                },
                "latitude = NaN",
            ),
            (
                RateReference::Table {
                    rate_deg_s: [0.0, f64::INFINITY, 0.0],
                },
                "table rate = [0.0, inf, 0.0]",
            ),
        ] {
            let Err(err) = Prepared::new(&rec, None, &with(r)) else {
                panic!("{want}: accepted");
            };
            let err = err.to_string();
            assert!(err.starts_with(want), "{err}");
        }
        let crossed = RateReference::Earth {
            site: Site {
                latitude_deg: 10.0,
                orientation: nav_sensors::sim::Orientation {
                    x: nav_sensors::sim::Direction::Up,
                    z: nav_sensors::sim::Direction::Up,
                },
            },
        };
        let Err(err) = Prepared::new(&rec, None, &with(crossed)) else {
            panic!("crossed axes: accepted");
        };
        let err = err.to_string();
        assert!(err.contains("orientation"), "{err}");
    }

    #[test]
    fn unknown_window_signal_lists_the_columns() {
        let rec = record(100);
        let pre = Preprocess {
            window: WindowSpec::new(vec!["aw".into()], 10).unwrap(),
            ..Preprocess::default()
        };
        let err = Prepared::new(&rec, None, &pre).unwrap_err();
        assert_eq!(
            err.to_string(),
            "window signal 'aw' is not a record column (use ax, ay, az or an extra column: temp)"
        );
    }

    #[test]
    fn record_shorter_than_a_window_is_an_error() {
        let rec = record(30);
        let err = Prepared::new(
            &rec,
            None,
            &Preprocess {
                filter: None,
                ..Preprocess::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                DtgVibError::Window(crate::window::WindowError::TooShort {
                    samples: 30,
                    length: 50
                })
            ),
            "{err}"
        );
    }
}
