//! Lloyd's iterations: assignment by one f32 faer product checked in f64, deterministic relocation of
//! empty clusters, centroids as plain means, scikit-learn's stopping rule.

use faer::{Mat, MatRef, Par};

use super::KMeansCentres;
use super::assign::Assigner;
use crate::widest::widest;

/// Mean squared distance of the rows of `x` to their assigned centres, computed
/// directly (O(n·d)).
pub(super) fn inertia(x: MatRef<'_, f64>, centres: MatRef<'_, f64>, memberships: &[usize]) -> f64 {
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
/// 1. *assignment*: every sample's nearest centroid, the lowest index on a tie, from
///    one f32 faer product of the mean-shifted samples and centroids (parallel as
///    `par`), the samples whose two nearest centroids f32 cannot tell apart checked
///    by f64 distances computed directly (`assign.rs`);
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
    let mut assigner = Assigner::new(x);
    let mut labels = vec![0usize; n];
    let mut nearest = vec![0.0; n];
    let mut previous = vec![usize::MAX; n];
    let mut counts = vec![0usize; k];
    // x row by row: the columns of its transpose (one faer copy).
    let rows = x.transpose().to_owned();
    let mut sums = vec![0.0; k * d];
    let mut unchanged = false;
    let mut iterations = 0;
    while iterations < max_iterations {
        iterations += 1;
        assigner.assign(x, centres.as_ref(), &mut labels, par);
        count(&labels, &mut counts);
        if counts.contains(&0) {
            // the relocation needs every sample's distance to its centroid
            to_own(rows.as_ref(), centres.as_ref(), &labels, &mut nearest);
            relocate_empty(&mut labels, &mut nearest, &mut counts);
        }
        means(rows.as_ref(), &labels, &counts, &mut sums, &mut next);
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
        assigner.assign(x, centres.as_ref(), &mut labels, par);
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

/// The members of every cluster.
fn count(labels: &[usize], counts: &mut [usize]) {
    counts.fill(0);
    for &l in labels {
        counts[l] += 1;
    }
}

/// Every sample's squared distance to its centroid, computed directly (`rows`: the
/// samples as columns, d × n).
fn to_own(rows: MatRef<'_, f64>, centres: MatRef<'_, f64>, labels: &[usize], out: &mut [f64]) {
    for (i, (&a, o)) in labels.iter().zip(out.iter_mut()).enumerate() {
        *o = (0..rows.nrows())
            .map(|t| (rows[(t, i)] - centres[(a, t)]).powi(2))
            .sum();
    }
}

/// Counts the members of every cluster and gives each empty cluster, in index order,
/// the sample farthest from its centroid among clusters with at least two members
/// (the lowest index on a tie). With k ≤ n such a cluster always exists.
fn relocate_empty(labels: &mut [usize], nearest: &mut [f64], counts: &mut [usize]) {
    count(labels, counts);
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

/// Centroids as the plain means of their members (every cluster has one). `rows` is
/// the transpose of `x` (d × n, a sample per column): a sample's columns are added to
/// its cluster's sums together, so a run of samples of one cluster is d independent
/// sums rather than one chain through memory; each sum still adds its members in row
/// order.
fn means(
    rows: MatRef<'_, f64>,
    labels: &[usize],
    counts: &[usize],
    sums: &mut [f64],
    out: &mut Mat<f64>,
) {
    let d = out.ncols();
    sums.fill(0.0);
    if d > 0 {
        for (i, &l) in labels.iter().enumerate() {
            let row = rows
                .col(i)
                .try_as_col_major()
                .expect("an owned matrix has contiguous columns")
                .as_slice();
            add_to(&mut sums[l * d..(l + 1) * d], row);
        }
    }
    for (j, &c) in counts.iter().enumerate() {
        let inv = 1.0 / c as f64;
        for t in 0..d {
            out[(j, t)] = sums[j * d + t] * inv;
        }
    }
}

widest! {
    /// `acc += row`, element by element.
    fn add_to(acc: &mut [f64], row: &[f64]) {
        for (a, &v) in acc.iter_mut().zip(row) {
            *a += v;
        }
    }
}
