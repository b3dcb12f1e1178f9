//! The seeded start of k-means: k-means++ (D² sampling).

use faer::MatRef;
use ndarray::Array2;
use rand::Rng;
use rand::distributions::{Distribution, WeightedIndex};

use crate::widest::widest;

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
    squared_distances_to_rows(x, &[i], &mut [out]);
}

/// Squared distances of every row of `x` to each row `ids[t]` of `x`, into `outs[t]`.
/// Each distance is summed over the columns in order from 0, exactly as one row at a
/// time would sum it, but one sweep over `x` serves every row of `ids` (greedy
/// k-means++ asks for 2 + ln k of them at each step): sixteen rows at a time, their
/// sums for three centres kept in registers while the columns are read once (2 + ln k
/// trials: six for k = 100).
fn squared_distances_to_rows(x: MatRef<'_, f64>, ids: &[usize], outs: &mut [&mut [f64]]) {
    let (n, d) = (x.nrows(), x.ncols());
    let owned;
    let x = if (0..d).all(|j| x.col(j).try_as_col_major().is_some()) {
        x
    } else {
        owned = x.to_owned();
        owned.as_ref()
    };
    let cols: Vec<&[f64]> = (0..d)
        .map(|j| x.col(j).try_as_col_major().expect("contiguous").as_slice())
        .collect();
    for (group, outs) in ids.chunks(GROUP).zip(outs.chunks_mut(GROUP)) {
        // A short last group repeats its first centre; those sums are not kept.
        let centres: [Vec<f64>; GROUP] = std::array::from_fn(|t| {
            let i = group[t.min(group.len() - 1)];
            (0..d).map(|j| x[(i, j)]).collect()
        });
        let blocks = n / ROWS;
        let mut sums = [[0.0f64; ROWS]; GROUP];
        for b in 0..blocks {
            block_distances(&cols, ROWS * b, &centres, &mut sums);
            for (out, s) in outs.iter_mut().zip(&sums) {
                out[ROWS * b..ROWS * (b + 1)].copy_from_slice(s);
            }
        }
        for r in ROWS * blocks..n {
            for (out, c) in outs.iter_mut().zip(&centres) {
                let mut acc = 0.0;
                for (col, &cj) in cols.iter().zip(c) {
                    let v = col[r] - cj;
                    acc += v * v;
                }
                out[r] = acc;
            }
        }
    }
}

/// Centres whose distances one sweep keeps in registers.
const GROUP: usize = 3;
/// Rows a sweep keeps in registers: two AVX-512 registers a centre, so six
/// independent sums hide the additions' latency.
const ROWS: usize = 16;

widest! {
    /// The squared distances of rows `r..r + ROWS` to the centres, into `sums`; each
    /// lane sums its row's columns in order.
    fn block_distances(
        cols: &[&[f64]],
        r: usize,
        centres: &[Vec<f64>; GROUP],
        sums: &mut [[f64; ROWS]; GROUP],
    ) {
        let mut acc = [[0.0f64; ROWS]; GROUP];
        for (j, col) in cols.iter().enumerate() {
            let x: &[f64; ROWS] = col[r..r + ROWS].try_into().expect("a block of rows");
            for (a, c) in acc.iter_mut().zip(centres) {
                let cj = c[j];
                for l in 0..ROWS {
                    let v = x[l] - cj;
                    a[l] += v * v;
                }
            }
        }
        *sums = acc;
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
    let mut candidates = vec![vec![0.0; n]; trials];
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
        // The draws depend on the potential only: all of them first, then the trials'
        // distances in one sweep over x.
        let ids: Vec<usize> = (0..trials)
            .map(|_| {
                let r = rng.r#gen::<f64>() * potential;
                // np.searchsorted(cumsum, r) (side "left"), clipped to n − 1
                cumulative.partition_point(|&s| s < r).min(n - 1)
            })
            .collect();
        {
            let mut outs: Vec<&mut [f64]> = candidates.iter_mut().map(|v| &mut v[..]).collect();
            squared_distances_to_rows(x, &ids, &mut outs);
        }
        let mut best: Option<(f64, usize)> = None;
        for (candidate, &id) in candidates.iter_mut().zip(&ids) {
            let pot = min_and_sum(candidate, &nearest);
            if best.is_none_or(|(b, _)| pot < b) {
                best = Some((pot, id));
                best_dist.copy_from_slice(candidate);
            }
        }
        let (pot, id) = best.expect("at least two trials");
        potential = pot;
        chosen = id;
        std::mem::swap(&mut nearest, &mut best_dist);
    }
    centres
}

/// Partial sums of a trial's potential.
const LANES: usize = 8;

/// `v ← min(v, m)` element by element, and the sum of the new `v` in
/// [`LANES`] partial sums (element i into sum i mod 8) added pairwise, not
/// one serial chain of n dependent additions per trial. The potentials
/// compared differ from a serial sum in the last bits only (the bench data's
/// centres are the same to the bit).
fn min_and_sum(v: &mut [f64], m: &[f64]) -> f64 {
    let mut acc = [0.0f64; LANES];
    let mut vs = v.chunks_exact_mut(LANES);
    let mut ms = m.chunks_exact(LANES);
    for (v8, m8) in (&mut vs).zip(&mut ms) {
        for ((x, &y), a) in v8.iter_mut().zip(m8).zip(acc.iter_mut()) {
            *x = x.min(y);
            *a += *x;
        }
    }
    for ((x, &y), a) in vs
        .into_remainder()
        .iter_mut()
        .zip(ms.remainder())
        .zip(acc.iter_mut())
    {
        *x = x.min(y);
        *a += *x;
    }
    let mut w = LANES;
    while w > 1 {
        w /= 2;
        for i in 0..w {
            acc[i] += acc[i + w];
        }
    }
    acc[0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// One sweep for several centres gives, to the bit, the row-at-a-time sums over the
    /// columns in order (the seeding's choices, and so the centres, must not depend on
    /// how the distances are blocked): row counts with and without a partial block,
    /// one to seven centres (partial groups), and a row-major view of x.
    #[test]
    fn blocked_distances_equal_row_by_row_sums() {
        for &(n, d) in &[(37usize, 5usize), (16, 3), (100, 50), (7, 1)] {
            let x = Mat::from_fn(n, d, |i, j| {
                ((i * 7 + j * 13) as f64 * 0.173).sin() * (1.0 + j as f64)
            });
            let xt = x.transpose().to_owned();
            for t in 1..=7usize {
                let ids: Vec<usize> = (0..t).map(|k| (k * 5) % n).collect();
                for view in [x.as_ref(), xt.as_ref().transpose()] {
                    let mut outs = vec![vec![f64::NAN; n]; t];
                    let mut refs: Vec<&mut [f64]> = outs.iter_mut().map(|v| &mut v[..]).collect();
                    squared_distances_to_rows(view, &ids, &mut refs);
                    for (out, &c) in outs.iter().zip(&ids) {
                        for (r, &got) in out.iter().enumerate() {
                            let mut want = 0.0;
                            for j in 0..d {
                                let v = x[(r, j)] - x[(c, j)];
                                want += v * v;
                            }
                            assert_eq!(
                                got.to_bits(),
                                want.to_bits(),
                                "n {n}, d {d}, row {r}, centre {c}"
                            );
                        }
                    }
                }
            }
        }
    }
}
