//! The Allan analysis of a unit's record, before and (with a model) after
//! compensation, as [`crate::allan`] makes it for the paper's unit: before
//! is the calibrated output from the model's first full window on, after
//! what `compensate` writes; without a model, the record as logged. The
//! residues are the unit's P0, … of the same series (none for three gyros).

use super::applied::{compensated, residues_of};
use super::model::UnitModel;
use super::signals::to_signals;
use crate::allan::{AllanAnalysis, NamedSeries};
use crate::error::DtgVibError;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;

/// Per gyro, the series before, after (with a model), and the first
/// record sample they start at.
type Series = (Vec<Vec<f64>>, Option<Vec<Vec<f64>>>, usize);

/// Analyses one segment of `unit` (a record between time gaps), with
/// intervals at `confidence`.
pub fn unit_allan(
    unit: &Unit,
    model: Option<&UnitModel>,
    segment: &Record,
    confidence: f64,
) -> Result<AllanAnalysis, DtgVibError> {
    let n = unit.gyros().len();
    let (before, after, first): Series = match model {
        None => (
            (0..n).map(|k| segment.gyro_at(k).to_vec()).collect(),
            None,
            0,
        ),
        Some(m) => {
            let s = to_signals(segment)?;
            let prepared = m.inner().prepare(&s)?;
            let first = prepared.first_sample();
            let calibrated = prepared.calibrated();
            let before = unit
                .gyro_names()
                .iter()
                .map(|g| {
                    calibrated
                        .column(g)
                        .map(|c| c[first..].to_vec())
                        .ok_or_else(|| {
                            DtgVibError::from(super::UnitSensorError::MissingColumn {
                                name: g.to_string(),
                                unit_file: unit.file().to_string(),
                                columns: calibrated.names().iter().map(|n| n.to_string()).collect(),
                            })
                        })
                })
                .collect::<Result<Vec<_>, _>>()?;
            let c = compensated(m, &s)?;
            let after = (0..n).map(|k| c.gyro_at(k).to_vec()).collect();
            (before, Some(after), first)
        }
    };
    let name = |k: usize| unit.gyro_names()[k].to_string();
    let res_before = residues_of(unit, &before);
    let res_after = after.as_ref().map(|a| residues_of(unit, a));
    let channels: Vec<NamedSeries> = before
        .into_iter()
        .enumerate()
        .map(|(k, b)| (name(k), b, after.as_ref().map(|a| a[k].clone())))
        .collect();
    let residues: Vec<NamedSeries> = res_before
        .into_iter()
        .enumerate()
        .map(|(k, b)| {
            (
                unit.residue_names()[k].clone(),
                b,
                res_after.as_ref().map(|a| a[k].clone()),
            )
        })
        .collect();
    AllanAnalysis::of_series(segment.dt(), first, confidence, channels, residues)
}
