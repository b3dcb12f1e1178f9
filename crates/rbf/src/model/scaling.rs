//! Per-input standardisation, computed by the fit and stored in the model.

use faer::{Mat, MatRef};
use serde::{Deserialize, Serialize};

/// Per-input standardisation x ↦ (x − mean)/scale (population standard deviation;
/// constant inputs keep scale 1).
///
/// ```
/// let s = rbf::Scaling::from_data(faer::mat![[1.0], [3.0]].as_ref());
/// assert_eq!((s.mean[0], s.scale[0]), (2.0, 1.0));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scaling {
    /// Mean of each input.
    pub mean: Vec<f64>,
    /// Standard deviation of each input (1 where it is 0).
    pub scale: Vec<f64>,
}

impl Scaling {
    /// Mean and population standard deviation of every column of `x`.
    ///
    /// ```
    /// let s = rbf::Scaling::from_data(faer::mat![[5.0, 0.0], [5.0, 2.0]].as_ref());
    /// assert_eq!(s.scale, vec![1.0, 1.0]);
    /// ```
    pub fn from_data(x: MatRef<'_, f64>) -> Self {
        let (n, d) = (x.nrows(), x.ncols());
        let mut mean = vec![0.0; d];
        let mut scale = vec![1.0; d];
        for k in 0..d {
            let m = (0..n).map(|i| x[(i, k)]).sum::<f64>() / n as f64;
            let v = (0..n).map(|i| (x[(i, k)] - m).powi(2)).sum::<f64>() / n as f64;
            mean[k] = m;
            if v.sqrt() > 0.0 {
                scale[k] = v.sqrt();
            }
        }
        Self { mean, scale }
    }

    /// The standardised copy of `x`.
    ///
    /// # Panics
    /// If `x` does not have one column per input.
    ///
    /// ```
    /// let s = rbf::Scaling { mean: vec![1.0], scale: vec![2.0] };
    /// assert_eq!(s.apply(faer::mat![[5.0]].as_ref())[(0, 0)], 2.0);
    /// ```
    #[track_caller]
    pub fn apply(&self, x: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(x.ncols(), self.mean.len(), "wrong number of inputs");
        Mat::from_fn(x.nrows(), x.ncols(), |i, k| {
            (x[(i, k)] - self.mean[k]) / self.scale[k]
        })
    }
}
