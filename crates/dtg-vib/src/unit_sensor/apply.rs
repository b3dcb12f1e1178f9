//! A model applied to records of its unit (a log's segments between time
//! gaps, each prepared on its own and laid end to end): each channel's
//! predicted error, what compensation subtracts, the compensated records
//! (what `compensate` writes), the parity residues before and after, and
//! the rows of the model's split. A causal model runs sample by sample
//! through the onboard evaluator (the code a flight computer runs), a
//! zero-phase one as a batch.

use super::error::UnitSensorError;
use super::model::UnitModel;
use super::parity::{ResidueSeries, ResidueStats};
use super::sensor::UnitSensor;
use super::signals::{to_record, to_signals};
use crate::error::DtgVibError;
use crate::onboard::{ExportError, Stepped, step_record};
use nav_sensors::record::Record;
use sysid::{ChannelScores, Prepared, Signals};

/// A model applied to records of its unit.
#[derive(Debug, Clone)]
pub struct Applied {
    /// The records prepared as the model's training data were.
    pub prepared: Prepared<UnitSensor>,
    /// Predicted error per channel and row, deg/h, of the pre-processed
    /// (filtered) output: the effects filtered as the output is, the network
    /// part faded outside the training range.
    pub predicted: Vec<Vec<f64>>,
    /// What compensation subtracts from the unfiltered output per channel
    /// and row, deg/h: `predicted` with the effects unfiltered (θ·z), whose
    /// part above the filter's cut-off is the effect's too.
    pub compensation: Vec<Vec<f64>>,
    /// Training rows of the model's split (meaningful on the records it was
    /// fitted on); empty from [`Applied::unsplit`] or on records without it.
    pub train: Vec<usize>,
    /// Validation rows; empty as `train`.
    pub val: Vec<usize>,
    /// A causal model's run through the onboard evaluator, per record.
    onboard: Option<Vec<Stepped>>,
}

impl Applied {
    /// Prepares the records as the model's data, predicts every channel's
    /// error and splits the rows as at fit time.
    pub fn new(model: &UnitModel, records: &[(String, &Record)]) -> Result<Self, DtgVibError> {
        let mut applied = Self::unsplit(model, records)?;
        (applied.train, applied.val) = model.inner().rows(&applied.prepared)?;
        Ok(applied)
    }

    /// As [`Applied::new`] without the split (`train` and `val` empty): all
    /// that compensation and the residue series need, on any records with
    /// at least two full windows, however short.
    pub fn unsplit(model: &UnitModel, records: &[(String, &Record)]) -> Result<Self, DtgVibError> {
        let signals = records
            .iter()
            .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
            .collect::<Result<Vec<(String, Signals)>, UnitSensorError>>()?;
        let named: Vec<(String, &Signals)> = signals.iter().map(|(n, s)| (n.clone(), s)).collect();
        let inner = model.inner();
        let prepared = inner.prepare_many(&named)?;
        if prepared.rows() < 2 {
            return Err(sysid::SysidError::TooFewSamples {
                what: "full windows",
                have: prepared.rows(),
                need: 2,
                hint: "a compensated record needs two samples with a full window: use a longer record",
            }
            .into());
        }
        let onboard = match inner.preprocess().causal {
            true => stepped(model, records)?,
            false => None,
        };
        // The onboard evaluator subtracts the effects unfiltered, as the
        // batch compensation does; the filtered outputs' prediction has them
        // filtered.
        let above = inner.effects_above_band(&prepared)?;
        let shift = |series: &[Vec<f64>], sign: f64| -> Vec<Vec<f64>> {
            series
                .iter()
                .zip(&above)
                .map(|(s, a)| s.iter().zip(a).map(|(p, a)| p + sign * a).collect())
                .collect()
        };
        let (predicted, compensation) = match &onboard {
            Some(runs) => {
                let error: Vec<Vec<f64>> = (0..inner.channels().len())
                    .map(|k| runs.iter().flat_map(|s| s.error_deg_h[k].clone()).collect())
                    .collect();
                (shift(&error, -1.0), error)
            }
            // Outside the training range the network part fades
            // (sysid::model::fade), as the onboard evaluator fades it.
            None => {
                let p = inner.predict_faded(&prepared)?.predicted;
                let c = shift(&p, 1.0);
                (p, c)
            }
        };
        Ok(Self {
            prepared,
            predicted,
            compensation,
            train: Vec::new(),
            val: Vec::new(),
            onboard,
        })
    }

    /// A channel's scores on the split's rows (the model's own
    /// [`sysid::ChannelModel::scores`] on the records it was fitted on).
    /// Needs the split: from [`Applied::new`].
    pub fn scores(&self, channel: usize) -> ChannelScores {
        sysid::score(
            self.prepared.target(channel),
            &self.predicted[channel],
            &self.train,
            &self.val,
        )
    }

    /// Time of each row, s (the sample its window ends at, in its record).
    pub fn row_times(&self) -> Vec<f64> {
        (0..self.prepared.rows())
            .map(|r| {
                let (s, i) = self.prepared.locate(r);
                s.t()[i]
            })
            .collect()
    }

    /// The parity residues of the pre-processed outputs before and after
    /// subtracting the predicted errors, per row.
    pub fn residues(&self) -> ResidueSeries {
        let p = &self.prepared;
        let first = p.first_sample();
        let outputs: Vec<Vec<f64>> = (0..self.predicted.len())
            .map(|k| p.target_full(k)[first..].to_vec())
            .collect();
        ResidueSeries::new(
            &p.sensor().unit,
            self.row_times(),
            &outputs,
            &self.predicted,
        )
    }

    /// Residue rms before and after on the validation rows.
    pub fn validation_residues(&self) -> Vec<ResidueStats> {
        self.residues().stats(&self.val)
    }

    /// Residue rms before and after on every row.
    pub fn all_residues(&self) -> Vec<ResidueStats> {
        let all: Vec<usize> = (0..self.prepared.rows()).collect();
        self.residues().stats(&all)
    }

    /// Each record (calibrated, from its first sample with a full window
    /// on) and the range of rows it holds.
    fn records(&self) -> Vec<(&Signals, usize, std::ops::Range<usize>)> {
        self.prepared
            .record_rows()
            .into_iter()
            .map(|(_, rows)| {
                let (s, first) = self.prepared.locate(rows.start);
                (s, first, rows)
            })
            .collect()
    }

    /// Each record compensated (what `compensate` writes): from its first
    /// sample with a full window on, each gyro output (after the model's
    /// ground calibration, not filtered) minus the channel's
    /// [`Applied::compensation`]; accelerations calibrated; extra columns as
    /// given. For a causal model, the onboard evaluator's compensated rates
    /// and calibrated accelerations.
    pub fn compensated(&self) -> Result<Vec<Record>, DtgVibError> {
        let unit = &self.prepared.sensor().unit;
        self.records()
            .into_iter()
            .enumerate()
            .map(|(k, (s, first, rows))| {
                let sliced = to_record(unit, s)?.slice(first..s.len());
                if let Some(runs) = &self.onboard {
                    let run = &runs[k];
                    return Ok(sliced
                        .with_gyro_series(run.rate_deg_h.clone())
                        .with_accel_series(run.accel_g.clone()));
                }
                let gyro = (0..self.compensation.len())
                    .map(|c| {
                        sliced
                            .gyro_at(c)
                            .iter()
                            .zip(&self.compensation[c][rows.clone()])
                            .map(|(m, p)| m - p)
                            .collect()
                    })
                    .collect();
                Ok(sliced.with_gyro_series(gyro))
            })
            .collect()
    }

    /// Each gyro's calibrated output less the model's rate reference, every
    /// record from its first sample with a full window on, one after the
    /// other, deg/h: the series before compensation that Allan deviation
    /// and fault detection read beside [`Applied::compensated`]'s.
    pub fn calibrated_gyros(&self) -> Vec<Vec<f64>> {
        let sensor = self.prepared.sensor();
        let gyros = sensor.unit.gyros();
        let mut out = vec![Vec::new(); gyros.len()];
        for (s, first, _) in self.records() {
            let reference = sensor.reference_rates(s).ok().flatten();
            for (k, g) in gyros.iter().enumerate() {
                let r = |i: usize| reference.as_ref().map_or(0.0, |w| g.input.dot(&w[i]));
                let column = s.column(&g.name).unwrap_or(&[]);
                out[k].extend(column.iter().enumerate().skip(first).map(|(i, v)| v - r(i)));
            }
        }
        out
    }

    /// Each gyro's compensated output ([`Applied::compensated`]) less the
    /// model's rate reference, as [`Applied::calibrated_gyros`] holds the
    /// output before: on a record fitted in parity the reference varies
    /// with the motion, which neither series must carry.
    pub fn compensated_gyros(&self) -> Result<Vec<Vec<f64>>, DtgVibError> {
        let sensor = self.prepared.sensor();
        let gyros = sensor.unit.gyros();
        let mut out = vec![Vec::new(); gyros.len()];
        for ((s, first, _), c) in self.records().into_iter().zip(self.compensated()?) {
            let reference = sensor.reference_rates(s).ok().flatten();
            for (k, g) in gyros.iter().enumerate() {
                let r = |i: usize| {
                    reference
                        .as_ref()
                        .map_or(0.0, |w| g.input.dot(&w[first + i]))
                };
                out[k].extend(c.gyro_at(k).iter().enumerate().map(|(i, v)| v - r(i)));
            }
        }
        Ok(out)
    }
}

/// A causal model run through the onboard evaluator, record by record;
/// `None` for a model its tables cannot carry (another kernel, input
/// scaling: only from the library), which is compensated as a batch.
fn stepped(
    model: &UnitModel,
    records: &[(String, &Record)],
) -> Result<Option<Vec<Stepped>>, DtgVibError> {
    let mut runs = Vec::with_capacity(records.len());
    for (_, r) in records {
        match step_record(model, r) {
            Ok(s) => runs.push(s),
            Err(DtgVibError::Export(ExportError::Unsupported { .. })) => return Ok(None),
            Err(e) => return Err(e),
        }
    }
    Ok(Some(runs))
}
