//! A compensation as `dtg-vib compensate` writes it: each segment of the
//! record with the model's prediction removed, in the unit's column names
//! and units, one CSV after the other under one header.

use anyhow::Result;

use super::records::{Read, unit_csv};
use crate::unit_sensor::{Applied, UnitModel};

/// The compensated record as CSV text, and what it holds.
pub struct Compensated {
    /// The CSV: one header, then every segment's rows.
    pub text: Vec<u8>,
    /// Data rows.
    pub rows: usize,
    /// The samples at the start of each segment without a full window (not written).
    pub first_sample: usize,
}

/// Removes the model's prediction from every record of `read`.
pub fn compensate(model: &UnitModel, read: &Read) -> Result<Compensated> {
    let applied = Applied::unsplit(model, &read.borrowed())?;
    let compensated = applied.compensated()?;
    let named = read
        .records
        .iter()
        .map(|(n, _)| n.as_str())
        .zip(&compensated);
    let (text, rows) = unit_csv(named, model.unit())?;
    Ok(Compensated {
        text,
        rows,
        first_sample: applied.prepared.first_sample(),
    })
}
