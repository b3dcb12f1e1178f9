//! The RBF library as the `rbf fit` command runs it: `fit_rbf` builds the
//! command's settings from the estimator's parameters (checked by the command's
//! own parsers, so the ranges and messages are the command's) and calls
//! [`rbf_cli::train::fit`], the command's fit. [`RbfModel`] holds the result.

use std::path::PathBuf;

use numpy::{PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rbf::faer::Mat;
use rbf::{Kernel, PolyTail};
use rbf_cli::saved::SavedModel;
use rbf_cli::settings::{
    Centres, FitSettings, StopArg, WidthArg, parse_count, parse_ridge, parse_tol,
};
use rbf_cli::train;

use crate::arrays::{to_mat, to_numpy, to_numpy_1d};
use crate::error::{Error, invalid, raise};
use crate::interrupt::detached;

/// The estimator's parameters, as `RBFRegressor.get_params()` holds them (plus the
/// seed drawn from `random_state`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct FitArgs {
    centers: String,
    kernel: String,
    width: Option<f64>,
    max_centers: Option<i64>,
    ridge: f64,
    tol: Option<f64>,
    degree: Option<i64>,
    standardize: bool,
    stop: Option<String>,
    seed: u64,
}

/// `FromStr` of the command line, with the parameter's name in the refusal.
fn parsed<T>(name: &str, value: impl ToString) -> PyResult<T>
where
    T: std::str::FromStr,
    T::Err: std::fmt::Display,
{
    let text = value.to_string();
    text.parse().map_err(|e| invalid(name, &text, e))
}

/// A value checked by one of the command's value parsers (`--ridge`, `--tol`, …).
fn checked<T>(
    name: &str,
    value: impl ToString,
    parse: fn(&str) -> Result<T, String>,
) -> PyResult<T> {
    let text = value.to_string();
    parse(&text).map_err(|e| invalid(name, &text, e))
}

impl FitArgs {
    /// The command's settings for these parameters.
    fn settings(&self) -> PyResult<FitSettings> {
        Ok(FitSettings {
            centres: parsed::<Centres>("centers", &self.centers)?,
            kernel: parsed::<Kernel>("kernel", &self.kernel)?,
            width: match self.width {
                None => WidthArg::Auto,
                Some(b) => parsed::<WidthArg>("width", b)?,
            },
            max_centres: self
                .max_centers
                .map(|k| checked("max_centers", k, parse_count))
                .transpose()?,
            ridge: checked("ridge", self.ridge, parse_ridge)?,
            tol: self.tol.map(|t| checked("tol", t, parse_tol)).transpose()?,
            degree: self
                .degree
                .map(|d| parsed::<PolyTail>("degree", d))
                .transpose()?,
            stop: self
                .stop
                .as_ref()
                .map(|s| parsed::<StopArg>("stop", s))
                .transpose()?,
            standardize: self.standardize,
            seed: self.seed,
            ..FitSettings::default()
        })
    }
}

/// `max_centers=None`: the command's default size for these settings, lowered to
/// the most `rows` training rows of `dim` inputs take (by the library's rule), so
/// that small data sets (a fold of a cross-validation) fit with the defaults.
/// `None` when the default fits, for `centers="all"`, and for `stop="k:K"`.
fn default_size(s: &FitSettings, rows: usize, dim: usize) -> PyResult<Option<usize>> {
    let Some(k) = s.n_centres_for(rows) else {
        return Ok(None);
    };
    if matches!(s.stop, Some(StopArg::K(_))) {
        return Ok(None);
    }
    let most = s
        .build(rows, s.width.rule())
        .map_err(raise)?
        .most_centres(rows, dim, 0);
    Ok((1..k).contains(&most).then_some(most))
}

/// Fits a network on `x` (n × d) → `y` (n × q) as `rbf fit` does with the same
/// settings; without the GIL, stopped by Ctrl-C between OLS picks and stages.
#[pyfunction]
pub fn fit_rbf(
    py: Python<'_>,
    x: PyReadonlyArray2<'_, f64>,
    y: PyReadonlyArray2<'_, f64>,
    args: FitArgs,
) -> PyResult<RbfModel> {
    let (x, y) = (to_mat(&x), to_mat(&y));
    if x.nrows() != y.nrows() {
        return Err(Error::new_err(format!(
            "x has {} rows but y has {}",
            x.nrows(),
            y.nrows()
        )));
    }
    let (rows, dim) = (x.nrows(), x.ncols());
    let mut settings = args.settings()?;
    if settings.max_centres.is_none() {
        settings.max_centres = default_size(&settings, rows, dim)?;
    }
    let params = settings.params(rows, dim).map_err(raise)?;
    let fitted = detached(py, |checkpoint| {
        train::fit(&settings, &params, x.as_ref(), y.as_ref(), &|_| {
            checkpoint.check()
        })
    })?
    .map_err(raise)?;
    Ok(RbfModel {
        model: fitted.model,
    })
}

/// A fitted network: the library's model, which the `rbf` command saves.
#[pyclass(module = "rbf_dtg._native", frozen)]
pub struct RbfModel {
    model: rbf::RbfModel,
}

#[pymethods]
impl RbfModel {
    /// Predictions (n × outputs) for `x` (n × inputs), without the GIL.
    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let x = to_mat(&x);
        if x.ncols() != self.model.dim() {
            return Err(Error::new_err(format!(
                "x has {} columns but the model has {} inputs",
                x.ncols(),
                self.model.dim()
            )));
        }
        let out: Mat<f64> = detached(py, |_| self.model.predict(x.as_ref()))?;
        Ok(to_numpy(py, out.as_ref()))
    }

    /// The centres in data units (centres × inputs).
    #[getter]
    fn centres<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, self.model.centres().as_ref())
    }

    /// The kernel weights (centres × outputs).
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        to_numpy(py, self.model.weights())
    }

    /// The bias of each output, or None when a polynomial tail replaces it.
    #[getter]
    fn bias<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.model.bias().map(|b| to_numpy_1d(py, b))
    }

    /// The width β of each centre.
    #[getter]
    fn widths<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let w: Vec<f64> = (0..self.model.n_centres())
            .map(|j| self.model.widths().get(j))
            .collect();
        to_numpy_1d(py, &w)
    }

    /// OLS: each pick as (training row, ERR, ΣERR after it); None for other centres.
    #[getter]
    fn picks(&self) -> Option<Vec<(usize, f64, f64)>> {
        self.model.selection().map(|s| {
            s.picks
                .iter()
                .map(|p| (p.index, p.err, p.cumulative_err))
                .collect()
        })
    }

    /// The estimated condition number of the weights' least squares.
    #[getter]
    fn condition(&self) -> f64 {
        self.model.condition()
    }

    /// The kernel's name, as `--kernel` spells it.
    #[getter]
    fn kernel(&self) -> &'static str {
        self.model.kernel().name()
    }

    /// Number of inputs.
    #[getter]
    fn dim(&self) -> usize {
        self.model.dim()
    }

    /// Number of outputs.
    #[getter]
    fn n_outputs(&self) -> usize {
        self.model.n_outputs()
    }

    /// The library's model file as JSON (numbers round-trip exactly).
    fn to_json(&self) -> PyResult<String> {
        let mut buf = Vec::new();
        self.model.to_writer(&mut buf).map_err(raise)?;
        String::from_utf8(buf).map_err(raise)
    }

    /// A model from [`RbfModel::to_json`]'s text, checked as a model file is.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        let model = rbf::RbfModel::from_reader(text.as_bytes()).map_err(raise)?;
        Ok(Self { model })
    }

    /// Pickling: the JSON, which predicts bit-identically once read back.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let from_json = py.get_type::<RbfModel>().getattr("from_json")?;
        Ok((from_json, PyTuple::new(py, [self.to_json()?])?))
    }

    /// Writes the `rbf` command's model file (`rbf predict --model` reads it),
    /// atomically.
    fn save(
        &self,
        path: PathBuf,
        inputs: Vec<String>,
        target: String,
        data: String,
    ) -> PyResult<()> {
        SavedModel {
            target,
            inputs,
            data,
            model: self.model.clone(),
        }
        .save(&path)
        .map_err(raise)
    }

    /// Reads a model file of `rbf fit --out`: (model, input names, target name).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<(Self, Vec<String>, String)> {
        let saved = SavedModel::load(&path).map_err(raise)?;
        Ok((Self { model: saved.model }, saved.inputs, saved.target))
    }
}
