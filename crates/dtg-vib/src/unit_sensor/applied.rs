//! A unit's model applied to records of its unit: each segment
//! compensated (what `compensate` writes), the parity residues before and
//! after (what `residues` writes), and per channel the measured error
//! against the model's prediction with rms before and after (what the
//! unit's report shows).

use super::model::UnitModel;
use super::signals::{to_record, to_signals};
use crate::error::DtgVibError;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use sysid::Signals;
use sysid::inference::Coefficient;

/// A segment compensated: its calibrated outputs less what compensation
/// subtracts (the prediction, its network part faded outside the training
/// range, the effects unfiltered: as for the paper's unit and onboard),
/// from the first sample with a full window on, in the unit's column names
/// (deg/h and g inside).
pub fn compensated(m: &UnitModel, segment: &Signals) -> Result<Record, DtgVibError> {
    let prepared = m.inner().prepare(segment)?;
    let predicted = m.compensation(&prepared)?;
    let first = prepared.first_sample();
    let calibrated = prepared.calibrated();
    let gyros = m.unit().gyro_names();
    let columns = calibrated
        .columns()
        .iter()
        .map(|(n, v)| {
            let tail = &v[first..];
            let out = match gyros.iter().position(|g| g == n) {
                Some(k) => tail.iter().zip(&predicted[k]).map(|(y, e)| y - e).collect(),
                None => tail.to_vec(),
            };
            (n.clone(), out)
        })
        .collect();
    let s = Signals::new(calibrated.t()[first..].to_vec(), columns)
        .map_err(super::error::UnitSensorError::from)?;
    Ok(to_record(m.unit(), &s)?)
}

/// Per parity residue (V·m), its series over a record's samples; none for
/// a unit of three gyros.
///
/// ```
/// use nav_sensors::record::Record;
/// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let csv = "t,g1,g2,g3,g4,ax,ay,az\n0,1,1,1,1,0,0,1\n0.02,1,1,1,5,0,0,1\n";
/// let mut read = Record::from_reader_with_unit(csv.as_bytes(), "r.csv", &u).unwrap();
/// let r = read.records.remove(0); // one segment: no gap in the times
/// let p = dtg_vib::unit_sensor::residue_series(&u, &r);
/// assert_eq!((p.len(), p[0].len()), (1, 2));
/// assert!(p[0][1].abs() > p[0][0].abs()); // a step on g4 shows in P0
/// ```
pub fn residue_series(unit: &Unit, r: &Record) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::with_capacity(r.len()); unit.residue_names().len()];
    for i in 0..r.len() {
        for (o, v) in out.iter_mut().zip(unit.residues(&r.gyro_row(i))) {
            o.push(v);
        }
    }
    out
}

/// One effect of a channel's model with its coefficient.
#[derive(Debug, Clone, PartialEq)]
pub struct EffectRow {
    /// The effect id (`g_y`, `col:temp`, …).
    pub id: String,
    /// Its coefficient with standard error, 95% interval and unit (absent
    /// in a model file written before they were estimated).
    pub coefficient: Option<Coefficient>,
}

/// One channel of a unit's model on records.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelOnRecord {
    /// The gyro's name.
    pub name: String,
    /// Its error model: `rate` or `dtg`.
    pub model: &'static str,
    /// The model's effects on it.
    pub effects: Vec<EffectRow>,
    /// Rms of the target about its mean on the rows compared, deg/h: what
    /// the best constant correction leaves.
    pub rms_before: f64,
    /// Rms of target − prediction on those rows, deg/h.
    pub rms_after: f64,
    /// Time of each row compared, s (its window's last sample).
    pub t: Vec<f64>,
    /// The pre-processed target (output less the rate reference), deg/h.
    pub measured: Vec<f64>,
    /// The model's prediction of it, deg/h.
    pub predicted: Vec<f64>,
}

/// A unit's model on records: per channel, measured against predicted.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitApplied {
    /// Every channel, in the unit's gyro order.
    pub channels: Vec<ChannelOnRecord>,
    /// Which rows were compared: "validation rows" (the model's split)
    /// or "every row" (a record without the model's split).
    pub rows: &'static str,
    /// Rows compared.
    pub n_rows: usize,
}

impl UnitApplied {
    /// Applies `m` to the named records (segments of its unit's logs), all
    /// together.
    pub fn new(m: &UnitModel, records: &[(String, &Signals)]) -> Result<Self, DtgVibError> {
        let inner = m.inner();
        let prepared = inner.prepare_many(records)?;
        let predicted = inner.predict(&prepared)?;
        let (rows, which) = match inner.rows(&prepared) {
            Ok((_, val)) if !val.is_empty() => (val, "validation rows"),
            _ => ((0..prepared.rows()).collect(), "every row"),
        };
        let t: Vec<f64> = rows
            .iter()
            .map(|&r| {
                let (s, i) = prepared.locate(r);
                s.t()[i]
            })
            .collect();
        let channels = inner
            .channels()
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let y = prepared.target(k);
                let measured: Vec<f64> = rows.iter().map(|&r| y[r]).collect();
                let pred: Vec<f64> = rows.iter().map(|&r| predicted[k][r]).collect();
                let mean = measured.iter().sum::<f64>() / measured.len().max(1) as f64;
                let about: Vec<f64> = measured.iter().map(|v| v - mean).collect();
                let after: Vec<f64> = measured.iter().zip(&pred).map(|(a, b)| a - b).collect();
                let effects = c
                    .effects()
                    .iter()
                    .enumerate()
                    .map(|(j, e)| EffectRow {
                        id: e.id(),
                        coefficient: c.coefficients().and_then(|co| co.get(j).cloned()),
                    })
                    .collect();
                ChannelOnRecord {
                    name: c.channel(),
                    model: m.unit().gyros()[k].model.name(),
                    effects,
                    rms_before: stats::rms(&about),
                    rms_after: stats::rms(&after),
                    t: t.clone(),
                    measured,
                    predicted: pred,
                }
            })
            .collect();
        Ok(Self {
            channels,
            rows: which,
            n_rows: rows.len(),
        })
    }
}

/// Every record's gyro outputs before (as logged) and after the model's
/// compensation (what `compensate` writes), per channel, deg/h, every
/// sample from the model's first full window on, the records one after
/// the other: the series `residues` and fault detection read.
pub fn gyros_before_after(
    m: &UnitModel,
    records: &[(String, Record)],
) -> Result<BeforeAfter, DtgVibError> {
    let n = m.unit().gyros().len();
    let (mut before, mut after) = (vec![Vec::new(); n], vec![Vec::new(); n]);
    let mut t = Vec::new();
    for (_, r) in records {
        let c = compensated(m, &to_signals(r)?)?;
        let first = r.len() - c.len();
        t.extend_from_slice(&r.t()[first..]);
        for k in 0..n {
            before[k].extend_from_slice(&r.gyro_at(k)[first..]);
            after[k].extend_from_slice(c.gyro_at(k));
        }
    }
    Ok(BeforeAfter { t, before, after })
}

/// Gyro series before and after compensation ([`gyros_before_after`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BeforeAfter {
    /// Time of each sample, s.
    pub t: Vec<f64>,
    /// Per channel, as logged, deg/h.
    pub before: Vec<Vec<f64>>,
    /// Per channel, compensated, deg/h.
    pub after: Vec<Vec<f64>>,
}

/// The parity residues (V·m) of gyro series (per channel, equal lengths).
///
/// ```
/// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let g = vec![vec![1.0, 1.0]; 4];
/// let p = dtg_vib::unit_sensor::residues_of(&u, &g);
/// assert_eq!(p.len(), 1);
/// ```
pub fn residues_of(unit: &Unit, gyros: &[Vec<f64>]) -> Vec<Vec<f64>> {
    per_sample(gyros, unit.residue_names().len(), |row| unit.residues(row))
}

/// `f` of each sample's row of the gyro series (per channel, equal
/// lengths), as `width` series: the residues, or the parity vectors V·m.
pub(crate) fn per_sample<T: IntoIterator<Item = f64>>(
    gyros: &[Vec<f64>],
    width: usize,
    f: impl Fn(&[f64]) -> T,
) -> Vec<Vec<f64>> {
    let len = gyros.first().map_or(0, Vec::len);
    let mut out = vec![Vec::with_capacity(len); width];
    let mut row = vec![0.0; gyros.len()];
    for i in 0..len {
        for (r, g) in row.iter_mut().zip(gyros) {
            *r = g[i];
        }
        for (o, v) in out.iter_mut().zip(f(&row)) {
            o.push(v);
        }
    }
    out
}
