//! Cross-fitting: two blocks of rows, each residualised by a fit on the other.

use faer::{Mat, MatRef};
use rbf::{LstsqOptions, SolveError, lstsq};

/// Two blocks of row indices, with the leakage gap between them left out of
/// both: each block is predicted by what was fitted on the other.
///
/// ```
/// use sysid::inference::Blocks;
/// let rows: Vec<usize> = (0..100).collect();
/// let b = Blocks::halves(&rows, 10).unwrap();
/// // Cut at row 49; rows 44..54 (the gap) belong to neither block.
/// assert_eq!((b.first.len(), b.second.len()), (44, 46));
/// assert_eq!((b.first[43], b.second[0]), (43, 54));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Blocks {
    /// The earlier rows.
    pub first: Vec<usize>,
    /// The later rows.
    pub second: Vec<usize>,
}

impl Blocks {
    /// The first and second half of `rows` (sorted), with `gap` record rows
    /// between them dropped; `None` if either half would be empty.
    pub fn halves(rows: &[usize], gap: usize) -> Option<Self> {
        Self::cut(rows, gap, 0.5)
    }

    /// `rows` (sorted) in `chunks` equal spans of time, alternately assigned
    /// to the first and second block, with `gap` record rows around every
    /// boundary dropped; `None` if either block would be empty. Both blocks
    /// then cover the whole record (every level step, the whole temperature
    /// range), so neither block's network has to extrapolate to the other's
    /// operating points.
    ///
    /// ```
    /// let rows: Vec<usize> = (0..100).collect();
    /// let b = sysid::inference::Blocks::alternating(&rows, 4, 4).unwrap();
    /// // Spans 0..25 and 50..75 against 25..50 and 75..100, 2 rows each side of a boundary dropped.
    /// assert_eq!((b.first[0], *b.first.last().unwrap()), (0, 72));
    /// assert_eq!((b.second[0], *b.second.last().unwrap()), (27, 99));
    /// assert!(!b.first.contains(&24) && !b.second.contains(&25));
    /// ```
    pub fn alternating(rows: &[usize], gap: usize, chunks: usize) -> Option<Self> {
        let &last = rows.last()?;
        let &start = rows.first()?;
        let chunks = chunks.max(2);
        let span = (last - start + 1) as f64 / chunks as f64;
        let chunk_of = |r: usize| (((r - start) as f64 / span) as usize).min(chunks - 1);
        let boundary = |k: usize| start + (k as f64 * span).round() as usize;
        let near_boundary = |r: usize| {
            (1..chunks).any(|k| {
                let b = boundary(k);
                r + gap / 2 >= b && r < b + (gap - gap / 2)
            })
        };
        let (mut first, mut second) = (Vec::new(), Vec::new());
        for &r in rows.iter().filter(|&&r| !near_boundary(r)) {
            if chunk_of(r) % 2 == 0 {
                first.push(r);
            } else {
                second.push(r);
            }
        }
        (!first.is_empty() && !second.is_empty()).then_some(Self { first, second })
    }

    /// `rows` (sorted) cut at `fraction` of their span, with `gap` record
    /// rows around the cut dropped; `None` if either side would be empty.
    ///
    /// ```
    /// let rows: Vec<usize> = (0..100).collect();
    /// let b = sysid::inference::Blocks::cut(&rows, 0, 0.25).unwrap();
    /// assert_eq!((b.first.len(), b.second.len()), (24, 76));
    /// ```
    pub fn cut(rows: &[usize], gap: usize, fraction: f64) -> Option<Self> {
        let &last = rows.last()?;
        let &first_row = rows.first()?;
        let mid = first_row + ((last - first_row) as f64 * fraction.clamp(0.0, 1.0)) as usize;
        let lo = mid.saturating_sub(gap / 2);
        let hi = mid + (gap - gap / 2);
        let first: Vec<usize> = rows.iter().copied().filter(|&r| r < lo).collect();
        let second: Vec<usize> = rows.iter().copied().filter(|&r| r >= hi).collect();
        (!first.is_empty() && !second.is_empty()).then_some(Self { first, second })
    }
}

/// `targets_test − basis_test·W`, W the least-squares fit of `targets_fit` on
/// `basis_fit` (every target column at once, one pivoted QR; `ridge` on all
/// but the first `unpenalised` columns, so a nearly redundant kernel column
/// cannot blow the projection up while the bias and effects stay unshrunk).
///
/// # Errors
/// The solve's, e.g. a basis with more columns than rows.
///
/// ```
/// use sysid::inference::residualise;
/// use faer::mat;
/// // A basis of [1, t]: what is linear in t is removed, the rest kept.
/// let b = mat![[1.0, 0.0], [1.0, 1.0], [1.0, 2.0], [1.0, 3.0]];
/// let y = mat![[1.0], [3.0], [5.0], [7.0]];
/// let r = residualise(b.as_ref(), y.as_ref(), b.as_ref(), y.as_ref(), 2, 0.0).unwrap();
/// assert!(r.norm_max() < 1e-12);
/// ```
pub fn residualise(
    basis_fit: MatRef<'_, f64>,
    targets_fit: MatRef<'_, f64>,
    basis_test: MatRef<'_, f64>,
    targets_test: MatRef<'_, f64>,
    unpenalised: usize,
    ridge: f64,
) -> Result<Mat<f64>, SolveError> {
    let sol = lstsq(
        basis_fit,
        targets_fit,
        &LstsqOptions {
            ridge,
            unpenalised: unpenalised.min(basis_fit.ncols()),
            // Called per channel inside a parallel loop.
            par: faer::Par::Seq,
            ..Default::default()
        },
    )?;
    Ok(targets_test - basis_test * &sol.coefficients)
}
