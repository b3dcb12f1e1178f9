//! The analyses of a record with or without a model, as `dtg-vib residues`
//! and `dtg-vib allan` make them ([`dtg_vib::commands::residues`],
//! [`dtg_vib::commands::allan`]), on a staged record, without the GIL.

use dtg_vib::commands::allan::{DEFAULT_CONFIDENCE, allan as allan_of};
use dtg_vib::commands::parse::{parse_alpha, parse_sigma};
use dtg_vib::commands::records::{Read, read_records, unit_and_min};
use dtg_vib::commands::residues::{refuse_without_residues, residues as residues_of};
use dtg_vib::unit_sensor::UnitModel;
use dtg_vib::unit_sensor::fdi::DEFAULT_FALSE_ALARM;
use nav_sensors::unit::Unit;
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::Path;

use crate::calls::Frame;
use crate::error::invalid;
use crate::interrupt::detached;
use crate::model::Model;
use crate::stage::{Source, Stage};

/// A value checked by the command's value parser of that flag.
fn checked(name: &str, value: f64, parse: fn(&str) -> Result<f64, String>) -> PyResult<f64> {
    parse(&value.to_string()).map_err(|e| invalid(name, value, e))
}

/// The record (staged at `data`) read with the unit (the model's, where
/// one is given) as the command reads `--data`, named as the caller named
/// it; `before` runs on the unit first (a refusal that needs no record).
fn read_with(
    stage: &Stage,
    data: &Path,
    unit: Option<&str>,
    model: Option<&UnitModel>,
    before: fn(&Unit) -> anyhow::Result<()>,
) -> anyhow::Result<(Unit, Read)> {
    let (unit, min) = unit_and_min(model, "the model", unit)?;
    before(&unit)?;
    let mut read = read_records(&[data.to_path_buf()], &unit, min)?;
    stage.rename(&mut read.records);
    Ok((unit, read))
}

/// `dtg-vib residues` on the record: `(columns of --out, --json's object, notes)`.
#[pyfunction]
#[pyo3(signature = (record, unit=None, model=None, fdi_sigma=None, fdi_false_alarm=None))]
pub fn residues<'py>(
    py: Python<'py>,
    record: Source,
    unit: Option<String>,
    model: Option<PyRef<'py, Model>>,
    fdi_sigma: Option<f64>,
    fdi_false_alarm: Option<f64>,
) -> PyResult<(Frame<'py>, String, Vec<String>)> {
    let sigma = fdi_sigma
        .map(|v| checked("fdi_sigma", v, parse_sigma))
        .transpose()?;
    let alpha = match fdi_false_alarm {
        None => DEFAULT_FALSE_ALARM,
        Some(v) => checked("fdi_false_alarm", v, parse_alpha)?,
    };
    let m = model.as_ref().map(|m| m.inner());
    let stage = Stage::new()?;
    let data = stage.path(&record)?;
    let (names, columns, json, notes) = detached(py, |_| -> anyhow::Result<_> {
        let (unit, read) = read_with(&stage, &data, unit.as_deref(), m, refuse_without_residues)?;
        let r = residues_of(&unit, m, &read, sigma, alpha)?;
        let (names, columns) = r.columns();
        let columns: Vec<Vec<f64>> = columns.into_iter().map(<[f64]>::to_vec).collect();
        Ok((names, columns, r.to_json()?.to_string(), read.notes))
    })?
    .map_err(|e| stage.raise(e))?;
    let arrays = columns
        .into_iter()
        .map(|c| PyArray1::from_vec(py, c))
        .collect();
    let notes = notes.iter().map(|n| stage.clean(n)).collect();
    Ok(((names, arrays), stage.clean(&json), notes))
}

/// `dtg-vib allan --json` on the record: `(the object, notes and warnings)`.
#[pyfunction]
#[pyo3(signature = (record, unit=None, model=None, confidence=None))]
pub fn allan(
    py: Python<'_>,
    record: Source,
    unit: Option<String>,
    model: Option<PyRef<'_, Model>>,
    confidence: Option<f64>,
) -> PyResult<(String, Vec<String>)> {
    let m = model.as_ref().map(|m| m.inner());
    let confidence = confidence.unwrap_or(DEFAULT_CONFIDENCE);
    let stage = Stage::new()?;
    let data = stage.path(&record)?;
    let (json, notes) = detached(py, |_| -> anyhow::Result<_> {
        let (unit, read) = read_with(&stage, &data, unit.as_deref(), m, |_| Ok(()))?;
        let a = allan_of(&unit, m, &read, confidence)?;
        let mut notes = read.notes;
        notes.extend(a.warning.iter().map(|w| format!("warning: {w}")));
        Ok((a.to_json().to_string(), notes))
    })?
    .map_err(|e| stage.raise(e))?;
    let notes = notes.iter().map(|n| stage.clean(n)).collect();
    Ok((stage.clean(&json), notes))
}
