//! Errors of the Allan-variance computation and noise-term fitting.

/// Why an Allan deviation cannot be computed.
///
/// ```
/// use allan::{overlapping_adev, AllanError};
/// let err = overlapping_adev(&[1.0, 2.0], 0.02, &[1]).unwrap_err();
/// assert!(matches!(err, AllanError::TooShort { .. }));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AllanError {
    /// Too few samples for the requested averaging factor.
    #[error(
        "{samples} sample(s) cannot give an Allan deviation at averaging factor {m}: it needs at least {need} (2m + 1); use a longer series or a smaller τ"
    )]
    TooShort {
        /// Samples in the series.
        samples: usize,
        /// The averaging factor asked for.
        m: usize,
        /// Samples it needs.
        need: usize,
    },
    /// The sample interval is not a positive finite number.
    #[error("sample interval τ₀ = {tau0_s} s: must be positive and finite")]
    BadInterval {
        /// The interval given, s.
        tau0_s: f64,
    },
    /// An averaging factor of zero.
    #[error("averaging factor 0: τ = m·τ₀ needs m ≥ 1")]
    ZeroFactor,
    /// A sample is NaN or infinite.
    #[error("sample {index} is {value}: every sample must be finite")]
    NonFinite {
        /// Index of the first bad sample (0-based).
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The confidence level is not in (0, 1).
    #[error("confidence level {0}: must be strictly between 0 and 1")]
    BadConfidence(f64),
}
