//! What every file of a test shares: reading it with its path in the error,
//! a calibration's format version checked, JSON written pretty (maps
//! ordered, so deterministic) and atomically.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

use super::error::CalibrationFileError;

/// Reads a text file and hands it with its displayed path to `parse`; an
/// I/O failure becomes `io(path, error)`.
pub(crate) fn load_with<T, E>(
    path: &Path,
    io: impl FnOnce(String, std::io::Error) -> E,
    parse: impl FnOnce(&str, &str) -> Result<T, E>,
) -> Result<T, E> {
    let shown = path.display().to_string();
    match std::fs::read_to_string(path) {
        Ok(text) => parse(&text, &shown),
        Err(source) => Err(io(shown, source)),
    }
}

/// Parses a calibration's JSON and checks its format version.
pub(crate) fn parse_versioned<T: DeserializeOwned>(
    text: &str,
    path: &str,
    version: impl Fn(&T) -> u32,
    supported: u32,
) -> Result<T, CalibrationFileError> {
    let value: T = serde_json::from_str(text).map_err(|source| CalibrationFileError::Json {
        path: path.to_string(),
        source,
    })?;
    let found = version(&value);
    if found != supported {
        return Err(CalibrationFileError::Version {
            path: path.to_string(),
            found,
            supported,
        });
    }
    Ok(value)
}

/// Pretty JSON with a final newline.
pub(crate) fn pretty<T: Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).expect("plain data serialises") + "\n"
}

/// Writes a calibration's pretty JSON atomically.
pub(crate) fn save_calibration<T: Serialize>(
    value: &T,
    path: &Path,
) -> Result<(), CalibrationFileError> {
    outfile::write_bytes(path, pretty(value)).map_err(|source| CalibrationFileError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// The I/O error of a calibration file.
pub(crate) fn calibration_io(path: String, source: std::io::Error) -> CalibrationFileError {
    CalibrationFileError::Io { path, source }
}
