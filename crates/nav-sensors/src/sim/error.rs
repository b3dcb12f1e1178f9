//! Errors of the simulator.

use super::scenario::ScenarioError;
use crate::files::calibration::CalibrationFileError;
use crate::files::record::RecordError;
use crate::vibration::VibrationError;

/// Everything that can stop a simulation or writing its files.
///
/// ```
/// use nav_sensors::sim::{simulate_unit, Scenario, SimError};
/// let paper = nav_sensors::unit::Unit::paper();
/// let err = simulate_unit(&paper, &Scenario { output_rate_hz: 0.0, ..Scenario::default() }).unwrap_err();
/// assert!(matches!(err, SimError::Scenario(_)));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// The scenario is invalid.
    #[error("scenario: {0}")]
    Scenario(#[from] ScenarioError),
    /// The vibration could not be generated.
    #[error("vibration: {0}")]
    Vibration(#[from] VibrationError),
    /// Building or writing the record failed.
    #[error(transparent)]
    Record(#[from] RecordError),
    /// Writing the calibration failed.
    #[error(transparent)]
    Calibration(#[from] CalibrationFileError),
    /// Writing an output file or creating the directory failed.
    #[error("{path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
}
