//! Design (kernel) matrices Φ[i, j] = φ(‖x_i − c_j‖; β_j): rows are samples, columns centres.

use faer::linalg::matmul::matmul;
use faer::prelude::ReborrowMut;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use serde::{Deserialize, Serialize};

use crate::kernel::Kernel;
use crate::parallel::for_each_chunk_mut;

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
    assert_eq!(
        x.ncols(),
        centres.ncols(),
        "samples have {} columns but centres have {}",
        x.ncols(),
        centres.ncols()
    );
    assert_eq!(
        (out.nrows(), out.ncols()),
        (x.nrows(), centres.nrows()),
        "output must be samples × centres"
    );
    widths.assert_len(centres.nrows());
    let (n, m, d) = (x.nrows(), centres.nrows(), x.ncols());
    let mut out = out;
    if n == 0 || m == 0 {
        return;
    }

    // Shift both point sets by the centres' mean (see the doc comment: accuracy).
    let mut shift = vec![0.0; d];
    for (k, s) in shift.iter_mut().enumerate() {
        *s = (0..m).map(|j| centres[(j, k)]).sum::<f64>() / m as f64;
    }
    let xs = Mat::from_fn(n, d, |i, k| x[(i, k)] - shift[k]);
    let cs = Mat::from_fn(m, d, |j, k| centres[(j, k)] - shift[k]);
    let xn: Vec<f64> = (0..n)
        .map(|i| (0..d).map(|k| xs[(i, k)].powi(2)).sum())
        .collect();
    let cn: Vec<f64> = (0..m)
        .map(|j| (0..d).map(|k| cs[(j, k)].powi(2)).sum())
        .collect();

    if d > 0 {
        matmul(
            out.rb_mut(),
            Accum::Replace,
            xs.as_ref(),
            cs.transpose(),
            -2.0,
            par,
        );
    } else {
        out.fill(0.0);
    }

    // Kernel evaluation column by column; columns of a faer matrix may not be contiguous
    // for a user-provided view, so go through a contiguous scratch when needed.
    let apply = |j: usize, col: &mut [f64]| {
        let b = widths.get(j);
        for (i, v) in col.iter_mut().enumerate() {
            let r2 = (*v + xn[i] + cn[j]).max(0.0);
            *v = kernel.eval_squared(r2, b);
        }
    };
    if out.row_stride() == 1 {
        // Split the output into one contiguous slice per column for the parallel loop.
        let mut cols: Vec<&mut [f64]> = Vec::with_capacity(m);
        let mut rest = out;
        for _ in 0..m {
            let (head, tail) = rest.split_at_col_mut(1);
            let col = head
                .col_mut(0)
                .try_as_col_major_mut()
                .expect("unit row stride");
            cols.push(col.as_slice_mut());
            rest = tail;
        }
        for_each_chunk_mut(&mut cols, par, 1.max(4096 / n.max(1)), |start, chunk| {
            for (k, col) in chunk.iter_mut().enumerate() {
                apply(start + k, col);
            }
        });
    } else {
        let mut buf = vec![0.0; n];
        for j in 0..m {
            for (i, b) in buf.iter_mut().enumerate() {
                *b = out[(i, j)];
            }
            apply(j, &mut buf);
            for (i, b) in buf.iter().enumerate() {
                out[(i, j)] = *b;
            }
        }
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
