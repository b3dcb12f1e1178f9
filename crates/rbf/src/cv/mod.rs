//! Cross-validation: splits, per-fold scores, and grid search.
//!
//! Time series of windowed inputs need care: a window of 50 shares 49 samples with its
//! neighbour, so any split that puts neighbouring windows on both sides (k-fold,
//! interleaved) validates on near-copies of training vectors and flatters the model.
//! [`Split::Blocked`] with a `gap` of at least the window length is the honest split;
//! [`Split::Interleaved`] reproduces the seed paper's alternate-vector split.

mod grid;
mod grid_each;
mod validate;

pub use crate::split::{Fold, Holdout, Split, SplitError, holdout};
pub use grid::{Grid, GridPoint, GridReport, Sizes, grid_search, grid_search_with_linear};
pub use grid_each::grid_search_each_with_linear;
pub use validate::{
    CvReport, FoldReport, cross_validate, cross_validate_folds, cross_validate_with_linear,
};
