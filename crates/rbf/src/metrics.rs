//! Goodness-of-fit measures, as the system-identification field reports them.
//!
//! All take the measured `y` first and the prediction `yhat` second, and panic on
//! length mismatch (a programmer error). Multi-output versions average over outputs.

use faer::MatRef;
use serde::{Deserialize, Serialize};

#[track_caller]
fn same_len(y: &[f64], yhat: &[f64]) {
    assert_eq!(
        y.len(),
        yhat.len(),
        "y has {} values, yhat {}",
        y.len(),
        yhat.len()
    );
}

fn sse(y: &[f64], yhat: &[f64]) -> f64 {
    y.iter().zip(yhat).map(|(a, b)| (a - b).powi(2)).sum()
}

fn sst(y: &[f64]) -> f64 {
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    y.iter().map(|a| (a - mean).powi(2)).sum()
}

/// Mean squared error.
///
/// ```
/// assert_eq!(rbf::metrics::mse(&[1.0, 2.0], &[1.0, 4.0]), 2.0);
/// ```
#[track_caller]
pub fn mse(y: &[f64], yhat: &[f64]) -> f64 {
    same_len(y, yhat);
    sse(y, yhat) / y.len() as f64
}

/// Root mean squared error.
///
/// ```
/// assert_eq!(rbf::metrics::rmse(&[0.0, 0.0], &[3.0, 3.0]), 3.0);
/// ```
#[track_caller]
pub fn rmse(y: &[f64], yhat: &[f64]) -> f64 {
    mse(y, yhat).sqrt()
}

/// Normalised MSE: MSE / var(y) (population variance of the measured values);
/// 1 is the score of predicting the mean.
///
/// ```
/// assert_eq!(rbf::metrics::nmse(&[1.0, 3.0], &[2.0, 2.0]), 1.0);
/// ```
#[track_caller]
pub fn nmse(y: &[f64], yhat: &[f64]) -> f64 {
    same_len(y, yhat);
    sse(y, yhat) / sst(y)
}

/// MATLAB's `compare` fit: 100·(1 − ‖y − ŷ‖/‖y − ȳ‖) per cent.
///
/// ```
/// assert_eq!(rbf::metrics::fit_percent(&[1.0, 3.0], &[1.0, 3.0]), 100.0);
/// assert_eq!(rbf::metrics::fit_percent(&[1.0, 3.0], &[2.0, 2.0]), 0.0);
/// ```
#[track_caller]
pub fn fit_percent(y: &[f64], yhat: &[f64]) -> f64 {
    same_len(y, yhat);
    100.0 * (1.0 - (sse(y, yhat) / sst(y)).sqrt())
}

/// Coefficient of determination 1 − SSE/SST.
///
/// ```
/// assert_eq!(rbf::metrics::r2(&[1.0, 3.0], &[1.5, 2.5]), 0.75);
/// ```
#[track_caller]
pub fn r2(y: &[f64], yhat: &[f64]) -> f64 {
    same_len(y, yhat);
    1.0 - sse(y, yhat) / sst(y)
}

/// The four scores together (averaged over outputs by [`Scores::of`]).
///
/// ```
/// let s = rbf::metrics::Scores::of_slices(&[1.0, 3.0], &[1.5, 2.5]);
/// assert_eq!((s.rmse, s.nmse, s.fit_percent, s.r2), (0.5, 0.25, 50.0, 0.75));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Scores {
    /// Root mean squared error.
    pub rmse: f64,
    /// MSE / var(y).
    pub nmse: f64,
    /// 100·(1 − ‖y − ŷ‖/‖y − ȳ‖).
    pub fit_percent: f64,
    /// 1 − SSE/SST.
    pub r2: f64,
}

impl Scores {
    /// Scores of one output.
    ///
    /// ```
    /// assert_eq!(rbf::metrics::Scores::of_slices(&[0.0, 2.0], &[0.0, 2.0]).rmse, 0.0);
    /// ```
    #[track_caller]
    pub fn of_slices(y: &[f64], yhat: &[f64]) -> Self {
        Self {
            rmse: rmse(y, yhat),
            nmse: nmse(y, yhat),
            fit_percent: fit_percent(y, yhat),
            r2: r2(y, yhat),
        }
    }

    /// Scores of every column of `y` against `yhat`, averaged over the columns.
    ///
    /// # Panics
    /// If the shapes differ.
    ///
    /// ```
    /// let y = faer::mat![[1.0, 0.0], [3.0, 2.0]];
    /// let s = rbf::metrics::Scores::of(y.as_ref(), y.as_ref());
    /// assert_eq!(s.fit_percent, 100.0);
    /// ```
    #[track_caller]
    pub fn of(y: MatRef<'_, f64>, yhat: MatRef<'_, f64>) -> Self {
        assert_eq!(
            (y.nrows(), y.ncols()),
            (yhat.nrows(), yhat.ncols()),
            "shapes differ"
        );
        let q = y.ncols();
        let mut acc = Scores::default();
        for o in 0..q {
            let a: Vec<f64> = (0..y.nrows()).map(|i| y[(i, o)]).collect();
            let b: Vec<f64> = (0..y.nrows()).map(|i| yhat[(i, o)]).collect();
            let s = Self::of_slices(&a, &b);
            acc.rmse += s.rmse / q as f64;
            acc.nmse += s.nmse / q as f64;
            acc.fit_percent += s.fit_percent / q as f64;
            acc.r2 += s.r2 / q as f64;
        }
        acc
    }
}
