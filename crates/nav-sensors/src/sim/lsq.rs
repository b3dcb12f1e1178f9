//! Least-squares fitted values by Householder QR, with rank detection.
//!
//! The noise floor needs the projection of a few series onto the span of a
//! few dozen feature columns, thousands of rows long, some of them exactly
//! dependent (a constant level gain, fully correlated shaker axes, a quiet
//! record whose features are all zero). Normal equations square the
//! condition number; nalgebra's `ColPivQR` pivots on the largest element
//! rather than the largest column norm and is not rank-revealing. So this is
//! the textbook Householder QR (Golub & Van Loan §5.2) in the given column
//! order, dropping a column whose part outside the span of the columns
//! before it is below `RANK_TOL` of its norm, with the fitted values formed
//! as `Q·[Qᵀy restricted to the kept directions]`. No coefficient is ever
//! solved for, so dropped or nearly dependent columns cannot blow up.

/// Relative size below which a column counts as a combination of the
/// columns before it.
const RANK_TOL: f64 = 1e-9;

/// Dot product with four partial sums (vectorises; the order of summation
/// is fixed, so results are deterministic).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            s[k] += x[k] * y[k];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

/// `y ← y − beta·(vᵀy)·v`: one Householder reflection on rows `k..`.
#[inline]
fn reflect(v: &[f64], beta: f64, y: &mut [f64]) {
    let s = beta * dot(v, y);
    for (yi, vi) in y.iter_mut().zip(v) {
        *yi -= s * vi;
    }
}

/// Least-squares fitted values of each target on the span of `columns` (all
/// of one length): `ŷ = A·argmin‖y − A·x‖`, with A's dependent columns
/// dropped. Returns the fitted series and the rank used.
pub(crate) fn fitted(mut columns: Vec<Vec<f64>>, targets: &[&[f64]]) -> (Vec<Vec<f64>>, usize) {
    let n = targets.first().map_or(0, |t| t.len());
    debug_assert!(columns.iter().all(|c| c.len() == n));
    let mut qty: Vec<Vec<f64>> = targets.iter().map(|t| t.to_vec()).collect();
    // Householder vectors (rows k.. of the column they came from) and their
    // beta = 2/(vᵀv); reflector k acts on rows k..n.
    let mut reflectors: Vec<(Vec<f64>, f64)> = Vec::new();
    let ncols = columns.len();
    for j in 0..ncols {
        let k = reflectors.len();
        if k == n {
            break;
        }
        let (done, rest) = columns.split_at_mut(j + 1);
        let col = &mut done[j];
        // Reflections preserve the norm: the whole column's norm is the
        // original one, rows k.. are what the kept columns do not explain.
        let total = dot(col, col).sqrt();
        let x = &mut col[k..];
        let remaining = dot(x, x).sqrt();
        let independent = remaining.is_finite() && remaining > RANK_TOL * total;
        if !independent {
            continue; // dependent (or zero, or not finite): drop
        }
        let alpha = if x[0] >= 0.0 { -remaining } else { remaining };
        x[0] -= alpha;
        let vtv = dot(x, x);
        let beta = 2.0 / vtv;
        for other in rest.iter_mut() {
            reflect(x, beta, &mut other[k..]);
        }
        for y in qty.iter_mut() {
            reflect(x, beta, &mut y[k..]);
        }
        reflectors.push((col[k..].to_vec(), beta));
    }
    let rank = reflectors.len();
    let fits = qty
        .into_iter()
        .map(|mut y| {
            y[rank..].iter_mut().for_each(|v| *v = 0.0);
            for (k, (v, beta)) in reflectors.iter().enumerate().rev() {
                reflect(v, *beta, &mut y[k..]);
            }
            y
        })
        .collect();
    (fits, rank)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// Uniform in [−0.5, 0.5): SplitMix64, so that nearby seeds give
    /// unrelated sequences.
    fn pseudo_random(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        (0..n)
            .map(|_| {
                s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut z = s;
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                z ^= z >> 31;
                (z >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    #[test]
    fn fitted_values_match_an_svd_least_squares_solution() {
        let n = 203;
        let cols: Vec<Vec<f64>> = (0..7).map(|j| pseudo_random(n, j + 1)).collect();
        let y = pseudo_random(n, 99);
        let (fit, rank) = fitted(cols.clone(), &[&y]);
        assert_eq!(rank, 7);
        let a = DMatrix::from_fn(n, 7, |i, j| cols[j][i]);
        let x = a
            .clone()
            .svd(true, true)
            .solve(&DVector::from_vec(y.clone()), 1e-12)
            .unwrap();
        let expect = &a * x;
        for i in 0..n {
            assert!((fit[0][i] - expect[i]).abs() < 1e-12, "{i}");
        }
        // The residual is orthogonal to every column.
        let r: Vec<f64> = y.iter().zip(&fit[0]).map(|(a, b)| a - b).collect();
        for c in &cols {
            assert!(dot(c, &r).abs() < 1e-12);
        }
    }

    #[test]
    fn dependent_and_zero_columns_are_dropped_without_changing_the_fit() {
        let n = 100;
        let a = pseudo_random(n, 1);
        let b = pseudo_random(n, 2);
        let sum: Vec<f64> = a.iter().zip(&b).map(|(x, y)| 3.0 * x - 0.5 * y).collect();
        let y = pseudo_random(n, 3);
        let (full, rank) = fitted(
            vec![a.clone(), vec![0.0; n], b.clone(), sum, a.clone()],
            &[&y, &a],
        );
        assert_eq!(rank, 2);
        let (plain, _) = fitted(vec![a.clone(), b], &[&y]);
        for i in 0..n {
            assert!((full[0][i] - plain[0][i]).abs() < 1e-13);
            assert!((full[1][i] - a[i]).abs() < 1e-13); // a is in the span
        }
    }

    #[test]
    fn as_many_columns_as_rows_fit_exactly_and_no_columns_fit_nothing() {
        let n = 6;
        let cols: Vec<Vec<f64>> = (0..9).map(|j| pseudo_random(n, j + 10)).collect();
        let y = pseudo_random(n, 42);
        let (fit, rank) = fitted(cols, &[&y]);
        assert_eq!(rank, n);
        for i in 0..n {
            assert!((fit[0][i] - y[i]).abs() < 1e-12);
        }
        let (none, rank) = fitted(Vec::new(), &[&y]);
        assert_eq!(rank, 0);
        assert!(none[0].iter().all(|v| *v == 0.0));
    }
}
