//! The report of `rbf fit`: its context, its OLS record, the `--json` object
//! ([`FitJson`]) and the summary for people.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use rbf::metrics::Scores;
use rbf::{RbfModel, Widths};
use serde::Serialize;

use super::{finite, kmeans_algorithm};
use crate::progress::StageTimes;
use crate::settings::{FitSettings, WidthArg};

/// One OLS pick as reported: where the centre came from and its ERR. Fields in
/// alphabetical order, the order of the keys (see the [module](super) doc).
///
/// ```
/// let p = rbf_cli::report::PickOut { row: 4, line: 6, err: 0.5, cumulative_err: 0.9 };
/// assert_eq!(serde_json::to_value(&p).unwrap()["line"], 6);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PickOut {
    /// ΣERR after the pick (the forced bias included).
    pub cumulative_err: f64,
    /// Error-reduction ratio when picked.
    pub err: f64,
    /// Its line in the file (the header is line 1).
    pub line: u64,
    /// 0-based data row of the centre in the file.
    pub row: usize,
}

/// The OLS record of a fit. Fields in alphabetical order, the order of the keys.
///
/// ```
/// let o = rbf_cli::report::OlsOut { forced_errs: vec![0.1], sum_err: 0.1, stop: "max_terms".into(), picks: vec![] };
/// assert_eq!(o.picks.len(), 0);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OlsOut {
    /// ERR of the forced columns (the bias).
    pub forced_errs: Vec<f64>,
    /// The picks in order.
    pub picks: Vec<PickOut>,
    /// Why selection stopped: `max_terms`, `tolerance` or `exhausted`.
    pub stop: String,
    /// ΣERR of the model (1 − ΣERR is the unexplained share of the target energy).
    pub sum_err: f64,
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

/// One width of the `--width auto` search. Fields in alphabetical order, the order
/// of the keys.
///
/// ```
/// let t = rbf_cli::report::WidthTrial { scale: 1.0, width: 2.5, k: 10, criterion: 3.0 };
/// assert_eq!(t.k, 10);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WidthTrial {
    /// PRESS there (the widths are compared by it).
    pub criterion: f64,
    /// Centres kept (the least PRESS or GCV along the path, as `--stop` says).
    pub k: usize,
    /// Multiple of the median pairwise distance.
    pub scale: f64,
    /// The width β it gave.
    pub width: f64,
}

/// PRESS and GCV at one size of the OLS path, as `criterion` lists them: the library's
/// [`rbf::ols::Criterion`] with its fields in alphabetical order, the order of the keys.
///
/// ```
/// let c = rbf_cli::report::CriterionOut::from(&rbf::ols::Criterion { k: 3, press: 1.5, gcv: 0.01 });
/// assert_eq!(serde_json::to_string(&c).unwrap(), r#"{"gcv":0.01,"k":3,"press":1.5}"#);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CriterionOut {
    /// GCV: n·RSS/(n − t)².
    pub gcv: f64,
    /// Picks (forced columns not counted).
    pub k: usize,
    /// PRESS: the leave-one-out residual sum of squares.
    pub press: f64,
}

impl From<&rbf::ols::Criterion> for CriterionOut {
    fn from(c: &rbf::ols::Criterion) -> Self {
        Self {
            gcv: c.gcv,
            k: c.k,
            press: c.press,
        }
    }
}

/// What the fitted model says of itself, copied out so that the report does not
/// borrow the model.
#[derive(Clone, Debug)]
struct ModelFacts {
    kernel: &'static str,
    /// β of uniform widths (`None` for per-centre widths).
    width: Option<f64>,
    /// The least and largest β of per-centre widths (`None` for a uniform width).
    width_range: Option<(f64, f64)>,
    condition: Option<f64>,
    n_centres: usize,
    dim: usize,
    bias: Option<f64>,
    /// PRESS and GCV along the OLS path (empty without them).
    criterion: Vec<CriterionOut>,
    /// The threads the OLS passes ran on and why (OLS only).
    pass_threads: Option<(usize, String)>,
}

/// The report of `rbf fit`.
///
/// ```
/// use rbf_cli::report::{FitContext, FitReport};
/// let model = rbf::doc_model();
/// let ctx = FitContext { train_rows: (0..40).collect(), train_lines: (2..42).collect(), ..FitContext::default() };
/// let r = FitReport::new(&model, ctx);
/// let v = serde_json::to_value(r.json()).unwrap();
/// for key in ["n_train", "n_val", "dim", "n_centers", "fit_seconds", "train_rmse", "val_rmse", "val_nmse"] {
///     assert!(v.get(key).is_some(), "{key}");
/// }
/// assert!(v["val_rmse"].is_null());
/// assert!(r.summary().contains("centres"));
/// ```
#[derive(Clone, Debug)]
pub struct FitReport {
    model_facts: ModelFacts,
    ctx: FitContext,
    ols: Option<OlsOut>,
}

/// What `rbf fit --json` prints, borrowed from a [`FitReport`]. Fields in the
/// alphabetical order of their keys, the order of the keys (see the [module](super) doc;
/// `centres` prints as the key `centers`, a contract); a key marked "absent"
/// is left out, not `null`, as scripts have always seen it.
///
/// ```
/// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
/// let v = serde_json::to_value(r.json()).unwrap();
/// assert_eq!(v["command"], "fit");
/// assert!(v.get("width_min").is_none() && v.get("width_search").is_none());
/// ```
#[derive(Clone, Debug, Serialize)]
pub struct FitJson<'a> {
    bias: Option<f64>,
    candidates: Option<usize>,
    #[serde(rename = "centers")]
    centres: &'static str,
    command: &'static str,
    condition: Option<f64>,
    /// Absent without PRESS and GCV along an OLS path.
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    criterion: &'a [CriterionOut],
    data: &'a str,
    dim: usize,
    fit_seconds: f64,
    inputs: &'a [String],
    kernel: &'static str,
    kmeans_algorithm: Option<&'static str>,
    #[serde(rename = "max_centers")]
    max_centres: Option<usize>,
    model: &'a str,
    #[serde(rename = "n_centers")]
    n_centres: usize,
    n_train: usize,
    n_val: usize,
    ols: Option<&'a OlsOut>,
    ols_candidates: Option<usize>,
    predict_seconds: f64,
    ridge: f64,
    seconds_per_pick: Option<f64>,
    seed: u64,
    selection_rows: Option<usize>,
    /// Seconds per stage, keyed and sorted by stage name; a stage that ran more than
    /// once (one fit per width of `--width auto`) keeps its last time.
    stage_seconds: BTreeMap<&'a str, f64>,
    standardize: bool,
    stop: Option<String>,
    target: &'a str,
    threads: usize,
    /// Why the OLS passes ran on `threads_used` threads (null for other centres).
    threads_reason: Option<&'a str>,
    /// The threads the OLS passes ran on: the library keeps the parallelism asked for
    /// only where it makes them faster (null for other centres).
    threads_used: Option<usize>,
    tol: Option<f64>,
    train_nmse: Option<f64>,
    train_rmse: Option<f64>,
    val_fit_percent: Option<f64>,
    val_nmse: Option<f64>,
    val_r2: Option<f64>,
    val_rmse: Option<f64>,
    width: Option<f64>,
    /// Absent for a uniform width.
    #[serde(skip_serializing_if = "Option::is_none")]
    width_max: Option<f64>,
    /// Absent for a uniform width.
    #[serde(skip_serializing_if = "Option::is_none")]
    width_min: Option<f64>,
    width_rule: &'static str,
    /// Absent unless `--width auto` searched.
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    width_search: &'a [WidthTrial],
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

impl FitReport {
    /// Collects the report of `model` fitted in context `ctx`.
    ///
    /// ```
    /// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
    /// assert_eq!(serde_json::to_value(r.json()).unwrap()["kernel"], "gaussian");
    /// ```
    pub fn new(model: &RbfModel, ctx: FitContext) -> Self {
        let (width, width_range) = width_facts(model.widths());
        let model_facts = ModelFacts {
            kernel: model.kernel().name(),
            width,
            width_range,
            condition: finite(model.condition()),
            n_centres: model.n_centres(),
            dim: model.dim(),
            bias: model.bias().map(|b| b[0]),
            criterion: model
                .selection()
                .map(|s| s.criterion.iter().map(CriterionOut::from).collect())
                .unwrap_or_default(),
            pass_threads: model.pass_threads().map(|t| (t.threads, t.to_string())),
        };
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
            model_facts,
            ctx,
            ols,
        }
    }

    /// The `--json` object.
    ///
    /// ```
    /// let r = rbf_cli::report::FitReport::new(&rbf::doc_model(), Default::default());
    /// assert_eq!(serde_json::to_value(r.json()).unwrap()["dim"], 1);
    /// ```
    pub fn json(&self) -> FitJson<'_> {
        let c = &self.ctx;
        let s = &c.settings;
        let f = &self.model_facts;
        let val = |score: fn(&Scores) -> f64| c.val.as_ref().and_then(|v| finite(score(v)));
        let (selection_rows, ols_candidates) = s.ols_rows(c.train_rows.len());
        FitJson {
            bias: f.bias,
            candidates: s.candidates,
            centres: s.centres.name(),
            command: "fit",
            condition: f.condition,
            criterion: &f.criterion,
            data: &c.data,
            dim: f.dim,
            fit_seconds: c.fit_seconds,
            inputs: &c.inputs,
            kernel: f.kernel,
            kmeans_algorithm: kmeans_algorithm(s),
            max_centres: s.n_centres_for(c.train_rows.len()),
            model: &c.out,
            n_centres: f.n_centres,
            n_train: c.train_rows.len(),
            n_val: c.n_val,
            ols: self.ols.as_ref(),
            ols_candidates,
            predict_seconds: c.predict_seconds,
            ridge: s.ridge,
            seconds_per_pick: c.times.seconds_per_pick,
            seed: s.seed,
            selection_rows,
            stage_seconds: c
                .times
                .stages
                .iter()
                .map(|(k, v)| (k.as_str(), *v))
                .collect(),
            standardize: s.standardize,
            stop: s.stop.map(|v| v.name()),
            target: &c.target,
            threads: c.threads,
            threads_reason: f.pass_threads.as_ref().map(|t| t.1.as_str()),
            threads_used: f.pass_threads.as_ref().map(|t| t.0),
            tol: s.tol,
            train_nmse: finite(c.train.nmse),
            train_rmse: finite(c.train.rmse),
            val_fit_percent: val(|v| v.fit_percent),
            val_nmse: val(|v| v.nmse),
            val_r2: val(|v| v.r2),
            val_rmse: val(|v| v.rmse),
            width: f.width,
            width_max: f.width_range.map(|(_, hi)| hi),
            width_min: f.width_range.map(|(lo, _)| lo),
            width_rule: width_rule_text(s.width),
            width_search: &c.width_search,
        }
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
        let width = match (f.width, f.width_range) {
            (Some(b), _) => format!("β = {b:.6}"),
            (None, range) => {
                let (lo, hi) = range.unwrap_or((f64::NAN, f64::NAN));
                format!("β per centre in [{lo:.4}, {hi:.4}]")
            }
        };
        let _ = writeln!(
            out,
            "  {} centres ({}{}), {} kernel, width {} ({}), ridge {}{}",
            f.n_centres,
            s.centres,
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
            f.condition.unwrap_or(f64::NAN)
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
