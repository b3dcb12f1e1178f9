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
mod ols_inputs;
mod persist;
mod poly;
mod progress;
mod scaling;

pub use error::{RbfError, RbfParamsError};
pub use fitted::{MAX_COEFFICIENT, RbfModel, Selection};
pub use hyperparams::{Candidates, CentreSelection, RbfParams, RbfValidParams, Strategy};
pub use persist::{FORMAT_VERSION, PersistError};
pub use poly::{PolyTail, UnknownPolyTail};
pub use progress::{Progress, Stage};
pub use scaling::Scaling;

pub(crate) use algorithm::OlsStage;
pub(crate) use ols_inputs::OlsInputs;
