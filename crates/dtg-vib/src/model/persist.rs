//! Saving and loading compensation models as versioned JSON.

use super::CompensationModel;
use crate::error::DtgVibError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Version of the model file; bumped on any incompatible change.
pub const FORMAT_VERSION: u32 = 1;

/// A tag that tells a dtg-vib model from other JSON (an `rbf` model, a calibration).
const KIND: &str = "dtg-vib compensation model";

#[derive(Serialize)]
struct FileRef<'a> {
    kind: &'static str,
    format_version: u32,
    model: &'a CompensationModel,
}

#[derive(Deserialize)]
struct Header {
    kind: Option<String>,
    format_version: Option<u64>,
}

#[derive(Deserialize)]
struct FileOwned {
    model: CompensationModel,
}

impl CompensationModel {
    /// Writes the model as JSON.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), DtgVibError> {
        let path = path.as_ref();
        let text = serde_json::to_string_pretty(&FileRef {
            kind: KIND,
            format_version: FORMAT_VERSION,
            model: self,
        })
        .map_err(|e| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
        outfile::write_bytes(path, text).map_err(|source| DtgVibError::ModelIo {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Reads a model saved by [`CompensationModel::save`], checking its kind
    /// and format version.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, DtgVibError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|source| DtgVibError::ModelIo {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_json(&text, path)
    }

    /// Parses model JSON; `path` names the source in errors.
    pub fn from_json(text: &str, path: &Path) -> Result<Self, DtgVibError> {
        let corrupt = |reason: String| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason,
        };
        let header: Header = serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
        if header.kind.as_deref() != Some(KIND) {
            return Err(corrupt(format!("expected \"kind\": \"{KIND}\"")));
        }
        match header.format_version {
            Some(v) if v == u64::from(FORMAT_VERSION) => {}
            Some(found) => {
                return Err(DtgVibError::ModelVersion {
                    path: path.to_path_buf(),
                    found,
                    expected: FORMAT_VERSION,
                });
            }
            None => return Err(corrupt("no format_version".into())),
        }
        let file: FileOwned = serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
        let m = file.model;
        if m.channels.len() != 6
            || m.channels
                .iter()
                .enumerate()
                .any(|(k, c)| c.channel().index() != k)
        {
            return Err(corrupt(
                "expected six channel models in X, X1, Y, Y1, Z, Z1 order".into(),
            ));
        }
        m.check_consistency().map_err(corrupt)?;
        Ok(m)
    }
}
