//! What `rbf fit`, `rbf cv` and `rbf predict` print: one JSON object with `--json`, a
//! short human summary otherwise.
//!
//! Key names of the fit object are a contract (scripts read them): `n_train`, `n_val`,
//! `dim`, `n_centers`, `fit_seconds` (the library fit alone, timed in-process),
//! `train_rmse`, `val_rmse`, `val_nmse` (validation MSE over the variance of the
//! validation targets). Undefined scores (no validation rows) are `null`.
//!
//! Each `--json` object is a `#[derive(Serialize)]` struct that borrows from the report
//! ([`FitJson`]; those of `cv` and `predict` are still built by hand), so its keys are spelled once, as fields.
//! The fields of these structs, and of every struct nested in them, are declared in
//! alphabetical order: serde writes keys in field order, and sorted keys are what
//! `serde_json::Value` prints, so the output is byte for byte what scripts have already
//! seen. The tests below check that every object is sorted.
//!
//! | module | what |
//! |---|---|
//! | [`fit`] | `rbf fit`: the context of a fit, its OLS record, [`FitJson`] |

pub mod fit;

pub use fit::{
    CriterionOut, FitContext, FitJson, FitReport, OlsOut, PickOut, WidthTrial, width_rule_text,
};

use std::fmt::Write as _;

use rbf::metrics::Scores;
use rbf::{CvReport, FoldReport, GridReport, WidthRule};
use serde_json::{Value, json};

use crate::settings::{Centers, FitSettings};

/// The k-means algorithm that ran (`--kmeans-algorithm`, or the library's default),
/// for k-means fits only.
///
/// ```
/// use rbf_cli::settings::{Centers, FitSettings};
/// let s = FitSettings { centers: Centers::Kmeans, ..FitSettings::default() };
/// assert_eq!(rbf_cli::report::kmeans_algorithm(&s), Some("lloyd"));
/// assert_eq!(rbf_cli::report::kmeans_algorithm(&FitSettings::default()), None);
/// ```
pub fn kmeans_algorithm(s: &FitSettings) -> Option<&'static str> {
    (s.centers == Centers::Kmeans).then(|| s.kmeans_algorithm.unwrap_or_default().name())
}

/// A score as JSON: `None` (printed `null`) when it is undefined (NaN) or infinite.
pub(crate) fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

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

/// The report of `rbf cv`.
///
/// ```
/// use rbf_cli::report::{CvContext, CvOut};
/// let grid = rbf::GridReport { points: vec![], best: None };
/// let out = CvOut::new(&grid, CvContext::default());
/// assert!(out.json()["best"].is_null());
/// assert!(out.summary().contains("no grid point"));
/// ```
#[derive(Clone, Debug)]
pub struct CvOut {
    ctx: CvContext,
    points: Vec<Value>,
    folds: Vec<Vec<FoldReport>>,
    best: Option<usize>,
}

fn point_json(p: &rbf::GridPoint) -> Value {
    let (mean, std, folds, error) = match &p.result {
        Ok(r) => (
            json!(scores_json(&r.mean)),
            json!(scores_json(&r.std)),
            json!(r.folds),
            Value::Null,
        ),
        Err(e) => (Value::Null, Value::Null, json!([]), json!(e.to_string())),
    };
    let width = match p.width {
        WidthRule::Fixed(b) => json!(b),
        _ => json!("auto"),
    };
    json!({
        "width": width,
        "n_centers": p.n_centres,
        "tol": p.tol,
        "ridge": p.ridge,
        "mean": mean,
        "std": std,
        "folds": folds,
        "error": error,
    })
}

/// A JSON value as a table cell: strings bare, null as `-`.
fn cell(v: &Value) -> String {
    match v {
        Value::Null => "-".to_string(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

fn scores_json(s: &Scores) -> Value {
    json!({
        "rmse": finite(s.rmse),
        "nmse": finite(s.nmse),
        "fit_percent": finite(s.fit_percent),
        "r2": finite(s.r2),
    })
}

impl CvOut {
    /// Collects the report of a grid search.
    ///
    /// ```
    /// let g = rbf::GridReport { points: vec![], best: None };
    /// let out = rbf_cli::report::CvOut::new(&g, Default::default());
    /// assert_eq!(out.json()["points"], serde_json::json!([]));
    /// ```
    pub fn new(grid: &GridReport, ctx: CvContext) -> Self {
        Self {
            ctx,
            points: grid.points.iter().map(point_json).collect(),
            folds: grid
                .points
                .iter()
                .map(|p| {
                    p.result
                        .as_ref()
                        .map(|r: &CvReport| r.folds.clone())
                        .unwrap_or_default()
                })
                .collect(),
            best: grid.best,
        }
    }

    /// The `--json` object.
    ///
    /// ```
    /// let g = rbf::GridReport { points: vec![], best: None };
    /// let v = rbf_cli::report::CvOut::new(&g, Default::default()).json();
    /// assert_eq!(v["command"], "cv");
    /// ```
    pub fn json(&self) -> Value {
        let c = &self.ctx;
        json!({
            "command": "cv",
            "data": c.data,
            "target": c.target,
            "inputs": c.inputs,
            "n_rows": c.n_rows,
            "dim": c.inputs.len(),
            "centers": c.settings.centers.name(),
            "kmeans_algorithm": kmeans_algorithm(&c.settings),
            "kernel": c.settings.kernel.name(),
            "split": c.split,
            "folds": c.folds,
            "gap": c.gap,
            "seed": c.settings.seed,
            "seconds": c.seconds,
            "points": self.points,
            "best": self.best,
            "best_point": self.best.map(|i| self.points[i].clone()),
        })
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
            c.settings.centers,
            c.settings.kernel,
            c.seconds
        );
        let _ = writeln!(
            out,
            "    {:>10} {:>8} {:>8} {:>10}  {:>24} {:>12}",
            "width", "centres", "tol", "ridge", "val NMSE mean ± sd", "val RMSE"
        );
        for (i, p) in self.points.iter().enumerate() {
            let mark = if Some(i) == self.best { "*" } else { " " };
            let _ = write!(
                out,
                "  {mark} {:>10} {:>8} {:>8} {:>10}  ",
                cell(&p["width"]),
                cell(&p["n_centers"]),
                cell(&p["tol"]),
                cell(&p["ridge"])
            );
            if p["error"].is_null() {
                let f = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
                let _ = writeln!(
                    out,
                    "{:>24} {:>12.6}",
                    format!("{:.6} ± {:.6}", f(&p["mean"]["nmse"]), f(&p["std"]["nmse"])),
                    f(&p["mean"]["rmse"])
                );
            } else {
                let _ = writeln!(out, "failed: {}", cell(&p["error"]));
            }
        }
        let Some(b) = self.best else {
            let _ = write!(out, "no grid point could be fitted on every fold");
            return out;
        };
        let p = &self.points[b];
        let mut point = vec![format!("width {}", cell(&p["width"]))];
        if !p["n_centers"].is_null() {
            point.push(format!("{} centres", cell(&p["n_centers"])));
        }
        if !p["tol"].is_null() {
            point.push(format!("tol {}", cell(&p["tol"])));
        }
        point.push(format!("ridge {}", cell(&p["ridge"])));
        let _ = writeln!(
            out,
            "best: {}: validation NMSE {:.6}, RMSE {:.6} (mean over folds)",
            point.join(", "),
            p["mean"]["nmse"].as_f64().unwrap_or(f64::NAN),
            p["mean"]["rmse"].as_f64().unwrap_or(f64::NAN)
        );
        let _ = writeln!(
            out,
            "  {:>4} {:>7} {:>7} {:>8} {:>12} {:>12} {:>12}",
            "fold", "train", "val", "centres", "train RMSE", "val RMSE", "val NMSE"
        );
        for (i, f) in self.folds[b].iter().enumerate() {
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

#[cfg(test)]
mod tests {
    use serde::Serialize;
    use serde_json::Value;

    use super::*;

    /// The text of `out` is already sorted: reading it into a `Value` (whose objects
    /// sort their keys) and printing that again gives the same bytes.
    fn assert_keys_sorted(out: &impl Serialize) {
        let text = serde_json::to_string(out).unwrap();
        let again = serde_json::from_str::<Value>(&text).unwrap().to_string();
        assert_eq!(text, again, "keys out of alphabetical order");
    }

    #[test]
    fn fit_json_keys_are_sorted() {
        let model = rbf::doc_model();
        let ctx = FitContext {
            train_rows: (0..40).collect(),
            train_lines: (2..42).collect(),
            val: Some(rbf::metrics::Scores::default()),
            times: crate::progress::StageTimes {
                stages: vec![("widths".into(), 1.0), ("kernel_matrix".into(), 2.0)],
                seconds_per_pick: Some(0.5),
            },
            width_search: vec![WidthTrial {
                scale: 1.0,
                width: 2.0,
                k: 3,
                criterion: 4.0,
            }],
            ..FitContext::default()
        };
        let report = FitReport::new(&model, ctx);
        let v = serde_json::to_value(report.json()).unwrap();
        assert!(!v["ols"]["picks"].as_array().unwrap().is_empty());
        assert!(!v["width_search"].as_array().unwrap().is_empty());
        assert_keys_sorted(&report.json());
    }
}
