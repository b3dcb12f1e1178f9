//! Least squares min ‖A x − B‖² (+ λ‖x_penalised‖²) by column-pivoted Householder QR.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::matmul::matmul;
use faer::linalg::qr::col_pivoting::{factor as cpqr, solve as cpsolve};
use faer::linalg::qr::no_pivoting::factor::recommended_block_size;
use faer::{Accum, Mat, MatRef, Par};

use super::condition::upper_triangular_condition;
use super::error::SolveError;
use crate::check::first_non_finite;

/// Default limit on the estimated condition number: 1/(1000 ε) ≈ 4.5·10¹².
///
/// The relative forward error of a least-squares solution is at least of order κ·ε; at
/// this limit the coefficients keep about three significant digits. Beyond it the
/// weights are dominated by rounding (large, cancelling coefficients) even though the
/// fitted values may still look fine on the training data, so the fit is refused rather
/// than returned silently wrong. A ridge brings κ down.
///
/// ```
/// assert!(rbf::DEFAULT_MAX_CONDITION > 4e12 && rbf::DEFAULT_MAX_CONDITION < 5e12);
/// ```
pub const DEFAULT_MAX_CONDITION: f64 = 1.0 / (1000.0 * f64::EPSILON);

/// Options of [`lstsq`].
///
/// ```
/// let o = rbf::LstsqOptions { ridge: 1e-3, unpenalised: 1, ..Default::default() };
/// assert_eq!(o.rank_tol, None);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct LstsqOptions {
    /// Tikhonov λ ≥ 0: minimise ‖A x − B‖² + λ Σ x_j² over the penalised columns, solved
    /// as the augmented least-squares problem [A; √λ I] (never the normal equations).
    pub ridge: f64,
    /// The first `unpenalised` columns (bias, linear effects) are not shrunk by the ridge.
    pub unpenalised: usize,
    /// Rank tolerance: column k of the pivoted R counts if |R_kk| > tol·|R_11|.
    /// `None` uses max(rows, columns)·ε, the numpy `lstsq` convention.
    pub rank_tol: Option<f64>,
    /// Refuse solutions whose estimated condition number exceeds this
    /// (see [`DEFAULT_MAX_CONDITION`]); `f64::INFINITY` disables the check.
    pub max_condition: f64,
    /// Parallelism of the factorisation and products.
    pub par: Par,
}

impl Default for LstsqOptions {
    fn default() -> Self {
        Self {
            ridge: 0.0,
            unpenalised: 0,
            rank_tol: None,
            max_condition: DEFAULT_MAX_CONDITION,
            par: faer::get_global_parallelism(),
        }
    }
}

/// A least-squares solution.
///
/// ```
/// use faer::mat;
/// let a = mat![[1.0, 0.0], [0.0, 2.0], [0.0, 0.0]];
/// let b = mat![[1.0], [4.0], [3.0]];
/// let s = rbf::lstsq(a.as_ref(), b.as_ref(), &Default::default()).unwrap();
/// assert!((s.coefficients[(1, 0)] - 2.0).abs() < 1e-15);
/// assert!((s.residual_sum_squares[0] - 9.0).abs() < 1e-12);
/// assert_eq!(s.rank, 2);
/// ```
#[derive(Clone, Debug)]
pub struct Solution {
    /// Coefficients, columns × right-hand sides.
    pub coefficients: Mat<f64>,
    /// Numerical rank (equal to the number of columns on success).
    pub rank: usize,
    /// 1-norm condition estimate of the (augmented) matrix's R factor.
    pub condition: f64,
    /// ‖A x − b‖² per right-hand side, on the original rows (the ridge term excluded).
    pub residual_sum_squares: Vec<f64>,
}

/// Least squares for several right-hand sides at once: min ‖A X − B‖²_F (+ ridge).
///
/// Factorises A (or [A; √λ I] with a ridge) by column-pivoted Householder QR, reads the
/// numerical rank off |R_kk| ≤ tol·|R_11| and refuses rank-deficient problems naming the
/// dependent columns, estimates the condition number (Hager's 1-norm estimator on R) and
/// refuses it above `options.max_condition`.
///
/// # Errors
/// [`SolveError::NonFinite`], [`SolveError::Underdetermined`],
/// [`SolveError::RankDeficient`], [`SolveError::IllConditioned`],
/// [`SolveError::InvalidOption`].
///
/// # Panics
/// If `a` and `b` have different numbers of rows or `unpenalised > a.ncols()`.
///
/// ```
/// use faer::mat;
/// use rbf::{lstsq, LstsqOptions, SolveError};
/// // the third column duplicates the first: reported, not silently solved
/// let a = mat![[1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [1.0, 2.0, 1.0], [1.0, 3.0, 1.0]];
/// let b = mat![[1.0], [2.0], [3.0], [4.0]];
/// match lstsq(a.as_ref(), b.as_ref(), &LstsqOptions::default()) {
///     Err(SolveError::RankDeficient { rank: 2, columns: 3, dependent }) => assert_eq!(dependent.len(), 1),
///     other => panic!("{other:?}"),
/// }
/// // a ridge makes it solvable
/// let s = lstsq(a.as_ref(), b.as_ref(), &LstsqOptions { ridge: 1e-6, ..Default::default() }).unwrap();
/// assert!(s.residual_sum_squares[0] < 1e-9);
/// ```
#[track_caller]
pub fn lstsq(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    options: &LstsqOptions,
) -> Result<Solution, SolveError> {
    check_inputs(a, b, options)?;
    let (n, c, q) = (a.nrows(), a.ncols(), b.ncols());
    let par = options.par;
    if c == 0 {
        return Ok(Solution {
            coefficients: Mat::zeros(0, q),
            rank: 0,
            condition: 1.0,
            residual_sum_squares: (0..q)
                .map(|k| (0..n).map(|i| b[(i, k)].powi(2)).sum())
                .collect(),
        });
    }
    let (mut qr, mut rhs) = augmented(a, b, options)?;
    let rows = qr.nrows();

    let size = rows.min(c);
    let bs = recommended_block_size::<f64>(rows, c);
    let mut h = Mat::<f64>::zeros(bs, size);
    let mut fwd = vec![0usize; c];
    let mut inv = vec![0usize; c];
    let mut mem = MemBuffer::new(StackReq::any_of(&[
        cpqr::qr_in_place_scratch::<usize, f64>(rows, c, bs, par, Default::default()),
        cpsolve::solve_lstsq_in_place_scratch::<usize, f64>(rows, c, bs, q, par),
    ]));
    let stack = MemStack::new(&mut mem);
    let (_, perm) = cpqr::qr_in_place(
        qr.as_mut(),
        h.as_mut(),
        &mut fwd,
        &mut inv,
        par,
        stack,
        Default::default(),
    );

    let tol = options
        .rank_tol
        .unwrap_or(rows.max(c) as f64 * f64::EPSILON);
    let rank = pivoted_rank(qr.as_ref(), tol);
    if rank < c {
        return Err(rank_deficient(rank, perm.arrays().0));
    }
    let condition = upper_triangular_condition(qr.as_ref().submatrix(0, 0, c, c));
    if condition.is_nan() || condition > options.max_condition {
        return Err(SolveError::IllConditioned {
            condition,
            limit: options.max_condition,
        });
    }

    cpsolve::solve_lstsq_in_place(
        qr.as_ref(),
        h.as_ref(),
        qr.as_ref(),
        perm,
        rhs.as_mut(),
        par,
        stack,
    );
    let coefficients = rhs.as_ref().subrows(0, c).to_owned();
    let residual_sum_squares = residual_sums(a, b, coefficients.as_ref(), par);
    Ok(Solution {
        coefficients,
        rank,
        condition,
        residual_sum_squares,
    })
}

/// Shapes (programmer errors: panics), the options and finite entries.
#[track_caller]
fn check_inputs(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    options: &LstsqOptions,
) -> Result<(), SolveError> {
    assert_eq!(
        a.nrows(),
        b.nrows(),
        "A has {} rows but B has {}",
        a.nrows(),
        b.nrows()
    );
    assert!(
        options.unpenalised <= a.ncols(),
        "unpenalised = {} exceeds the {} columns",
        options.unpenalised,
        a.ncols()
    );
    if !crate::check::non_negative(options.ridge) {
        return Err(SolveError::InvalidOption {
            option: "ridge",
            value: options.ridge,
        });
    }
    if let Some(t) = options.rank_tol
        && !(t > 0.0 && t < 1.0)
    {
        return Err(SolveError::InvalidOption {
            option: "rank_tol",
            value: t,
        });
    }
    if options.max_condition.is_nan() || options.max_condition < 1.0 {
        return Err(SolveError::InvalidOption {
            option: "max_condition",
            value: options.max_condition,
        });
    }
    for (matrix, m) in [("A", a), ("B", b)] {
        if let Some((row, col)) = first_non_finite(m) {
            return Err(SolveError::NonFinite { matrix, row, col });
        }
    }
    Ok(())
}

/// The augmented system [A; √λ E] x ≈ [B; 0], E selecting the penalised columns (no
/// extra rows without a ridge).
fn augmented(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    options: &LstsqOptions,
) -> Result<(Mat<f64>, Mat<f64>), SolveError> {
    let (n, c, q) = (a.nrows(), a.ncols(), b.ncols());
    let extra = if options.ridge > 0.0 {
        c - options.unpenalised
    } else {
        0
    };
    let rows = n + extra;
    if rows < c {
        return Err(SolveError::Underdetermined {
            rows: n,
            columns: c,
        });
    }
    let mut qr = Mat::<f64>::zeros(rows, c);
    qr.as_mut().subrows_mut(0, n).copy_from(a);
    let sl = options.ridge.sqrt();
    for t in 0..extra {
        qr[(n + t, options.unpenalised + t)] = sl;
    }
    let mut rhs = Mat::<f64>::zeros(rows, q);
    rhs.as_mut().subrows_mut(0, n).copy_from(b);
    Ok((qr, rhs))
}

/// Numerical rank from the diagonal of a column-pivoted R, which is non-increasing in
/// magnitude: the columns before the first |rₖₖ| ≤ `tol`·|r₁₁|.
pub(super) fn pivoted_rank(r: MatRef<'_, f64>, tol: f64) -> usize {
    let c = r.ncols();
    let r11 = r[(0, 0)].abs();
    if r11 == 0.0 {
        return 0;
    }
    (0..c)
        .position(|k| r[(k, k)].abs() <= tol * r11)
        .unwrap_or(c)
}

/// The error of a pivoted QR of rank `rank`: the original indices of the columns
/// pivoted past it, sorted.
pub(super) fn rank_deficient(rank: usize, pivots: &[usize]) -> SolveError {
    let mut dependent = pivots[rank..].to_vec();
    dependent.sort_unstable();
    SolveError::RankDeficient {
        rank,
        columns: pivots.len(),
        dependent,
    }
}

/// Σ residual² per column of B on the original rows, recomputed rather than read off
/// Qᵀb: an honest check.
fn residual_sums(
    a: MatRef<'_, f64>,
    b: MatRef<'_, f64>,
    coefficients: MatRef<'_, f64>,
    par: Par,
) -> Vec<f64> {
    let mut res = b.to_owned();
    matmul(res.as_mut(), Accum::Add, a, coefficients, -1.0, par);
    (0..b.ncols())
        .map(|k| (0..b.nrows()).map(|i| res[(i, k)].powi(2)).sum())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256Plus;

    fn random(n: usize, c: usize, rng: &mut Xoshiro256Plus) -> Mat<f64> {
        Mat::from_fn(n, c, |_, _| rng.gen_range(-1.0..1.0))
    }

    /// The residual is orthogonal to the columns (the defining property of least squares),
    /// relative to ‖A‖‖r‖, over several shapes, several right-hand sides, both parallelisms.
    #[test]
    fn residual_is_orthogonal_to_the_columns() {
        let mut rng = Xoshiro256Plus::seed_from_u64(7);
        for &(n, c, q) in &[
            (1, 1, 1),
            (5, 3, 2),
            (40, 40, 1),
            (200, 17, 3),
            (600, 120, 2),
        ] {
            let a = random(n, c, &mut rng);
            let b = random(n, q, &mut rng);
            for par in [Par::Seq, Par::rayon(2)] {
                let s = lstsq(
                    a.as_ref(),
                    b.as_ref(),
                    &LstsqOptions {
                        par,
                        ..Default::default()
                    },
                )
                .unwrap();
                let r = &b - &a * &s.coefficients;
                let atr = a.transpose() * &r;
                let scale = a.norm_l2() * r.norm_l2().max(1e-300) + b.norm_l2() * a.norm_l2();
                assert!(
                    atr.norm_l2() <= 1e-13 * scale,
                    "{n}x{c}: {}",
                    atr.norm_l2() / scale
                );
                for k in 0..q {
                    let rss: f64 = (0..n).map(|i| r[(i, k)].powi(2)).sum();
                    assert!((rss - s.residual_sum_squares[k]).abs() <= 1e-12 * (1.0 + rss));
                }
            }
        }
    }

    /// The ridge solution satisfies its own normal equations (AᵀA + λE)x = Aᵀb (checked, not solved, that way).
    #[test]
    fn ridge_matches_its_optimality_condition() {
        let mut rng = Xoshiro256Plus::seed_from_u64(8);
        let (n, c) = (30, 6);
        let a = random(n, c, &mut rng);
        let b = random(n, 1, &mut rng);
        let lam = 0.3;
        let s = lstsq(
            a.as_ref(),
            b.as_ref(),
            &LstsqOptions {
                ridge: lam,
                unpenalised: 2,
                ..Default::default()
            },
        )
        .unwrap();
        let mut g = a.transpose() * (&a * &s.coefficients - &b);
        for j in 2..c {
            g[(j, 0)] += lam * s.coefficients[(j, 0)];
        }
        assert!(g.norm_l2() < 1e-12, "{}", g.norm_l2());
    }

    #[test]
    fn dependent_columns_are_named() {
        let mut rng = Xoshiro256Plus::seed_from_u64(9);
        let mut a = random(20, 5, &mut rng);
        for i in 0..20 {
            a[(i, 3)] = 2.0 * a[(i, 0)] - a[(i, 1)];
        }
        let b = random(20, 1, &mut rng);
        match lstsq(a.as_ref(), b.as_ref(), &Default::default()) {
            Err(SolveError::RankDeficient {
                rank,
                columns,
                dependent,
            }) => {
                assert_eq!((rank, columns), (4, 5));
                assert_eq!(dependent.len(), 1);
                assert!([0, 1, 3].contains(&dependent[0]));
            }
            other => panic!("{other:?}"),
        }
        // an all-zero column is the dependent one, unambiguously
        let mut z = random(10, 3, &mut rng);
        for i in 0..10 {
            z[(i, 1)] = 0.0;
        }
        let e = lstsq(
            z.as_ref(),
            Mat::<f64>::ones(10, 1).as_ref(),
            &Default::default(),
        )
        .unwrap_err();
        assert_eq!(
            e,
            SolveError::RankDeficient {
                rank: 2,
                columns: 3,
                dependent: vec![1]
            }
        );
    }

    #[test]
    fn ill_conditioning_is_refused_and_reported() {
        // Columns 1, t, t², ... on [0, 1e-3]: a monomial basis on a tiny interval.
        let n = 50;
        let a = Mat::from_fn(n, 5, |i, j| (i as f64 * 2e-5).powi(j as i32));
        let b = Mat::from_fn(n, 1, |i, _| i as f64);
        match lstsq(
            a.as_ref(),
            b.as_ref(),
            &LstsqOptions {
                max_condition: 1e8,
                rank_tol: Some(1e-300),
                ..Default::default()
            },
        ) {
            Err(SolveError::IllConditioned { condition, limit }) => assert!(condition > limit),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn non_finite_and_underdetermined_are_errors() {
        let mut a = Mat::<f64>::ones(3, 2);
        a[(2, 1)] = f64::NAN;
        let b = Mat::<f64>::ones(3, 1);
        assert_eq!(
            lstsq(a.as_ref(), b.as_ref(), &Default::default()).unwrap_err(),
            SolveError::NonFinite {
                matrix: "A",
                row: 2,
                col: 1
            }
        );
        let wide = Mat::<f64>::ones(2, 3);
        assert_eq!(
            lstsq(
                wide.as_ref(),
                Mat::<f64>::ones(2, 1).as_ref(),
                &Default::default()
            )
            .unwrap_err(),
            SolveError::Underdetermined {
                rows: 2,
                columns: 3
            }
        );
        assert!(matches!(
            lstsq(
                b.as_ref(),
                b.as_ref(),
                &LstsqOptions {
                    ridge: -1.0,
                    ..Default::default()
                }
            ),
            Err(SolveError::InvalidOption {
                option: "ridge",
                ..
            })
        ));
    }
}
