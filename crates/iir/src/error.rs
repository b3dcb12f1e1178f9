//! Why a filter could not be designed or applied.

use crate::num;

/// Why a filter could not be designed or applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilterError {
    /// The order is zero or above [`MAX_ORDER`](crate::MAX_ORDER).
    #[error("filter order {order} is out of range: use 1 to {max}")]
    Order { order: usize, max: usize },
    /// The cut-off is not strictly between 0 and the Nyquist frequency.
    #[error(
        "cut-off {} Hz must lie strictly between 0 and the Nyquist frequency {} Hz",
        num(*cutoff_hz),
        num(*nyquist_hz)
    )]
    Cutoff { cutoff_hz: f64, nyquist_hz: f64 },
    /// The cut-off is below a ten-thousandth of the sample rate: a filter
    /// that slow has a time constant of tens of thousands of samples, longer
    /// than any test record, and the whiteness test's reference would need
    /// an impulse response of that length (a model edited to 1e-9 Hz asked
    /// for 32 TB).
    #[error(
        "cut-off {} Hz is below {} Hz, a ten-thousandth of the sample rate: use a cut-off from {} Hz up to the Nyquist frequency",
        num(*cutoff_hz),
        num(*min_hz),
        num(*min_hz)
    )]
    CutoffTooLow { cutoff_hz: f64, min_hz: f64 },
    /// The sample rate is not a positive number.
    #[error("sample rate {sample_rate_hz} Hz must be a positive number")]
    SampleRate { sample_rate_hz: f64 },
    /// The signal is shorter than the zero-phase filter's edge extension.
    #[error("{len} samples are too few for zero-phase filtering: need at least {min}")]
    TooShort { len: usize, min: usize },
    /// The signal holds NaN or an infinity.
    #[error("sample {index} (data row {}) is not finite", index + 1)]
    NotFinite { index: usize },
}
