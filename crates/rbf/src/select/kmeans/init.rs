//! The seeded start of k-means: k-means++ (D² sampling).

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};
use ndarray::Array2;
use rand::Rng;
use rand::distributions::{Distribution, WeightedIndex};

use crate::widest::widest_fma;

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
    let mut samples = Centred::new(x);
    let mut next = rng.gen_range(0..n);
    for c in 0..k {
        for j in 0..d {
            centres[[c, j]] = x[(next, j)];
        }
        if c + 1 == k {
            break;
        }
        // squared distances to the new centre (row `next` of x)
        samples.squared_distances(&[next], &mut [&mut dist]);
        for (m, &v) in nearest.iter_mut().zip(&dist) {
            *m = m.min(v);
        }
        next = WeightedIndex::new(nearest.iter())
            .map(|w| w.sample(rng))
            .unwrap_or(0);
    }
    centres
}

/// The samples shifted by their column means, with their squared norms: squared
/// distances between samples then come from one faer product per step,
/// ‖x̃ᵢ‖² + ‖x̃ⱼ‖² − 2·x̃ᵢ·x̃ⱼ (scikit-learn's `euclidean_distances` does the same), one
/// multiply–add an element in the product's kernels where the difference form took a
/// subtraction, a multiplication and an addition (the seeding's time on the peer data:
/// 7.0 → 4.3 ms).
///
/// Cancellation: the result's rounding error is about (d + 2)·ε·(‖x̃ᵢ‖² + ‖x̃ⱼ‖²),
/// which the shift keeps at the scale of the data's spread, not of its offset (a test
/// measures it on data offset by 10⁶). The seeding only weighs samples by these
/// distances and sums them into potentials, where an error of 10⁻¹⁴ of the spread
/// changes no draw but one that falls within that much of a boundary; no assignment is
/// decided by them (Lloyd's iterations compute their own). A sample's distance to
/// itself is set to exactly 0; two equal samples get 0 up to that rounding bound (an
/// all-equal data set shifts to zeros: potential exactly 0).
pub(super) struct Centred {
    /// n × d.
    xs: Mat<f64>,
    norms: Vec<f64>,
    /// The samples asked for, d × t (kept between calls).
    picked: Mat<f64>,
    /// Their products with every sample, n × t.
    products: Mat<f64>,
}

impl Centred {
    pub(super) fn new(x: MatRef<'_, f64>) -> Self {
        let (n, d) = (x.nrows(), x.ncols());
        let mut xs = Mat::<f64>::zeros(n, d);
        for j in 0..d {
            let mean = (0..n).map(|i| x[(i, j)]).sum::<f64>() / n.max(1) as f64;
            for i in 0..n {
                xs[(i, j)] = x[(i, j)] - mean;
            }
        }
        let mut norms = vec![0.0; n];
        for j in 0..d {
            add_squares(&mut norms, xs.col_as_slice(j));
        }
        Self {
            xs,
            norms,
            picked: Mat::zeros(0, 0),
            products: Mat::zeros(0, 0),
        }
    }

    /// Squared distances of every sample to each sample `ids[t]`, into `outs[t]`: the
    /// products of all of them in one faer product (a sample's distance to itself is
    /// set to 0).
    pub(super) fn squared_distances(&mut self, ids: &[usize], outs: &mut [&mut [f64]]) {
        let (n, d, t) = (self.xs.nrows(), self.xs.ncols(), ids.len());
        if (self.picked.nrows(), self.picked.ncols()) != (d, t) {
            self.picked = Mat::zeros(d, t);
            self.products = Mat::zeros(n, t);
        }
        for (c, &id) in ids.iter().enumerate() {
            for j in 0..d {
                self.picked[(j, c)] = self.xs[(id, j)];
            }
        }
        matmul(
            self.products.as_mut(),
            Accum::Replace,
            self.xs.as_ref(),
            self.picked.as_ref(),
            1.0,
            Par::Seq,
        );
        for ((out, &id), c) in outs.iter_mut().zip(ids).zip(0..) {
            finish(
                out,
                &self.norms,
                self.norms[id],
                self.products.col_as_slice(c),
            );
            out[id] = 0.0;
        }
    }
}

widest_fma! {
    /// ‖a − b‖² = ‖a‖² + ‖b‖² − 2·a·b for every sample a, tiny negative results of the
    /// cancellation clamped to 0.
    fn finish(out: &mut [f64], norms: &[f64], bn: f64, products: &[f64]) {
        for ((o, &an), &ab) in out.iter_mut().zip(norms).zip(products) {
            *o = (-2.0f64).mul_add(ab, an + bn).max(0.0);
        }
    }
}

widest_fma! {
    /// `norms += col²`, element by element.
    fn add_squares(norms: &mut [f64], col: &[f64]) {
        for (m, &v) in norms.iter_mut().zip(col) {
            *m = v.mul_add(v, *m);
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
    let mut samples = Centred::new(x);
    let first = rng.gen_range(0..n);
    let mut nearest = vec![0.0; n];
    samples.squared_distances(&[first], &mut [&mut nearest]);
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
            samples.squared_distances(&ids, &mut outs);
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

    /// The direct squared distances of rows `r` and `c` of `x`.
    fn direct(x: MatRef<'_, f64>, r: usize, c: usize) -> f64 {
        (0..x.ncols())
            .map(|j| (x[(r, j)] - x[(c, j)]).powi(2))
            .sum()
    }

    /// The product form gives the direct squared distances to its rounding bound,
    /// (d + 2)·ε·(‖x̃ᵣ‖² + ‖x̃ᵢ‖²), and 0 for a sample and itself; for any number of
    /// samples asked at once, for a row-major view of x, and again after the buffers
    /// were sized for another count.
    #[test]
    fn product_distances_are_the_direct_ones() {
        for &(n, d) in &[(37usize, 5usize), (16, 3), (100, 50), (7, 1)] {
            let x = Mat::from_fn(n, d, |i, j| {
                ((i * 7 + j * 13) as f64 * 0.173).sin() * (1.0 + j as f64)
            });
            let xt = x.transpose().to_owned();
            for view in [x.as_ref(), xt.as_ref().transpose()] {
                let mut c = Centred::new(view);
                for t in [1usize, 6, 13, 2] {
                    let ids: Vec<usize> = (0..t).map(|k| (k * 5) % n).collect();
                    let mut outs = vec![vec![f64::NAN; n]; t];
                    let mut refs: Vec<&mut [f64]> = outs.iter_mut().map(|v| &mut v[..]).collect();
                    c.squared_distances(&ids, &mut refs);
                    for (out, &id) in outs.iter().zip(&ids) {
                        for (r, &got) in out.iter().enumerate() {
                            let bound =
                                (d as f64 + 2.0) * f64::EPSILON * (c.norms[r] + c.norms[id]);
                            let want = direct(x.as_ref(), r, id);
                            assert!(
                                (got - want).abs() <= bound + 1e-300,
                                "n {n}, d {d}, row {r}, sample {id}: {got} vs {want}"
                            );
                        }
                        assert_eq!(out[id], 0.0, "a sample's distance to itself");
                    }
                }
            }
        }
    }

    /// The product form loses nothing to the data's offset: samples 10⁶ from the
    /// origin, spread over about 1, get their direct squared distances to 1e-9 (the
    /// product of the raw samples would be off by about 50·ε·10¹² ≈ 10⁻²).
    #[test]
    fn product_distances_survive_a_large_offset() {
        let (n, d) = (200, 50);
        let x = Mat::from_fn(n, d, |i, j| 1e6 + ((i * 31 + j * 17) as f64 * 0.377).sin());
        let mut c = Centred::new(x.as_ref());
        let ids = [0, 3, 77, 199];
        let mut outs = vec![vec![0.0; n]; ids.len()];
        let mut refs: Vec<&mut [f64]> = outs.iter_mut().map(|v| &mut v[..]).collect();
        c.squared_distances(&ids, &mut refs);
        for (out, &id) in outs.iter().zip(&ids) {
            for (r, &got) in out.iter().enumerate() {
                let want = direct(x.as_ref(), r, id);
                assert!(
                    (got - want).abs() <= 1e-9 * want.max(1.0),
                    "row {r}, sample {id}: {got} vs {want}"
                );
            }
        }
    }
}
