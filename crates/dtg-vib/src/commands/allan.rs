//! An Allan analysis as `dtg-vib allan` makes it: the overlapping Allan
//! deviation and IEEE 952 noise terms of every channel and residue of the
//! record's longest segment (an average never spans a time gap), before
//! and, with a model, after its compensation.

use anyhow::Result;
use nav_sensors::unit::Unit;

use super::records::{Read, turning};
use crate::allan::AllanAnalysis;
use crate::unit_sensor::{MOVING_RATE_STD_DEG_S, RateReference, UnitModel};

/// The two-sided confidence level of the intervals unless told (`--confidence`).
pub const DEFAULT_CONFIDENCE: f64 = 0.683;

/// The analysis and the segment it is of.
pub struct Allan {
    pub analysis: AllanAnalysis,
    /// The longest segment's name.
    pub segment: String,
    /// Segments read (more than one: the log had time gaps).
    pub segments: usize,
    /// The unit's name.
    pub unit: String,
    /// That the unit turns, where it does and the model does not remove
    /// the motion: the deviations hold it.
    pub warning: Option<String>,
}

/// The analysis of `read`'s longest segment with the unit (the model's,
/// where one is given) at two-sided `confidence`.
pub fn allan(
    unit: &Unit,
    model: Option<&UnitModel>,
    read: &Read,
    confidence: f64,
) -> Result<Allan> {
    let (name, record) = read
        .records
        .iter()
        .max_by_key(|(_, r)| r.len())
        .ok_or_else(|| anyhow::anyhow!("no segment to analyse"))?;
    // A model fitted in parity removes the unit's own rate from every
    // channel before and after: the motion is not in the deviations.
    let parity = model.is_some_and(|m| m.inner().sensor().rate_reference == RateReference::Parity);
    let warning = turning(unit, record).filter(|_| !parity).map(|std| {
        format!(
            "{name}: the unit turns (its rate varies by {std:.2} deg/s over 1-s averages, above {MOVING_RATE_STD_DEG_S} deg/s): the deviations hold the motion as well as the sensors' noise"
        )
    });
    let analysis = AllanAnalysis::new(unit, model, record, confidence)?;
    Ok(Allan {
        analysis,
        segment: name.clone(),
        segments: read.records.len(),
        unit: unit.name().to_string(),
        warning,
    })
}

impl Allan {
    /// `allan --json`'s object.
    pub fn to_json(&self) -> serde_json::Value {
        let mut v = self.analysis.to_json();
        v["unit"] = serde_json::Value::String(self.unit.clone());
        v["segment"] = serde_json::Value::String(self.segment.clone());
        v["compensated"] = serde_json::Value::Bool(self.analysis.compensated);
        v
    }
}
