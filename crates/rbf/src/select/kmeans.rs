//! k-means centres through linfa-clustering (k-means++ initialisation, seeded).
//!
//! The k-means++ seeding is done here and handed to linfa as a precomputed start:
//! linfa 0.8's own k-means++ recomputes every sample's distance to *all* centres chosen
//! so far at each of the k steps (O(n·k²·d): 0.25 s of a 0.3 s fit for n = 2500,
//! d = 50, k = 100), where keeping each sample's nearest distance and updating it with
//! the one new centre gives the same D² sampling in O(n·k·d). linfa then runs the Lloyd
//! iterations.

use faer::{Mat, MatRef};
use linfa::prelude::*;
use linfa_clustering::{KMeans, KMeansError, KMeansInit};
use ndarray::Array2;
use rand::Rng;
use rand::SeedableRng;
use rand::distributions::{Distribution, WeightedIndex};
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
    let k = settings.n_centres;
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    // linfa draws from its generator only to initialise, which a precomputed start skips
    let params = |init, rng: Xoshiro256Plus| {
        KMeans::params_with_rng(k, rng)
            .n_runs(1)
            .max_n_iterations(settings.max_iterations)
            .tolerance(settings.tolerance)
            .init_method(init)
    };
    let model = if k == 0 || x.nrows() < k {
        // what the seeding below cannot do: linfa's own checks and behaviour
        params(KMeansInit::KMeansPlusPlus, rng.clone())
            .n_runs(settings.n_runs)
            .fit(&dataset)?
    } else {
        let mut best: Option<KMeans<f64, _>> = None;
        for _ in 0..settings.n_runs {
            let start = kmeans_plusplus(x, k, &mut rng);
            let model = params(KMeansInit::Precomputed(start), rng.clone()).fit(&dataset)?;
            if best.as_ref().is_none_or(|b| model.inertia() < b.inertia()) {
                best = Some(model);
            }
        }
        best.ok_or(KMeansError::InertiaError)?
    };
    let memberships = model.predict(&records.view()).to_vec();
    let c = model.centroids();
    Ok(KMeansCentres {
        centres: Mat::from_fn(c.nrows(), c.ncols(), |i, j| c[[i, j]]),
        memberships,
        inertia: model.inertia(),
    })
}

/// k-means++ seeding (Arthur & Vassilvitskii 2007): the first centre is a uniformly
/// drawn sample, each next one a sample drawn with probability proportional to its
/// squared distance to the nearest centre chosen so far. Each sample's nearest squared
/// distance is kept and updated with every new centre, so the seeding costs O(n·k·d).
/// When every remaining distance is 0 (fewer distinct samples than k), the first sample
/// is taken, as linfa does.
///
/// # Panics
/// If `x` has fewer than `k` rows or `k` is 0 (checked by the caller).
///
/// ```
/// use rand::SeedableRng;
/// let x = faer::Mat::from_fn(60, 1, |i, _| (i / 20) as f64 * 100.0 + (i % 20) as f64 * 0.01);
/// let mut rng = rand_xoshiro::Xoshiro256Plus::seed_from_u64(1);
/// let c = rbf::select::kmeans::kmeans_plusplus(x.as_ref(), 3, &mut rng);
/// let mut groups: Vec<i64> = (0..3).map(|i| (c[[i, 0]] / 100.0).round() as i64).collect();
/// groups.sort();
/// assert_eq!(groups, vec![0, 1, 2]); // one seed in each well-separated cluster
/// ```
#[track_caller]
pub fn kmeans_plusplus(x: MatRef<'_, f64>, k: usize, rng: &mut impl Rng) -> Array2<f64> {
    let (n, d) = (x.nrows(), x.ncols());
    assert!(
        k >= 1 && n >= k,
        "k-means++ needs 1 ≤ k ≤ n (k = {k}, n = {n})"
    );
    let mut centres = Array2::<f64>::zeros((k, d));
    let mut nearest = vec![f64::INFINITY; n];
    let mut dist = vec![0.0; n];
    let mut next = rng.gen_range(0..n);
    for c in 0..k {
        for j in 0..d {
            centres[[c, j]] = x[(next, j)];
        }
        if c + 1 == k {
            break;
        }
        // squared distances to the new centre, column by column (contiguous in faer)
        dist.fill(0.0);
        for j in 0..d {
            let cj = centres[[c, j]];
            let col = x.col(j);
            for (i, acc) in dist.iter_mut().enumerate() {
                let v = col[i] - cj;
                *acc += v * v;
            }
        }
        for (m, &v) in nearest.iter_mut().zip(&dist) {
            *m = m.min(v);
        }
        next = WeightedIndex::new(nearest.iter())
            .map(|w| w.sample(rng))
            .unwrap_or(0);
    }
    centres
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The linear-time seeding draws what linfa's own k-means++ draws (same generator,
    /// same D² weights), so the whole k-means run is unchanged.
    #[test]
    fn seeding_matches_linfas_kmeans_plusplus() {
        let x = Mat::from_fn(400, 6, |i, j| {
            ((i * (j + 3)) as f64 * 0.731).sin() + (i % 7) as f64
        });
        for (k, seed) in [(5, 1), (20, 7), (60, 42)] {
            let settings = KMeansSettings::new(k);
            let ours = kmeans_centres(x.as_ref(), &settings, seed).unwrap();
            let records = as_array(x.as_ref());
            let linfa = KMeans::params_with_rng(k, Xoshiro256Plus::seed_from_u64(seed))
                .n_runs(1)
                .max_n_iterations(settings.max_iterations)
                .tolerance(settings.tolerance)
                .init_method(KMeansInit::KMeansPlusPlus)
                .fit(&DatasetBase::from(records.view()))
                .unwrap();
            let c = linfa.centroids();
            for i in 0..k {
                for j in 0..6 {
                    assert!(
                        (ours.centres[(i, j)] - c[[i, j]]).abs() < 1e-12,
                        "k {k} seed {seed}"
                    );
                }
            }
        }
    }

    #[test]
    fn several_runs_keep_the_lowest_inertia() {
        let x = Mat::from_fn(300, 2, |i, j| ((i * (j + 5)) as f64 * 0.37).sin());
        let one = kmeans_centres(x.as_ref(), &KMeansSettings::new(8), 3).unwrap();
        let many = KMeansSettings {
            n_runs: 5,
            ..KMeansSettings::new(8)
        };
        let best = kmeans_centres(x.as_ref(), &many, 3).unwrap();
        assert!(best.inertia <= one.inertia);
    }

    #[test]
    fn more_clusters_than_samples_is_left_to_linfa_not_a_panic() {
        let x = Mat::from_fn(3, 1, |i, _| i as f64);
        let _ = kmeans_centres(x.as_ref(), &KMeansSettings::new(5), 0);
        let bad = KMeansSettings {
            n_centres: 0,
            ..KMeansSettings::new(1)
        };
        assert!(kmeans_centres(x.as_ref(), &bad, 0).is_err());
    }
}
