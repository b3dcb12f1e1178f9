//! Where candidate columns live while the engine selects among them.
//!
//! An owned matrix ([`crate::forward_select_owned`]) keeps the engine's refreshed
//! columns: a refreshed column (deflated against the basis, see the module docs)
//! overwrites the stored one. A borrowed matrix is never written: with f64 streaming it
//! is copied at its first refresh (so a [`crate::forward_select`] run that needs
//! refreshing holds two candidate matrices); with f32 streaming refreshed columns go to
//! the f32 copy only, and a contender is read from the original column.
//!
//! Generated columns ([`crate::forward_select_columns`]) are never stored in f64: the
//! engine streams their f32 copy and asks the generator again for the few columns it
//! must evaluate exactly, so the candidates cost 4 bytes an entry instead of 12.

use faer::{Mat, MatMut, MatRef};

/// Candidate columns computed on demand, for [`crate::forward_select_columns`].
///
/// The engine asks for blocks of columns while it builds its f32 copy, then for single
/// columns when it evaluates a contender exactly. The same column must come out the
/// same each time, up to rounding (the engine allows 10⁻¹² of the column's norm).
///
/// ```
/// use faer::{Mat, MatMut};
/// /// Powers x^j of one input, as candidate regressors.
/// struct Powers(Vec<f64>);
/// impl rbf::CandidateColumns for Powers {
///     fn nrows(&self) -> usize { self.0.len() }
///     fn ncols(&self) -> usize { 6 }
///     fn columns_into(&self, cols: &[usize], mut out: MatMut<'_, f64>) {
///         for (k, &j) in cols.iter().enumerate() {
///             for (i, x) in self.0.iter().enumerate() {
///                 out[(i, k)] = x.powi(j as i32 + 1);
///             }
///         }
///     }
/// }
/// let x: Vec<f64> = (0..40).map(|i| i as f64 / 20.0 - 1.0).collect();
/// let y = Mat::from_fn(40, 1, |i, _| 3.0 * x[i].powi(3));
/// let path = rbf::forward_select_columns(&Powers(x), Mat::<f64>::zeros(40, 0).as_ref(), y.as_ref(),
///     &rbf::OlsOptions::new(1)).unwrap();
/// assert_eq!(path.selected(), vec![2]); // x³
/// assert!((path.cumulative_err() - 1.0).abs() < 1e-12);
/// ```
pub trait CandidateColumns: Sync {
    /// Rows of every column (samples).
    fn nrows(&self) -> usize;
    /// Number of candidates.
    fn ncols(&self) -> usize;
    /// Writes candidates `cols`, in that order, into the columns of `out`
    /// (`nrows() × cols.len()`).
    fn columns_into(&self, cols: &[usize], out: MatMut<'_, f64>);
}

impl CandidateColumns for MatRef<'_, f64> {
    fn nrows(&self) -> usize {
        MatRef::nrows(self)
    }
    fn ncols(&self) -> usize {
        MatRef::ncols(self)
    }
    fn columns_into(&self, cols: &[usize], mut out: MatMut<'_, f64>) {
        for (k, &j) in cols.iter().enumerate() {
            out.rb_mut().col_mut(k).copy_from(self.col(j));
        }
    }
}

use faer::prelude::ReborrowMut;

pub(crate) enum Store<'a> {
    Borrowed(MatRef<'a, f64>),
    Owned(Mat<f64>),
    Generated(&'a dyn CandidateColumns),
}

impl Store<'_> {
    /// The whole stored matrix, for f64 streaming; `None` for generated columns.
    pub(crate) fn mat(&self) -> Option<MatRef<'_, f64>> {
        match self {
            Store::Borrowed(m) => Some(*m),
            Store::Owned(m) => Some(m.as_ref()),
            Store::Generated(_) => None,
        }
    }

    /// Columns `cols` (n × cols.len()): the stored columns, or the generated originals.
    pub(crate) fn gather(&self, n: usize, cols: &[usize]) -> Mat<f64> {
        let mut out = Mat::zeros(n, cols.len());
        match self {
            Store::Borrowed(m) => m.columns_into(cols, out.as_mut()),
            Store::Owned(m) => m.as_ref().columns_into(cols, out.as_mut()),
            Store::Generated(g) => g.columns_into(cols, out.as_mut()),
        }
        out
    }

    /// Overwrites column `j` of a stored matrix, copying a borrowed matrix first.
    /// Generated columns are not stored: nothing to do.
    pub(crate) fn replace(&mut self, j: usize, data: &[f64]) {
        if let Store::Borrowed(m) = self {
            *self = Store::Owned(m.to_owned());
        }
        if let Store::Owned(m) = self {
            m.col_as_slice_mut(j).copy_from_slice(data);
        }
    }
}
