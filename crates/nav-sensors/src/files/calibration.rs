//! The ground calibration files: a unit's ([`UnitCalibration`], gyro tables
//! by name each saying its model), and the paper's format
//! ([`crate::unit::FileFormat::Paper`]: DTG tables by channel without
//! `model`, accelerometers by axis `x`, `y`, `z`), which the built-in
//! `paper` unit writes and which reads as the paper unit's calibration.

use std::collections::BTreeMap;

use serde::Serialize;

pub use super::error::CalibrationFileError;
pub use super::unit_calibration::{GyroCoefficients, UnitCalibration, UnitCalibrationError};
use crate::accel::AccelCoefficients;
use crate::dtg::DtgCoefficients;
use crate::geometry::{Axis, Channel};

/// A calibration in the paper's format, as written: per channel its DTG
/// table, per axis its accelerometer table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct PaperCalibration {
    /// File format version (1).
    pub(crate) format_version: u32,
    /// DTG coefficients per channel.
    pub(crate) gyros: BTreeMap<Channel, DtgCoefficients>,
    /// Accelerometer coefficients per axis.
    pub(crate) accels: BTreeMap<Axis, AccelCoefficients>,
}

impl PaperCalibration {
    /// The format version written.
    pub(crate) const FORMAT_VERSION: u32 = 1;

    /// Writes the calibration as a JSON file, atomically.
    pub(crate) fn save(
        &self,
        path: impl AsRef<std::path::Path>,
    ) -> Result<(), CalibrationFileError> {
        super::io::save_calibration(self, path.as_ref())
    }
}
