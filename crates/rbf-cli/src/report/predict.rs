//! The `--json` object of `rbf predict`.

use serde::Serialize;

/// What `rbf predict --json` prints. Fields in alphabetical order, the order of the
/// keys (see the [module](super) doc).
///
/// ```
/// let inputs = vec!["a".to_string()];
/// let p = rbf_cli::report::PredictJson {
///     command: "predict", data: "d.csv", inputs: &inputs, model: "m.json", n_rows: 2,
///     nmse: None, out: "p.csv", predict_seconds: 0.0, rmse: None, target: "y",
/// };
/// assert!(serde_json::to_string(&p).unwrap().starts_with(r#"{"command":"predict","data":"d.csv""#));
/// ```
#[derive(Clone, Debug, Serialize)]
pub struct PredictJson<'a> {
    /// Always `predict`.
    pub command: &'static str,
    /// The data file.
    pub data: &'a str,
    /// The model's input columns.
    pub inputs: &'a [String],
    /// The model file.
    pub model: &'a str,
    /// Rows predicted.
    pub n_rows: usize,
    /// NMSE against the target column; `null` without it, without rows, or undefined.
    pub nmse: Option<f64>,
    /// The predictions file.
    pub out: &'a str,
    /// Seconds of the prediction alone.
    pub predict_seconds: f64,
    /// RMSE against the target column, `null` as `nmse`.
    pub rmse: Option<f64>,
    /// The model's target column.
    pub target: &'a str,
}
