//! Structure selection: which centres (or which candidate regressors) enter the model.
//!
//! - [`ols`]: orthogonal least squares forward selection by error-reduction ratio
//!   (Chen, Cowan & Grant 1991), generic over candidate columns;
//! - [`kmeans`]: k-means centres (seeded k-means++, then Lloyd iterations by faer
//!   products, or linfa-clustering's `KMeans`);
//! - [`random`]: a seeded random subset of the training vectors.

pub mod kmeans;
pub mod ols;
pub mod random;
