//! A model of the paper's own path (`CompensationModel`) as the unit
//! model of the paper's unit (`units/paper.toml`) that the one exporter
//! and evaluator read: its channels, effects and calibration under the
//! unit's names. Here only until the paper's commands carry the unit model
//! themselves.

use crate::error::DtgVibError;
use crate::model::CompensationModel;
use crate::unit_sensor::{UnitEffect, UnitModel, UnitSensor};
use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::unit::Unit;

/// The paper model `model` as a model of the paper's unit.
pub fn unit_model_of(model: &CompensationModel) -> Result<UnitModel, DtgVibError> {
    let parts = model.inner().clone().into_parts();
    let corrupt = |reason: String| DtgVibError::ModelCorrupt {
        path: "the paper model".into(),
        reason,
    };
    // A channel's file form is its channel's name and its effects' ids,
    // which the unit's channel and effects read back.
    let channels = parts
        .channels
        .iter()
        .map(|c| {
            let v = serde_json::to_value(c).map_err(|e| corrupt(e.to_string()))?;
            serde_json::from_value::<sysid::ChannelModel<String, UnitEffect>>(v)
                .map_err(|e| corrupt(e.to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let calibration = model.calibration().map(|cal| UnitCalibration {
        format_version: UnitCalibration::FORMAT_VERSION,
        gyros: Channel::ALL
            .iter()
            .map(|&ch| (ch.to_string(), GyroCoefficients::Dtg(cal.gyro(ch))))
            .collect(),
        accels: Axis::ALL
            .iter()
            .map(|&a| (a.column().to_string(), cal.accel(a)))
            .collect(),
    });
    let inner = sysid::Model::from_parts(sysid::ModelParts {
        sensor: UnitSensor {
            unit: Unit::paper(),
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
    .map_err(corrupt)?;
    Ok(UnitModel::of(inner))
}
