//! Input screening shared by every entry point: bad data is an error, not a panic.

use faer::MatRef;

/// Row and column of the first non-finite entry (NaN or ±inf), scanning column by column.
pub(crate) fn first_non_finite(m: MatRef<'_, f64>) -> Option<(usize, usize)> {
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            if !m[(i, j)].is_finite() {
                return Some((i, j));
            }
        }
    }
    None
}

/// Whether a value is a usable non-negative finite number.
pub(crate) fn non_negative(v: f64) -> bool {
    v.is_finite() && v >= 0.0
}

/// Whether a value is a usable strictly positive finite number.
pub(crate) fn positive(v: f64) -> bool {
    v.is_finite() && v > 0.0
}
