//! The report of `rbf cv`: the `--json` object ([`CvJson`]) and the table for people.

use std::fmt::Write as _;

use rbf::metrics::Scores;
use rbf::{FoldReport, GridPoint, GridReport, WidthRule};
use serde::Serialize;

use super::{finite, kmeans_algorithm};
use crate::settings::FitSettings;

/// How a grid width is shown: the fixed β, or `auto`.
///
/// ```
/// assert_eq!(rbf_cli::report::width_label(&rbf::WidthRule::Fixed(0.5)), "0.5");
/// assert_eq!(rbf_cli::report::width_label(&rbf::WidthRule::default()), "auto");
/// ```
pub fn width_label(w: &WidthRule) -> String {
    match w {
        WidthRule::Fixed(b) => format!("{b}"),
        _ => "auto".to_string(),
    }
}

/// The facts of a cross-validation that the grid report does not hold.
///
/// ```
/// let c = rbf_cli::report::CvContext::default();
/// assert_eq!(c.folds, 0);
/// ```
#[derive(Clone, Debug, Default)]
pub struct CvContext {
    /// The data file.
    pub data: String,
    /// The target column.
    pub target: String,
    /// The input columns.
    pub inputs: Vec<String>,
    /// Rows used.
    pub n_rows: usize,
    /// `--split`.
    pub split: String,
    /// `--folds`.
    pub folds: usize,
    /// `--gap`.
    pub gap: usize,
    /// The base flags.
    pub settings: FitSettings,
    /// Seconds of the whole grid search.
    pub seconds: f64,
}

/// The four scores as JSON, `null` where undefined or infinite. Fields in alphabetical
/// order, the order of the keys (see the [module](super) doc).
///
/// ```
/// let s = rbf::metrics::Scores { rmse: f64::NAN, ..Default::default() };
/// let text = serde_json::to_string(&rbf_cli::report::ScoresJson::from(&s)).unwrap();
/// assert_eq!(text, r#"{"fit_percent":0.0,"nmse":0.0,"r2":0.0,"rmse":null}"#);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ScoresJson {
    /// 100·(1 − ‖y − ŷ‖/‖y − ȳ‖).
    pub fit_percent: Option<f64>,
    /// MSE / var(y).
    pub nmse: Option<f64>,
    /// 1 − SSE/SST.
    pub r2: Option<f64>,
    /// Root mean squared error.
    pub rmse: Option<f64>,
}

impl From<&Scores> for ScoresJson {
    fn from(s: &Scores) -> Self {
        Self {
            fit_percent: finite(s.fit_percent),
            nmse: finite(s.nmse),
            r2: finite(s.r2),
            rmse: finite(s.rmse),
        }
    }
}

/// One fold of a grid point: the library's [`FoldReport`] with its fields in
/// alphabetical order, the order of the keys.
///
/// ```
/// let f = rbf::FoldReport { train_size: 10, validation_size: 5, n_centres: 3,
///     train: Default::default(), validation: Default::default() };
/// let text = serde_json::to_string(&rbf_cli::report::FoldJson::from(&f)).unwrap();
/// assert!(text.starts_with(r#"{"n_centres":3,"train":{"#));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FoldJson {
    /// Centres of the fold's model.
    pub n_centres: usize,
    /// Scores on the training rows.
    pub train: ScoresJson,
    /// Training rows.
    pub train_size: usize,
    /// Scores on the validation rows.
    pub validation: ScoresJson,
    /// Validation rows.
    pub validation_size: usize,
}

impl From<&FoldReport> for FoldJson {
    fn from(f: &FoldReport) -> Self {
        Self {
            n_centres: f.n_centres,
            train: ScoresJson::from(&f.train),
            train_size: f.train_size,
            validation: ScoresJson::from(&f.validation),
            validation_size: f.validation_size,
        }
    }
}

/// A grid width as JSON: the fixed β as a number, any other rule as `"auto"`.
///
/// ```
/// use rbf_cli::report::WidthJson;
/// assert_eq!(serde_json::to_string(&WidthJson::from(&rbf::WidthRule::Fixed(0.5))).unwrap(), "0.5");
/// assert_eq!(serde_json::to_string(&WidthJson::from(&rbf::WidthRule::default())).unwrap(), r#""auto""#);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum WidthJson {
    /// `--widths β`.
    Fixed(f64),
    /// `--widths auto`: always the string `auto`.
    Auto(&'static str),
}

impl From<&WidthRule> for WidthJson {
    fn from(w: &WidthRule) -> Self {
        match w {
            WidthRule::Fixed(b) => WidthJson::Fixed(*b),
            _ => WidthJson::Auto("auto"),
        }
    }
}

/// One grid point as JSON. Fields in alphabetical order, the order of the keys; a
/// point whose folds failed has `error` and no scores.
///
/// ```
/// let p = rbf::GridPoint { width: rbf::WidthRule::Fixed(1.0), n_centres: Some(5), tol: None, ridge: 0.0,
///     result: Err(rbf::RbfError::FoldFailed { reason: "example".into() }) };
/// let v = serde_json::to_value(rbf_cli::report::PointJson::from(&p)).unwrap();
/// assert!(v["mean"].is_null() && v["folds"] == serde_json::json!([]));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PointJson {
    /// Why a fold failed, if one did.
    pub error: Option<String>,
    /// Every fold (none if one failed).
    pub folds: Vec<FoldJson>,
    /// Mean of the validation scores over the folds.
    pub mean: Option<ScoresJson>,
    /// Centres asked for, if the grid gives sizes.
    #[serde(rename = "n_centers")]
    pub n_centres: Option<usize>,
    /// Ridge λ.
    pub ridge: f64,
    /// Standard deviation of the validation scores over the folds.
    pub std: Option<ScoresJson>,
    /// OLS tolerance ρ, if the grid gives tolerances.
    pub tol: Option<f64>,
    /// Width β, or `auto`.
    pub width: WidthJson,
}

impl From<&GridPoint> for PointJson {
    fn from(p: &GridPoint) -> Self {
        let (error, folds, mean, std) = match &p.result {
            Ok(r) => (
                None,
                r.folds.iter().map(FoldJson::from).collect(),
                Some(ScoresJson::from(&r.mean)),
                Some(ScoresJson::from(&r.std)),
            ),
            Err(e) => (Some(e.to_string()), Vec::new(), None, None),
        };
        Self {
            error,
            folds,
            mean,
            n_centres: p.n_centres,
            ridge: p.ridge,
            std,
            tol: p.tol,
            width: WidthJson::from(&p.width),
        }
    }
}

/// What `rbf cv --json` prints, borrowed from a [`CvOut`]. Fields in the alphabetical
/// order of their keys, the order of the keys (see the [module](super) doc; `centres`
/// prints as the key `centers`, a contract).
///
/// ```
/// let g = rbf::GridReport { points: vec![], best: None };
/// let out = rbf_cli::report::CvOut::new(&g, Default::default());
/// assert_eq!(serde_json::to_value(out.json()).unwrap()["command"], "cv");
/// ```
#[derive(Clone, Debug, Serialize)]
pub struct CvJson<'a> {
    best: Option<usize>,
    best_point: Option<&'a PointJson>,
    #[serde(rename = "centers")]
    centres: &'static str,
    command: &'static str,
    data: &'a str,
    dim: usize,
    folds: usize,
    gap: usize,
    inputs: &'a [String],
    kernel: &'static str,
    kmeans_algorithm: Option<&'static str>,
    n_rows: usize,
    points: &'a [PointJson],
    seconds: f64,
    seed: u64,
    split: &'a str,
    target: &'a str,
}

/// The report of `rbf cv`.
///
/// ```
/// use rbf_cli::report::{CvContext, CvOut};
/// let grid = rbf::GridReport { points: vec![], best: None };
/// let out = CvOut::new(&grid, CvContext::default());
/// assert!(serde_json::to_value(out.json()).unwrap()["best"].is_null());
/// assert!(out.summary().contains("no grid point"));
/// ```
#[derive(Clone, Debug)]
pub struct CvOut<'a> {
    ctx: CvContext,
    /// The grid, for the folds of the best point in the summary.
    grid: &'a GridReport,
    /// The points as printed, built once for both the JSON and the table.
    points: Vec<PointJson>,
}

/// A number of a grid point as a table cell: as `--json` prints it, `-` when absent.
fn cell<T: Serialize>(v: Option<T>) -> String {
    v.and_then(|v| serde_json::to_string(&v).ok())
        .unwrap_or_else(|| "-".to_string())
}

/// A grid width as a table cell: as `--json` prints it, `auto` without quotes.
fn width_cell(w: WidthJson) -> String {
    match w {
        WidthJson::Fixed(b) => cell(Some(b)),
        WidthJson::Auto(s) => s.to_string(),
    }
}

/// A score of a grid point for the table, NaN where `--json` has `null`.
fn score(s: Option<ScoresJson>, pick: fn(&ScoresJson) -> Option<f64>) -> f64 {
    s.as_ref().and_then(pick).unwrap_or(f64::NAN)
}

impl<'a> CvOut<'a> {
    /// Collects the report of a grid search.
    ///
    /// ```
    /// let g = rbf::GridReport { points: vec![], best: None };
    /// let out = rbf_cli::report::CvOut::new(&g, Default::default());
    /// assert_eq!(serde_json::to_value(out.json()).unwrap()["points"], serde_json::json!([]));
    /// ```
    pub fn new(grid: &'a GridReport, ctx: CvContext) -> Self {
        Self {
            ctx,
            grid,
            points: grid.points.iter().map(PointJson::from).collect(),
        }
    }

    /// The `--json` object.
    ///
    /// ```
    /// let g = rbf::GridReport { points: vec![], best: None };
    /// let out = rbf_cli::report::CvOut::new(&g, Default::default());
    /// assert_eq!(serde_json::to_value(out.json()).unwrap()["command"], "cv");
    /// ```
    pub fn json(&self) -> CvJson<'_> {
        let c = &self.ctx;
        CvJson {
            best: self.grid.best,
            best_point: self.grid.best.map(|i| &self.points[i]),
            centres: c.settings.centres.name(),
            command: "cv",
            data: &c.data,
            dim: c.inputs.len(),
            folds: c.folds,
            gap: c.gap,
            inputs: &c.inputs,
            kernel: c.settings.kernel.name(),
            kmeans_algorithm: kmeans_algorithm(&c.settings),
            n_rows: c.n_rows,
            points: &self.points,
            seconds: c.seconds,
            seed: c.settings.seed,
            split: &c.split,
            target: &c.target,
        }
    }

    /// A table of the grid, the best point and its folds, for people.
    ///
    /// ```
    /// let g = rbf::GridReport { points: vec![], best: None };
    /// let text = rbf_cli::report::CvOut::new(&g, Default::default()).summary();
    /// assert!(text.starts_with("rbf cv:"));
    /// ```
    pub fn summary(&self) -> String {
        let c = &self.ctx;
        let best = self.grid.best;
        let mut out = String::new();
        let gap = if c.split == "blocked" {
            format!(" (gap {})", c.gap)
        } else {
            String::new()
        };
        let _ = writeln!(
            out,
            "rbf cv: {} split, {} folds{gap}, {} rows of {}, {} inputs → '{}'; {} centres, {} kernel; {:.2} s",
            c.split,
            c.folds,
            c.n_rows,
            c.data,
            c.inputs.len(),
            c.target,
            c.settings.centres,
            c.settings.kernel,
            c.seconds
        );
        let _ = writeln!(
            out,
            "    {:>10} {:>8} {:>8} {:>10}  {:>24} {:>12}",
            "width", "centres", "tol", "ridge", "val NMSE mean ± sd", "val RMSE"
        );
        for (i, p) in self.points.iter().enumerate() {
            let mark = if Some(i) == best { "*" } else { " " };
            let _ = write!(
                out,
                "  {mark} {:>10} {:>8} {:>8} {:>10}  ",
                width_cell(p.width),
                cell(p.n_centres),
                cell(p.tol),
                cell(Some(p.ridge))
            );
            match &p.error {
                None => {
                    let _ = writeln!(
                        out,
                        "{:>24} {:>12.6}",
                        format!(
                            "{:.6} ± {:.6}",
                            score(p.mean, |s| s.nmse),
                            score(p.std, |s| s.nmse)
                        ),
                        score(p.mean, |s| s.rmse)
                    );
                }
                Some(e) => {
                    let _ = writeln!(out, "failed: {e}");
                }
            }
        }
        let Some(b) = best else {
            let _ = write!(out, "no grid point could be fitted on every fold");
            return out;
        };
        let p = &self.points[b];
        let mut point = vec![format!("width {}", width_cell(p.width))];
        if p.n_centres.is_some() {
            point.push(format!("{} centres", cell(p.n_centres)));
        }
        if p.tol.is_some() {
            point.push(format!("tol {}", cell(p.tol)));
        }
        point.push(format!("ridge {}", cell(Some(p.ridge))));
        let _ = writeln!(
            out,
            "best: {}: validation NMSE {:.6}, RMSE {:.6} (mean over folds)",
            point.join(", "),
            score(p.mean, |s| s.nmse),
            score(p.mean, |s| s.rmse)
        );
        let _ = writeln!(
            out,
            "  {:>4} {:>7} {:>7} {:>8} {:>12} {:>12} {:>12}",
            "fold", "train", "val", "centres", "train RMSE", "val RMSE", "val NMSE"
        );
        let folds: &[FoldReport] = self.grid.points[b]
            .result
            .as_ref()
            .map_or(&[], |r| &r.folds);
        for (i, f) in folds.iter().enumerate() {
            let _ = writeln!(
                out,
                "  {:>4} {:>7} {:>7} {:>8} {:>12.6} {:>12.6} {:>12.6}",
                i + 1,
                f.train_size,
                f.validation_size,
                f.n_centres,
                f.train.rmse,
                f.validation.rmse,
                f.validation.nmse
            );
        }
        out.pop();
        out
    }
}
