//! A diagnosis as `dtg-vib diagnose` makes it: the model's records
//! refused where the gyro errors are not observable, and every candidate
//! effect ranked on them.

use anyhow::Result;

use super::records::{Read, borrowed, check_observable, signals};
use super::thresholds::Thresholds;
use crate::unit_sensor::UnitModel;

/// The diagnosis of every channel of a unit's model.
pub type UnitDiagnosis = sysid::diagnose::Diagnosis<String, nav_sensors::geometry::Axis>;

/// Diagnoses `model` on its records (read by [`super::records::records_of`]).
pub fn diagnose(model: &UnitModel, read: &Read, thresholds: Thresholds) -> Result<UnitDiagnosis> {
    check_observable(model.inner().sensor(), &read.records)?;
    let named = signals(&read.records)?;
    Ok(sysid::explain::diagnose_records(
        model.inner(),
        &borrowed(&named),
        &thresholds.options(),
    )?)
}
