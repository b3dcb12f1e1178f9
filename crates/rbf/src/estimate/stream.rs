//! Least squares over row blocks: a streaming (TSQR-style) Householder QR whose memory
//! does not grow with the number of rows.
//!
//! The augmented matrix [A | B] (c + q columns) is reduced block by block: the
//! triangular factor kept so far (at most c + q rows) is stacked on the next block of
//! rows and factorised again by Householder QR. The factor of [A | B] that results is
//! [[R, Qᵀb], [0, s]], so `finish` solves the small problem min ‖R x − Qᵀb‖ (plus the
//! residual rows) with [`lstsq`] — column-pivoted QR, rank and condition checks, the
//! ridge as extra rows — and never forms AᵀA. Memory: (c + q + block) × (c + q) doubles.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::qr::no_pivoting::factor::{
    qr_in_place, qr_in_place_scratch, recommended_block_size,
};
use faer::{Mat, MatRef, Par};

use super::error::SolveError;
use super::lstsq::{LstsqOptions, Solution, lstsq};
use crate::check::first_non_finite;

/// Row-block least squares: feed the rows of A and B with [`StreamingLstsq::push`], then
/// [`StreamingLstsq::finish`]. The result equals [`lstsq`] on the whole matrices (up to
/// rounding), with the same errors.
///
/// ```
/// use faer::Mat;
/// use rbf::{LstsqOptions, estimate::StreamingLstsq};
/// let a = Mat::from_fn(1000, 3, |i, j| ((i * (j + 1)) as f64 * 0.01).sin() + j as f64);
/// let b = Mat::from_fn(1000, 1, |i, _| 2.0 * a[(i, 0)] - a[(i, 2)]);
/// let mut s = StreamingLstsq::new(3, 1);
/// for start in (0..1000).step_by(128) {
///     let m = 128.min(1000 - start);
///     s.push(a.as_ref().subrows(start, m), b.as_ref().subrows(start, m)).unwrap();
/// }
/// let sol = s.finish(&LstsqOptions::default()).unwrap();
/// assert!((sol.coefficients[(0, 0)] - 2.0).abs() < 1e-10 && (sol.coefficients[(2, 0)] + 1.0).abs() < 1e-10);
/// ```
#[derive(Clone, Debug)]
pub struct StreamingLstsq {
    /// The triangular factor of [A | B] so far (`kept` rows used).
    r: Mat<f64>,
    kept: usize,
    rows: usize,
    c: usize,
    q: usize,
}

impl StreamingLstsq {
    /// For A with `columns` columns and B with `rhs` columns.
    pub fn new(columns: usize, rhs: usize) -> Self {
        Self {
            r: Mat::zeros(columns + rhs, columns + rhs),
            kept: 0,
            rows: 0,
            c: columns,
            q: rhs,
        }
    }

    /// Rows pushed so far.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Adds a block of rows of A and B.
    ///
    /// # Errors
    /// [`SolveError::NonFinite`] (row numbers count from the first row pushed).
    ///
    /// # Panics
    /// If the blocks' shapes do not match the columns given to [`StreamingLstsq::new`].
    #[track_caller]
    pub fn push(&mut self, a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Result<(), SolveError> {
        assert_eq!(
            a.ncols(),
            self.c,
            "A block has {} columns, expected {}",
            a.ncols(),
            self.c
        );
        assert_eq!(
            b.ncols(),
            self.q,
            "B block has {} columns, expected {}",
            b.ncols(),
            self.q
        );
        assert_eq!(a.nrows(), b.nrows(), "A and B blocks differ in rows");
        for (matrix, m) in [("A", a), ("B", b)] {
            if let Some((row, col)) = first_non_finite(m) {
                return Err(SolveError::NonFinite {
                    matrix,
                    row: self.rows + row,
                    col,
                });
            }
        }
        let m = a.nrows();
        if m == 0 {
            return Ok(());
        }
        let (w, kept) = (self.c + self.q, self.kept);
        let rows = kept + m;
        let mut work = Mat::<f64>::zeros(rows, w);
        work.as_mut()
            .subrows_mut(0, kept)
            .copy_from(self.r.as_ref().subrows(0, kept));
        work.as_mut().submatrix_mut(kept, 0, m, self.c).copy_from(a);
        work.as_mut()
            .submatrix_mut(kept, self.c, m, self.q)
            .copy_from(b);
        let size = rows.min(w);
        let bs = recommended_block_size::<f64>(rows, w);
        let mut h = Mat::<f64>::zeros(bs, size);
        let mut mem = MemBuffer::new(qr_in_place_scratch::<f64>(
            rows,
            w,
            bs,
            Par::Seq,
            Default::default(),
        ));
        qr_in_place(
            work.as_mut(),
            h.as_mut(),
            Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        );
        self.r.fill(0.0);
        for j in 0..w {
            for i in 0..=j.min(size - 1) {
                self.r[(i, j)] = work[(i, j)];
            }
        }
        self.kept = size;
        self.rows += m;
        Ok(())
    }

    /// Solves min ‖A x − B‖² (+ ridge) over every row pushed.
    ///
    /// # Errors
    /// As [`lstsq`]; its rank tolerance defaults to max(rows pushed, columns)·ε, as it
    /// would on the whole matrix.
    pub fn finish(&self, options: &LstsqOptions) -> Result<Solution, SolveError> {
        let opts = LstsqOptions {
            rank_tol: Some(
                options
                    .rank_tol
                    .unwrap_or(self.rows.max(self.c) as f64 * f64::EPSILON),
            ),
            ..*options
        };
        if self.rows < self.c && options.ridge == 0.0 {
            return Err(SolveError::Underdetermined {
                rows: self.rows,
                columns: self.c,
            });
        }
        let r = self.r.as_ref().subrows(0, self.kept);
        lstsq(r.subcols(0, self.c), r.subcols(self.c, self.q), &opts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data(n: usize, c: usize) -> (Mat<f64>, Mat<f64>) {
        let a = Mat::from_fn(n, c, |i, j| {
            ((i as f64 + 1.0) * (j as f64 + 1.0) * 0.37).sin() + if j == 0 { 1.0 } else { 0.0 }
        });
        let b = Mat::from_fn(n, 2, |i, k| ((i * (k + 3)) as f64 * 0.11).cos());
        (a, b)
    }

    fn streamed(
        a: MatRef<'_, f64>,
        b: MatRef<'_, f64>,
        block: usize,
        o: &LstsqOptions,
    ) -> Result<Solution, SolveError> {
        let mut s = StreamingLstsq::new(a.ncols(), b.ncols());
        for start in (0..a.nrows()).step_by(block) {
            let m = block.min(a.nrows() - start);
            s.push(a.subrows(start, m), b.subrows(start, m))?;
        }
        s.finish(o)
    }

    #[test]
    fn equals_the_whole_matrix_solve_for_any_block_size() {
        let (a, b) = data(777, 9);
        for ridge in [0.0, 1e-3] {
            let o = LstsqOptions {
                ridge,
                unpenalised: 1,
                par: Par::Seq,
                ..Default::default()
            };
            let whole = lstsq(a.as_ref(), b.as_ref(), &o).unwrap();
            for block in [1, 5, 64, 1000] {
                let s = streamed(a.as_ref(), b.as_ref(), block, &o).unwrap();
                assert!(
                    (&s.coefficients - &whole.coefficients).norm_max() < 1e-10,
                    "block {block}"
                );
                for k in 0..2 {
                    let rel = (s.residual_sum_squares[k] - whole.residual_sum_squares[k]).abs()
                        / whole.residual_sum_squares[k];
                    assert!(rel < 1e-10, "rss {k} block {block}: {rel}");
                }
                let ratio = s.condition / whole.condition;
                assert!(
                    (0.5..2.0).contains(&ratio),
                    "condition estimates {} and {}",
                    s.condition,
                    whole.condition
                );
            }
        }
    }

    #[test]
    fn reports_rank_deficiency_and_bad_values() {
        let (mut a, b) = data(300, 4);
        for i in 0..300 {
            a[(i, 3)] = 2.0 * a[(i, 1)];
        }
        match streamed(a.as_ref(), b.as_ref(), 50, &LstsqOptions::default()) {
            Err(SolveError::RankDeficient {
                rank: 3,
                columns: 4,
                ..
            }) => {}
            other => panic!("{other:?}"),
        }
        a[(123, 2)] = f64::NAN;
        match streamed(a.as_ref(), b.as_ref(), 50, &LstsqOptions::default()) {
            Err(SolveError::NonFinite {
                matrix: "A",
                row: 123,
                col: 2,
            }) => {}
            other => panic!("{other:?}"),
        }
        let (a, b) = data(3, 4);
        assert!(matches!(
            streamed(a.as_ref(), b.as_ref(), 2, &LstsqOptions::default()),
            Err(SolveError::Underdetermined {
                rows: 3,
                columns: 4
            })
        ));
    }
}
