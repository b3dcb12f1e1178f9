//! k-means centres: a seeded k-means++ start, then Lloyd iterations — the library's own
//! ([`KMeansAlgorithm::Lloyd`], the default: distances by one faer product per
//! iteration) or linfa-clustering's `KMeans` ([`KMeansAlgorithm::Linfa`]).
//!
//! The k-means++ seeding is done here for both: linfa 0.8's own k-means++ recomputes
//! every sample's distance to *all* centres chosen so far at each of the k steps
//! (O(n·k²·d): 0.25 s of a 0.3 s fit for n = 2500, d = 50, k = 100), where keeping each
//! sample's nearest distance and updating it with the one new centre gives the same D²
//! sampling in O(n·k·d). Both algorithms start from the same centres for the same seed.
//!
//! Why the library has its own Lloyd iterations: linfa's assignment step computes every
//! sample–centroid distance in a scalar loop (≈ 7 ms an iteration for n = 2500, d = 50,
//! k = 100 on one core), and its update step counts the old centroid as one more member
//! of its cluster, which slows convergence (34 iterations against 19 for scikit-learn on
//! the bench data). [`lloyd`] computes the distances as ‖x‖² + ‖c‖² − 2·X·Cᵀ through the
//! kernel matrices' product code and updates the centroids as plain means, with
//! scikit-learn's stopping rule.

use std::fmt;
use std::str::FromStr;

use faer::{Mat, MatRef, Par};
use linfa::prelude::*;
use linfa_clustering::{KMeans, KMeansError, KMeansInit};
use ndarray::Array2;
use rand::Rng;
use rand::SeedableRng;
use rand::distributions::{Distribution, WeightedIndex};
use rand_xoshiro::Xoshiro256Plus;
use serde::{Deserialize, Serialize};

use crate::convert::as_array;
use crate::design::squared_distances_into;

/// Which Lloyd iterations follow the (shared, seeded) k-means++ start.
///
/// ```
/// use rbf::select::kmeans::KMeansAlgorithm;
/// assert_eq!(KMeansAlgorithm::default(), KMeansAlgorithm::Lloyd);
/// assert_eq!("linfa".parse::<KMeansAlgorithm>().unwrap(), KMeansAlgorithm::Linfa);
/// assert_eq!(serde_json::to_string(&KMeansAlgorithm::Lloyd).unwrap(), "\"lloyd\"");
/// assert!("elkan".parse::<KMeansAlgorithm>().unwrap_err().to_string().contains("lloyd, linfa"));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum KMeansAlgorithm {
    /// [`lloyd`]: distances by one faer product per iteration, centroids as plain means,
    /// scikit-learn's stopping rule (`tolerance` relative to the mean feature variance).
    /// Parallel as the fit's [`Par`].
    #[default]
    Lloyd,
    /// linfa-clustering's `KMeans` (its update counts the old centroid as one more
    /// member; `tolerance` is absolute, on the Euclidean norm of the centroids' movement).
    /// Runs on rayon's global pool.
    Linfa,
}

impl KMeansAlgorithm {
    /// Every algorithm, in the order of [`KMeansAlgorithm::NAMES`].
    pub const ALL: [KMeansAlgorithm; 2] = [KMeansAlgorithm::Lloyd, KMeansAlgorithm::Linfa];
    /// The names [`FromStr`] accepts.
    pub const NAMES: [&'static str; 2] = ["lloyd", "linfa"];

    /// The name of this algorithm.
    ///
    /// ```
    /// assert_eq!(rbf::KMeansAlgorithm::Linfa.name(), "linfa");
    /// ```
    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }
}

impl fmt::Display for KMeansAlgorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A k-means algorithm name that [`KMeansAlgorithm::from_str`] does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown k-means algorithm {name:?}; valid names: {}", KMeansAlgorithm::NAMES.join(", "))]
pub struct UnknownKMeansAlgorithm {
    /// The name given.
    pub name: String,
}

impl FromStr for KMeansAlgorithm {
    type Err = UnknownKMeansAlgorithm;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name() == s)
            .ok_or_else(|| UnknownKMeansAlgorithm {
                name: s.to_string(),
            })
    }
}

/// Settings of a k-means run.
///
/// `n_runs` defaults to 1 (linfa's and scikit-learn's defaults are 10 and 1): one
/// k-means++ start is reproducible, fast, and the output weights re-solved by least
/// squares absorb most of the difference between starts; raise it when the centres
/// themselves matter.
///
/// ```
/// let s = rbf::select::kmeans::KMeansSettings::new(20);
/// assert_eq!((s.n_runs, s.max_iterations), (1, 300));
/// assert_eq!(s.algorithm, rbf::KMeansAlgorithm::Lloyd);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KMeansSettings {
    /// Number of clusters (centres).
    pub n_centres: usize,
    /// Independent k-means++ starts; the lowest inertia wins.
    pub n_runs: usize,
    /// Lloyd iterations per start.
    pub max_iterations: u64,
    /// Convergence tolerance on the centroids' movement: for [`KMeansAlgorithm::Lloyd`]
    /// relative (stop once the summed squared movement is at most `tolerance` × the mean
    /// variance of the input columns, scikit-learn's rule), for [`KMeansAlgorithm::Linfa`]
    /// absolute (linfa's rule). 1e-4 is both libraries' default.
    pub tolerance: f64,
    /// Whose Lloyd iterations run (default [`KMeansAlgorithm::Lloyd`]).
    pub algorithm: KMeansAlgorithm,
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
            algorithm: KMeansAlgorithm::default(),
        }
    }

    /// The same settings with another algorithm.
    ///
    /// ```
    /// use rbf::{KMeansAlgorithm, KMeansSettings};
    /// let s = KMeansSettings::new(5).algorithm(KMeansAlgorithm::Linfa);
    /// assert_eq!((s.n_centres, s.algorithm), (5, KMeansAlgorithm::Linfa));
    /// ```
    pub fn algorithm(self, algorithm: KMeansAlgorithm) -> Self {
        Self { algorithm, ..self }
    }
}

/// Centres found by k-means.
///
/// ```
/// use faer::{Mat, Par};
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = Mat::from_fn(40, 1, |i, _| if i < 20 { i as f64 * 0.01 } else { 10.0 + i as f64 * 0.01 });
/// for alg in rbf::KMeansAlgorithm::ALL {
///     let c = kmeans_centres(x.as_ref(), &KMeansSettings::new(2).algorithm(alg), 1, Par::Seq).unwrap();
///     let mut cs = [c.centres[(0, 0)], c.centres[(1, 0)]];
///     cs.sort_by(f64::total_cmp);
///     // converged to the cluster means
///     assert!((cs[0] - 0.095).abs() < 1e-4 && (cs[1] - 10.295).abs() < 1e-4);
///     assert_eq!(c.memberships.len(), 40);
/// }
/// ```
#[derive(Clone, Debug)]
pub struct KMeansCentres {
    /// Centroids, k × d.
    pub centres: Mat<f64>,
    /// Cluster of every sample: its nearest centroid.
    pub memberships: Vec<usize>,
    /// Mean squared distance of the samples to their assigned centroid.
    pub inertia: f64,
    /// Lloyd iterations of the run kept ([`KMeansAlgorithm::Lloyd`]; linfa does not
    /// report them).
    pub iterations: Option<u64>,
}

/// Runs k-means on the rows of `x`: `n_runs` seeded k-means++ starts (one
/// `Xoshiro256Plus` seeded with `seed` draws them all), each followed by the Lloyd
/// iterations of `settings.algorithm`; the run with the lowest inertia is kept (the
/// first on a tie). `par` is the parallelism of [`KMeansAlgorithm::Lloyd`].
///
/// With fewer samples than clusters (or none) the call goes to linfa whichever the
/// algorithm, for linfa's errors and behaviour.
///
/// # Errors
/// linfa's [`KMeansError`] (invalid settings — checked by linfa's rules for both
/// algorithms —, or fewer samples than clusters).
///
/// ```
/// use rbf::select::kmeans::{kmeans_centres, KMeansSettings};
/// let x = faer::Mat::from_fn(30, 2, |i, j| ((i * (j + 1)) % 11) as f64);
/// let a = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3, faer::Par::Seq).unwrap();
/// let b = kmeans_centres(x.as_ref(), &KMeansSettings::new(4), 3, faer::Par::rayon(2)).unwrap();
/// assert_eq!(a.centres, b.centres); // same seed, same centres
/// assert!(a.memberships.iter().all(|&c| c < 4));
/// ```
pub fn kmeans_centres(
    x: MatRef<'_, f64>,
    settings: &KMeansSettings,
    seed: u64,
    par: Par,
) -> Result<KMeansCentres, KMeansError> {
    let k = settings.n_centres;
    let mut rng = Xoshiro256Plus::seed_from_u64(seed);
    let params = |init, rng: Xoshiro256Plus| {
        KMeans::params_with_rng(k, rng)
            .n_runs(1)
            .max_n_iterations(settings.max_iterations)
            .tolerance(settings.tolerance)
            .init_method(init)
    };
    if k == 0 || x.nrows() < k {
        // what the seeding cannot do: linfa's own checks and behaviour
        let model = params(KMeansInit::KMeansPlusPlus, rng)
            .n_runs(settings.n_runs)
            .fit(&DatasetBase::from(as_array(x)))?;
        return Ok(linfa_result(
            x,
            model.centroids(),
            model.predict(&as_array(x)).to_vec(),
        ));
    }
    // linfa's rules for the settings, whichever the algorithm
    params(KMeansInit::KMeansPlusPlus, rng.clone())
        .n_runs(settings.n_runs)
        .check()?;
    let mut best: Option<KMeansCentres> = None;
    for _ in 0..settings.n_runs {
        let start = kmeans_plusplus(x, k, &mut rng);
        let run = match settings.algorithm {
            KMeansAlgorithm::Lloyd => {
                let start = Mat::from_fn(k, x.ncols(), |i, j| start[[i, j]]);
                lloyd(
                    x,
                    start.as_ref(),
                    settings.max_iterations,
                    settings.tolerance,
                    par,
                )
            }
            KMeansAlgorithm::Linfa => {
                // linfa draws from its generator only to initialise, which a
                // precomputed start skips
                let model = params(KMeansInit::Precomputed(start), rng.clone())
                    .fit(&DatasetBase::from(as_array(x)))?;
                linfa_result(x, model.centroids(), model.predict(&as_array(x)).to_vec())
            }
        };
        if best.as_ref().is_none_or(|b| run.inertia < b.inertia) {
            best = Some(run);
        }
    }
    best.ok_or(KMeansError::InertiaError)
}

/// Centres and memberships from linfa, with the inertia of those memberships.
fn linfa_result(x: MatRef<'_, f64>, c: &Array2<f64>, memberships: Vec<usize>) -> KMeansCentres {
    let centres = Mat::from_fn(c.nrows(), c.ncols(), |i, j| c[[i, j]]);
    KMeansCentres {
        inertia: inertia(x, centres.as_ref(), &memberships),
        centres,
        memberships,
        iterations: None,
    }
}

/// Mean squared distance of the rows of `x` to their assigned centres, computed
/// directly (O(n·d)).
fn inertia(x: MatRef<'_, f64>, centres: MatRef<'_, f64>, memberships: &[usize]) -> f64 {
    let n = x.nrows();
    if n == 0 {
        return 0.0;
    }
    let mut sum = 0.0;
    for t in 0..x.ncols() {
        for (i, &c) in memberships.iter().enumerate() {
            let v = x[(i, t)] - centres[(c, t)];
            sum += v * v;
        }
    }
    sum / n as f64
}

/// Lloyd's algorithm from the centres `start` (k × d), standard as in scikit-learn's
/// `KMeans(algorithm="lloyd")`:
///
/// 1. *assignment*: the squared distances of every sample to every centroid come from
///    one faer product (‖x‖² + ‖c‖² − 2·X·Cᵀ, the kernel matrices' code, parallel as
///    `par`); each sample goes to its nearest centroid, the lowest index on a tie;
/// 2. *empty clusters* (deterministic): each cluster left without a sample, in index
///    order, takes the sample farthest from its centroid among clusters with at least
///    two members (the lowest index on a tie) — scikit-learn relocates empty centres to
///    the farthest samples the same way;
/// 3. *update*: every centroid becomes the plain mean of its members;
/// 4. *stop* when the assignment did not change (the centroids are then fixed), when the
///    summed squared movement of the centroids is at most `tolerance` × the mean
///    variance of the columns of `x` (scikit-learn's rule and default 1e-4), or after
///    `max_iterations` iterations. Unless the assignment was unchanged, a last
///    assignment step makes the memberships those of the final centroids.
///
/// The returned inertia is the mean squared distance to the assigned centroid, computed
/// directly. Deterministic: the same start gives bit-identical centres for any `par`.
///
/// # Panics
/// If `start` has no rows, more rows than `x`, or a different number of columns.
///
/// ```
/// use faer::{mat, Par};
/// use rbf::select::kmeans::lloyd;
/// let x = mat![[0.0], [1.0], [10.0], [11.0]];
/// let start = mat![[0.0], [1.0]];
/// let r = lloyd(x.as_ref(), start.as_ref(), 100, 1e-4, Par::Seq);
/// // first step: {0} and {1, 10, 11}; second: {0, 1} and {10, 11}; the third changes nothing
/// assert_eq!(r.centres, mat![[0.5], [10.5]]);
/// assert_eq!(r.memberships, vec![0, 0, 1, 1]);
/// assert_eq!(r.iterations, Some(3));
/// ```
#[track_caller]
pub fn lloyd(
    x: MatRef<'_, f64>,
    start: MatRef<'_, f64>,
    max_iterations: u64,
    tolerance: f64,
    par: Par,
) -> KMeansCentres {
    let (n, d, k) = (x.nrows(), x.ncols(), start.nrows());
    assert!(
        k >= 1 && k <= n,
        "Lloyd's algorithm needs 1 ≤ k ≤ n (k = {k}, n = {n})"
    );
    assert_eq!(
        start.ncols(),
        d,
        "start centres have {} columns, samples {d}",
        start.ncols()
    );
    let tol = tolerance * mean_variance(x);
    let mut centres = start.to_owned();
    let mut next = Mat::<f64>::zeros(k, d);
    let mut dist = Mat::<f64>::zeros(n, k);
    let mut labels = vec![0usize; n];
    let mut nearest = vec![0.0; n];
    let mut previous = vec![usize::MAX; n];
    let mut counts = vec![0usize; k];
    let mut unchanged = false;
    let mut iterations = 0;
    while iterations < max_iterations {
        iterations += 1;
        assign(
            x,
            centres.as_ref(),
            &mut dist,
            &mut labels,
            &mut nearest,
            par,
        );
        relocate_empty(&mut labels, &mut nearest, &mut counts);
        means(x, &labels, &counts, &mut next);
        let shift = (0..d)
            .map(|t| {
                (0..k)
                    .map(|j| (next[(j, t)] - centres[(j, t)]).powi(2))
                    .sum::<f64>()
            })
            .sum::<f64>();
        std::mem::swap(&mut centres, &mut next);
        if labels == previous {
            unchanged = true;
            break;
        }
        if shift <= tol {
            break;
        }
        previous.copy_from_slice(&labels);
    }
    if !unchanged {
        assign(
            x,
            centres.as_ref(),
            &mut dist,
            &mut labels,
            &mut nearest,
            par,
        );
    }
    KMeansCentres {
        inertia: inertia(x, centres.as_ref(), &labels),
        centres,
        memberships: labels,
        iterations: Some(iterations),
    }
}

/// Mean over the columns of their population variance (scikit-learn's scale for the
/// tolerance); 0 without columns.
fn mean_variance(x: MatRef<'_, f64>) -> f64 {
    let (n, d) = (x.nrows(), x.ncols());
    if n == 0 || d == 0 {
        return 0.0;
    }
    let total: f64 = (0..d)
        .map(|t| {
            let col = x.col(t);
            let mean = (0..n).map(|i| col[i]).sum::<f64>() / n as f64;
            (0..n).map(|i| (col[i] - mean).powi(2)).sum::<f64>() / n as f64
        })
        .sum();
    total / d as f64
}

/// Nearest centroid (lowest index on a tie) and its squared distance, for every sample.
fn assign(
    x: MatRef<'_, f64>,
    centres: MatRef<'_, f64>,
    dist: &mut Mat<f64>,
    labels: &mut [usize],
    nearest: &mut [f64],
    par: Par,
) {
    squared_distances_into(x, centres, dist.as_mut(), par);
    let (n, k) = (dist.nrows(), dist.ncols());
    let dist = dist.as_ref();
    let column = |j: usize| {
        dist.col(j)
            .try_as_col_major()
            .expect("an owned matrix has contiguous columns")
            .as_slice()
    };
    // rows in chunks, columns swept in order: contiguous reads, branch-free selects
    let argmin = |start: usize, labels: &mut [usize], nearest: &mut [f64]| {
        let rows = start..start + labels.len();
        nearest.copy_from_slice(&column(0)[rows.clone()]);
        labels.fill(0);
        for j in 1..k {
            for ((l, m), &v) in labels
                .iter_mut()
                .zip(nearest.iter_mut())
                .zip(&column(j)[rows.clone()])
            {
                let closer = v < *m;
                *m = if closer { v } else { *m };
                *l = if closer { j } else { *l };
            }
        }
    };
    let threads = par.degree();
    const MIN_ROWS: usize = 256;
    if threads <= 1 || n <= MIN_ROWS {
        argmin(0, labels, nearest);
    } else {
        use rayon::prelude::*;
        let chunk = n.div_ceil(threads).max(MIN_ROWS);
        labels
            .par_chunks_mut(chunk)
            .zip(nearest.par_chunks_mut(chunk))
            .enumerate()
            .for_each(|(c, (l, m))| argmin(c * chunk, l, m));
    }
}

/// Counts the members of every cluster and gives each empty cluster, in index order,
/// the sample farthest from its centroid among clusters with at least two members
/// (the lowest index on a tie). With k ≤ n such a cluster always exists.
fn relocate_empty(labels: &mut [usize], nearest: &mut [f64], counts: &mut [usize]) {
    counts.fill(0);
    for &l in labels.iter() {
        counts[l] += 1;
    }
    for j in 0..counts.len() {
        if counts[j] > 0 {
            continue;
        }
        let mut far: Option<usize> = None;
        for (i, &l) in labels.iter().enumerate() {
            if counts[l] >= 2 && far.is_none_or(|f| nearest[i] > nearest[f]) {
                far = Some(i);
            }
        }
        let i = far.expect("k ≤ n leaves a cluster with two members");
        counts[labels[i]] -= 1;
        labels[i] = j;
        counts[j] = 1;
        nearest[i] = 0.0;
    }
}

/// Centroids as the plain means of their members (every cluster has one).
fn means(x: MatRef<'_, f64>, labels: &[usize], counts: &[usize], out: &mut Mat<f64>) {
    out.fill(0.0);
    for t in 0..x.ncols() {
        let col = x.col(t);
        let mut o = out.col_mut(t);
        for (i, &l) in labels.iter().enumerate() {
            o[l] += col[i];
        }
    }
    for (j, &c) in counts.iter().enumerate() {
        let inv = 1.0 / c as f64;
        for t in 0..x.ncols() {
            out[(j, t)] *= inv;
        }
    }
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
            match col.try_as_col_major() {
                // slices: no bounds checks, so the loop vectorises (same sums, same order)
                Some(col) => {
                    for (acc, &xi) in dist.iter_mut().zip(col.as_slice()) {
                        let v = xi - cj;
                        *acc += v * v;
                    }
                }
                None => {
                    for (i, acc) in dist.iter_mut().enumerate() {
                        let v = col[i] - cj;
                        *acc += v * v;
                    }
                }
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
    use faer::mat;

    /// The linear-time seeding draws what linfa's own k-means++ draws (same generator,
    /// same D² weights), so linfa's whole k-means run is unchanged.
    #[test]
    fn seeding_matches_linfas_kmeans_plusplus() {
        let x = Mat::from_fn(400, 6, |i, j| {
            ((i * (j + 3)) as f64 * 0.731).sin() + (i % 7) as f64
        });
        for (k, seed) in [(5, 1), (20, 7), (60, 42)] {
            let settings = KMeansSettings::new(k).algorithm(KMeansAlgorithm::Linfa);
            let ours = kmeans_centres(x.as_ref(), &settings, seed, Par::Seq).unwrap();
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

    /// Both algorithms start from the same k-means++ centres: one Lloyd iteration from
    /// that start is the mean of the samples nearest each seed.
    #[test]
    fn both_algorithms_share_the_seeded_start() {
        let x = Mat::from_fn(200, 3, |i, j| ((i * (j + 2)) as f64 * 0.53).cos());
        let mut rng = Xoshiro256Plus::seed_from_u64(9);
        let start = kmeans_plusplus(x.as_ref(), 6, &mut rng);
        let start = Mat::from_fn(6, 3, |i, j| start[[i, j]]);
        let one = lloyd(x.as_ref(), start.as_ref(), 1, 1e-4, Par::Seq);
        let settings = KMeansSettings {
            max_iterations: 1,
            ..KMeansSettings::new(6)
        };
        let ours = kmeans_centres(x.as_ref(), &settings, 9, Par::Seq).unwrap();
        assert_eq!(ours.centres, one.centres);
        assert_eq!(ours.iterations, Some(1));
    }

    #[test]
    fn several_runs_keep_the_lowest_inertia() {
        let x = Mat::from_fn(300, 2, |i, j| ((i * (j + 5)) as f64 * 0.37).sin());
        for alg in KMeansAlgorithm::ALL {
            let one = KMeansSettings::new(8).algorithm(alg);
            let one = kmeans_centres(x.as_ref(), &one, 3, Par::Seq).unwrap();
            let many = KMeansSettings {
                n_runs: 5,
                ..KMeansSettings::new(8).algorithm(alg)
            };
            let best = kmeans_centres(x.as_ref(), &many, 3, Par::Seq).unwrap();
            assert!(best.inertia <= one.inertia, "{alg}");
        }
    }

    #[test]
    fn more_clusters_than_samples_is_left_to_linfa_not_a_panic() {
        let x = Mat::from_fn(3, 1, |i, _| i as f64);
        for alg in KMeansAlgorithm::ALL {
            let s = KMeansSettings::new(5).algorithm(alg);
            let _ = kmeans_centres(x.as_ref(), &s, 0, Par::Seq);
            let bad = KMeansSettings { n_centres: 0, ..s };
            assert!(kmeans_centres(x.as_ref(), &bad, 0, Par::Seq).is_err());
        }
    }

    /// linfa's rules for the settings hold for the library's Lloyd iterations too.
    #[test]
    fn lloyd_settings_are_checked_by_linfas_rules() {
        let x = Mat::from_fn(20, 1, |i, _| i as f64);
        let ok = KMeansSettings::new(2);
        for bad in [
            KMeansSettings { n_runs: 0, ..ok },
            KMeansSettings {
                tolerance: 0.0,
                ..ok
            },
            KMeansSettings {
                max_iterations: 0,
                ..ok
            },
        ] {
            let e = kmeans_centres(x.as_ref(), &bad, 0, Par::Seq).unwrap_err();
            assert!(matches!(e, KMeansError::InvalidParams(_)), "{e}");
        }
    }

    /// An empty cluster takes the sample farthest from its centroid (among clusters with
    /// two members or more), then the iterations go on as usual.
    #[test]
    fn an_empty_cluster_takes_the_farthest_sample() {
        let x = mat![[0.0], [1.0], [2.0], [3.4], [10.0], [11.0]];
        // centre 1 at 100 attracts nothing; sample 3 (3.4 from centre 0) is the farthest
        let start = mat![[0.0], [100.0], [10.0]];
        let r = lloyd(x.as_ref(), start.as_ref(), 100, 1e-4, Par::Seq);
        assert_eq!(r.centres, mat![[1.0], [3.4], [10.5]]);
        assert_eq!(r.memberships, vec![0, 0, 0, 1, 2, 2]);
        assert_eq!(r.iterations, Some(2));
        assert!((r.inertia - (1.0 + 0.0 + 1.0 + 0.0 + 0.25 + 0.25) / 6.0).abs() < 1e-15);
    }

    /// Two empty clusters in one step: in index order, each takes the farthest sample
    /// left (a relocated sample is not taken again).
    #[test]
    fn empty_clusters_are_filled_in_index_order() {
        let x = mat![[0.0], [1.0], [2.0], [3.0], [10.0], [11.0]];
        let start = mat![[0.0], [100.0], [200.0], [10.0]];
        let r = lloyd(x.as_ref(), start.as_ref(), 100, 1e-4, Par::Seq);
        // cluster 1 takes sample 3 (9 from centre 0), cluster 2 sample 2 (4 from it)
        assert_eq!(r.centres, mat![[0.5], [3.0], [2.0], [10.5]]);
        assert_eq!(r.memberships, vec![0, 0, 2, 1, 3, 3]);
    }

    /// Fewer distinct samples than clusters: the relocation still finds members (the
    /// lowest indices on the all-zero tie), no cluster stays empty, nothing panics.
    #[test]
    fn duplicate_samples_fill_every_cluster() {
        let x = Mat::from_fn(5, 2, |_, j| j as f64);
        let start = mat![[0.0, 1.0], [0.0, 1.0], [0.0, 1.0]];
        let r = lloyd(x.as_ref(), start.as_ref(), 10, 1e-4, Par::Seq);
        assert_eq!(r.inertia, 0.0);
        assert_eq!(r.memberships.len(), 5);
        let s = KMeansSettings::new(3);
        let r = kmeans_centres(x.as_ref(), &s, 1, Par::Seq).unwrap();
        assert_eq!(r.inertia, 0.0);
        assert!(r.centres.col(1).iter().all(|&v| v == 1.0));
    }

    /// The assignment does not depend on the parallelism, nor do the centres (bit for
    /// bit), and the maximum number of iterations is respected.
    #[test]
    fn lloyd_is_bit_identical_across_parallelism() {
        let x = Mat::from_fn(3000, 7, |i, j| {
            ((i * (j + 3)) as f64 * 0.0731).sin() * (1.0 + (i % 5) as f64)
        });
        let start = Mat::from_fn(130, 7, |i, j| x[(i * 23, j)]);
        let a = lloyd(x.as_ref(), start.as_ref(), 300, 1e-4, Par::Seq);
        let b = lloyd(x.as_ref(), start.as_ref(), 300, 1e-4, Par::rayon(2));
        assert_eq!(a.centres, b.centres);
        assert_eq!(a.memberships, b.memberships);
        assert_eq!(a.inertia, b.inertia);
        let two = lloyd(x.as_ref(), start.as_ref(), 2, 1e-4, Par::Seq);
        assert_eq!(two.iterations, Some(2));
        assert!(a.iterations.unwrap() > 2 && a.inertia <= two.inertia);
    }

    /// The memberships are the nearest final centroids, and the inertia is theirs.
    #[test]
    fn memberships_and_inertia_belong_to_the_final_centres() {
        let x = Mat::from_fn(500, 4, |i, j| ((i * (j + 1)) as f64 * 0.917).sin());
        for (alg, max_iterations) in [
            (KMeansAlgorithm::Lloyd, 300),
            (KMeansAlgorithm::Lloyd, 3),
            (KMeansAlgorithm::Linfa, 300),
        ] {
            let s = KMeansSettings {
                max_iterations,
                ..KMeansSettings::new(12).algorithm(alg)
            };
            let r = kmeans_centres(x.as_ref(), &s, 5, Par::Seq).unwrap();
            let mut total = 0.0;
            for i in 0..500 {
                let d2 = |c: usize| {
                    (0..4)
                        .map(|t| (x[(i, t)] - r.centres[(c, t)]).powi(2))
                        .sum::<f64>()
                };
                let best = (0..12).map(d2).fold(f64::INFINITY, f64::min);
                let own = d2(r.memberships[i]);
                assert!(own <= best * (1.0 + 1e-12) + 1e-14, "{alg} sample {i}");
                total += own;
            }
            assert!((r.inertia - total / 500.0).abs() < 1e-12, "{alg}");
        }
    }
}
