//! The error of reading or writing a calibration file (of either format)
//! and its common I/O.

/// Reading or writing a calibration file failed.
///
/// ```
/// use nav_sensors::calibration::{CalibrationFileError, UnitCalibration};
/// let err = UnitCalibration::from_json("{\"format_version\": 9, \"gyros\": {}, \"accels\": {}}", "c.json").unwrap_err();
/// assert!(matches!(err, CalibrationFileError::Version { found: 9, .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum CalibrationFileError {
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The JSON does not describe a calibration (serde's message has line and column).
    #[error("{path}: {source}")]
    Json {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: serde_json::Error,
    },
    /// A format version this code does not read.
    #[error("{path}: calibration format_version {found}, this version reads {supported}")]
    Version {
        /// The file.
        path: String,
        /// The version found.
        found: u32,
        /// The version supported.
        supported: u32,
    },
}
