//! What `rbf fit` and `rbf cv` print: one JSON object with `--json`, a short human
//! summary otherwise.
//!
//! Key names of the fit object are a contract (scripts read them): `n_train`, `n_val`,
//! `dim`, `n_centers`, `fit_seconds` (the library fit alone, timed in-process),
//! `train_rmse`, `val_rmse`, `val_nmse` (validation MSE over the variance of the
//! validation targets). Undefined scores (no validation rows) are `null`.

use std::fmt::Write as _;

use rbf::metrics::Scores;
use rbf::{CvReport, FoldReport, GridReport, RbfModel, WidthRule, Widths};
use serde::Serialize;
use serde_json::{Map, Value, json};

use crate::progress::StageTimes;
use crate::settings::{Centers, FitSettings, WidthArg};

/// One OLS pick as reported: where the centre came from and its ERR.
///
/// ```
/// let p = rbf_cli::report::PickOut { row: 4, line: 6, err: 0.5, cumulative_err: 0.9 };
/// assert_eq!(serde_json::to_value(&p).unwrap()["line"], 6);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PickOut {
    /// 0-based data row of the centre in the file.
    pub row: usize,
    /// Its line in the file (the header is line 1).
    pub line: u64,
    /// Error-reduction ratio when picked.
    pub err: f64,
    /// ΣERR after the pick (the forced bias included).
    pub cumulative_err: f64,
}

/// The OLS record of a fit.
///
/// ```
/// let o = rbf_cli::report::OlsOut { forced_errs: vec![0.1], sum_err: 0.1, stop: "max_terms".into(), picks: vec![] };
/// assert_eq!(o.picks.len(), 0);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OlsOut {
    /// ERR of the forced columns (the bias).
    pub forced_errs: Vec<f64>,
    /// ΣERR of the model (1 − ΣERR is the unexplained share of the target energy).
    pub sum_err: f64,
    /// Why selection stopped: `max_terms`, `tolerance` or `exhausted`.
    pub stop: String,
    /// The picks in order.
    pub picks: Vec<PickOut>,
}

/// The facts of a fit that the model does not hold itself.
///
/// ```
/// let c = rbf_cli::report::FitContext::default();
/// assert_eq!(c.n_val, 0);
/// ```
#[derive(Clone, Debug, Default)]
pub struct FitContext {
    /// The data file.
    pub data: String,
    /// The target column.
    pub target: String,
    /// The input columns.
    pub inputs: Vec<String>,
    /// File rows (0-based data rows) of the training matrix, in order.
    pub train_rows: Vec<usize>,
    /// File lines of the training rows.
    pub train_lines: Vec<u64>,
    /// Validation rows.
    pub n_val: usize,
    /// The flags.
    pub settings: FitSettings,
    /// Seconds of the library fit.
    pub fit_seconds: f64,
    /// Seconds to predict the validation rows.
    pub predict_seconds: f64,
    /// Scores on the training rows.
    pub train: Scores,
    /// Scores on the validation rows (None without validation rows).
    pub val: Option<Scores>,
    /// Stage timings from the progress callback.
    pub times: StageTimes,
    /// Where the model was written.
    pub out: String,
    /// Threads the fit ran on.
    pub threads: usize,
    /// `--width auto` with `--stop press|gcv`: every width tried, with the size it kept
    /// and the criterion there (empty otherwise).
    pub width_search: Vec<WidthTrial>,
}

/// One width of the `--width auto` search.
///
/// ```
/// let t = rbf_cli::report::WidthTrial { scale: 1.0, width: 2.5, k: 10, criterion: 3.0 };
/// assert_eq!(t.k, 10);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WidthTrial {
    /// Multiple of the median pairwise distance.
    pub scale: f64,
    /// The width β it gave.
    pub width: f64,
    /// Centres kept (the least PRESS or GCV along the path, as `--stop` says).
    pub k: usize,
    /// PRESS there (the widths are compared by it).
    pub criterion: f64,
}

/// The report of `rbf fit`.
///
/// ```
/// use rbf_cli::report::{FitContext, FitReport};
/// let model = rbf::doc_model();
/// let ctx = FitContext { train_rows: (0..40).collect(), train_lines: (2..42).collect(), ..FitContext::default() };
/// let r = FitReport::new(&model, ctx);
/// let v = r.json();
/// for key in ["n_train", "n_val", "dim", "n_centers", "fit_seconds", "train_rmse", "val_rmse", "val_nmse"] {
///     assert!(v.get(key).is_some(), "{key}");
/// }
/// assert!(v["val_rmse"].is_null());
/// assert!(r.summary().contains("centres"));
/// ```
#[derive(Clone, Debug)]
pub struct FitReport {
    model_facts: Map<String, Value>,
    ctx: FitContext,
    ols: Option<OlsOut>,
}

fn width_facts(widths: &Widths) -> (Option<f64>, Option<(f64, f64)>) {
    match widths {
        Widths::Uniform(b) => (Some(*b), None),
        Widths::PerCentre(v) => {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (None, Some((lo, hi)))
        }
    }
}

/// How `--width` was applied, in words.
///
/// ```
/// use rbf_cli::settings::WidthArg;
/// assert!(rbf_cli::report::width_rule_text(WidthArg::Auto).contains("median"));
/// ```
pub fn width_rule_text(w: WidthArg) -> &'static str {
    match w {
        WidthArg::Auto => "auto: median pairwise distance between candidate centres",
        WidthArg::Fixed(_) => "fixed",
    }
}

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

fn nan_to_none(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

impl FitReport {
    /// Collects the report of `model` fitted in context `ctx`.
    ///
    /// ```
    /// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
    /// assert_eq!(r.json()["kernel"], "gaussian");
    /// ```
    pub fn new(model: &RbfModel, ctx: FitContext) -> Self {
        let (width, range) = width_facts(model.widths());
        let mut m = Map::new();
        m.insert("kernel".into(), json!(model.kernel().name()));
        m.insert("width".into(), json!(width));
        if let Some((lo, hi)) = range {
            m.insert("width_min".into(), json!(lo));
            m.insert("width_max".into(), json!(hi));
        }
        m.insert("condition".into(), json!(nan_to_none(model.condition())));
        m.insert("n_centers".into(), json!(model.n_centres()));
        m.insert("dim".into(), json!(model.dim()));
        m.insert("bias".into(), json!(model.bias().map(|b| b[0])));
        if let Some(sel) = model.selection().filter(|s| !s.criterion.is_empty()) {
            m.insert("criterion".into(), json!(sel.criterion));
        }
        let ols = model.selection().map(|s| OlsOut {
            forced_errs: s.forced_errs.clone(),
            sum_err: s
                .picks
                .last()
                .map_or_else(|| s.forced_errs.iter().sum(), |p| p.cumulative_err),
            stop: serde_json::to_value(s.stop)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default(),
            picks: s
                .picks
                .iter()
                .map(|p| {
                    let row = ctx.train_rows.get(p.index).copied().unwrap_or(p.index);
                    let line = ctx.train_lines.get(p.index).copied().unwrap_or(0);
                    PickOut {
                        row,
                        line,
                        err: p.err,
                        cumulative_err: p.cumulative_err,
                    }
                })
                .collect(),
        });
        Self {
            model_facts: m,
            ctx,
            ols,
        }
    }

    /// The `--json` object.
    ///
    /// ```
    /// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
    /// assert_eq!(r.json()["dim"], 1);
    /// ```
    pub fn json(&self) -> Value {
        let c = &self.ctx;
        let s = &c.settings;
        let val = c.val.as_ref();
        let mut m = Map::new();
        let mut put = |k: &str, v: Value| {
            m.insert(k.to_string(), v);
        };
        put("command", json!("fit"));
        put("data", json!(c.data));
        put("target", json!(c.target));
        put("inputs", json!(c.inputs));
        put("n_train", json!(c.train_rows.len()));
        put("n_val", json!(c.n_val));
        put("dim", self.model_facts["dim"].clone());
        put("n_centers", self.model_facts["n_centers"].clone());
        put("centers", json!(s.centers.name()));
        put("fit_seconds", json!(c.fit_seconds));
        put("predict_seconds", json!(c.predict_seconds));
        put("train_rmse", json!(nan_to_none(c.train.rmse)));
        put("train_nmse", json!(nan_to_none(c.train.nmse)));
        put("val_rmse", json!(val.and_then(|v| nan_to_none(v.rmse))));
        put("val_nmse", json!(val.and_then(|v| nan_to_none(v.nmse))));
        put(
            "val_fit_percent",
            json!(val.and_then(|v| nan_to_none(v.fit_percent))),
        );
        put("val_r2", json!(val.and_then(|v| nan_to_none(v.r2))));
        for (k, v) in &self.model_facts {
            if !["dim", "n_centers"].contains(&k.as_str()) {
                put(k, v.clone());
            }
        }
        put("width_rule", json!(width_rule_text(s.width)));
        put("ridge", json!(s.ridge));
        put("standardize", json!(s.standardize));
        put("seed", json!(s.seed));
        put("max_centers", json!(s.n_centers_for(c.train_rows.len())));
        put("candidates", json!(s.candidates));
        let (sel_rows, ols_cands) = s.ols_rows(c.train_rows.len());
        put("selection_rows", json!(sel_rows));
        put("ols_candidates", json!(ols_cands));
        put("kmeans_algorithm", json!(kmeans_algorithm(s)));
        put("tol", json!(s.tol));
        put("stop", json!(s.stop.map(|v| v.name())));
        if !c.width_search.is_empty() {
            put("width_search", json!(c.width_search));
        }
        let stages: Map<String, Value> = c
            .times
            .stages
            .iter()
            .map(|(k, v)| (k.clone(), json!(v)))
            .collect();
        put("stage_seconds", Value::Object(stages));
        put("seconds_per_pick", json!(c.times.seconds_per_pick));
        put("threads", json!(c.threads));
        put("ols", json!(self.ols));
        put("model", json!(c.out));
        Value::Object(m)
    }

    /// A few lines for people.
    ///
    /// ```
    /// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
    /// assert!(r.summary().contains("OLS: ΣERR"));
    /// ```
    pub fn summary(&self) -> String {
        let c = &self.ctx;
        let s = &c.settings;
        let f = &self.model_facts;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "rbf fit: {} training / {} validation rows of {}, {} inputs → '{}'",
            c.train_rows.len(),
            c.n_val,
            c.data,
            c.inputs.len(),
            c.target
        );
        let width = match f["width"].as_f64() {
            Some(b) => format!("β = {b:.6}"),
            None => format!(
                "β per centre in [{:.4}, {:.4}]",
                f.get("width_min")
                    .and_then(Value::as_f64)
                    .unwrap_or(f64::NAN),
                f.get("width_max")
                    .and_then(Value::as_f64)
                    .unwrap_or(f64::NAN)
            ),
        };
        let _ = writeln!(
            out,
            "  {} centres ({}{}), {} kernel, width {} ({}), ridge {}{}",
            f["n_centers"],
            s.centers,
            kmeans_algorithm(s).map_or(String::new(), |a| format!(", {a}")),
            s.kernel,
            width,
            width_rule_text(s.width),
            s.ridge,
            if s.standardize {
                ", inputs standardised"
            } else {
                ""
            }
        );
        if let Some(o) = &self.ols {
            let _ = writeln!(
                out,
                "  OLS: ΣERR {:.6} after {} picks (bias ERR {:.4}), stopped: {}",
                o.sum_err,
                o.picks.len(),
                o.forced_errs.first().copied().unwrap_or(0.0),
                o.stop
            );
        }
        let _ = writeln!(
            out,
            "  fit {:.3} s, condition estimate {:.3e}",
            c.fit_seconds,
            f["condition"].as_f64().unwrap_or(f64::NAN)
        );
        match &c.val {
            Some(v) => {
                let _ = writeln!(
                    out,
                    "  RMSE train {:.6}, validation {:.6}; validation NMSE {:.6} (fit {:.2}%)",
                    c.train.rmse, v.rmse, v.nmse, v.fit_percent
                );
            }
            None => {
                let _ = writeln!(out, "  RMSE train {:.6}; no validation rows", c.train.rmse);
            }
        }
        let _ = write!(out, "  model written to {}", c.out);
        out
    }
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
        "rmse": nan_to_none(s.rmse),
        "nmse": nan_to_none(s.nmse),
        "fit_percent": nan_to_none(s.fit_percent),
        "r2": nan_to_none(s.r2),
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
