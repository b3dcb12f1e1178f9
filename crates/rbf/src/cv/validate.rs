//! Cross-validation of one hyperparameter set.

use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};

use crate::metrics::Scores;
use crate::model::{RbfError, RbfModel, RbfValidParams};
use crate::split::{Fold, Split};

/// Scores of one fold.
///
/// ```
/// let f = rbf::FoldReport { train_size: 10, validation_size: 5, n_centres: 3,
///     train: Default::default(), validation: Default::default() };
/// assert_eq!(f.validation.rmse, 0.0);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FoldReport {
    /// Training rows.
    pub train_size: usize,
    /// Validation rows.
    pub validation_size: usize,
    /// Centres of the fold's model.
    pub n_centres: usize,
    /// Scores on the training rows.
    pub train: Scores,
    /// Scores on the validation rows.
    pub validation: Scores,
}

/// Per-fold validation scores with their mean and (sample, k − 1) standard deviation.
///
/// ```
/// let f = |r| rbf::FoldReport { train_size: 1, validation_size: 1, n_centres: 1, train: Default::default(),
///     validation: rbf::metrics::Scores { rmse: r, ..Default::default() } };
/// let rep = rbf::CvReport::from_folds(vec![f(1.0), f(3.0)]);
/// assert_eq!(rep.mean.rmse, 2.0);
/// assert!((rep.std.rmse - 2f64.sqrt()).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CvReport {
    /// Every fold.
    pub folds: Vec<FoldReport>,
    /// Mean of the validation scores.
    pub mean: Scores,
    /// Standard deviation of the validation scores (0 for one fold).
    pub std: Scores,
}

impl CvReport {
    /// Summarises fold reports.
    ///
    /// ```
    /// let r = rbf::CvReport::from_folds(vec![]);
    /// assert!(r.mean.rmse.is_nan());
    /// ```
    pub fn from_folds(folds: Vec<FoldReport>) -> Self {
        let k = folds.len() as f64;
        let get = |f: fn(&Scores) -> f64| -> (f64, f64) {
            let v: Vec<f64> = folds.iter().map(|r| f(&r.validation)).collect();
            let mean = v.iter().sum::<f64>() / k;
            let var = if v.len() > 1 {
                v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (k - 1.0)
            } else {
                0.0
            };
            (mean, var.sqrt())
        };
        let (rm, rs) = get(|s| s.rmse);
        let (nm, ns) = get(|s| s.nmse);
        let (fm, fs) = get(|s| s.fit_percent);
        let (qm, qs) = get(|s| s.r2);
        CvReport {
            folds,
            mean: Scores {
                rmse: rm,
                nmse: nm,
                fit_percent: fm,
                r2: qm,
            },
            std: Scores {
                rmse: rs,
                nmse: ns,
                fit_percent: fs,
                r2: qs,
            },
        }
    }
}

pub(crate) fn take_rows(m: MatRef<'_, f64>, idx: &[usize]) -> Mat<f64> {
    Mat::from_fn(idx.len(), m.ncols(), |i, k| m[(idx[i], k)])
}

/// The rows of x, z, y of one side of a fold.
pub(crate) struct Part {
    pub(crate) x: Mat<f64>,
    pub(crate) z: Mat<f64>,
    pub(crate) y: Mat<f64>,
}

impl Part {
    pub(crate) fn new(
        x: MatRef<'_, f64>,
        z: MatRef<'_, f64>,
        y: MatRef<'_, f64>,
        idx: &[usize],
    ) -> Self {
        Self {
            x: take_rows(x, idx),
            z: take_rows(z, idx),
            y: take_rows(y, idx),
        }
    }

    pub(crate) fn scores(&self, model: &RbfModel) -> Scores {
        let yhat = model.predict_with_linear(self.x.as_ref(), self.z.as_ref());
        Scores::of(self.y.as_ref(), yhat.as_ref())
    }
}

pub(crate) fn fold_report(model: &RbfModel, train: &Part, val: &Part) -> FoldReport {
    FoldReport {
        train_size: train.x.nrows(),
        validation_size: val.x.nrows(),
        n_centres: model.n_centres(),
        train: train.scores(model),
        validation: val.scores(model),
    }
}

/// Cross-validates `params` on inputs `x` (n × d) and targets `y` (n × q).
///
/// # Errors
/// A split that cannot be made, or the first fold whose fit fails.
///
/// # Panics
/// If `x` and `y` have different numbers of rows.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// use rbf::{cross_validate, CentreSelection, RbfParams, Split, WidthRule};
/// let x = Mat::from_fn(120, 1, |i, _| i as f64 / 20.0);
/// let y = Mat::from_fn(120, 1, |i, _| x[(i, 0)].sin());
/// let p = RbfParams::new().centres(CentreSelection::ols(10)).width(WidthRule::Fixed(1.0))
///     .parallelism(Par::Seq).check().unwrap();
/// let rep = cross_validate(&p, x.as_ref(), y.as_ref(), &Split::Interleaved { k: 2 }).unwrap();
/// assert_eq!(rep.folds.len(), 2);
/// assert!(rep.mean.nmse < 1e-4);
/// ```
#[track_caller]
pub fn cross_validate(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    split: &Split,
) -> Result<CvReport, RbfError> {
    let z = Mat::<f64>::zeros(x.nrows(), 0);
    cross_validate_with_linear(params, x, z.as_ref(), y, split)
}

/// [`cross_validate`] for the semi-parametric model with linear regressors `z` (n × r).
///
/// # Errors
/// As [`cross_validate`].
///
/// # Panics
/// If the row counts differ.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// let x = Mat::from_fn(80, 1, |i, _| (i as f64 * 0.1).sin());
/// let z = Mat::from_fn(80, 1, |i, _| (i % 5) as f64);
/// let y = Mat::from_fn(80, 1, |i, _| x[(i, 0)].powi(2) + 0.5 * z[(i, 0)]);
/// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(8)).width(rbf::WidthRule::Fixed(0.5))
///     .parallelism(Par::Seq).check().unwrap();
/// let rep = rbf::cross_validate_with_linear(&p, x.as_ref(), z.as_ref(), y.as_ref(), &rbf::Split::Blocked { k: 4, gap: 2 }).unwrap();
/// assert!(rep.mean.fit_percent > 90.0);
/// ```
#[track_caller]
pub fn cross_validate_with_linear(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    split: &Split,
) -> Result<CvReport, RbfError> {
    let folds = split.folds(x.nrows())?;
    cross_validate_folds(params, x, z, y, &folds)
}

/// Cross-validation on explicit folds (e.g. a train/validation column of a file).
///
/// # Errors
/// The first fold whose fit fails.
///
/// # Panics
/// If the row counts differ or a fold index is out of range.
///
/// ```
/// use faer::{Mat, Par};
/// use linfa::ParamGuard;
/// let x = Mat::from_fn(60, 1, |i, _| i as f64 / 10.0);
/// let y = Mat::from_fn(60, 1, |i, _| x[(i, 0)].cos());
/// let p = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(8)).width(rbf::WidthRule::Fixed(1.0))
///     .parallelism(Par::Seq).check().unwrap();
/// let fold = rbf::holdout(60, 0.7, 0).unwrap();
/// let rep = rbf::cross_validate_folds(&p, x.as_ref(), Mat::<f64>::zeros(60, 0).as_ref(), y.as_ref(), &[fold]).unwrap();
/// assert_eq!(rep.folds[0].validation_size, 18);
/// ```
#[track_caller]
pub fn cross_validate_folds(
    params: &RbfValidParams,
    x: MatRef<'_, f64>,
    z: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    folds: &[Fold],
) -> Result<CvReport, RbfError> {
    assert_eq!(x.nrows(), y.nrows(), "x and y row counts differ");
    assert_eq!(x.nrows(), z.nrows(), "x and z row counts differ");
    let mut reports = Vec::with_capacity(folds.len());
    for fold in folds {
        let train = Part::new(x, z, y, &fold.train);
        let val = Part::new(x, z, y, &fold.validation);
        let model = params.fit_with_linear(train.x.as_ref(), train.z.as_ref(), train.y.as_ref())?;
        reports.push(fold_report(&model, &train, &val));
    }
    Ok(CvReport::from_folds(reports))
}
