//! The ground calibration the commands read: a unit calibration file
//! (docs/formats.md), or a calibration of the paper's unit written before
//! the one format (gyros keyed `X` … `Z1` without a model tag, accelerometers
//! keyed `x`, `y`, `z`), read as the unit calibration it is.

use crate::error::DtgVibError;
use nav_sensors::calibration::{CalibrationFileError, GyroCoefficients, UnitCalibration};
use nav_sensors::dtg::DtgTerm;
use std::path::Path;

/// Reads a calibration file of either format.
///
/// ```
/// let dir = std::env::temp_dir();
/// let path = dir.join("dtg-vib-doc-paper-calibration.json");
/// std::fs::write(&path, r#"{"format_version": 1, "gyros": {"Z": {"bias_deg_h": 2.0}}, "accels": {"z": {"bias_ug": 50.0}}}"#).unwrap();
/// let c = dtg_vib::unit_sensor::load_calibration(&path).unwrap();
/// assert!(c.check(&nav_sensors::unit::Unit::paper()).is_ok());
/// assert_eq!(c.accels["az"].bias_ug, 50.0);
/// ```
pub fn load_calibration(path: &Path) -> Result<UnitCalibration, DtgVibError> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|source| CalibrationFileError::Io {
            path: shown.clone(),
            source,
        })
        .map_err(DtgVibError::from)?;
    calibration_from_json(&text, &shown).map_err(DtgVibError::from)
}

/// Parses calibration JSON of either format (a unit calibration's gyro
/// tables carry a `model` tag; the paper's do not); `path` names it in
/// errors.
pub fn calibration_from_json(
    text: &str,
    path: &str,
) -> Result<UnitCalibration, CalibrationFileError> {
    UnitCalibration::from_json(text, path)
}

/// The calibration a paper model file written before the one format
/// embeds, as the paper unit's: each DTG table without `temp` and
/// `rect_2n`, which ground calibration never covers and the paper's
/// compensation zeroed.
pub(crate) fn from_paper(c: UnitCalibration) -> UnitCalibration {
    let gyros = c
        .gyros
        .into_iter()
        .map(|(name, t)| match t {
            GyroCoefficients::Dtg(t) => (
                name,
                GyroCoefficients::Dtg(t.without(&[DtgTerm::Temp, DtgTerm::Rect2N])),
            ),
            rate => (name, rate),
        })
        .collect();
    UnitCalibration { gyros, ..c }
}
