//! What `rbf fit`, `rbf cv` and `rbf predict` print: one JSON object with `--json`, a
//! short human summary otherwise.
//!
//! Key names of the fit object are a contract (scripts read them): `n_train`, `n_val`,
//! `dim`, `n_centers`, `fit_seconds` (the library fit alone, timed in-process),
//! `train_rmse`, `val_rmse`, `val_nmse` (validation MSE over the variance of the
//! validation targets). Undefined scores (no validation rows) are `null`.
//!
//! Each `--json` object is a `#[derive(Serialize)]` struct that borrows from the report
//! ([`FitJson`], [`CvJson`], [`PredictJson`]), so its keys are spelled once, as fields,
//! and a key that is sometimes left out says so with `skip_serializing_if`.
//!
//! Keys are printed in alphabetical order at every level, the order a
//! `serde_json::Value` object (a sorted map) prints them in, which is what saved outputs
//! hold. serde writes a struct's keys in field order, so the fields of these structs,
//! and of every struct nested in them, are declared alphabetically; where a library
//! type's fields are not (`rbf::FoldReport`, `rbf::ols::Criterion`) a small copy here
//! reorders them. The tests below check every object.
//!
//! | module | what |
//! |---|---|
//! | [`fit`] | `rbf fit`: the context of a fit, its OLS record, [`FitJson`] |
//! | [`cv`] | `rbf cv`: the grid of points and their folds, [`CvJson`] |
//! | [`predict`] | `rbf predict`: [`PredictJson`] |

pub mod cv;
pub mod fit;
pub mod predict;

pub use cv::{CvContext, CvJson, CvOut, FoldJson, PointJson, ScoresJson, WidthJson, width_label};
pub use fit::{
    CriterionOut, FitContext, FitJson, FitReport, OlsOut, PickOut, WidthTrial, width_rule_text,
};
pub use predict::PredictJson;

use crate::settings::{Centres, FitSettings};

/// The k-means algorithm that ran (`--kmeans-algorithm`, or the library's default),
/// for k-means fits only.
///
/// ```
/// use rbf_cli::settings::{Centres, FitSettings};
/// let s = FitSettings { centres: Centres::Kmeans, ..FitSettings::default() };
/// assert_eq!(rbf_cli::report::kmeans_algorithm(&s), Some("lloyd"));
/// assert_eq!(rbf_cli::report::kmeans_algorithm(&FitSettings::default()), None);
/// ```
pub fn kmeans_algorithm(s: &FitSettings) -> Option<&'static str> {
    (s.centres == Centres::Kmeans).then(|| s.kmeans_algorithm.unwrap_or_default().name())
}

/// A score as JSON: `None` (printed `null`) when it is undefined (NaN) or infinite.
///
/// ```
/// assert_eq!(rbf_cli::report::finite(f64::NAN), None);
/// assert_eq!(rbf_cli::report::finite(0.5), Some(0.5));
/// ```
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
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

    fn fold(rmse: f64) -> rbf::FoldReport {
        let s = rbf::metrics::Scores {
            rmse,
            nmse: 0.5,
            fit_percent: 30.0,
            r2: f64::NAN,
        };
        rbf::FoldReport {
            train_size: 8,
            validation_size: 2,
            n_centres: 3,
            train: s,
            validation: s,
        }
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

    #[test]
    fn cv_json_keys_are_sorted() {
        let point = |width, result| rbf::GridPoint {
            width,
            n_centres: Some(3),
            tol: None,
            ridge: 0.0,
            result,
        };
        let grid = rbf::GridReport {
            points: vec![
                point(
                    rbf::WidthRule::Fixed(0.5),
                    Ok(rbf::CvReport::from_folds(vec![fold(1.0), fold(2.0)])),
                ),
                point(
                    rbf::WidthRule::default(),
                    Err(rbf::RbfError::FoldFailed { reason: "x".into() }),
                ),
            ],
            best: Some(0),
        };
        let out = CvOut::new(&grid, CvContext::default());
        assert_keys_sorted(&out.json());
    }

    #[test]
    fn predict_json_keys_are_sorted() {
        let inputs = vec!["a".to_string()];
        let p = PredictJson {
            command: "predict",
            data: "d.csv",
            inputs: &inputs,
            model: "m.json",
            n_rows: 3,
            nmse: Some(0.5),
            out: "p.csv",
            predict_seconds: 0.1,
            rmse: None,
            target: "y",
        };
        assert_keys_sorted(&p);
    }
}
