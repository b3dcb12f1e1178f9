//! What a fit reports while it runs: the stage and how far into it.

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
