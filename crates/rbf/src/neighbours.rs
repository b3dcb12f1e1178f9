//! Nearest-neighbour and pairwise distances between centres, for the width heuristics.
//!
//! A k-d tree (kiddo) pays off in low dimension only; it takes the dimension as a const
//! generic, so [`nearest_neighbour_distances`] dispatches on the runtime dimension for
//! d = 1..=10 and uses brute force through faer products above (at d = 50 a tree is no
//! faster than brute force: it must visit most leaves).

use std::num::NonZeroUsize;

use faer::linalg::matmul::matmul;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Accum, Mat, MatRef, Par};
use kiddo::{ImmutableKdTree, SquaredEuclidean};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256Plus;

use crate::parallel::for_each_chunk_mut;

/// Highest dimension served by the k-d tree.
///
/// ```
/// assert_eq!(rbf::neighbours::KD_TREE_MAX_DIM, 10);
/// ```
pub const KD_TREE_MAX_DIM: usize = 10;

/// Euclidean distance from every row of `points` to its nearest *other* row
/// (0 for duplicated points, +∞ when there is a single point).
///
/// ```
/// use faer::{mat, Par};
/// let p = mat![[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]];
/// let d = rbf::neighbours::nearest_neighbour_distances(p.as_ref(), Par::Seq);
/// assert_eq!(d, vec![5.0, 1.0, 1.0]);
/// ```
pub fn nearest_neighbour_distances(points: MatRef<'_, f64>, par: Par) -> Vec<f64> {
    kd_tree_nearest(points).unwrap_or_else(|| brute_force_nearest(points, par))
}

/// Nearest-other-point distances with a kiddo k-d tree; `None` when the dimension is
/// 0 or above [`KD_TREE_MAX_DIM`] (or the tree cannot be built).
///
/// ```
/// use faer::mat;
/// let p = mat![[0.0], [1.0], [3.0]];
/// assert_eq!(rbf::neighbours::kd_tree_nearest(p.as_ref()), Some(vec![1.0, 1.0, 2.0]));
/// ```
pub fn kd_tree_nearest(points: MatRef<'_, f64>) -> Option<Vec<f64>> {
    match points.ncols() {
        1 => kd::<1>(points),
        2 => kd::<2>(points),
        3 => kd::<3>(points),
        4 => kd::<4>(points),
        5 => kd::<5>(points),
        6 => kd::<6>(points),
        7 => kd::<7>(points),
        8 => kd::<8>(points),
        9 => kd::<9>(points),
        10 => kd::<10>(points),
        _ => None,
    }
}

fn kd<const D: usize>(points: MatRef<'_, f64>) -> Option<Vec<f64>> {
    let n = points.nrows();
    if n < 2 {
        return Some(vec![f64::INFINITY; n]);
    }
    if n > u32::MAX as usize {
        return None;
    }
    let rows: Vec<[f64; D]> = (0..n)
        .map(|i| std::array::from_fn(|k| points[(i, k)]))
        .collect();
    let tree = ImmutableKdTree::<f64, D>::new_from_slice(&rows).ok()?;
    let two = NonZeroUsize::new(2).expect("2 > 0");
    let out = rows
        .iter()
        .enumerate()
        .map(|(i, q)| {
            let found = tree
                .query(q)
                .nearest_n::<SquaredEuclidean<f64>>(two)
                .execute();
            // The point itself is among the two nearest; with duplicates either may come first.
            found
                .iter()
                .find(|r| r.item as usize != i)
                .map_or(f64::INFINITY, |r| r.distance.sqrt())
        })
        .collect();
    Some(out)
}

/// Nearest-other-point distances by brute force: blocks of rows against all rows through
/// one faer product each (‖a‖² + ‖b‖² − 2a·b after shifting by the mean).
///
/// ```
/// use faer::{mat, Par};
/// let p = mat![[0.0], [1.0], [3.0]];
/// assert_eq!(rbf::neighbours::brute_force_nearest(p.as_ref(), Par::Seq), vec![1.0, 1.0, 2.0]);
/// ```
pub fn brute_force_nearest(points: MatRef<'_, f64>, par: Par) -> Vec<f64> {
    let (n, d) = (points.nrows(), points.ncols());
    if n < 2 {
        return vec![f64::INFINITY; n];
    }
    let centred = centred(points);
    let norms: Vec<f64> = (0..n)
        .map(|i| (0..d).map(|k| centred[(i, k)].powi(2)).sum())
        .collect();
    let mut out = vec![f64::INFINITY; n];
    // Blocks bound the scratch to block × n doubles whatever n is.
    const BLOCK: usize = 256;
    let mut g = Mat::<f64>::zeros(BLOCK.min(n), n);
    for start in (0..n).step_by(BLOCK) {
        let b = BLOCK.min(n - start);
        let mut gb = g.as_mut().subrows_mut(0, b);
        matmul(
            gb.rb_mut(),
            Accum::Replace,
            centred.as_ref().subrows(start, b),
            centred.transpose(),
            -2.0,
            par,
        );
        let gb = gb.rb();
        for_each_chunk_mut(&mut out[start..start + b], par, 16, |off, chunk| {
            for (k, o) in chunk.iter_mut().enumerate() {
                let i = start + off + k;
                let mut best = f64::INFINITY;
                for j in 0..n {
                    if j != i {
                        let v = gb[(off + k, j)] + norms[i] + norms[j];
                        best = best.min(v);
                    }
                }
                *o = best.max(0.0).sqrt();
            }
        });
    }
    out
}

/// Median of the pairwise distances between rows; above `max_points` rows, of a seeded
/// random subsample of `max_points` rows (the median of a 1000-point subsample is within
/// a few per cent of the full one, at 1/n² of the cost). `None` with fewer than 2 rows.
///
/// ```
/// use faer::mat;
/// let p = mat![[0.0], [1.0], [3.0]];
/// // pairs: 1, 3, 2
/// assert_eq!(rbf::neighbours::median_pairwise_distance(p.as_ref(), 1000, 0), Some(2.0));
/// ```
pub fn median_pairwise_distance(
    points: MatRef<'_, f64>,
    max_points: usize,
    seed: u64,
) -> Option<f64> {
    let n = points.nrows();
    if n < 2 {
        return None;
    }
    let rows: Vec<usize> = if n > max_points.max(2) {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        let mut idx = rand::seq::index::sample(&mut rng, n, max_points.max(2)).into_vec();
        idx.sort_unstable();
        idx
    } else {
        (0..n).collect()
    };
    let d = points.ncols();
    let mut dist = Vec::with_capacity(rows.len() * (rows.len() - 1) / 2);
    for (a, &i) in rows.iter().enumerate() {
        for &j in &rows[a + 1..] {
            let s: f64 = (0..d)
                .map(|k| (points[(i, k)] - points[(j, k)]).powi(2))
                .sum();
            dist.push(s.sqrt());
        }
    }
    let mid = dist.len() / 2;
    let (_, m, _) = dist.select_nth_unstable_by(mid, f64::total_cmp);
    let upper = *m;
    if dist.len() % 2 == 1 {
        Some(upper)
    } else {
        let lower = dist[..mid]
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        Some(0.5 * (lower + upper))
    }
}

fn centred(points: MatRef<'_, f64>) -> Mat<f64> {
    let (n, d) = (points.nrows(), points.ncols());
    let mean: Vec<f64> = (0..d)
        .map(|k| (0..n).map(|i| points[(i, k)]).sum::<f64>() / n as f64)
        .collect();
    Mat::from_fn(n, d, |i, k| points[(i, k)] - mean[k])
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    /// The k-d tree and brute force agree for every dimension the tree serves.
    #[test]
    fn kd_tree_and_brute_force_agree() {
        let mut rng = Xoshiro256Plus::seed_from_u64(11);
        for d in 1..=KD_TREE_MAX_DIM {
            for &n in &[2usize, 3, 57, 300] {
                let p = Mat::from_fn(n, d, |_, _| rng.gen_range(-2.0..2.0));
                let a = kd_tree_nearest(p.as_ref()).unwrap();
                let b = brute_force_nearest(p.as_ref(), Par::rayon(2));
                for (x, y) in a.iter().zip(&b) {
                    // brute force goes through ‖a‖²+‖b‖²−2a·b: absolute error ~ ε·scale² in d².
                    assert!((x - y).abs() < 1e-6, "d={d} n={n}: {x} vs {y}");
                }
            }
        }
        assert!(kd_tree_nearest(Mat::<f64>::zeros(3, 11).as_ref()).is_none());
    }

    #[test]
    fn duplicates_have_zero_distance() {
        let p = faer::mat![[1.0, 2.0], [1.0, 2.0], [5.0, 5.0]];
        assert_eq!(kd_tree_nearest(p.as_ref()).unwrap()[..2], [0.0, 0.0]);
        assert_eq!(brute_force_nearest(p.as_ref(), Par::Seq)[..2], [0.0, 0.0]);
    }

    #[test]
    fn median_of_even_count_averages_the_middle_pair() {
        let p = faer::mat![[0.0], [1.0], [3.0], [7.0]];
        // pairs: 1 3 7 2 6 4 → sorted 1 2 3 4 6 7 → (3+4)/2
        assert_eq!(median_pairwise_distance(p.as_ref(), 100, 0), Some(3.5));
    }
}
