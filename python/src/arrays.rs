//! numpy ⇄ faer. Inputs are copied into column-major faer matrices, as the `rbf`
//! command builds them from a CSV, so that the library sees the same layout and
//! gives the same bits; outputs are new numpy arrays. A copy is n·d reads, small
//! against any fit or prediction (n·K·d).

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use rbf::faer::{Mat, MatRef};

/// A 2-D float64 array as a faer matrix.
pub fn to_mat(a: &PyReadonlyArray2<'_, f64>) -> Mat<f64> {
    let v = a.as_array();
    Mat::from_fn(v.nrows(), v.ncols(), |i, j| v[[i, j]])
}

/// A faer matrix as a new (C-ordered) numpy array.
pub fn to_numpy<'py>(py: Python<'py>, m: MatRef<'_, f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)]).into_pyarray(py)
}

/// A slice as a new 1-D numpy array.
pub fn to_numpy_1d<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}
