//! How many centres a fit can take: the rule a fit refuses by, for callers that propose a
//! size (a hint must propose a value that then works, so it asks the same rule).

use super::hyperparams::{Candidates, CentreSelection, RbfValidParams};

impl RbfValidParams {
    /// Whether a fit has the bias column and the linear tail [1 | x] (without a
    /// polynomial tail): as asked, or as all-points interpolation with a conditionally
    /// definite kernel needs for a uniquely solvable system (the tail of its order).
    pub(crate) fn bias_and_tail(&self) -> (bool, bool) {
        let all = matches!(self.centres, CentreSelection::AllPoints);
        let order = self.kernel.polynomial_order();
        (
            self.bias || (all && order >= 1),
            self.linear_tail || (all && order >= 2),
        )
    }

    /// The fixed columns of a fit on `dim` inputs and `linear` exogenous regressors: the
    /// polynomial tail's monomials, or the bias and the linear tail, plus the regressors.
    ///
    /// ```
    /// use linfa::ParamGuard;
    /// let p = rbf::RbfParams::new().check().unwrap();
    /// assert_eq!(p.fixed_columns(3, 2), 1 + 2); // the bias and two regressors
    /// let q = rbf::RbfParams::new().degree(rbf::PolyTail::Linear).check().unwrap();
    /// assert_eq!(q.fixed_columns(3, 0), 1 + 3);
    /// ```
    pub fn fixed_columns(&self, dim: usize, linear: usize) -> usize {
        let poly = match self.degree {
            Some(degree) => degree.n_terms(dim),
            None => {
                let (bias, tail) = self.bias_and_tail();
                usize::from(bias) + if tail { dim } else { 0 }
            }
        };
        poly + linear
    }

    /// The most centres a fit on `rows` training rows of `dim` inputs and `linear`
    /// exogenous regressors takes; a larger number is refused
    /// ([`RbfError::FewerRowsThanCentres`](crate::RbfError::FewerRowsThanCentres)).
    ///
    /// - k-means, random and given centres: a row per centre, and the weights' least
    ///   squares one row per unknown (centres plus [fixed columns](Self::fixed_columns)),
    ///   unless a ridge adds a row per centre; 0 when the rows do not cover the fixed
    ///   columns.
    /// - OLS: the candidates (the training rows, the `selection_rows` subsample or
    ///   [`Candidates`]); the selection stops by itself once they span the rows, so a
    ///   larger `max_centres` is not an error in the library, and callers use this bound.
    /// - all points: `rows` (every row is a centre).
    ///
    /// ```
    /// use linfa::ParamGuard;
    /// use rbf::{CentreSelection, RbfParams};
    /// // 15 rows, 2 inputs, the bias: 14 k-means centres leave 15 unknowns for 15 rows
    /// let p = RbfParams::new().centres(CentreSelection::kmeans(50)).check().unwrap();
    /// assert_eq!(p.most_centres(15, 2, 0), 14);
    /// // a ridge adds a row per centre: every row can be a centre
    /// let r = RbfParams::new().centres(CentreSelection::kmeans(50)).ridge(1e-8).check().unwrap();
    /// assert_eq!(r.most_centres(15, 2, 0), 15);
    /// assert_eq!(RbfParams::new().check().unwrap().most_centres(15, 2, 0), 15); // OLS
    /// ```
    pub fn most_centres(&self, rows: usize, dim: usize, linear: usize) -> usize {
        let fixed = self.fixed_columns(dim, linear);
        match &self.centres {
            CentreSelection::Ols { candidates, .. } => match candidates {
                Candidates::TrainingVectors => match self.selection_rows {
                    Some(s) if s.max(fixed + 1) < rows => s.max(fixed + 1),
                    _ => rows,
                },
                Candidates::Subsample { size } => (*size).min(rows),
                Candidates::Given(c) => c.nrows(),
            },
            CentreSelection::AllPoints => rows,
            CentreSelection::KMeans(_)
            | CentreSelection::Random { .. }
            | CentreSelection::Given(_) => {
                if rows < fixed {
                    0
                } else if self.ridge > 0.0 {
                    rows
                } else {
                    rows - fixed
                }
            }
        }
    }
}
