//! The all-points solve: every sample is a centre, as scipy's `RBFInterpolator` does.
//!
//! Solves  (Φ + σλI) a + P b = y,  Pᵀ a = 0,  where σ = ±1 is the kernel's definiteness
//! sign (so the smoothing λ always adds to the *definite* form σΦ, as scipy does with
//! its negated multiquadric) and P holds the polynomial tail and any other linear
//! columns. The null-space method: with P = Q [R; 0] (Householder, p reflections),
//! a = Q₂ α and Q₂ᵀ(σΦ + λI)Q₂ α = σ Q₂ᵀ y, a symmetric positive definite system for
//! positive definite kernels and for conditionally definite ones of order ≤ the tail's,
//! factored by Cholesky (N³/3 flops, half an LU). Forming Q₂ᵀMQ₂ costs O(pN²) with
//! the reflections, not the 4N³ of explicit products.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};
use faer::linalg::cholesky::llt::solve::solve_in_place_with_conj as llt_solve;
use faer::linalg::householder as hh;
use faer::linalg::qr::col_pivoting::factor as cpqr;
use faer::linalg::qr::no_pivoting::factor::recommended_block_size;
use faer::linalg::triangular_solve::solve_upper_triangular_in_place;
use faer::prelude::ReborrowMut;
use faer::{Conj, Mat, MatMut, MatRef, Par};

use super::condition::inverse_one_norm;
use super::error::SolveError;
use super::lstsq::{DEFAULT_MAX_CONDITION, pivoted_rank, rank_deficient};
use crate::check::first_non_finite;

/// Options of [`interpolate`].
///
/// ```
/// let o = rbf::InterpolationOptions { smoothing: 1e-8, ..Default::default() };
/// assert_eq!(o.sign, 1.0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct InterpolationOptions {
    /// Smoothing λ ≥ 0 added to the diagonal of σΦ (0: exact interpolation).
    pub smoothing: f64,
    /// The kernel's definiteness sign σ ([`crate::Kernel::definiteness_sign`]).
    pub sign: f64,
    /// Refuse a projected system whose 1-norm condition estimate exceeds this.
    pub max_condition: f64,
    /// Parallelism.
    pub par: Par,
}

impl Default for InterpolationOptions {
    fn default() -> Self {
        Self {
            smoothing: 0.0,
            sign: 1.0,
            max_condition: DEFAULT_MAX_CONDITION,
            par: faer::get_global_parallelism(),
        }
    }
}

/// Result of [`interpolate`].
///
/// ```
/// # use faer::{mat, Mat};
/// let phi = mat![[1.0, 0.5], [0.5, 1.0]];
/// let y = mat![[1.0], [1.0]];
/// let s = rbf::interpolate(phi, Mat::<f64>::zeros(2, 0).as_ref(), y.as_ref(), &Default::default()).unwrap();
/// assert!((s.weights[(0, 0)] - 2.0 / 3.0).abs() < 1e-15);
/// assert_eq!(s.tail.nrows(), 0);
/// ```
#[derive(Clone, Debug)]
pub struct Interpolation {
    /// Kernel weights a (N × q).
    pub weights: Mat<f64>,
    /// Coefficients b of the polynomial/linear columns (p × q).
    pub tail: Mat<f64>,
    /// 1-norm condition estimate of the projected system Q₂ᵀ(σΦ + λI)Q₂.
    pub condition: f64,
}

/// Solves the interpolation (or smoothing) system for kernel matrix `phi` (N × N,
/// symmetric; consumed as workspace), tail columns `poly` (N × p, p < N) and targets
/// `y` (N × q).
///
/// # Errors
/// [`SolveError::NotPositiveDefinite`] when Cholesky fails (add smoothing),
/// [`SolveError::RankDeficient`] when the tail columns are dependent,
/// [`SolveError::IllConditioned`], [`SolveError::NonFinite`], [`SolveError::Underdetermined`]
/// (p ≥ N), [`SolveError::InvalidOption`].
///
/// # Panics
/// On inconsistent shapes.
///
/// ```
/// use faer::{Mat, Par};
/// use rbf::{interpolate, kernel_matrix, InterpolationOptions, Kernel, Widths};
/// // thin-plate spline with a linear tail through 6 points in the plane
/// let x: Mat<f64> = faer::mat![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.5, 0.3], [0.2, 0.8]];
/// let y = Mat::from_fn(6, 1, |i, _| (x[(i, 0)] * 3.0).sin() + x[(i, 1)]);
/// let k = Kernel::ThinPlateSpline;
/// let phi = kernel_matrix(x.as_ref(), x.as_ref(), k, &Widths::Uniform(1.0), Par::Seq);
/// let p = Mat::from_fn(6, 3, |i, j| if j == 0 { 1.0 } else { x[(i, j - 1)] });
/// let opts = InterpolationOptions { sign: k.definiteness_sign(), ..Default::default() };
/// let s = interpolate(phi.clone(), p.as_ref(), y.as_ref(), &opts).unwrap();
/// let fit = &phi * &s.weights + &p * &s.tail;
/// assert!((&fit - &y).norm_max() < 1e-12);
/// ```
#[track_caller]
pub fn interpolate(
    phi: Mat<f64>,
    poly: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    options: &InterpolationOptions,
) -> Result<Interpolation, SolveError> {
    check_inputs(phi.as_ref(), poly, y, options)?;
    let (n, p, q, par) = (phi.nrows(), poly.ncols(), y.ncols(), options.par);
    let sigma = options.sign;

    // M = σΦ + λI, in place.
    let mut m = phi;
    definite_form(m.as_mut(), sigma, options.smoothing);
    let mut rhs = Mat::from_fn(n, q, |i, k| sigma * y[(i, k)]);

    let bs = recommended_block_size::<f64>(n, p.max(1)).max(1);
    let mut mem = MemBuffer::new(scratch(n, p, q, bs, par));
    let stack = MemStack::new(&mut mem);
    let tail_qr = TailQr::factor(poly, bs, par, stack)?;
    if let Some(t) = &tail_qr {
        t.project(m.as_mut(), rhs.as_mut(), par, stack);
    }

    // Cholesky of the trailing block G₂₂ (its lower triangle; G is symmetric).
    let k = n - p;
    cholesky_trailing(m.as_mut().submatrix_mut(p, p, k, k), par, stack)?;
    let l = m.as_ref().submatrix(p, p, k, k);
    let condition = llt_condition(l);
    if condition.is_nan() || condition > options.max_condition {
        return Err(SolveError::IllConditioned {
            condition,
            limit: options.max_condition,
        });
    }

    // α from L Lᵀ α = (Qᵀσy)₂.
    let mut alpha = rhs.as_ref().subrows(p, k).to_owned();
    llt_solve(l, Conj::No, alpha.as_mut(), par, stack);

    let mut tail = Mat::<f64>::zeros(p, q);
    // a = Q [0; α].
    let mut weights = Mat::<f64>::zeros(n, q);
    weights.as_mut().subrows_mut(p, k).copy_from(alpha.as_ref());
    if let Some(t) = &tail_qr {
        let g12 = m.as_ref().submatrix(0, p, p, k);
        t.coefficients(g12, rhs.as_ref(), alpha.as_ref(), sigma, tail.as_mut(), par);
        t.apply_q(weights.as_mut(), par, stack);
    }
    Ok(Interpolation {
        weights,
        tail,
        condition,
    })
}

/// Shapes (programmer errors: panics), the smoothing, finite entries and p < N.
#[track_caller]
fn check_inputs(
    phi: MatRef<'_, f64>,
    poly: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    options: &InterpolationOptions,
) -> Result<(), SolveError> {
    let n = phi.nrows();
    assert_eq!(phi.ncols(), n, "the kernel matrix must be square");
    assert_eq!(poly.nrows(), n, "tail rows must match the kernel matrix");
    assert_eq!(y.nrows(), n, "targets must have one row per centre");
    assert!(
        options.sign == 1.0 || options.sign == -1.0,
        "sign must be ±1"
    );
    if !crate::check::non_negative(options.smoothing) {
        return Err(SolveError::InvalidOption {
            option: "smoothing",
            value: options.smoothing,
        });
    }
    for (name, m) in [("kernel matrix", phi), ("tail", poly), ("targets", y)] {
        if let Some((row, col)) = first_non_finite(m) {
            return Err(SolveError::NonFinite {
                matrix: name,
                row,
                col,
            });
        }
    }
    let p = poly.ncols();
    if p >= n && n > 0 {
        return Err(SolveError::Underdetermined {
            rows: n,
            columns: n + p,
        });
    }
    Ok(())
}

/// M ← σM + λI: the definite form of the kernel matrix, smoothed.
fn definite_form(mut m: MatMut<'_, f64>, sigma: f64, smoothing: f64) {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            m[(i, j)] *= sigma;
        }
        m[(j, j)] += smoothing;
    }
}

/// The workspace of every step: the tail's QR, applying its reflections, Cholesky.
fn scratch(n: usize, p: usize, q: usize, bs: usize, par: Par) -> StackReq {
    StackReq::any_of(&[
        cpqr::qr_in_place_scratch::<usize, f64>(n, p, bs, par, Default::default()),
        hh::apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<f64>(
            n,
            bs,
            n.max(q),
        ),
        hh::apply_block_householder_sequence_on_the_right_in_place_scratch::<f64>(n, bs, n),
        hh::apply_block_householder_sequence_on_the_left_in_place_scratch::<f64>(n, bs, q),
        cholesky_in_place_scratch::<f64>(n, par, Default::default()),
    ])
}

/// The tail columns P = Q [R; 0] Πᵀ: Householder QR with column pivoting, so that
/// dependent columns are detected.
struct TailQr {
    /// The reflections below the diagonal, R above.
    pq: Mat<f64>,
    /// The block reflectors' factors.
    h: Mat<f64>,
    /// Π: the original column of each pivoted position.
    perm_fwd: Vec<usize>,
}

impl TailQr {
    /// `None` without tail columns.
    fn factor(
        poly: MatRef<'_, f64>,
        bs: usize,
        par: Par,
        stack: &mut MemStack,
    ) -> Result<Option<Self>, SolveError> {
        let (n, p) = (poly.nrows(), poly.ncols());
        if p == 0 {
            return Ok(None);
        }
        let mut pq = poly.to_owned();
        let mut h = Mat::<f64>::zeros(bs, p.min(n));
        let mut fwd = vec![0usize; p];
        let mut inv = vec![0usize; p];
        let (_, perm) = cpqr::qr_in_place(
            pq.as_mut(),
            h.as_mut(),
            &mut fwd,
            &mut inv,
            par,
            stack,
            Default::default(),
        );
        let rank = pivoted_rank(pq.as_ref(), n.max(p) as f64 * f64::EPSILON);
        let perm_fwd = perm.arrays().0.to_vec();
        if rank < p {
            return Err(rank_deficient(rank, &perm_fwd));
        }
        Ok(Some(Self { pq, h, perm_fwd }))
    }

    /// G = Qᵀ M Q and Qᵀ (σy), in place.
    fn project(
        &self,
        mut m: MatMut<'_, f64>,
        rhs: MatMut<'_, f64>,
        par: Par,
        stack: &mut MemStack,
    ) {
        let (pq, h) = (self.pq.as_ref(), self.h.as_ref());
        hh::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
            pq,
            h,
            Conj::No,
            m.rb_mut(),
            par,
            stack,
        );
        hh::apply_block_householder_sequence_on_the_right_in_place_with_conj(
            pq,
            h,
            Conj::No,
            m,
            par,
            stack,
        );
        hh::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
            pq,
            h,
            Conj::No,
            rhs,
            par,
            stack,
        );
    }

    /// The tail coefficients b (p × q): R c = (Qᵀ y)₁ − σ G₁₂ α, i.e.
    /// σ[(Qᵀσy)₁ − G₁₂ α]; then b = Π c.
    fn coefficients(
        &self,
        g12: MatRef<'_, f64>,
        rhs: MatRef<'_, f64>,
        alpha: MatRef<'_, f64>,
        sigma: f64,
        mut tail: MatMut<'_, f64>,
        par: Par,
    ) {
        let p = self.perm_fwd.len();
        let mut top = rhs.subrows(0, p).to_owned();
        faer::linalg::matmul::matmul(top.as_mut(), faer::Accum::Add, g12, alpha, -1.0, par);
        for v in top.as_mut().col_iter_mut().flat_map(|c| c.iter_mut()) {
            *v *= sigma;
        }
        let r = self.pq.as_ref().submatrix(0, 0, p, p);
        solve_upper_triangular_in_place(r, top.as_mut(), par);
        for (pos, &orig) in self.perm_fwd.iter().enumerate() {
            for c in 0..tail.ncols() {
                tail[(orig, c)] = top[(pos, c)];
            }
        }
    }

    /// x ← Q x.
    fn apply_q(&self, x: MatMut<'_, f64>, par: Par, stack: &mut MemStack) {
        hh::apply_block_householder_sequence_on_the_left_in_place_with_conj(
            self.pq.as_ref(),
            self.h.as_ref(),
            Conj::No,
            x,
            par,
            stack,
        );
    }
}

/// Cholesky L Lᵀ of the projected block G₂₂ in place (its lower triangle).
fn cholesky_trailing(
    g22: MatMut<'_, f64>,
    par: Par,
    stack: &mut MemStack,
) -> Result<(), SolveError> {
    cholesky_in_place(
        g22,
        LltRegularization::default(),
        par,
        stack,
        Default::default(),
    )
    .map_err(|e| match e {
        faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } => {
            SolveError::NotPositiveDefinite { pivot: index }
        }
    })?;
    Ok(())
}

/// κ₁(G₂₂) = ‖G₂₂‖₁‖G₂₂⁻¹‖₁ from its Cholesky factor `l`. For an SPD matrix ‖G₂₂‖₁
/// lies between its largest diagonal entry (the largest squared row norm of L) and k
/// times that; the lower bound keeps a refusal from ever being spurious.
fn llt_condition(l: MatRef<'_, f64>) -> f64 {
    let k = l.nrows();
    let diag_max = (0..k)
        .map(|i| (0..=i).map(|j| l[(i, j)].powi(2)).sum::<f64>())
        .fold(0.0, f64::max);
    // G₂₂ is symmetric: the solve with it and with its transpose are the same.
    let solve = |v: &mut [f64]| {
        let mut col = faer::MatMut::from_column_major_slice_mut(v, k, 1);
        llt_solve(
            l,
            Conj::No,
            col.as_mut(),
            Par::Seq,
            MemStack::new(&mut MemBuffer::new(StackReq::EMPTY)),
        );
    };
    diag_max * inverse_one_norm(k, solve, solve)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Kernel, Widths, kernel_matrix};
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256Plus;

    /// Every kernel interpolates (residual ≪ ‖y‖) with the tail its definiteness needs,
    /// and the weights are orthogonal to the tail (the side condition Pᵀa = 0).
    #[test]
    fn interpolates_with_side_conditions() {
        let mut rng = Xoshiro256Plus::seed_from_u64(5);
        for &n in &[8usize, 60, 150] {
            let x = Mat::from_fn(n, 2, |_, _| rng.gen_range(-1.0..1.0));
            let y = Mat::from_fn(n, 2, |i, k| {
                (x[(i, 0)] * (k + 1) as f64).sin() * x[(i, 1)].cos()
            });
            let p = Mat::from_fn(n, 3, |i, j| if j == 0 { 1.0 } else { x[(i, j - 1)] });
            for kern in Kernel::ALL {
                let w = Widths::Uniform(if kern == Kernel::Gaussian { 0.3 } else { 1.0 });
                let phi = kernel_matrix(x.as_ref(), x.as_ref(), kern, &w, Par::Seq);
                let opts = InterpolationOptions {
                    sign: kern.definiteness_sign(),
                    max_condition: f64::INFINITY,
                    ..Default::default()
                };
                let s = interpolate(phi.clone(), p.as_ref(), y.as_ref(), &opts).unwrap();
                let res = &phi * &s.weights + &p * &s.tail - &y;
                assert!(res.norm_max() < 1e-7, "{kern} n={n}: {}", res.norm_max());
                let side = p.transpose() * &s.weights;
                assert!(
                    side.norm_max() < 1e-8 * (1.0 + s.weights.norm_max()),
                    "{kern}"
                );
            }
        }
    }

    /// Smoothing matches its defining equations: (σΦ + λI)a·σ + Pb = y.
    #[test]
    fn smoothing_satisfies_its_equations() {
        let mut rng = Xoshiro256Plus::seed_from_u64(6);
        let n = 40;
        let x: Mat<f64> = Mat::from_fn(n, 1, |_, _| rng.gen_range(-1.0..1.0));
        let y = Mat::from_fn(n, 1, |i, _| x[(i, 0)].powi(3) + rng.gen_range(-0.1..0.1));
        let p = Mat::<f64>::ones(n, 1);
        let kern = Kernel::Multiquadric;
        let phi = kernel_matrix(
            x.as_ref(),
            x.as_ref(),
            kern,
            &Widths::Uniform(0.5),
            Par::Seq,
        );
        let lam = 0.1;
        let s = interpolate(
            phi.clone(),
            p.as_ref(),
            y.as_ref(),
            &InterpolationOptions {
                smoothing: lam,
                sign: -1.0,
                ..Default::default()
            },
        )
        .unwrap();
        let res = &phi * &s.weights - &s.weights * lam + &p * &s.tail - &y;
        assert!(res.norm_max() < 1e-10, "{}", res.norm_max());
    }

    #[test]
    fn indefinite_matrix_is_a_typed_error() {
        let phi = faer::mat![[1.0, 2.0], [2.0, 1.0]];
        let e = interpolate(
            phi,
            Mat::<f64>::zeros(2, 0).as_ref(),
            Mat::<f64>::ones(2, 1).as_ref(),
            &Default::default(),
        )
        .unwrap_err();
        assert!(matches!(e, SolveError::NotPositiveDefinite { .. }));
        assert!(e.to_string().contains("ridge"));
    }
}
