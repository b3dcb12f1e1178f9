//! The paper's calibration file format ([`crate::unit::FileFormat::Paper`]:
//! DTG tables by channel without `model`, accelerometers by axis `x`, `y`,
//! `z`), which the built-in `paper` unit writes and which reads as the
//! paper unit's [`super::calibration::UnitCalibration`].

use std::collections::BTreeMap;

use serde::Serialize;

use super::error::CalibrationFileError;
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
