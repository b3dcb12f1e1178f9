//! Errors of the OLS engine.

/// Why forward selection could not run.
///
/// ```
/// let e = rbf::OlsError::ForcedCollinear { column: 2 };
/// assert!(e.to_string().contains("2"));
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OlsError {
    /// A NaN or infinite entry.
    #[error("non-finite value in {matrix} at row {row}, column {col}")]
    NonFinite {
        /// `candidates`, `forced` or `targets`.
        matrix: &'static str,
        /// Row of the first bad entry.
        row: usize,
        /// Column of the first bad entry.
        col: usize,
    },
    /// No samples (zero rows).
    #[error("no samples")]
    NoSamples,
    /// The targets are identically zero, so no ERR is defined.
    #[error("the targets are identically zero: error-reduction ratios are undefined")]
    ZeroTarget,
    /// A forced column is zero or a linear combination of the forced columns before it.
    #[error("forced column {column} is zero or collinear with the forced columns before it")]
    ForcedCollinear {
        /// Index of the forced column.
        column: usize,
    },
    /// The columns overflow `f64`: a column energy or an error-reduction
    /// ratio (a product of squares) is infinite or NaN. Entries beyond about
    /// 1e154 overflow the energies and beyond about 1e75 the ratios.
    /// Selection stops rather than compare NaN scores.
    #[error(
        "the {what} overflow f64 (a sum of squares or an error-reduction ratio is {value}): entries beyond about 1e75 in magnitude cannot be scored; scale the data"
    )]
    Overflow {
        /// `targets`, `candidates` or `forced columns`.
        what: &'static str,
        /// The non-finite value met.
        value: f64,
    },
    /// An option out of range.
    #[error("invalid OLS option {option} = {value}")]
    InvalidOption {
        /// Option name.
        option: &'static str,
        /// Value given.
        value: f64,
    },
}
