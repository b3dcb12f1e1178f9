//! Saving and loading compensation models as versioned JSON.

use super::{ChannelModel, CompensationModel};
use crate::error::DtgVibError;
use crate::paper_unit::PaperUnit;
use crate::pipeline::Preprocess;
use crate::split::Holdout;
use nav_sensors::calibration::Calibration;
use serde::{Deserialize, Serialize};
use std::path::Path;
use sysid::FitSettings;
use sysid::fit::ChoiceReport;
use sysid::operating::OperatingPoints;

/// Version of the model file; bumped on any incompatible change.
pub const FORMAT_VERSION: u32 = 1;

/// A tag that tells a dtg-vib model from other JSON (an `rbf` model, a calibration).
pub(crate) const KIND: &str = "dtg-vib compensation model";

#[derive(Serialize)]
struct FileRef<'a> {
    kind: &'static str,
    format_version: u32,
    model: ModelRef<'a>,
}

/// The model as the file lays it out (the layout of every file written
/// since format version 1: the unit's rate reference inside the
/// pre-processing, its calibration next).
#[derive(Serialize)]
struct ModelRef<'a> {
    preprocess: &'a Preprocess,
    calibration: Option<&'a Calibration>,
    dt_s: f64,
    split: Holdout,
    channels: &'a [ChannelModel],
    fit: &'a FitSettings,
    #[serde(skip_serializing_if = "<[String]>::is_empty")]
    records: &'a [String],
    #[serde(skip_serializing_if = "Option::is_none")]
    validated_on: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    operating_points: Option<&'a OperatingPoints>,
    #[serde(skip_serializing_if = "Option::is_none")]
    choice: Option<&'a ChoiceReport>,
}

/// The model as read from a file (what older files lack has a default).
#[derive(Deserialize)]
struct ModelOwned {
    preprocess: Preprocess,
    calibration: Option<Calibration>,
    dt_s: f64,
    split: Holdout,
    channels: Vec<ChannelModel>,
    /// How the networks were chosen (absent in older files: the defaults).
    #[serde(default)]
    fit: FitSettings,
    /// The records fitted together, when there were several.
    #[serde(default)]
    records: Vec<String>,
    /// Of several records, the one that only validated.
    #[serde(default)]
    validated_on: Option<String>,
    /// Where the training windows sat (absent in older files: `check` then
    /// cannot say what is outside).
    #[serde(default)]
    operating_points: Option<OperatingPoints>,
    /// The fit's choice of input and smoother with every candidate's
    /// figures (absent in older files and in fits told both).
    #[serde(default)]
    choice: Option<ChoiceReport>,
}

#[derive(Deserialize)]
struct Header {
    kind: Option<String>,
    format_version: Option<u64>,
}

#[derive(Deserialize)]
struct FileOwned {
    model: ModelOwned,
}

impl CompensationModel {
    /// Writes the model as JSON.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), DtgVibError> {
        let path = path.as_ref();
        let m = &self.inner;
        write_json(
            path,
            &FileRef {
                kind: KIND,
                format_version: FORMAT_VERSION,
                model: ModelRef {
                    preprocess: &self.preprocess,
                    calibration: self.calibration(),
                    dt_s: m.dt_s(),
                    split: m.split(),
                    channels: m.channels(),
                    fit: m.settings(),
                    records: m.records(),
                    validated_on: m.validated_on(),
                    operating_points: m.operating_points(),
                    choice: m.choice(),
                },
            },
        )
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
        check_header(text, path)?;
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
        let inner = sysid::Model::from_parts(sysid::ModelParts {
            sensor: PaperUnit {
                calibration: m.calibration,
                rate_reference: m.preprocess.rate_reference,
            },
            preprocess: m.preprocess.sysid(),
            dt_s: m.dt_s,
            split: m.split,
            channels: m.channels,
            settings: m.fit,
            records: m.records,
            validated_on: m.validated_on,
            operating_points: m.operating_points,
            choice: m.choice,
        })
        .map_err(corrupt)?;
        Ok(CompensationModel::of(inner))
    }
}

/// Checks that `text` is a dtg-vib model file of the supported format
/// version (the paper's, or another unit's: one header for both).
pub(crate) fn check_header(text: &str, path: &Path) -> Result<(), DtgVibError> {
    let corrupt = |reason: String| DtgVibError::ModelCorrupt {
        path: path.to_path_buf(),
        reason,
    };
    let header: Header = serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
    if header.kind.as_deref() != Some(KIND) {
        return Err(corrupt(format!("expected \"kind\": \"{KIND}\"")));
    }
    match header.format_version {
        Some(v) if v == u64::from(FORMAT_VERSION) => Ok(()),
        Some(found) => Err(DtgVibError::ModelVersion {
            path: path.to_path_buf(),
            found,
            expected: FORMAT_VERSION,
        }),
        None => Err(corrupt("no format_version".into())),
    }
}

/// Writes a model file's JSON (pretty) atomically.
pub(crate) fn write_json(path: &Path, file: &impl Serialize) -> Result<(), DtgVibError> {
    let text = serde_json::to_string_pretty(file).map_err(|e| DtgVibError::ModelCorrupt {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    outfile::write_bytes(path, text).map_err(|source| DtgVibError::ModelIo {
        path: path.to_path_buf(),
        source,
    })
}
