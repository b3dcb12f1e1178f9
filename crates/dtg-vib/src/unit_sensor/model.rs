//! The model file: the loop's model of a [`UnitSensor`] as versioned JSON
//! (`kind`, `format_version`, `model` with the pre-processing and its rate
//! reference, the calibration, the channel models, …) with the unit inside
//! (`model.unit`, the unit file's keys), so commands given `--model` need
//! no `--unit`. A file of the paper's unit written before the unit was
//! stored (no `unit` key, the paper's calibration format) reads as the
//! paper unit's model; every file written now carries its unit.

use super::calibration::from_paper;
use super::effect::UnitEffect;
use super::preprocess::StoredPreprocess;
use super::sensor::UnitSensor;
use crate::error::DtgVibError;
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
    preprocess: StoredPreprocess,
    calibration: Option<&'a UnitCalibration>,
    dt_s: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    median_dt_s: Option<f64>,
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

/// Version of the model file; bumped on any incompatible change.
pub const FORMAT_VERSION: u32 = 1;

/// A tag that tells a dtg-vib model from other JSON (an `rbf` model, a calibration).
pub(crate) const KIND: &str = "dtg-vib compensation model";

/// The model as read from a file (what older files lack has a default):
/// `C` is the calibration's format, the unit's, or the paper's in a file
/// without a unit.
#[derive(Deserialize)]
struct ModelOwned<C> {
    #[serde(default)]
    unit: Option<Unit>,
    preprocess: StoredPreprocess,
    calibration: Option<C>,
    dt_s: f64,
    #[serde(default)]
    median_dt_s: Option<f64>,
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
struct FileOwned<C> {
    model: ModelOwned<C>,
}

#[derive(Deserialize)]
struct Header {
    kind: Option<String>,
    format_version: Option<u64>,
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
    /// outside the training range and the effects unfiltered (θ·z); the
    /// onboard evaluator computes the same.
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

    /// Whether the model file at `path` stores its unit (every file written
    /// now does; a paper model file written before does not); an
    /// unreadable file says so.
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
                kind: KIND,
                format_version: FORMAT_VERSION,
                model: ModelRef {
                    unit: &s.unit,
                    preprocess: StoredPreprocess::of(m.preprocess(), s.rate_reference),
                    calibration: s.calibration.as_ref(),
                    dt_s: m.dt_s(),
                    median_dt_s: stored_median(m.dt_s(), m.median_dt_s()),
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

    /// Reads a model file: one written by [`UnitModel::save`], or a paper
    /// model file written before the unit was stored (read as the paper
    /// unit's, its calibration converted).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, DtgVibError> {
        let path = path.as_ref();
        let text = read(path)?;
        Self::from_json(&text, path)
    }

    /// Parses model JSON; `path` names the source in errors.
    pub fn from_json(text: &str, path: &Path) -> Result<Self, DtgVibError> {
        let corrupt = |reason: String| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason,
        };
        check_header(text, path)?;
        let probe: Probe = serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
        if !probe.model.is_some_and(|m| m.contains_key("unit")) {
            let mut f: FileOwned<UnitCalibration> =
                serde_json::from_str(text).map_err(|e| corrupt(e.to_string()))?;
            let calibration = f.model.calibration.take().map(from_paper);
            return Self::from_owned(f.model, Unit::paper(), calibration, path);
        }
        // The unit's keys are checked as it is read, before its file is
        // known to it: its messages name this model file instead.
        let stored = format!("the unit stored in {}", path.display());
        let f: FileOwned<UnitCalibration> = serde_json::from_str(text)
            .map_err(|e| corrupt(e.to_string().replace(STORED_UNIT, &stored)))?;
        let mut m = f.model;
        let unit = m.unit.take().expect("probed").with_file(stored);
        let calibration = m.calibration.take();
        Self::from_owned(m, unit, calibration, path)
    }

    /// The model of `unit` from what its file holds, checked: one channel
    /// model per gyro of the unit, in order, and a calibration of the unit.
    fn from_owned<C>(
        m: ModelOwned<C>,
        unit: Unit,
        calibration: Option<UnitCalibration>,
        path: &Path,
    ) -> Result<Self, DtgVibError> {
        let corrupt = |reason: String| DtgVibError::ModelCorrupt {
            path: path.to_path_buf(),
            reason,
        };
        let names = unit.gyro_names();
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
        if let Some(c) = &calibration {
            c.check(&unit)
                .map_err(|e| corrupt(format!("calibration: {e}")))?;
        }
        // Effects are stored by id: a column's role comes from the unit.
        let channels = m
            .channels
            .into_iter()
            .map(|c| c.map_effects(|e| e.resolved(&unit)))
            .collect();
        let inner = sysid::Model::from_parts(sysid::ModelParts {
            sensor: UnitSensor {
                unit,
                calibration,
                rate_reference: m.preprocess.rate_reference,
            },
            preprocess: m.preprocess.sysid(),
            dt_s: m.dt_s,
            median_dt_s: m.median_dt_s,
            split: m.split,
            channels,
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

/// The median sample interval as the file stores it: only where it is not
/// the mean `dt_s` (a record with dropped samples; the fit takes the mean
/// as the median of an evenly sampled record), so that the file of an
/// evenly sampled record reads as one written before the key existed.
fn stored_median(dt_s: f64, median_dt_s: f64) -> Option<f64> {
    (median_dt_s != dt_s).then_some(median_dt_s)
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

/// Checks that `text` is a dtg-vib model file of the supported format
/// version.
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
