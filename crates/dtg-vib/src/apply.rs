//! Applying a fitted model to a record: predicted errors, the compensated
//! record, and the residues before and after.

use crate::error::DtgVibError;
use crate::model::{ChannelScores, CompensationModel};
use crate::parity::{ResidueSeries, ResidueStats};
use crate::pipeline::Prepared;
use nav_sensors::geometry::{Channel, residues};
use nav_sensors::record::Record;

/// A model applied to a record.
#[derive(Debug, Clone)]
pub struct Applied {
    /// The record prepared as the model's training data were.
    pub prepared: Prepared,
    /// Predicted error per channel and row, deg/h, of the pre-processed
    /// (filtered) output: the effects filtered as the output is, the network
    /// part faded outside the training range.
    pub predicted: [Vec<f64>; 6],
    /// What compensation subtracts from the unfiltered output per channel
    /// and row, deg/h: `predicted` with the effects unfiltered (θ·z), whose
    /// part above the filter's cut-off is the effect's too.
    pub compensation: [Vec<f64>; 6],
    /// Residues of the pre-processed outputs before and after compensation, per row.
    pub residues: ResidueSeries,
    /// Training rows of the model's split (meaningful on the record it was
    /// fitted on); empty from [`Applied::unsplit`].
    pub train: Vec<usize>,
    /// Validation rows; empty from [`Applied::unsplit`].
    pub val: Vec<usize>,
    /// A causal model's run through the onboard evaluator, which gives its
    /// predictions and compensated record.
    onboard: Option<crate::onboard::Stepped>,
}

impl Applied {
    /// Prepares `record` as the model's data, predicts every channel's error,
    /// forms the residues and splits the rows as at fit time.
    pub fn new(model: &CompensationModel, record: &Record) -> Result<Self, DtgVibError> {
        let mut applied = Self::unsplit(model, record)?;
        (applied.train, applied.val) = model.rows(&applied.prepared)?;
        Ok(applied)
    }

    /// As [`Applied::new`] without the split (`train` and `val` empty): all
    /// that compensation and the residue series need, on any record with at
    /// least two full windows, however short.
    pub fn unsplit(model: &CompensationModel, record: &Record) -> Result<Self, DtgVibError> {
        let prepared = model.prepare(record)?;
        if prepared.rows() < 2 {
            return Err(sysid::SysidError::TooFewSamples {
                what: "full windows",
                have: prepared.rows(),
                need: 2,
                hint: "a compensated record needs two samples with a full window: use a longer record",
            }
            .into());
        }
        // A causal model runs sample by sample through the onboard evaluator
        // (the code a flight computer runs); a zero-phase one as a batch.
        // A model the onboard layout cannot carry (another kernel, input
        // scaling: only from the library) is still compensated, as a batch.
        let stepped = if model.preprocess().causal {
            match crate::onboard::step_record(&crate::onboard::unit_model_of(model)?, record) {
                Ok(s) => Some(s),
                Err(DtgVibError::Export(crate::onboard::ExportError::Unsupported { .. })) => None,
                Err(e) => return Err(e),
            }
        } else {
            None
        };
        // The onboard evaluator subtracts the effects unfiltered, as the
        // batch compensation does; the filtered outputs' prediction has them
        // filtered.
        let above = model.inner().effects_above_band(prepared.inner())?;
        let shift = |series: &[Vec<f64>; 6], sign: f64| -> [Vec<f64>; 6] {
            std::array::from_fn(|k| {
                series[k]
                    .iter()
                    .zip(&above[k])
                    .map(|(p, a)| p + sign * a)
                    .collect()
            })
        };
        let (predicted, compensation, onboard) = match stepped {
            Some(s) => {
                let errors = six(&s.error_deg_h);
                (shift(&errors, -1.0), errors, Some(s))
            }
            // Outside the training range the network part fades
            // (sysid::operating::fade), as the onboard evaluator fades it.
            None => {
                let f = model.inner().predict_faded(prepared.inner())?;
                let mut it = f.predicted.into_iter();
                let p: [Vec<f64>; 6] = std::array::from_fn(|_| it.next().unwrap_or_default());
                let c = shift(&p, 1.0);
                (p, c, None)
            }
        };
        let first = prepared.first_sample();
        let outputs: [Vec<f64>; 6] =
            std::array::from_fn(|k| prepared.target_full(Channel::ALL[k])[first..].to_vec());
        let t = prepared.calibrated().t()[first..].to_vec();
        let residues = ResidueSeries::new(t, &outputs, &predicted);
        Ok(Self {
            prepared,
            predicted,
            compensation,
            residues,
            train: Vec::new(),
            val: Vec::new(),
            onboard,
        })
    }

    /// A channel's scores on the split's rows of this record (the model's
    /// own [`ChannelModel::scores`](crate::model::ChannelModel::scores) on the
    /// record it was fitted on). Needs the split: from [`Applied::new`].
    pub fn scores(&self, channel: Channel) -> ChannelScores {
        sysid::score(
            self.prepared.target(channel),
            &self.predicted[channel.index()],
            &self.train,
            &self.val,
        )
    }

    /// Residue rms before and after on the validation rows.
    pub fn validation_residues(&self) -> Vec<ResidueStats> {
        self.residues.stats(&self.val)
    }

    /// Residue rms before and after on every row.
    pub fn all_residues(&self) -> Vec<ResidueStats> {
        let all: Vec<usize> = (0..self.residues.t.len()).collect();
        self.residues.stats(&all)
    }

    /// The record compensated: from the first sample with a full window on,
    /// each gyro output (after the model's ground calibration, not filtered)
    /// minus the channel's [`Applied::compensation`]; accelerations calibrated; extra
    /// columns as given. The first `window − 1` samples have no window and
    /// are not in it. For a causal model, the onboard evaluator's
    /// compensated rates and calibrated accelerations.
    pub fn compensated_record(&self) -> Record {
        let first = self.prepared.first_sample();
        let rec = self.prepared.calibrated();
        let sliced = rec.slice(first..rec.len());
        if let Some(s) = &self.onboard {
            let accel: [Vec<f64>; 3] = std::array::from_fn(|k| s.accel_g[k].clone());
            return sliced.with_gyro(six(&s.rate_deg_h)).with_accel(accel);
        }
        let gyro: [Vec<f64>; 6] = std::array::from_fn(|k| {
            sliced
                .gyro(Channel::ALL[k])
                .iter()
                .zip(&self.compensation[k])
                .map(|(m, p)| m - p)
                .collect()
        });
        sliced.with_gyro(gyro)
    }
}

/// The residues of a record as given (no calibration, no filter), per sample:
/// `[K0..K5]` series.
///
/// ```
/// use nav_sensors::record::Record;
/// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0.02,1,0,0,0,0,0,0,0,1\n0.04,1,0,0,0,0,0,0,0,1\n";
/// let rec = Record::from_reader(csv.as_bytes(), "r.csv").unwrap();
/// let k = dtg_vib::apply::raw_residues(&rec);
/// assert_eq!(k[0], vec![1.0, 1.0]); // K0 = x0 − x1 sees an error on X
/// ```
pub fn raw_residues(record: &Record) -> [Vec<f64>; 6] {
    let mut out: [Vec<f64>; 6] = Default::default();
    for i in 0..record.len() {
        let k = residues(&record.gyro_sample(i));
        for (o, v) in out.iter_mut().zip(k) {
            o.push(v);
        }
    }
    out
}

/// Writes the residues CSV: `t,K0..K5` of the record as given for every
/// sample; with a model, from the first windowed sample on, also
/// `K0_pre..K5_pre` (after the model's calibration and filter) and
/// `K0_comp..K5_comp` (after compensation).
pub fn write_residues(
    path: &std::path::Path,
    record: &Record,
    applied: Option<&Applied>,
) -> Result<(), DtgVibError> {
    let raw = raw_residues(record);
    let names = ["K0", "K1", "K2", "K3", "K4", "K5"];
    match applied {
        None => {
            let mut cols: Vec<&[f64]> = vec![record.t()];
            cols.extend(raw.iter().map(Vec::as_slice));
            let mut header = vec!["t".to_string()];
            header.extend(names.iter().map(|s| s.to_string()));
            write(path, &header, &cols)
        }
        Some(a) => {
            let first = a.prepared.first_sample();
            let mut header = vec!["t".to_string()];
            header.extend(names.iter().map(|s| s.to_string()));
            header.extend(names.iter().map(|s| format!("{s}_pre")));
            header.extend(names.iter().map(|s| format!("{s}_comp")));
            let mut cols: Vec<&[f64]> = vec![&record.t()[first..]];
            cols.extend(raw.iter().map(|c| &c[first..]));
            cols.extend(a.residues.before.iter().map(Vec::as_slice));
            cols.extend(a.residues.after.iter().map(Vec::as_slice));
            write(path, &header, &cols)
        }
    }
}

fn write(path: &std::path::Path, header: &[String], cols: &[&[f64]]) -> Result<(), DtgVibError> {
    let names: Vec<&str> = header.iter().map(String::as_str).collect();
    Ok(tabular::write_csv(path, &names, cols)?)
}

/// The paper unit's six channels of a unit's per-channel series.
fn six(v: &[Vec<f64>]) -> [Vec<f64>; 6] {
    std::array::from_fn(|k| v[k].clone())
}
