//! The seeded start of k-means: k-means++ (D² sampling).

use faer::MatRef;
use ndarray::Array2;
use rand::Rng;
use rand::distributions::{Distribution, WeightedIndex};

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
        // squared distances to the new centre (row `next` of x), column by column
        squared_distances_to_row(x, next, &mut dist);
        for (m, &v) in nearest.iter_mut().zip(&dist) {
            *m = m.min(v);
        }
        next = WeightedIndex::new(nearest.iter())
            .map(|w| w.sample(rng))
            .unwrap_or(0);
    }
    centres
}

/// Squared distances of every row of `x` to row `i` of `x`, into `out` (column by
/// column, contiguous in faer).
fn squared_distances_to_row(x: MatRef<'_, f64>, i: usize, out: &mut [f64]) {
    out.fill(0.0);
    for j in 0..x.ncols() {
        let col = x.col(j);
        let cj = col[i];
        match col.try_as_col_major() {
            Some(col) => {
                for (acc, &xi) in out.iter_mut().zip(col.as_slice()) {
                    let v = xi - cj;
                    *acc += v * v;
                }
            }
            None => {
                for (r, acc) in out.iter_mut().enumerate() {
                    let v = col[r] - cj;
                    *acc += v * v;
                }
            }
        }
    }
}

/// Greedy k-means++, scikit-learn's default seeding (`sklearn.cluster.kmeans_plusplus`,
/// after Arthur & Vassilvitskii 2007 §5): the first centre is a uniformly drawn sample;
/// for each next one, 2 + ⌊ln k⌋ candidates are drawn with probability proportional to
/// their squared distance to the nearest centre so far, and the candidate that leaves
/// the smallest potential (sum of nearest squared distances) is kept. linfa-clustering
/// 0.8 has k-means++ and k-means|| but no greedy variant, so it is written here.
///
/// Costs O(n·k·d·(2 + ln k)). When every remaining distance is 0 (fewer distinct samples
/// than k), the candidates are the last sample, as scikit-learn's clipped search gives.
///
/// # Panics
/// If `x` has fewer than `k` rows or `k` is 0 (checked by the caller).
///
/// ```
/// use rand::SeedableRng;
/// let x = faer::Mat::from_fn(60, 1, |i, _| (i / 20) as f64 * 100.0 + (i % 20) as f64 * 0.01);
/// let mut rng = rand_xoshiro::Xoshiro256Plus::seed_from_u64(1);
/// let c = rbf::select::kmeans::greedy_kmeans_plusplus(x.as_ref(), 3, &mut rng);
/// let mut groups: Vec<i64> = (0..3).map(|i| (c[[i, 0]] / 100.0).round() as i64).collect();
/// groups.sort();
/// assert_eq!(groups, vec![0, 1, 2]);
/// ```
#[track_caller]
pub fn greedy_kmeans_plusplus(x: MatRef<'_, f64>, k: usize, rng: &mut impl Rng) -> Array2<f64> {
    let (n, d) = (x.nrows(), x.ncols());
    assert!(
        k >= 1 && n >= k,
        "k-means++ needs 1 ≤ k ≤ n (k = {k}, n = {n})"
    );
    // scikit-learn: n_local_trials = 2 + int(np.log(n_clusters))
    let trials = 2 + (k as f64).ln() as usize;
    let mut centres = Array2::<f64>::zeros((k, d));
    let first = rng.gen_range(0..n);
    let mut nearest = vec![0.0; n];
    squared_distances_to_row(x, first, &mut nearest);
    let mut potential: f64 = nearest.iter().sum();
    let mut cumulative = vec![0.0; n];
    let mut candidate = vec![0.0; n];
    let mut best_dist = vec![0.0; n];
    let mut chosen = first;
    for c in 0..k {
        for j in 0..d {
            centres[[c, j]] = x[(chosen, j)];
        }
        if c + 1 == k {
            break;
        }
        let mut acc = 0.0;
        for (s, &v) in cumulative.iter_mut().zip(&nearest) {
            acc += v;
            *s = acc;
        }
        let mut best: Option<(f64, usize)> = None;
        for _ in 0..trials {
            let r = rng.r#gen::<f64>() * potential;
            // np.searchsorted(cumsum, r) (side "left"), clipped to n − 1
            let id = cumulative.partition_point(|&s| s < r).min(n - 1);
            squared_distances_to_row(x, id, &mut candidate);
            let mut pot = 0.0;
            for (v, &m) in candidate.iter_mut().zip(&nearest) {
                *v = v.min(m);
                pot += *v;
            }
            if best.is_none_or(|(b, _)| pot < b) {
                best = Some((pot, id));
                best_dist.copy_from_slice(&candidate);
            }
        }
        let (pot, id) = best.expect("at least two trials");
        potential = pot;
        chosen = id;
        std::mem::swap(&mut nearest, &mut best_dist);
    }
    centres
}
