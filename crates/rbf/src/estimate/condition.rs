//! 1-norm condition estimates without forming an inverse (Hager 1984, with Higham's
//! 1988 extra probe), O(n²) per probe for triangular or factored matrices.

use faer::MatRef;

/// Estimates ‖A⁻¹‖₁ given solvers for A x = b and Aᵀ x = b (in place).
pub(crate) fn inverse_one_norm(
    n: usize,
    mut solve: impl FnMut(&mut [f64]),
    mut solve_t: impl FnMut(&mut [f64]),
) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let mut x = vec![1.0 / n as f64; n];
    let mut est = 0.0;
    let mut last_j = usize::MAX;
    for iter in 0..5 {
        let mut y = x.clone();
        solve(&mut y);
        est = y.iter().map(|v| v.abs()).sum::<f64>();
        let mut z: Vec<f64> = y
            .iter()
            .map(|&v| if v >= 0.0 { 1.0 } else { -1.0 })
            .collect();
        solve_t(&mut z);
        let (j, zmax) = z
            .iter()
            .enumerate()
            .fold((0, f64::NEG_INFINITY), |(bj, bv), (j, v)| {
                if v.abs() > bv { (j, v.abs()) } else { (bj, bv) }
            });
        let ztx: f64 = z.iter().zip(&x).map(|(a, b)| a * b).sum();
        if iter > 0 && (zmax <= ztx || j == last_j) {
            break;
        }
        last_j = j;
        x.fill(0.0);
        x[j] = 1.0;
    }
    // Higham's alternating probe catches matrices that fool the power iteration.
    let mut b: Vec<f64> = (0..n)
        .map(|i| {
            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
            s * (1.0 + i as f64 / (n.max(2) - 1) as f64)
        })
        .collect();
    solve(&mut b);
    let alt = 2.0 * b.iter().map(|v| v.abs()).sum::<f64>() / (3.0 * n as f64);
    est.max(alt)
}

/// κ₁ estimate of an upper-triangular `r` (k × k, only the upper triangle is read).
pub(crate) fn upper_triangular_condition(r: MatRef<'_, f64>) -> f64 {
    let k = r.ncols();
    if k == 0 {
        return 1.0;
    }
    let norm = (0..k)
        .map(|j| (0..=j).map(|i| r[(i, j)].abs()).sum::<f64>())
        .fold(0.0, f64::max);
    let inv = inverse_one_norm(
        k,
        |v| {
            // back substitution R x = v
            for i in (0..k).rev() {
                let mut s = v[i];
                for j in i + 1..k {
                    s -= r[(i, j)] * v[j];
                }
                v[i] = s / r[(i, i)];
            }
        },
        |v| {
            // forward substitution Rᵀ x = v
            for i in 0..k {
                let mut s = v[i];
                for j in 0..i {
                    s -= r[(j, i)] * v[j];
                }
                v[i] = s / r[(i, i)];
            }
        },
    );
    norm * inv
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// For a diagonal matrix the estimate is exact: max|d| / min|d|.
    #[test]
    fn diagonal_is_exact() {
        let r = Mat::from_fn(5, 5, |i, j| {
            if i == j {
                [1.0, 1e-3, 5.0, 2.0, 0.5][i]
            } else {
                0.0
            }
        });
        let c = upper_triangular_condition(r.as_ref());
        assert!((c / 5e3 - 1.0).abs() < 1e-12, "{c}");
    }

    /// On a classic ill-conditioned triangle (ones above the diagonal, -1 style growth)
    /// the estimate is within a factor 3 of the exact 1-norm condition number.
    #[test]
    fn close_to_exact_on_a_triangle() {
        let k = 12;
        let r = Mat::from_fn(k, k, |i, j| {
            if i == j {
                1.0
            } else if j > i {
                -1.0
            } else {
                0.0
            }
        });
        // exact inverse: entries 2^(j-i-1) above the diagonal
        let inv_norm = (0..k)
            .map(|j| 1.0 + (0..j).map(|i| 2f64.powi((j - i - 1) as i32)).sum::<f64>())
            .fold(0.0, f64::max);
        let norm = k as f64;
        let exact = norm * inv_norm;
        let est = upper_triangular_condition(r.as_ref());
        assert!(
            est <= exact * (1.0 + 1e-12) && est >= exact / 3.0,
            "{est} vs {exact}"
        );
    }
}
