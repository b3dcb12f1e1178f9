//! Errors of the RBF model: invalid hyperparameters, bad data, numerical failure.

use crate::estimate::SolveError;
use crate::select::kmeans::KMeansError;
use crate::select::ols::OlsError;
use crate::split::SplitError;
use crate::width::WidthError;

/// An invalid hyperparameter, one variant per validation rule.
///
/// ```
/// use linfa::ParamGuard;
/// let e = rbf::RbfParams::new().ridge(-1.0).check().unwrap_err();
/// assert_eq!(e, rbf::RbfParamsError::Ridge { value: -1.0 });
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RbfParamsError {
    /// A fixed width must be finite and positive.
    #[error("fixed width β must be finite and > 0, got {value}")]
    Width {
        /// Value given.
        value: f64,
    },
    /// A width-rule scale must be finite and positive.
    #[error("width scale must be finite and > 0, got {value}")]
    WidthScale {
        /// Value given.
        value: f64,
    },
    /// The cluster-spread rule needs k-means centres.
    #[error("the cluster-spread width rule needs k-means centre selection")]
    ClusterSpreadNeedsKMeans,
    /// The ridge must be finite and non-negative.
    #[error("ridge λ must be finite and ≥ 0, got {value}")]
    Ridge {
        /// Value given.
        value: f64,
    },
    /// The condition limit must be ≥ 1 (∞ disables the check).
    #[error("max_condition must be ≥ 1, got {value}")]
    MaxCondition {
        /// Value given.
        value: f64,
    },
    /// OLS must be allowed at least one centre.
    #[error("OLS max_centres must be ≥ 1")]
    OlsMaxCentres,
    /// ρ must lie in [0, 1).
    #[error("OLS tolerance ρ must lie in [0, 1), got {value}")]
    OlsTolerance {
        /// Value given.
        value: f64,
    },
    /// The OLS regularisation must be finite and non-negative.
    #[error("OLS regularisation must be finite and ≥ 0, got {value}")]
    OlsRegularisation {
        /// Value given.
        value: f64,
    },
    /// A candidate subsample needs at least one candidate.
    #[error("the candidate subsample size must be ≥ 1")]
    SubsampleSize,
    /// Given candidates must not be empty.
    #[error("the given candidate matrix has no rows")]
    EmptyCandidates,
    /// Given candidates must be finite.
    #[error("non-finite given candidate at row {row}, column {col}")]
    NonFiniteCandidates {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// k-means needs at least one centre.
    #[error("k-means n_centres must be ≥ 1")]
    KMeansCentres,
    /// k-means needs at least one run.
    #[error("k-means n_runs must be ≥ 1")]
    KMeansRuns,
    /// k-means needs at least one iteration.
    #[error("k-means max_iterations must be ≥ 1")]
    KMeansIterations,
    /// The k-means tolerance must be finite and positive.
    #[error("k-means tolerance must be finite and > 0, got {value}")]
    KMeansTolerance {
        /// Value given.
        value: f64,
    },
    /// Random selection needs at least one centre.
    #[error("random n_centres must be ≥ 1")]
    RandomCentres,
    /// Given centres must not be empty.
    #[error("the given centre matrix has no rows")]
    EmptyCentres,
    /// Given centres must be finite.
    #[error("non-finite given centre at row {row}, column {col}")]
    NonFiniteCentres {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// All-points interpolation with a polynomial tail below the kernel's minimum degree
    /// has no unique solution.
    #[error(
        "the {kernel} kernel needs a polynomial of degree ≥ {minimum} to interpolate, got {degree}"
    )]
    DegreeTooLow {
        /// The kernel.
        kernel: crate::kernel::Kernel,
        /// Degree given.
        degree: i32,
        /// The kernel's minimum degree.
        minimum: i32,
    },
}

/// Why a fit (or cross-validation) failed.
///
/// ```
/// use faer::mat;
/// let p = linfa::ParamGuard::check(rbf::RbfParams::new()).unwrap();
/// let x = mat![[f64::NAN], [1.0]];
/// let y = mat![[0.0], [1.0]];
/// let e = p.fit(x.as_ref(), y.as_ref()).unwrap_err();
/// assert!(matches!(e, rbf::RbfError::NonFinite { matrix: "x", row: 0, col: 0 }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum RbfError {
    /// Invalid hyperparameters.
    #[error("invalid hyperparameters: {0}")]
    InvalidParams(#[from] RbfParamsError),
    /// A matrix the fit needs would not fit in memory.
    #[error(transparent)]
    Memory(#[from] crate::memory::MemoryError),
    /// The fit produced a number no model may hold (non-finite, or beyond
    /// [`crate::MAX_COEFFICIENT`]): the data's scale overflowed the solve.
    #[error("the fit produced an unusable model ({0}); rescale the inputs or the target")]
    UnusableModel(String),
    /// [`crate::RbfValidParams::fit_given_streaming`] was asked for a fit it
    /// cannot do over row blocks.
    #[error("a fit over row blocks needs {needs}")]
    NotStreamable {
        /// What the settings lack.
        needs: &'static str,
    },
    /// A NaN or infinite input.
    #[error("non-finite value in {matrix} at row {row}, column {col}")]
    NonFinite {
        /// `x`, `z` or `y`.
        matrix: &'static str,
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// Too few samples for the model's fixed columns.
    #[error("too few samples: {samples}, need at least {needed}")]
    TooFewSamples {
        /// Samples given.
        samples: usize,
        /// Samples needed.
        needed: usize,
    },
    /// Too few training rows for the requested centres: a row per centre and, without
    /// a ridge, one per unknown of the weights' least squares
    /// ([`RbfValidParams::most_centres`](crate::RbfValidParams::most_centres)).
    #[error("{rows} rows take at most {most} centres, not {centres}")]
    FewerRowsThanCentres {
        /// Training rows.
        rows: usize,
        /// Centres requested.
        centres: usize,
        /// The most centres these rows take.
        most: usize,
    },
    /// Given centres or candidates with the wrong number of columns.
    #[error("{what} have {found} columns but the inputs have {expected}")]
    Dimension {
        /// What was given.
        what: &'static str,
        /// Input dimension.
        expected: usize,
        /// Columns found.
        found: usize,
    },
    /// Width computation failed.
    #[error(transparent)]
    Width(#[from] WidthError),
    /// Forward selection failed.
    #[error(transparent)]
    Ols(#[from] OlsError),
    /// A linear solve failed (rank deficiency, ill-conditioning, ...).
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// k-means failed.
    #[error("k-means: {0}")]
    KMeans(#[from] KMeansError),
    /// A cross-validation split could not be made.
    #[error(transparent)]
    Split(#[from] SplitError),
    /// A grid that does not fit the strategy.
    #[error("grid search: {reason}")]
    GridMismatch {
        /// What does not fit.
        reason: &'static str,
    },
    /// A fit shared by several grid points failed (the message of the original error).
    #[error("fold fit failed: {reason}")]
    FoldFailed {
        /// The original error's message.
        reason: String,
    },
    /// An error raised by linfa itself (its message: no linfa type appears in rbf's
    /// errors).
    #[error("linfa: {0}")]
    Linfa(String),
}

impl From<linfa::error::Error> for RbfError {
    /// linfa's `Fit` needs this conversion; the error is kept as its message.
    ///
    /// ```
    /// let e = rbf::RbfError::from(linfa::error::Error::NotConverged("x".into()));
    /// assert!(matches!(e, rbf::RbfError::Linfa(_)));
    /// ```
    fn from(e: linfa::error::Error) -> Self {
        RbfError::Linfa(e.to_string())
    }
}
