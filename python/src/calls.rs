//! The loop's calls on records from Python: `read_record`, `simulate`,
//! `fit`, `explain`, each the command's library function
//! ([`dtg_vib::commands`]) on staged files, without the GIL.

use std::path::PathBuf;

use dtg_vib::commands::explain::{explain as explain_loop, explain_takes};
use dtg_vib::commands::fit::fit as fit_records;
use dtg_vib::commands::fit_args::FitRecipe;
use dtg_vib::commands::records::{read_records, unit_csv, unit_of};
use dtg_vib::commands::simulate::{scenario, simulate_into};
use pyo3::prelude::*;

use crate::error::raise;
use crate::flags::{ExplainFlags, FitFlags, parse};
use crate::interrupt::detached;
use crate::model::Model;
use crate::stage::{CalibrationSource, Source, Stage};
use crate::table::Columns;

/// A frame's columns for Python: names and arrays.
pub type Frame<'py> = (Vec<String>, Vec<Bound<'py, numpy::PyArray1<f64>>>);

/// A log read as `--data` is: `(columns, notes)`, the segments one after the other.
#[pyfunction]
#[pyo3(signature = (path, unit=None))]
pub fn read_record<'py>(
    py: Python<'py>,
    path: PathBuf,
    unit: Option<String>,
) -> PyResult<(Frame<'py>, Vec<String>)> {
    let (columns, notes) = detached(py, |_| -> anyhow::Result<_> {
        let unit = unit_of(unit.as_deref())?;
        let read = read_records(std::slice::from_ref(&path), &unit, 2)?;
        let named = read.records.iter().map(|(n, r)| (n.as_str(), r));
        let (text, _) = unit_csv(named, &unit)?;
        Ok((
            Columns::of_csv(&text, &path.display().to_string())?,
            read.notes,
        ))
    })?
    .map_err(raise)?;
    Ok((columns.into_py(py), notes))
}

/// `dtg-vib simulate`: `(record columns, calibration text, truth text, notes)`.
#[pyfunction]
#[pyo3(signature = (builtin=None, scenario_file=None, unit=None, seed=None, duration=None))]
pub fn simulate<'py>(
    py: Python<'py>,
    builtin: Option<String>,
    scenario_file: Option<PathBuf>,
    unit: Option<String>,
    seed: Option<u64>,
    duration: Option<f64>,
) -> PyResult<(Frame<'py>, String, String, Vec<String>)> {
    let stage = Stage::new()?;
    let out = detached(py, |_| -> anyhow::Result<_> {
        let unit = unit_of(unit.as_deref())?;
        let s = scenario(scenario_file.as_deref(), builtin.as_deref(), seed, duration)?;
        let notes = simulate_into(&s, &unit, &stage.file(""))?;
        let read = read_records(&[stage.file("record.csv")], &unit, 2)?;
        let named = read.records.iter().map(|(_, r)| ("record.csv", r));
        let (text, _) = unit_csv(named, &unit)?;
        let columns = Columns::of_csv(&text, "record.csv")?;
        let calibration = std::fs::read_to_string(stage.file("calibration.json"))?;
        let truth = std::fs::read_to_string(stage.file("truth.json"))?;
        Ok((columns, calibration, truth, notes))
    })?
    .map_err(|e| stage.raise(e))?;
    let (columns, calibration, truth, notes) = out;
    Ok((columns.into_py(py), calibration, truth, notes))
}

/// The command's argument list of a fit: the staged records, calibration
/// and an `--out` that is never written (a model returns to Python).
fn fit_argv(
    command: &str,
    stage: &Stage,
    sources: &[Source],
    calibration: Option<&CalibrationSource>,
    flags: Vec<String>,
) -> PyResult<Vec<String>> {
    let mut argv = vec![command.to_string()];
    for p in stage.paths(sources)? {
        argv.extend(["--data".to_string(), p.display().to_string()]);
    }
    if let Some(c) = calibration {
        argv.extend([
            "--calib".into(),
            stage.calibration(c)?.display().to_string(),
        ]);
    }
    argv.extend([
        "--out".into(),
        stage.file("model.json").display().to_string(),
    ]);
    argv.extend(flags);
    Ok(argv)
}

/// `dtg-vib fit` on the records: `(model, notes)`.
#[pyfunction]
#[pyo3(signature = (records, calibration, flags))]
pub fn fit(
    py: Python<'_>,
    records: Vec<Source>,
    calibration: Option<CalibrationSource>,
    flags: Vec<String>,
) -> PyResult<(Model, Vec<String>)> {
    let stage = Stage::new()?;
    let argv = fit_argv("fit", &stage, &records, calibration.as_ref(), flags)?;
    let a = parse::<FitFlags>(argv)?.fit;
    let (fitted, notes) = detached(py, |checkpoint| -> anyhow::Result<_> {
        let mut recipe = FitRecipe::resolve(&a)?;
        stage.rename(&mut recipe.read.records);
        let fitted = fit_records(&recipe, a.cv.is_some(), &|_| checkpoint.check(), &|_| ())?;
        Ok((fitted, recipe.read.notes))
    })?
    .map_err(|e| stage.raise(e))?;
    let notes = notes.iter().map(|n| stage.clean(n)).collect();
    Ok((Model::fitted(fitted.model, Some(fitted.seconds)), notes))
}

/// `dtg-vib explain` on the records: `(final model, rounds as JSON, converged, notes)`.
#[pyfunction]
#[pyo3(signature = (records, calibration, flags))]
pub fn explain(
    py: Python<'_>,
    records: Vec<Source>,
    calibration: Option<CalibrationSource>,
    flags: Vec<String>,
) -> PyResult<(Model, String, bool, Vec<String>)> {
    let stage = Stage::new()?;
    let argv = fit_argv("explain", &stage, &records, calibration.as_ref(), flags)?;
    let a = parse::<ExplainFlags>(argv)?.explain;
    let (e, notes) = detached(py, |checkpoint| -> anyhow::Result<_> {
        explain_takes(&a.fit)?;
        let mut recipe = FitRecipe::resolve(&a.fit)?;
        stage.rename(&mut recipe.read.records);
        // No page is drawn here, so the last diagnosis skips the longer
        // window's trial, as the command's `--json` does without `--report`.
        let e = explain_loop(&recipe, (a.thresholds, false), a.max_rounds, &|_| {
            checkpoint.check()
        })?;
        Ok((e, recipe.read.notes))
    })?
    .map_err(|e| stage.raise(e))?;
    let rounds = serde_json::to_string(&e.rounds).map_err(raise)?;
    let notes = notes.iter().map(|n| stage.clean(n)).collect();
    Ok((
        Model::fitted(e.model, Some(e.seconds)),
        stage.clean(&rounds),
        e.converged,
        notes,
    ))
}

/// Writes a text file atomically, as the command writes its outputs.
#[pyfunction]
pub fn write_text(path: PathBuf, text: &str) -> PyResult<()> {
    outfile::write_bytes(&path, text).map_err(|e| raise(anyhow::anyhow!("{}: {e}", path.display())))
}
