//! The ground calibration the commands read: a unit calibration file
//! (docs/formats.md), or a calibration of the paper's unit written before
//! the one format (gyros keyed `X` … `Z1` without a model tag, accelerometers
//! keyed `x`, `y`, `z`), read as the unit calibration it is.

use crate::error::DtgVibError;
use nav_sensors::calibration::{
    Calibration, CalibrationFileError, GyroCoefficients, UnitCalibration,
};
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

/// Parses calibration JSON of either format; `path` names it in errors,
/// which are those of the format the text is written in (a unit
/// calibration's gyro tables carry a `model` tag).
pub fn calibration_from_json(
    text: &str,
    path: &str,
) -> Result<UnitCalibration, CalibrationFileError> {
    match UnitCalibration::from_json(text, path) {
        Ok(c) => Ok(c),
        Err(unit_error) => match Calibration::from_json(text, path) {
            Ok(c) => Ok(from_paper(&c)),
            Err(_) if text.contains("\"model\"") => Err(unit_error),
            Err(paper_error) => Err(paper_error),
        },
    }
}

/// A calibration of the paper's unit as its unit calibration: each
/// channel's table under its name (without `temp` and `rect_2n`, which
/// ground calibration never covers and the paper's compensation zeroed),
/// each axis's accelerometer under its column name (`ax`, `ay`, `az`).
pub fn from_paper(c: &Calibration) -> UnitCalibration {
    UnitCalibration {
        format_version: UnitCalibration::FORMAT_VERSION,
        gyros: c
            .gyros
            .keys()
            .map(|&ch| (ch.name().to_string(), GyroCoefficients::Dtg(c.gyro(ch))))
            .collect(),
        accels: c
            .accels
            .iter()
            .map(|(a, k)| (a.column().to_string(), *k))
            .collect(),
    }
}
