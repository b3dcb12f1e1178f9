//! The model file of a unit other than the paper's: the loop's model of a
//! [`UnitSensor`], laid out as the paper's model file (same `kind` and
//! `format_version`) with one key more, `unit`, holding the unit file's
//! keys, so commands given `--model` need no `--unit`. A paper model file
//! has no `unit` key and stays byte-identical.

use super::{UnitEffect, UnitSensor};
use crate::error::DtgVibError;
use crate::model::{FORMAT_VERSION, check_header, write_json};
use crate::pipeline::Preprocess;
use crate::split::Holdout;
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::unit::Unit;
use serde::{Deserialize, Serialize};
use std::path::Path;
use sysid::FitSettings;
use sysid::operating::OperatingPoints;

/// One channel model of a unit.
pub type UnitChannelModel = sysid::ChannelModel<String, UnitEffect>;

/// A fitted model of any unit (see the module documentation).
///
/// ```
/// let dir = std::env::temp_dir();
/// let path = dir.join("dtg-vib-doc-not-a-unit-model.json");
/// std::fs::write(&path, r#"{"kind": "dtg-vib compensation model", "format_version": 1, "model": {}}"#).unwrap();
/// assert!(!dtg_vib::unit_sensor::UnitModel::has_unit(&path).unwrap());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct UnitModel {
    inner: sysid::Model<UnitSensor>,
}

#[derive(Serialize)]
struct FileRef<'a> {
    kind: &'static str,
    format_version: u32,
    model: ModelRef<'a>,
}

#[derive(Serialize)]
struct ModelRef<'a> {
    unit: &'a Unit,
    preprocess: Preprocess,
    calibration: Option<&'a UnitCalibration>,
    dt_s: f64,
    split: Holdout,
    channels: &'a [UnitChannelModel],
    fit: &'a FitSettings,
    #[serde(skip_serializing_if = "<[String]>::is_empty")]
    records: &'a [String],
    #[serde(skip_serializing_if = "Option::is_none")]
    validated_on: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    operating_points: Option<&'a OperatingPoints>,
    #[serde(skip_serializing_if = "Option::is_none")]
    choice: Option<&'a sysid::fit::ChoiceReport>,
}

#[derive(Deserialize)]
struct ModelOwned {
    unit: Unit,
    preprocess: Preprocess,
    calibration: Option<UnitCalibration>,
    dt_s: f64,
    split: Holdout,
    channels: Vec<UnitChannelModel>,
    #[serde(default)]
    fit: FitSettings,
    #[serde(default)]
    records: Vec<String>,
    #[serde(default)]
    validated_on: Option<String>,
    #[serde(default)]
    operating_points: Option<OperatingPoints>,
    #[serde(default)]
    choice: Option<sysid::fit::ChoiceReport>,
}

#[derive(Deserialize)]
struct FileOwned {
    model: ModelOwned,
}

#[derive(Deserialize)]
struct Probe {
    model: Option<serde_json::Map<String, serde_json::Value>>,
}

impl UnitModel {
    /// The unit's model of a loop's model.
    pub fn of(inner: sysid::Model<UnitSensor>) -> Self {
        Self { inner }
    }

    /// The loop's model.
    pub fn inner(&self) -> &sysid::Model<UnitSensor> {
        &self.inner
    }

    /// The unit it was fitted with.
    pub fn unit(&self) -> &Unit {
        &self.inner.sensor().unit
    }

    /// What compensation subtracts from each calibrated output, deg/h, in
    /// the unit's channel order: the prediction with its network part faded
    /// outside the training range and the effects unfiltered (θ·z), as
    /// [`crate::model::CompensationModel::compensation`] for the paper's
    /// unit; the onboard evaluator computes the same.
    pub fn compensation(
        &self,
        prepared: &sysid::Prepared<UnitSensor>,
    ) -> Result<Vec<Vec<f64>>, DtgVibError> {
        let above = self.inner.effects_above_band(prepared)?;
        let predicted = self.inner.predict_faded(prepared)?.predicted;
        Ok(predicted
            .iter()
            .zip(&above)
            .map(|(p, a)| p.iter().zip(a).map(|(p, a)| p + a).collect())
            .collect())
    }

    /// Whether the model file at `path` stores a unit (a model of a unit
    /// other than the paper's); an unreadable file says so.
    pub fn has_unit(path: &Path) -> Result<bool, DtgVibError> {
        let text = read(path)?;
        let probe: Probe = serde_json::from_str(&text).map_err(|e| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
        Ok(probe.model.is_some_and(|m| m.contains_key("unit")))
    }

    /// Writes the model as JSON, atomically.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), DtgVibError> {
        let path = path.as_ref();
        let m = &self.inner;
        let s = m.sensor();
        write_json(
            path,
            &FileRef {
                kind: "dtg-vib compensation model",
                format_version: FORMAT_VERSION,
                model: ModelRef {
                    unit: &s.unit,
                    preprocess: Preprocess::of(m.preprocess(), s.rate_reference),
                    calibration: s.calibration.as_ref(),
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

    /// Reads a model written by [`UnitModel::save`].
    pub fn load(path: impl AsRef<Path>) -> Result<Self, DtgVibError> {
        let path = path.as_ref();
        let text = read(path)?;
        let corrupt = |reason: String| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason,
        };
        check_header(&text, path)?;
        // The unit's keys are checked as it is read, before its file is
        // known to it: its messages name this model file instead.
        let stored = format!("the unit stored in {}", path.display());
        let f: FileOwned = serde_json::from_str(&text)
            .map_err(|e| corrupt(e.to_string().replace(STORED_UNIT, &stored)))?;
        let mut m = f.model;
        m.unit = m.unit.with_file(stored);
        let names = m.unit.gyro_names();
        if m.channels.len() != names.len()
            || m.channels
                .iter()
                .zip(&names)
                .any(|(c, n)| c.channel() != *n)
        {
            return Err(corrupt(format!(
                "expected one channel model per gyro of its unit, in order ({})",
                names.join(", ")
            )));
        }
        if let Some(c) = &m.calibration {
            c.check(&m.unit)
                .map_err(|e| corrupt(format!("calibration: {e}")))?;
        }
        let inner = sysid::Model::from_parts(sysid::ModelParts {
            sensor: UnitSensor {
                unit: m.unit,
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
        Ok(Self { inner })
    }
}

/// How a unit read from JSON names its file in messages
/// (`nav_sensors::unit::Unit`'s deserialiser).
const STORED_UNIT: &str = "<stored unit>";

fn read(path: &Path) -> Result<String, DtgVibError> {
    std::fs::read_to_string(path).map_err(|source| DtgVibError::ModelIo {
        path: path.to_path_buf(),
        source,
    })
}
