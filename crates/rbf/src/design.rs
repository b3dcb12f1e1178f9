//! Design (kernel) matrices Φ[i, j] = φ(‖x_i − c_j‖; β_j): rows are samples, columns centres.

use faer::linalg::matmul::matmul;
use faer::prelude::ReborrowMut;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use serde::{Deserialize, Serialize};

use crate::kernel::Kernel;
use crate::widest::widest;

/// Kernel widths β: one for every centre, or one per centre.
///
/// ```
/// use rbf::Widths;
/// let w = Widths::PerCentre(vec![0.5, 2.0]);
/// assert_eq!(w.get(1), 2.0);
/// assert_eq!(Widths::Uniform(1.5).get(7), 1.5);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Widths {
    /// The same β for every centre.
    Uniform(f64),
    /// β_j for centre j.
    PerCentre(Vec<f64>),
}

impl Widths {
    /// The width of centre `j`.
    ///
    /// ```
    /// assert_eq!(rbf::Widths::Uniform(2.0).get(0), 2.0);
    /// ```
    #[inline]
    #[track_caller]
    pub fn get(&self, j: usize) -> f64 {
        match self {
            Widths::Uniform(b) => *b,
            Widths::PerCentre(v) => v[j],
        }
    }

    /// The widths of the centres `indices`, in that order (a uniform width stays uniform).
    ///
    /// ```
    /// use rbf::Widths;
    /// let w = Widths::PerCentre(vec![1.0, 2.0, 3.0]);
    /// assert_eq!(w.select(&[2, 0]), Widths::PerCentre(vec![3.0, 1.0]));
    /// ```
    #[track_caller]
    pub fn select(&self, indices: &[usize]) -> Widths {
        match self {
            Widths::Uniform(b) => Widths::Uniform(*b),
            Widths::PerCentre(v) => Widths::PerCentre(indices.iter().map(|&i| v[i]).collect()),
        }
    }

    /// Whether every width is finite and strictly positive.
    ///
    /// ```
    /// assert!(!rbf::Widths::PerCentre(vec![1.0, 0.0]).all_positive());
    /// ```
    pub fn all_positive(&self) -> bool {
        match self {
            Widths::Uniform(b) => crate::check::positive(*b),
            Widths::PerCentre(v) => v.iter().all(|&b| crate::check::positive(b)),
        }
    }

    /// Checks that per-centre widths match `n_centres` (a programmer error otherwise).
    #[track_caller]
    pub(crate) fn assert_len(&self, n_centres: usize) {
        if let Widths::PerCentre(v) = self {
            assert_eq!(
                v.len(),
                n_centres,
                "{} per-centre widths for {} centres",
                v.len(),
                n_centres
            );
        }
    }
}

/// The kernel columns φ(‖x − c_j‖; β_j) of candidate centres, computed on demand for
/// OLS ([`crate::forward_select_columns`]) instead of being held as an n × m matrix.
///
/// # Panics
/// [`KernelColumns::new`] panics if `x` and `centres` have different numbers of
/// columns, or per-centre widths do not number `centres.nrows()`.
///
/// ```
/// use faer::{mat, Mat, Par};
/// use rbf::{kernel_matrix, CandidateColumns, Kernel, KernelColumns, Widths};
/// let x = mat![[0.0], [1.0], [2.5]];
/// let w = Widths::Uniform(1.0);
/// let cols = KernelColumns::new(x.as_ref(), x.as_ref(), Kernel::Gaussian, &w, Par::Seq);
/// let mut out = Mat::zeros(3, 1);
/// cols.columns_into(&[2], out.as_mut());
/// let phi = kernel_matrix(x.as_ref(), x.as_ref(), Kernel::Gaussian, &w, Par::Seq);
/// assert!((out[(0, 0)] - phi[(0, 2)]).abs() < 1e-15);
/// ```
pub struct KernelColumns<'a> {
    /// The samples shifted by the mean of all the centres, once: a column comes out
    /// the same whichever other columns are asked for with it.
    samples: Shifted,
    centres: MatRef<'a, f64>,
    kernel: Kernel,
    widths: &'a Widths,
    par: Par,
}

impl<'a> KernelColumns<'a> {
    /// The columns of `centres` (one candidate per row) against samples `x`; `par` is
    /// the parallelism of a request for many columns at once.
    #[track_caller]
    pub fn new(
        x: MatRef<'a, f64>,
        centres: MatRef<'a, f64>,
        kernel: Kernel,
        widths: &'a Widths,
        par: Par,
    ) -> Self {
        check_shapes(x, centres, (x.nrows(), centres.nrows()));
        widths.assert_len(centres.nrows());
        let m = centres.nrows().max(1);
        let shift: Vec<f64> = (0..centres.ncols())
            .map(|k| (0..centres.nrows()).map(|j| centres[(j, k)]).sum::<f64>() / m as f64)
            .collect();
        Self {
            samples: Shifted::new(x, shift),
            centres,
            kernel,
            widths,
            par,
        }
    }
}

impl crate::select::ols::CandidateColumns for KernelColumns<'_> {
    fn nrows(&self) -> usize {
        self.samples.xs.nrows()
    }

    fn ncols(&self) -> usize {
        self.centres.nrows()
    }

    #[track_caller]
    fn columns_into(&self, cols: &[usize], out: MatMut<'_, f64>) {
        assert_eq!(
            (out.nrows(), out.ncols()),
            (self.samples.xs.nrows(), cols.len()),
            "output must be samples × requested columns"
        );
        let c = Mat::from_fn(cols.len(), self.centres.ncols(), |k, t| {
            self.centres[(cols[k], t)]
        });
        let (cs, cn) = self.samples.centres(c.as_ref());
        let widths = self.widths.select(cols);
        // Many columns at once (a whole matrix) may use the threads; the engine's blocks
        // and single columns are already one thread's work.
        let par = if cols.len() > 256 { self.par } else { Par::Seq };
        let kernel = self.kernel;
        self.samples
            .tiles(cs.as_ref(), &cn, out, par, |j, col, xn, cn| {
                apply_kernel(kernel, widths.get(j), col, xn, cn)
            });
    }
}

/// The kernel matrix Φ (n × m) of samples `x` (n × d) against `centres` (m × d).
///
/// Squared distances come from ‖x‖² + ‖c‖² − 2 x·c through one faer matrix product
/// (so the cost is one n×d×m product plus n·m kernel evaluations); both sets are first
/// shifted by the centres' mean, which keeps the cancellation in that formula small
/// when the data sit far from the origin, and tiny negative results are clamped to 0.
///
/// # Panics
/// If `x` and `centres` have different numbers of columns, or per-centre widths do not
/// number `centres.nrows()`.
///
/// ```
/// use faer::{mat, Par};
/// use rbf::{kernel_matrix, Kernel, Widths};
/// let x = mat![[0.0, 0.0], [3.0, 4.0]];
/// let c = mat![[0.0, 0.0]];
/// let phi = kernel_matrix(x.as_ref(), c.as_ref(), Kernel::Gaussian, &Widths::Uniform(5.0), Par::Seq);
/// assert!((phi[(0, 0)] - 1.0).abs() < 1e-15);
/// assert!((phi[(1, 0)] - (-1.0f64).exp()).abs() < 1e-14); // r = 5 = β
/// ```
#[track_caller]
pub fn kernel_matrix(
    x: MatRef<'_, f64>,
    centres: MatRef<'_, f64>,
    kernel: Kernel,
    widths: &Widths,
    par: Par,
) -> Mat<f64> {
    let mut out = Mat::zeros(x.nrows(), centres.nrows());
    kernel_matrix_into(x, centres, kernel, widths, out.as_mut(), par);
    out
}

/// [`kernel_matrix`] written into `out` (n × m), which avoids an allocation in loops.
///
/// # Panics
/// On the dimension mismatches of [`kernel_matrix`], or if `out` is not n × m.
///
/// ```
/// use faer::{mat, Mat, Par};
/// use rbf::{kernel_matrix_into, Kernel, Widths};
/// let x = mat![[1.0], [2.0]];
/// let mut out = Mat::zeros(2, 2);
/// kernel_matrix_into(x.as_ref(), x.as_ref(), Kernel::Cubic, &Widths::Uniform(1.0), out.as_mut(), Par::Seq);
/// assert_eq!(out[(0, 1)], 1.0);
/// assert_eq!(out[(1, 1)], 0.0);
/// ```
#[track_caller]
pub fn kernel_matrix_into(
    x: MatRef<'_, f64>,
    centres: MatRef<'_, f64>,
    kernel: Kernel,
    widths: &Widths,
    out: MatMut<'_, f64>,
    par: Par,
) {
    check_shapes(x, centres, (out.nrows(), out.ncols()));
    widths.assert_len(centres.nrows());
    product_tiles(x, centres, out, par, |j, col, xn, cn| {
        apply_kernel(kernel, widths.get(j), col, xn, cn)
    });
}

widest! {
    /// A column shifted, `dst = src − shift`, its squares added to the rows' norms.
    fn shift_column(dst: &mut [f64], src: &[f64], shift: f64, norms: &mut [f64]) {
        for ((v, &x), norm) in dst.iter_mut().zip(src).zip(norms.iter_mut()) {
            *v = x - shift;
            *norm += v.powi(2);
        }
    }
}

#[track_caller]
fn check_shapes(x: MatRef<'_, f64>, centres: MatRef<'_, f64>, out: (usize, usize)) {
    assert_eq!(
        x.ncols(),
        centres.ncols(),
        "samples have {} columns but centres have {}",
        x.ncols(),
        centres.ncols()
    );
    assert_eq!(
        out,
        (x.nrows(), centres.nrows()),
        "output must be samples × centres"
    );
}

/// Fills `out` (n × m) tile by tile with −2 x̃_i·c̃_j (x̃, c̃: both sets shifted by the
/// centres' mean) and calls `finish(j, column j of the tile, ‖x̃_i‖² of the tile's rows,
/// ‖c̃_j‖²)` on each tile column while it is in cache; `finish` turns the products into
/// r² = v + ‖x̃_i‖² + ‖c̃_j‖² and whatever is wanted of them.
fn product_tiles(
    x: MatRef<'_, f64>,
    centres: MatRef<'_, f64>,
    out: MatMut<'_, f64>,
    par: Par,
    finish: impl Fn(usize, &mut [f64], &[f64], f64) + Sync,
) {
    if x.nrows() == 0 || centres.nrows() == 0 {
        return;
    }
    // Shift both point sets by the centres' mean (see the doc comment: accuracy).
    let d = x.ncols();
    let m = centres.nrows();
    let shift: Vec<f64> = (0..d)
        .map(|k| (0..m).map(|j| centres[(j, k)]).sum::<f64>() / m as f64)
        .collect();
    let samples = Shifted::new(x, shift);
    let (cs, cn) = samples.centres(centres);
    samples.tiles(cs.as_ref(), &cn, out, par, finish);
}

/// Samples shifted by a fixed point (the centres' mean), with their squared norms: the
/// half of the product formula that does not depend on the centres.
struct Shifted {
    xs: Mat<f64>,
    xn: Vec<f64>,
    shift: Vec<f64>,
}

impl Shifted {
    fn new(x: MatRef<'_, f64>, shift: Vec<f64>) -> Self {
        let mut s = Self {
            xs: Mat::zeros(0, 0),
            xn: Vec::new(),
            shift: Vec::new(),
        };
        s.refill(x, shift);
        s
    }

    /// The samples `x` shifted by `shift`, into the buffers already held.
    fn refill(&mut self, x: MatRef<'_, f64>, shift: Vec<f64>) {
        let (n, d) = (x.nrows(), x.ncols());
        if (self.xs.nrows(), self.xs.ncols()) != (n, d) {
            self.xs = Mat::zeros(n, d);
        }
        // Column by column (contiguous); each row's squared norm still sums its columns
        // in order from the first, as a row-wise sum would.
        self.xn.clear();
        self.xn.resize(n, 0.0);
        let (xs, xn) = (&mut self.xs, &mut self.xn);
        let mut copy = Vec::new();
        for (k, &sk) in shift.iter().enumerate().take(d) {
            let src = x.col(k);
            let src = match src.try_as_col_major() {
                Some(c) => c.as_slice(),
                None => {
                    copy.clear();
                    copy.extend((0..n).map(|i| src[i]));
                    &copy[..]
                }
            };
            shift_column(xs.col_as_slice_mut(k), src, sk, xn);
        }
        self.shift = shift;
    }

    /// Centres shifted the same way, and their squared norms.
    fn centres(&self, centres: MatRef<'_, f64>) -> (Mat<f64>, Vec<f64>) {
        let (m, d) = (centres.nrows(), centres.ncols());
        let cs = Mat::from_fn(m, d, |j, k| centres[(j, k)] - self.shift[k]);
        let cn: Vec<f64> = (0..m)
            .map(|j| (0..d).map(|k| cs[(j, k)].powi(2)).sum())
            .collect();
        (cs, cn)
    }

    fn tiles(
        &self,
        cs: MatRef<'_, f64>,
        cn: &[f64],
        out: MatMut<'_, f64>,
        par: Par,
        finish: impl Fn(usize, &mut [f64], &[f64], f64) + Sync,
    ) {
        let (xs, xn) = (&self.xs, &self.xn);
        let (n, m, d) = (xs.nrows(), cs.nrows(), xs.ncols());
        let mut out = out;
        if n == 0 || m == 0 {
            return;
        }
        // Tiles of TILE_ROWS × TILE_COLS: the product of a tile is written and turned into
        // kernel values while it is still in cache (one write pass over the output instead
        // of three), and tiles of different column blocks run in parallel. Writing a fresh
        // multi-GB output with one big product was also ~20× slower here than a prefaulted
        // one (first-touch page faults inside the product's blocked writes).
        const TILE_ROWS: usize = 2048;
        const TILE_COLS: usize = 64;
        let tile = |c0: usize, mut block: MatMut<'_, f64>| {
            let cols = block.ncols();
            for r0 in (0..n).step_by(TILE_ROWS) {
                let rows = TILE_ROWS.min(n - r0);
                let mut t = block.rb_mut().subrows_mut(r0, rows);
                if d > 0 {
                    matmul(
                        t.rb_mut(),
                        Accum::Replace,
                        xs.as_ref().subrows(r0, rows),
                        cs.subrows(c0, cols).transpose(),
                        -2.0,
                        Par::Seq,
                    );
                } else {
                    t.fill(0.0);
                }
                let xr = &xn[r0..r0 + rows];
                for jj in 0..cols {
                    let j = c0 + jj;
                    let cj = cn[j];
                    let mut col = t.rb_mut().col_mut(jj);
                    match col.rb_mut().try_as_col_major_mut() {
                        Some(c) => finish(j, c.as_slice_mut(), xr, cj),
                        None => {
                            let mut buf: Vec<f64> = (0..rows).map(|ii| col[ii]).collect();
                            finish(j, &mut buf, xr, cj);
                            (0..rows).for_each(|ii| col[ii] = buf[ii]);
                        }
                    }
                }
            }
        };
        if par.degree() > 1 && m > TILE_COLS {
            use rayon::prelude::*;
            out.par_col_chunks_mut(TILE_COLS)
                .enumerate()
                .for_each(|(c, block)| tile(c * TILE_COLS, block));
        } else {
            for c0 in (0..m).step_by(TILE_COLS) {
                let cols = TILE_COLS.min(m - c0);
                tile(c0, out.rb_mut().subcols_mut(c0, cols));
            }
        }
    }
}

widest! {
    /// v ← φ(v + xᵢ + c) for a column of −2x·c products: one monomorphised loop per
    /// kernel (the kernel match hoisted out) so that the compiler vectorises it, at the
    /// widest width the processor has, because the Gaussian's exponential dominates the
    /// design-matrix cost (an element-by-element loop: the same bits at any width).
    fn apply_kernel(kernel: Kernel, width: f64, col: &mut [f64], xn: &[f64], cn: f64) {
        apply_kernel_generic(kernel, width, col, xn, cn)
    }
}

#[inline(always)]
fn apply_kernel_generic(kernel: Kernel, width: f64, col: &mut [f64], xn: &[f64], cn: f64) {
    #[inline(always)]
    fn each(col: &mut [f64], xn: &[f64], cn: f64, f: impl Fn(f64) -> f64) {
        for (v, &xi) in col.iter_mut().zip(xn) {
            *v = f((*v + xi + cn).max(0.0));
        }
    }
    let inv = 1.0 / (width * width);
    match kernel {
        // exp(−r²/β²) in the vectorisable form; other kernels through `eval_squared`.
        Kernel::Gaussian => each(col, xn, cn, |r2| fastexp::exp_neg(-r2 * inv)),
        Kernel::InverseQuadratic => each(col, xn, cn, |r2| 1.0 / (1.0 + r2 * inv)),
        Kernel::InverseMultiquadric => each(col, xn, cn, |r2| 1.0 / (1.0 + r2 * inv).sqrt()),
        Kernel::Multiquadric => each(col, xn, cn, |r2| (1.0 + r2 * inv).sqrt()),
        k => each(col, xn, cn, |r2| k.eval_squared(r2, width)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256Plus;

    fn random(n: usize, d: usize, offset: f64, seed: u64) -> Mat<f64> {
        let mut rng = Xoshiro256Plus::seed_from_u64(seed);
        Mat::from_fn(n, d, |_, _| offset + rng.gen_range(-1.0..1.0))
    }

    /// The product formula agrees with direct distances, also far from the origin
    /// (the mean shift), to a tolerance a few ulps of the kernel values.
    #[test]
    fn matches_direct_evaluation() {
        for &(n, m, d, off) in &[
            (7, 5, 3, 0.0),
            (40, 33, 12, 1e4),
            (1, 1, 1, 0.0),
            (20, 9, 0, 0.0),
        ] {
            let x = random(n, d, off, 1);
            let c = random(m, d, off, 2);
            let w = Widths::PerCentre((0..m).map(|j| 0.5 + j as f64 * 0.1).collect());
            for k in Kernel::ALL {
                for par in [Par::Seq, Par::rayon(2)] {
                    let phi = kernel_matrix(x.as_ref(), c.as_ref(), k, &w, par);
                    for i in 0..n {
                        for j in 0..m {
                            let r = (0..d)
                                .map(|t| (x[(i, t)] - c[(j, t)]).powi(2))
                                .sum::<f64>()
                                .sqrt();
                            let want = k.eval(r, w.get(j));
                            assert!(
                                (phi[(i, j)] - want).abs() <= 1e-9 * (1.0 + want.abs()),
                                "{k} {i} {j}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn strided_output_is_supported() {
        let x = random(6, 2, 0.0, 3);
        let want = kernel_matrix(
            x.as_ref(),
            x.as_ref(),
            Kernel::Gaussian,
            &Widths::Uniform(1.0),
            Par::Seq,
        );
        let mut t = Mat::<f64>::zeros(6, 6);
        kernel_matrix_into(
            x.as_ref(),
            x.as_ref(),
            Kernel::Gaussian,
            &Widths::Uniform(1.0),
            t.as_mut().transpose_mut(),
            Par::Seq,
        );
        assert_eq!(t.transpose().to_owned(), want);
    }

    #[test]
    #[should_panic(expected = "columns")]
    fn mismatched_dimensions_panic() {
        let x = Mat::<f64>::zeros(2, 3);
        let c = Mat::<f64>::zeros(2, 2);
        let _ = kernel_matrix(
            x.as_ref(),
            c.as_ref(),
            Kernel::Cubic,
            &Widths::Uniform(1.0),
            Par::Seq,
        );
    }
}
