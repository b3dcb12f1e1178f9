//! Errors of the linear solvers: small enums carrying the numbers that explain them.

/// Why a least-squares or interpolation solve failed.
///
/// ```
/// let e = rbf::SolveError::RankDeficient { rank: 2, columns: 3, dependent: vec![2] };
/// assert!(e.to_string().contains("[2]"));
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// A NaN or infinite entry.
    #[error("non-finite value in {matrix} at row {row}, column {col}")]
    NonFinite {
        /// Which input.
        matrix: &'static str,
        /// Row of the first bad entry.
        row: usize,
        /// Column of the first bad entry.
        col: usize,
    },
    /// The numerical rank is below the number of columns.
    #[error(
        "rank deficient: numerical rank {rank} of {columns} columns; columns {dependent:?} are \
         (nearly) linear combinations of the others (drop them or add a ridge)"
    )]
    RankDeficient {
        /// Numerical rank (|R_kk| > tol·|R_11|).
        rank: usize,
        /// Number of columns.
        columns: usize,
        /// The columns found dependent (those left after the first `rank` pivots), ascending.
        dependent: Vec<usize>,
    },
    /// The estimated condition number exceeds the limit.
    #[error(
        "ill-conditioned: estimated condition number {condition:.3e} exceeds {limit:.3e}; \
         add a ridge (smoothing) or use fewer/wider-spaced centres"
    )]
    IllConditioned {
        /// 1-norm condition estimate.
        condition: f64,
        /// The limit in force.
        limit: f64,
    },
    /// Fewer equations than unknowns (and no ridge to make up for them).
    #[error("underdetermined: {rows} rows for {columns} unknowns")]
    Underdetermined {
        /// Rows.
        rows: usize,
        /// Unknowns.
        columns: usize,
    },
    /// Cholesky met a non-positive pivot: the (projected) kernel matrix is not numerically
    /// positive definite.
    #[error(
        "kernel matrix is not numerically positive definite (pivot {pivot}); add a ridge \
         (smoothing) λ > 0, widen the spacing of the centres or narrow the width"
    )]
    NotPositiveDefinite {
        /// Index of the failing pivot.
        pivot: usize,
    },
    /// An option out of range.
    #[error("invalid option {option} = {value}")]
    InvalidOption {
        /// Option name.
        option: &'static str,
        /// Value given.
        value: f64,
    },
}
