//! The RBF network f(x, z) = λ0 + p(x) + zᵀθ + Σᵢ λᵢ φ(‖x − cᵢ‖; βᵢ): the seed paper's
//! eq. 7 with an optional linear polynomial tail p(x) and exogenous linear regressors z.
//!
//! linfa style: [`RbfParams`] is a builder, checked once into [`RbfValidParams`]
//! (linfa's `ParamGuard`), whose `fit` returns a separate [`RbfModel`] with private
//! fields and getters.

mod algorithm;
mod capacity;
mod error;
mod fitted;
mod hyperparams;
mod linfa_impl;
mod matser;
mod persist;
mod poly;

pub use error::{RbfError, RbfParamsError};
pub use fitted::{MAX_COEFFICIENT, RbfModel, Scaling, Selection};
pub use hyperparams::{Candidates, CentreSelection, RbfParams, RbfValidParams, Strategy};
pub use persist::{FORMAT_VERSION, PersistError};
pub use poly::{PolyTail, UnknownPolyTail};

pub(crate) use algorithm::OlsStage;

/// A stage of a fit, for progress reporting.
///
/// ```
/// assert_ne!(rbf::Stage::Selection, rbf::Stage::Weights);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Computing widths.
    Widths,
    /// Computing the kernel (design) matrix.
    KernelMatrix,
    /// k-means clustering.
    Clustering,
    /// OLS forward selection; `done`/`total` count picks.
    Selection,
    /// Solving for the output weights.
    Weights,
}

/// Progress of a fit: a stage, and within it `done` of `total` units (0/1 for the
/// stages without inner steps).
///
/// ```
/// let p = rbf::Progress { stage: rbf::Stage::Selection, done: 3, total: 50 };
/// assert!(p.done < p.total);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Current stage.
    pub stage: Stage,
    /// Units done.
    pub done: usize,
    /// Units in the stage.
    pub total: usize,
}
