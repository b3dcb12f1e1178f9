//! The commands on a unit other than the paper's (`--unit FILE|NAME`, or a
//! model that stores its unit): the same loop through the unit's plug-in
//! ([`dtg_vib::unit_sensor`]). Without `--unit`, or with the paper's unit,
//! every command runs its paper path unchanged, so the paper's outputs and
//! model files stay what they were.

pub mod allan;
pub mod apply;
pub mod demo;
pub mod fit;
pub mod report;
pub mod residues;

use anyhow::{Result, anyhow, bail};
use dtg_vib::pipeline::RateReference;
use dtg_vib::unit_sensor::{
    MOVING_RATE_STD_DEG_S, UnitModel, UnitSensor, UnitSensorError, observability,
    read_unit_records, to_signals,
};
use nav_sensors::calibration::UnitCalibration;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use std::path::{Path, PathBuf};
use sysid::Signals;

/// `--unit ARG` resolved: `None` without one or for the paper's unit in
/// the paper's format (its own path), the unit otherwise.
pub fn chosen(arg: Option<&str>) -> Result<Option<Unit>> {
    let Some(arg) = arg else {
        return Ok(None);
    };
    let unit = Unit::resolve(arg).map_err(|e| anyhow!("--unit {arg}: {e}"))?;
    Ok((!unit.is_paper_format()).then_some(unit))
}

/// The model at `path` if it stores a unit (then `--unit`, if given, must
/// be that unit); `None` for a paper model, which a non-paper `--unit`
/// cannot go with.
pub fn model_unit(path: &Path, arg: Option<&str>) -> Result<Option<UnitModel>> {
    let given = chosen(arg)?;
    let has = match UnitModel::has_unit(path) {
        Ok(has) => has,
        // The paper path says what is wrong with the file, as it always did.
        Err(_) if given.is_none() => return Ok(None),
        Err(e) => return Err(e.into()),
    };
    if has {
        let m = UnitModel::load(path)?;
        if let Some(arg) = arg {
            let u = Unit::resolve(arg).map_err(|e| anyhow!("--unit {arg}: {e}"))?;
            if &u != m.unit() {
                bail!(
                    "--unit {arg}: {} was fitted with the unit '{}', which it stores: drop --unit (a model carries its unit)",
                    path.display(),
                    m.unit().name()
                );
            }
        }
        return Ok(Some(m));
    }
    if let (Some(arg), Some(_)) = (arg, given) {
        bail!(
            "--unit {arg}: {} is a model of the paper's unit (it stores no unit): fit a model on this unit's records with dtg-vib fit --unit {arg}",
            path.display()
        );
    }
    Ok(None)
}

/// Refuses each path given twice (a record fitted twice weighs double).
pub fn once_each(data: &[PathBuf]) -> Result<()> {
    super::fit_args::once_each(data)
}

/// Logs read with a unit: their segments and what the time columns
/// showed, said once the command has done its work (a refusal stays one
/// line).
pub struct Read {
    /// Every log's segments, in order.
    pub records: Vec<(String, Record)>,
    /// One line per log with gaps.
    pub notes: Vec<String>,
}

impl Read {
    /// Prints the notes on stderr.
    pub fn say_notes(&self) {
        for n in &self.notes {
            eprintln!("{n}");
        }
    }
}

/// Reads every log with the unit: its segments between time gaps (each a
/// record of its own), those shorter than `min_samples` dropped.
pub fn read_records(data: &[PathBuf], unit: &Unit, min_samples: usize) -> Result<Read> {
    once_each(data)?;
    let mut records = Vec::new();
    let mut notes = Vec::new();
    for d in data {
        let read = read_unit_records(d, unit, min_samples)?;
        notes.extend(read.gaps_notice(&d.display().to_string()));
        records.extend(read.segments);
    }
    Ok(Read { records, notes })
}

/// Named records as the loop's named signals.
pub fn signals(records: &[(String, Record)]) -> Result<Vec<(String, Signals)>> {
    records
        .iter()
        .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
        .collect()
}

pub use dtg_vib::paper_unit::borrowed;

/// The unit's plug-in with its calibration file (checked against it) and
/// rate reference.
pub fn sensor(unit: Unit, calib: Option<&Path>, reference: RateReference) -> Result<UnitSensor> {
    reference.check()?;
    let calibration = match calib {
        Some(p) => {
            let c = UnitCalibration::load(p)?;
            c.check(&unit)
                .map_err(|e| anyhow!("--calib {}: {e}", p.display()))?;
            Some(c)
        }
        None => None,
    };
    Ok(UnitSensor {
        unit,
        calibration,
        rate_reference: reference,
    })
}

/// Refuses records on which the gyro errors are not observable: a moving
/// unit without a rate reference (each target would be the motion).
pub fn check_observable(sensor: &UnitSensor, records: &[(String, Record)]) -> Result<()> {
    if sensor.rate_reference != RateReference::None {
        return Ok(());
    }
    for (name, r) in records {
        let o = observability(sensor, r);
        if o.rate_std_deg_s > MOVING_RATE_STD_DEG_S {
            let redundant = if sensor.unit.gyros().len() > 3 {
                "; or judge this redundant unit by its parity residues (dtg-vib residues), which the motion does not enter".to_string()
            } else {
                "; or use a redundant unit (four or more gyros), whose parity residues the motion does not enter".to_string()
            };
            return Err(UnitSensorError::Moving {
                record: name.clone(),
                rate_std_deg_s: o.rate_std_deg_s,
                max_deg_s: MOVING_RATE_STD_DEG_S,
                redundant,
            }
            .into());
        }
    }
    Ok(())
}

/// The note that a unit of three gyros has no parity residue, where one
/// would be shown.
pub fn no_residue_note(unit: &Unit) -> Option<String> {
    unit.residue_names().is_empty().then(|| {
        format!(
            "note: the unit '{}' has {} gyros: nothing is redundant, so it has no parity residue; its channels are judged against the rate reference (rms before and after per channel)",
            unit.name(),
            unit.gyros().len()
        )
    })
}
