//! linfa's `Fit` and `PredictInplace` (ndarray at this boundary only, zero-copy views).

use linfa::dataset::DatasetBase;
use linfa::traits::{Fit, PredictInplace};
use ndarray::{Array1, Array2, ArrayBase, Data, Ix1, Ix2};

use super::error::RbfError;
use super::fitted::RbfModel;
use super::hyperparams::RbfValidParams;
use crate::convert::{mat_from_array, mat_from_array1};

/// Single-output datasets.
///
/// ```
/// use linfa::prelude::*;
/// use ndarray::{Array1, Array2};
/// let x = Array2::from_shape_fn((40, 1), |(i, _)| i as f64 / 8.0);
/// let y = x.column(0).mapv(f64::sin);
/// let ds = Dataset::new(x.clone(), y);
/// let model = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(8))
///     .width(rbf::WidthRule::Fixed(1.0)).parallelism(faer::Par::Seq).fit(&ds).unwrap();
/// // the inherent `predict` takes faer views, so name the linfa trait explicitly
/// let yhat: Array1<f64> = linfa::traits::Predict::predict(&model, &x);
/// assert!((yhat[10] - (10.0f64 / 8.0).sin()).abs() < 1e-3);
/// ```
impl<D: Data<Elem = f64>, S: Data<Elem = f64>> Fit<ArrayBase<D, Ix2>, ArrayBase<S, Ix1>, RbfError>
    for RbfValidParams
{
    type Object = RbfModel;

    fn fit(
        &self,
        dataset: &DatasetBase<ArrayBase<D, Ix2>, ArrayBase<S, Ix1>>,
    ) -> Result<RbfModel, RbfError> {
        RbfValidParams::fit(
            self,
            mat_from_array(dataset.records()),
            mat_from_array1(dataset.targets()),
        )
    }
}

/// Multi-output datasets.
///
/// ```
/// use linfa::prelude::*;
/// use ndarray::Array2;
/// let x = Array2::from_shape_fn((40, 1), |(i, _)| i as f64 / 8.0);
/// let y = Array2::from_shape_fn((40, 2), |(i, k)| (x[[i, 0]] * (k + 1) as f64).cos());
/// let ds = DatasetBase::new(x.clone(), y);
/// let model = rbf::RbfParams::new().centres(rbf::CentreSelection::ols(10))
///     .width(rbf::WidthRule::Fixed(1.0)).parallelism(faer::Par::Seq).fit(&ds).unwrap();
/// let yhat: Array2<f64> = linfa::traits::Predict::predict(&model, &x);
/// assert_eq!(yhat.dim(), (40, 2));
/// ```
impl<D: Data<Elem = f64>, S: Data<Elem = f64>> Fit<ArrayBase<D, Ix2>, ArrayBase<S, Ix2>, RbfError>
    for RbfValidParams
{
    type Object = RbfModel;

    fn fit(
        &self,
        dataset: &DatasetBase<ArrayBase<D, Ix2>, ArrayBase<S, Ix2>>,
    ) -> Result<RbfModel, RbfError> {
        RbfValidParams::fit(
            self,
            mat_from_array(dataset.records()),
            mat_from_array(dataset.targets()),
        )
    }
}

impl<D: Data<Elem = f64>> PredictInplace<ArrayBase<D, Ix2>, Array1<f64>> for RbfModel {
    /// # Panics
    /// If the model has several outputs or linear regressors, or `x` has the wrong width.
    #[track_caller]
    fn predict_inplace(&self, x: &ArrayBase<D, Ix2>, y: &mut Array1<f64>) {
        assert_eq!(
            self.n_outputs(),
            1,
            "a {}-output model predicts into a 2-D array",
            self.n_outputs()
        );
        assert_eq!(y.len(), x.nrows(), "one target per sample");
        let p = RbfModel::predict(self, mat_from_array(x));
        for (i, v) in y.iter_mut().enumerate() {
            *v = p[(i, 0)];
        }
    }

    fn default_target(&self, x: &ArrayBase<D, Ix2>) -> Array1<f64> {
        Array1::zeros(x.nrows())
    }
}

impl<D: Data<Elem = f64>> PredictInplace<ArrayBase<D, Ix2>, Array2<f64>> for RbfModel {
    /// # Panics
    /// If the model has linear regressors, or the shapes do not match.
    #[track_caller]
    fn predict_inplace(&self, x: &ArrayBase<D, Ix2>, y: &mut Array2<f64>) {
        assert_eq!(
            y.dim(),
            (x.nrows(), self.n_outputs()),
            "targets must be n × outputs"
        );
        let p = RbfModel::predict(self, mat_from_array(x));
        for ((i, k), v) in y.indexed_iter_mut() {
            *v = p[(i, k)];
        }
    }

    fn default_target(&self, x: &ArrayBase<D, Ix2>) -> Array2<f64> {
        Array2::zeros((x.nrows(), self.n_outputs()))
    }
}
