//! `rbf_dtg.Model`'s native half: a unit's model (the command's model file)
//! and the commands that read one: `diagnose`, `check`, `compensate`, the model file
//! and `fit --json`'s summary.

use std::path::PathBuf;

use dtg_vib::commands::compensate::compensate as compensate_records;
use dtg_vib::commands::diagnose::diagnose as diagnose_records;
use dtg_vib::commands::fit_report::FitReport;
use dtg_vib::commands::parse::parse_share;
use dtg_vib::commands::records::records_of;
use dtg_vib::commands::report::{Caller, Reported, report as report_records};
use dtg_vib::unit_sensor::check::{self, DEFAULT_OUTSIDE_THRESHOLD};
use dtg_vib::unit_sensor::fdi;
use dtg_vib::unit_sensor::{Applied, UnitModel};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::calls::Frame;
use crate::error::{invalid, raise};
use crate::flags::{DiagnoseFlags, parse};
use crate::interrupt::detached;
use crate::stage::{Source, Stage};
use crate::table::Columns;

/// A fitted model of every gyro channel of a unit.
#[pyclass(module = "rbf_dtg._native", frozen)]
pub struct Model {
    model: UnitModel,
    /// The fit's seconds, for a model fitted here (not one read from a file).
    seconds: Option<f64>,
}

impl Model {
    pub fn fitted(model: UnitModel, seconds: Option<f64>) -> Self {
        Self { model, seconds }
    }

    /// The library's model.
    pub fn inner(&self) -> &UnitModel {
        &self.model
    }
}

/// What `report` prints besides the page: each residue's rms on every
/// sample `(name, before, after)`, the fault-detection lines, the
/// residues on the validation rows (JSON), each channel's validation rms
/// under the baseline and this model.
type Printed = (
    Vec<(String, f64, Option<f64>)>,
    Vec<String>,
    String,
    Vec<(String, f64, f64)>,
);

#[pymethods]
impl Model {
    /// Reads a model file (`dtg-vib fit --out`).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let model = detached(py, |_| UnitModel::load(&path).map_err(anyhow::Error::from))?
            .map_err(raise)?;
        Ok(Self::fitted(model, None))
    }

    /// Writes the model file, atomically.
    fn save(&self, path: PathBuf) -> PyResult<()> {
        self.model.save(&path).map_err(raise)
    }

    /// The model file's text.
    fn to_json(&self) -> PyResult<String> {
        let stage = Stage::new()?;
        let path = stage.file("model.json");
        self.model.save(&path).map_err(|e| stage.raise(e))?;
        std::fs::read_to_string(&path).map_err(|e| stage.raise(e))
    }

    /// The unit the model stores, as `rbf_dtg.Unit` shows it.
    fn unit_info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::unit::info(py, self.model.unit())
    }

    /// The unit the model stores, as a unit file.
    fn unit_toml(&self) -> String {
        self.model.unit().to_toml()
    }

    /// `dtg-vib fit --json`'s object of this model.
    fn summary_json(&self) -> PyResult<String> {
        let report = FitReport::of_model(self.model.inner(), self.seconds.unwrap_or(f64::NAN));
        serde_json::to_string(&report).map_err(raise)
    }

    /// `dtg-vib diagnose --json` on the records, and each channel's series
    /// (time, measured, predicted) for figures: `(json, {channel: (t, measured, predicted)})`.
    fn diagnose<'py>(
        &self,
        py: Python<'py>,
        records: Vec<Source>,
        flags: Vec<String>,
    ) -> PyResult<(String, Bound<'py, PyDict>)> {
        let thresholds =
            parse::<DiagnoseFlags>([vec!["diagnose".into()], flags].concat())?.thresholds;
        let stage = Stage::new()?;
        let data = stage.paths(&records)?;
        let d = detached(py, |_| -> anyhow::Result<_> {
            let mut read = records_of(&self.model, &data)?;
            stage.rename(&mut read.records);
            diagnose_records(&self.model, &read, thresholds)
        })?
        .map_err(|e| stage.raise(e))?;
        let json = serde_json::to_string(&d).map_err(raise)?;
        let series = PyDict::new(py);
        for c in &d.channels {
            let s = &c.series;
            series.set_item(
                &c.channel,
                (
                    PyArray1::from_slice(py, &s.t),
                    PyArray1::from_slice(py, &s.measured),
                    PyArray1::from_slice(py, &s.predicted),
                ),
            )?;
        }
        Ok((json, series))
    }

    /// `dtg-vib check --json` on a record the model was not fitted on, with
    /// `--outside-threshold` (None: the command's default).
    #[pyo3(signature = (record, outside_threshold=None))]
    fn check(
        &self,
        py: Python<'_>,
        record: Source,
        outside_threshold: Option<f64>,
    ) -> PyResult<String> {
        let threshold = match outside_threshold {
            None => DEFAULT_OUTSIDE_THRESHOLD,
            Some(v) => {
                parse_share(&v.to_string()).map_err(|e| invalid("outside_threshold", v, e))?
            }
        };
        let stage = Stage::new()?;
        let data = stage.path(&record)?;
        let c = detached(py, |_| -> anyhow::Result<_> {
            let mut read = records_of(&self.model, std::slice::from_ref(&data))?;
            stage.rename(&mut read.records);
            let applied = Applied::unsplit(&self.model, &read.borrowed())?;
            Ok(check::check(&self.model, &applied, threshold)?)
        })?
        .map_err(|e| stage.raise(e))?;
        serde_json::to_string(&c).map_err(raise)
    }

    /// `dtg-vib report` on the record into `out` (a model or a baseline
    /// handed over from memory staged as a file): `(index.html, printed, notes)`.
    #[pyo3(signature = (record, out, command, baseline=None))]
    fn report(
        &self,
        py: Python<'_>,
        record: Source,
        out: PathBuf,
        command: String,
        baseline: Option<PyRef<'_, Model>>,
    ) -> PyResult<(PathBuf, Printed, Vec<String>)> {
        let stage = Stage::new()?;
        let data = stage.path(&record)?;
        let user_data = matches!(record, Source::Path(_)).then_some(data.as_path());
        outfile::guard_dir("out_dir", &out, &["index.html"], &[("record", user_data)])
            .map_err(raise)?;
        let base = baseline.as_ref().map(|b| b.inner());
        let (index, printed, notes) = detached(py, |_| -> anyhow::Result<_> {
            let model_file = stage.file("model.json");
            self.model.save(&model_file)?;
            let base_file = stage.file("baseline.json");
            if let Some(b) = base {
                b.save(&base_file)?;
            }
            let mut read = records_of(&self.model, std::slice::from_ref(&data))?;
            stage.rename(&mut read.records);
            let caller = Caller {
                command: Some(command),
                staged: Some(stage.dir()),
            };
            let files = [data.clone()];
            let baseline = base.map(|b| (b, base_file.as_path()));
            let r = report_records(
                &self.model,
                &model_file,
                &read,
                &files,
                baseline,
                &out,
                caller,
            )?;
            Ok((
                r.written.index.clone(),
                printed(&self.model, &r)?,
                read.notes,
            ))
        })?
        .map_err(|e| stage.raise(e))?;
        let notes = notes.iter().map(|n| stage.clean(n)).collect();
        Ok((index, printed, notes))
    }

    /// `dtg-vib compensate` on the record: `(columns, notes, seconds in Rust)`.
    fn compensate<'py>(
        &self,
        py: Python<'py>,
        record: Source,
    ) -> PyResult<(Frame<'py>, Vec<String>, f64)> {
        let start = std::time::Instant::now();
        let stage = Stage::new()?;
        let data = stage.path(&record)?;
        let (columns, notes) = detached(py, |_| -> anyhow::Result<_> {
            let mut read = records_of(&self.model, std::slice::from_ref(&data))?;
            stage.rename(&mut read.records);
            let c = compensate_records(&self.model, &read)?;
            Ok((Columns::of_csv(&c.text, "compensated")?, read.notes))
        })?
        .map_err(|e| stage.raise(e))?;
        let notes = notes.iter().map(|n| stage.clean(n)).collect();
        let frame = columns.into_py(py);
        Ok((frame, notes, start.elapsed().as_secs_f64()))
    }
}

/// The numbers `report` prints.
fn printed(m: &UnitModel, r: &Reported) -> anyhow::Result<Printed> {
    let p = &r.written.parity;
    let every = p
        .residues
        .iter()
        .map(|x| (x.name.clone(), x.before, x.after))
        .collect();
    let lines = p.fdi.as_ref().map_or_else(Vec::new, |f| {
        f.found
            .iter()
            .map(|(what, s)| fdi::line(what, s, &f.setting))
            .collect()
    });
    let validation = serde_json::to_string(&r.applied.validation_residues())?;
    let against = match &r.baseline {
        Some(b) => m
            .unit()
            .gyro_names()
            .into_iter()
            .enumerate()
            .map(|(k, c)| {
                (
                    c.to_string(),
                    b.scores(k).val_rms,
                    r.applied.scores(k).val_rms,
                )
            })
            .collect(),
        None => Vec::new(),
    };
    Ok((every, lines, validation, against))
}
