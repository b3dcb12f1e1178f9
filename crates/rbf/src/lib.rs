//! Radial-basis-function networks for system identification.
//!
//! The network of the seed paper's eqs. 7–8, f(x) = λ0 + Σᵢ λᵢ φ(‖x − cᵢ‖) with the
//! Gaussian φ(v) = exp(−v²/β²), plus six other kernels, an optional polynomial tail (of
//! degree ≤ 2 on unit-box inputs, [`PolyTail`]) and exogenous linear regressors (a
//! semi-parametric model). It knows nothing of gyros, sensors or files: matrices in,
//! models and typed errors out.
//!
//! | concern | module | main items |
//! |---|---|---|
//! | basis functions | [`kernel`], [`design`] | [`Kernel`], [`kernel_matrix`], [`Widths`] |
//! | widths | [`width`], [`neighbours`] | [`WidthRule`] |
//! | structure selection | [`select`] | [`forward_select`] (OLS/ERR, generic over columns), k-means, random |
//! | estimation | [`estimate`] | [`lstsq`] (pivoted QR, ridge, rank and condition checks), [`interpolate`] |
//! | the model | [`model`] | [`RbfParams`] → [`RbfValidParams`] → [`RbfModel`]; linfa `Fit`/`Predict`; JSON |
//! | validation | [`split`], [`cv`], [`metrics`] | [`Split`], [`Holdout`], [`cross_validate`], [`grid_search`], [`metrics::Scores`] |
//!
//! Matrices are faer's (rows are samples); ndarray appears only at the linfa boundary
//! ([`convert`]). Hot kernels take their parallelism as a [`faer::Par`] value. Bad data
//! and numerical failure are typed errors; mismatched dimensions are programmer errors
//! and panic.
//!
//! ```
//! use faer::{Mat, Par};
//! use rbf::{CentreSelection, Kernel, ParamGuard, RbfParams, WidthRule};
//!
//! // y = sin(x₀)·cos(x₁) on a 15 × 15 grid, 60 OLS-selected Gaussian centres
//! let n = 225;
//! let x = Mat::from_fn(n, 2, |i, j| if j == 0 { (i % 15) as f64 / 4.0 } else { (i / 15) as f64 / 4.0 });
//! let y = Mat::from_fn(n, 1, |i, _| x[(i, 0)].sin() * x[(i, 1)].cos());
//! let model = RbfParams::new()
//!     .kernel(Kernel::Gaussian)
//!     .centres(CentreSelection::ols(60))
//!     .width(WidthRule::Fixed(1.0))
//!     .parallelism(Par::Seq)
//!     .check()?
//!     .fit(x.as_ref(), y.as_ref())?;
//! let yhat = model.predict(x.as_ref());
//! assert!((&yhat - &y).norm_max() < 5e-3); // measured 1.5e-3
//! let picks = &model.selection().unwrap().picks;
//! assert!(picks.windows(2).all(|w| w[0].cumulative_err < w[1].cumulative_err));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod check;
pub mod convert;
pub mod cv;
pub mod design;
pub mod estimate;
pub mod kernel;
pub mod memory;
pub mod metrics;
pub mod model;
pub mod neighbours;
mod parallel;
pub mod select;
pub mod split;
mod widest;
pub mod width;

pub use faer;
pub use faer::Par;
#[doc(no_inline)]
pub use linfa::ParamGuard;
/// linfa's traits that rbf's types implement, re-exported so that dependants need not
/// name linfa: [`ParamGuard`] checks an [`RbfParams`], [`Fit`] and [`Predict`] work on
/// linfa datasets and ndarray arrays.
pub use linfa::traits::{Fit, Predict};
/// `rbf::ols` (the path docs/architecture.md uses) is `rbf::select::ols`.
pub use select::ols;

pub use cv::{
    CvReport, Fold, FoldReport, Grid, GridPoint, GridReport, Holdout, Sizes, Split, SplitError,
    cross_validate, cross_validate_folds, cross_validate_with_linear, grid_search,
    grid_search_each_with_linear, grid_search_with_linear, holdout,
};
pub use design::{KernelColumns, Widths, kernel_matrix, kernel_matrix_into};
pub use estimate::{
    DEFAULT_MAX_CONDITION, Interpolation, InterpolationOptions, LstsqOptions, Solution, SolveError,
    interpolate, lstsq,
};
pub use kernel::{Kernel, UnknownKernel};
pub use model::{
    Candidates, CentreSelection, FORMAT_VERSION, MAX_COEFFICIENT, PersistError, PolyTail, Progress,
    RbfError, RbfModel, RbfParams, RbfParamsError, RbfValidParams, Scaling, Selection, Stage,
    Strategy, UnknownPolyTail,
};
pub use select::kmeans::{
    KMeansAlgorithm, KMeansError, KMeansInit, KMeansSettings, UnknownKMeansAlgorithm,
    UnknownKMeansInit,
};
pub use select::ols::{
    CandidateColumns, OlsError, OlsOptions, OlsPath, OlsProgress, PassThreads, PassThreadsReason,
    Pick, StopReason, StreamPrecision, UnknownStreamPrecision, forward_select,
    forward_select_columns, forward_select_owned,
};
pub use width::{WidthError, WidthRule};

/// `docs/rbf.md`, compiled as documentation so that its examples run as doctests
/// (the examples are the file's own code blocks).
#[cfg(doctest)]
#[doc = include_str!("../../../docs/rbf.md")]
pub struct RbfGuideDoctests;

/// A small fitted model for the documentation examples: an OLS Gaussian network (≤ 8
/// centres, β = 1) of sin on [0, 3].
///
/// ```
/// assert!(rbf::doc_model().n_centres() <= 8);
/// ```
#[doc(hidden)]
pub fn doc_model() -> RbfModel {
    use linfa::ParamGuard;
    let x = faer::Mat::from_fn(40, 1, |i, _| i as f64 * 3.0 / 39.0);
    let y = faer::Mat::from_fn(40, 1, |i, _| x[(i, 0)].sin());
    RbfParams::new()
        .centres(CentreSelection::ols(8))
        .width(WidthRule::Fixed(1.0))
        .parallelism(Par::Seq)
        .check()
        .expect("valid doc params")
        .fit(x.as_ref(), y.as_ref())
        .expect("doc model fits")
}
