//! Why k-means could not run: rbf's own error type, so that no linfa type appears in
//! rbf's public errors (linfa-clustering's failures are carried as their message).

/// Why k-means could not run.
///
/// ```
/// use rbf::select::kmeans::{kmeans_centres, KMeansError, KMeansSettings};
/// let x = faer::Mat::from_fn(10, 1, |i, _| i as f64);
/// let bad = KMeansSettings { n_runs: 0, ..KMeansSettings::new(2) };
/// let e = kmeans_centres(x.as_ref(), &bad, 0, faer::Par::Seq).unwrap_err();
/// assert_eq!(e, KMeansError::NoRuns);
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum KMeansError {
    /// `n_centres` is 0.
    #[error("k-means needs at least one cluster")]
    NoClusters,
    /// `n_runs` is 0.
    #[error("k-means needs at least one run")]
    NoRuns,
    /// `max_iterations` is 0.
    #[error("k-means needs at least one iteration")]
    NoIterations,
    /// The tolerance is not finite and positive.
    #[error("k-means tolerance must be finite and > 0, got {value}")]
    Tolerance {
        /// Value given.
        value: f64,
    },
    /// linfa-clustering's `KMeans` failed (its message; fewer samples than clusters
    /// go to linfa, see [`super::kmeans_centres`]).
    #[error("linfa-clustering: {0}")]
    Linfa(String),
}

impl From<linfa_clustering::KMeansError> for KMeansError {
    fn from(e: linfa_clustering::KMeansError) -> Self {
        KMeansError::Linfa(e.to_string())
    }
}
