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

pub use crate::unit_sensor::FORMAT_VERSION;
use crate::unit_sensor::{KIND, UnitModel, check_header, to_paper, write_json};

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
struct FileOwned {
    model: ModelOwned,
}

/// Whether a file's model names its unit.
#[derive(Deserialize)]
struct Probe {
    model: ProbeModel,
}

#[derive(Deserialize)]
struct ProbeModel {
    unit: Option<serde_json::Value>,
}

impl CompensationModel {
    /// The paper's model of a model of the paper's unit in the paper's
    /// record format (`None` for any other unit): what the paper path's
    /// callers (export, the onboard tables) read until they take the unit's
    /// model.
    pub fn of_unit(m: &UnitModel) -> Option<Self> {
        if !m.unit().is_paper_format() {
            return None;
        }
        let parts = m.inner().clone().into_parts();
        let calibration = match &parts.sensor.calibration {
            Some(c) => Some(to_paper(c)?),
            None => None,
        };
        let channels = serde_json::from_value(serde_json::to_value(&parts.channels).ok()?).ok()?;
        let inner = sysid::Model::from_parts(sysid::ModelParts {
            sensor: PaperUnit {
                calibration,
                rate_reference: parts.sensor.rate_reference,
            },
            preprocess: parts.preprocess,
            dt_s: parts.dt_s,
            split: parts.split,
            channels,
            settings: parts.settings,
            records: parts.records,
            validated_on: parts.validated_on,
            operating_points: parts.operating_points,
            choice: parts.choice,
        })
        .ok()?;
        Some(CompensationModel::of(inner))
    }

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
        if serde_json::from_str::<Probe>(text).is_ok_and(|p| p.model.unit.is_some()) {
            // A file written with its unit: the paper's unit's is this model.
            let m = UnitModel::from_json(text, path)?;
            return Self::of_unit(&m).ok_or_else(|| {
                corrupt(format!(
                    "a model of the unit '{}', not of the paper's unit in the paper's record format",
                    m.unit().name()
                ))
            });
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
