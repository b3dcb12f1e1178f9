//! k-means centres through linfa-clustering (k-means++ initialisation, seeded).

use faer::{Mat, MatRef};
use linfa::prelude::*;
use linfa_clustering::{KMeans, KMeansError, KMeansInit};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;

use crate::convert::as_array;

/// Settings of a k-means run.
///
/// `n_runs` defaults to 1 (linfa's default is 10): one k-means++ start is reproducible,
/// ten times faster, and the output weights re-solved by least squares absorb most of
/// the difference between starts; raise it when the centres themselves matter.
///
/// ```
/// let s = rbf::select::kmeans::KMeansSettings::new(20);
/// assert_eq!((s.n_runs, s.max_iterations), (1, 300));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KMeansSettings {
    /// Number of clusters (centres).
    pub n_centres: usize,
    /// Independent k-means++ starts; the lowest inertia wins.
    pub n_runs: usize,
    /// Lloyd iterations per start.
    pub max_iterations: u64,
    /// Convergence tolerance on the centroids' movement.
    pub tolerance: f64,
}

impl KMeansSettings {
    /// Defaults for `n_centres` clusters.
    ///
    /// ```
    /// assert_eq!(rbf::select::kmeans::KMeansSettings::new(3).tolerance, 1e-4);
    /// ```
    pub fn new(n_centres: usize) -> Self {
        Self {
            n_centres,
            n_runs: 1,
            max_iterations: 300,
            tolerance: 1e-4,
        }
    }
}

/// Centres found by k-means.
///
/// ```
/// use faer::Mat;
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = Mat::from_fn(40, 1, |i, _| if i < 20 { i as f64 * 0.01 } else { 10.0 + i as f64 * 0.01 });
/// let c = kmeans_centres(x.as_ref(), &KMeansSettings::new(2), 1).unwrap();
/// let mut cs = [c.centres[(0, 0)], c.centres[(1, 0)]];
/// cs.sort_by(f64::total_cmp);
/// // converged to the cluster means within the centroid-movement tolerance 1e-4
/// assert!((cs[0] - 0.095).abs() < 1e-4 && (cs[1] - 10.295).abs() < 1e-4);
/// assert_eq!(c.memberships.len(), 40);
/// ```
#[derive(Clone, Debug)]
pub struct KMeansCentres {
    /// Centroids, k × d.
    pub centres: Mat<f64>,
    /// Cluster of every sample.
    pub memberships: Vec<usize>,
    /// Mean squared distance to the assigned centroid.
    pub inertia: f64,
}

/// Runs k-means on the rows of `x` with a seeded `Xoshiro256Plus`.
///
/// # Errors
/// linfa's [`KMeansError`] (invalid settings, or fewer samples than clusters).
///
/// ```
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = faer::Mat::from_fn(30, 2, |i, j| ((i * (j + 1)) % 11) as f64);
/// let a = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3).unwrap();
/// let b = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3).unwrap();
/// assert_eq!(a.centres, b.centres); // same seed, same centres
/// assert!(a.memberships.iter().all(|&c| c < 4));
/// ```
pub fn kmeans_centres(
    x: MatRef<'_, f64>,
    settings: &KMeansSettings,
    seed: u64,
) -> Result<KMeansCentres, KMeansError> {
    let records = as_array(x);
    let dataset = DatasetBase::from(records.view());
    let model = KMeans::params_with_rng(settings.n_centres, Xoshiro256Plus::seed_from_u64(seed))
        .n_runs(settings.n_runs)
        .max_n_iterations(settings.max_iterations)
        .tolerance(settings.tolerance)
        .init_method(KMeansInit::KMeansPlusPlus)
        .fit(&dataset)?;
    let memberships = model.predict(&records.view()).to_vec();
    let c = model.centroids();
    Ok(KMeansCentres {
        centres: Mat::from_fn(c.nrows(), c.ncols(), |i, j| c[[i, j]]),
        memberships,
        inertia: model.inertia(),
    })
}
