//! What every command resolves the same way from its flags: the unit
//! (`--unit FILE|NAME`, the paper's by default), a model file (which
//! carries its unit), the unit's plug-in with its calibration and rate
//! reference, and logs read with the unit in segments between time gaps.

use crate::unit_sensor::{
    MOVING_RATE_STD_DEG_S, PARITY_NOTE, RateReference, UnitModel, UnitSensor, UnitSensorError,
    load_calibration, observability, read_unit_records, to_signals,
};
use anyhow::{Result, anyhow, bail};
use nav_sensors::record::{GLITCH_Z, Record, declared_unit_warnings, glitches, is_ulog};
use nav_sensors::unit::Unit;
use std::path::{Path, PathBuf};
use sysid::Signals;

/// `--unit ARG` resolved: the unit it names, or the paper's without one.
pub fn unit_of(arg: Option<&str>) -> Result<Unit> {
    match arg {
        None => Ok(Unit::paper()),
        Some(arg) => Unit::resolve(arg).map_err(|e| anyhow!("--unit {arg}: {e}")),
    }
}

/// The model at `path` (any model file: one that stores its unit, or a
/// paper model file written before, read as the paper unit's); `--unit`,
/// if given, must be the unit it stores.
pub fn open_model(path: &Path, arg: Option<&str>) -> Result<UnitModel> {
    let m = UnitModel::load(path)?;
    model_unit(&m, &path.display().to_string(), arg)?;
    Ok(m)
}

/// Refuses a `--unit` that is not the one the model (named `what`) stores.
pub fn model_unit(m: &UnitModel, what: &str, arg: Option<&str>) -> Result<()> {
    if let Some(arg) = arg {
        let u = unit_of(Some(arg))?;
        if &u != m.unit() {
            bail!(
                "--unit {arg}: {what} was fitted with the unit '{}', which it stores: drop --unit (a model carries its unit)",
                m.unit().name()
            );
        }
    }
    Ok(())
}

/// The unit of a command that takes `--unit` and an optional model: the
/// model's (`--unit` refused if another), else `--unit`'s; and the shortest
/// segment it reads, two of the model's windows (two samples without one).
pub fn unit_and_min(m: Option<&UnitModel>, what: &str, arg: Option<&str>) -> Result<(Unit, usize)> {
    match m {
        Some(m) => {
            model_unit(m, what, arg)?;
            Ok((m.unit().clone(), 2 * m.inner().preprocess().window.length()))
        }
        None => Ok((unit_of(arg)?, 2)),
    }
}

/// Refuses a record given twice: fitted twice it would weigh double, and a
/// split by record could not tell its two copies apart.
pub fn once_each(data: &[PathBuf]) -> Result<()> {
    let canonical = |p: &PathBuf| std::fs::canonicalize(p).unwrap_or_else(|_| p.clone());
    for (i, d) in data.iter().enumerate() {
        if let Some(e) = data[..i].iter().find(|e| canonical(e) == canonical(d)) {
            bail!(
                "--data {} is the same file as --data {}: give each record once",
                d.display(),
                e.display()
            );
        }
    }
    Ok(())
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

    /// The records as the library borrows them.
    pub fn borrowed(&self) -> Vec<(String, &Record)> {
        self.records.iter().map(|(n, r)| (n.clone(), r)).collect()
    }
}

/// Reads every log with the unit: its segments between time gaps (each a
/// record of its own), those shorter than `min_samples` dropped.
pub fn read_records(data: &[PathBuf], unit: &Unit, min_samples: usize) -> Result<Read> {
    once_each(data)?;
    let mut records = Vec::new();
    let mut notes = Vec::new();
    for d in data {
        let read = read_unit_records(d, unit, min_samples).map_err(|e| {
            // A log too short for the model reads with its unit: another
            // unit would not lengthen it.
            let suggestion = match e {
                UnitSensorError::TooShort { .. } => None,
                _ => builtin_suggestion(d, unit),
            };
            anyhow!("{e}{}", suggestion.unwrap_or_default())
        })?;
        notes.extend(read.gaps_notice(&d.display().to_string()));
        notes.extend(declared_unit_notes(d, unit, &read.segments));
        notes.extend(glitch_notes(unit, &read.segments));
        records.extend(read.segments);
    }
    Ok(Read { records, notes })
}

/// Whether the unit turns during the record (its least-squares rate's
/// 1-s averages vary by more than [`MOVING_RATE_STD_DEG_S`]), with how much.
pub fn turning(unit: &Unit, record: &Record) -> Option<f64> {
    let sensor = UnitSensor {
        unit: unit.clone(),
        calibration: None,
        rate_reference: RateReference::None,
    };
    let std = observability(&sensor, record).rate_std_deg_s;
    (std > MOVING_RATE_STD_DEG_S).then_some(std)
}

/// The warnings of the unit file's declared units that the log's longest
/// segment contradicts (nav_sensors::record::declared_unit_warnings), one
/// line each, naming the log.
fn declared_unit_notes(path: &Path, unit: &Unit, segments: &[(String, Record)]) -> Vec<String> {
    let Some((_, longest)) = segments.iter().max_by_key(|(_, r)| r.len()) else {
        return Vec::new();
    };
    let still = turning(unit, longest).is_none();
    declared_unit_warnings(unit, longest, still)
        .into_iter()
        .map(|w| format!("warning: {}: {w}", path.display()))
        .collect()
}

/// One line per segment with glitches (nav_sensors::record::glitches):
/// which gyro strays at which rows, counted from the segment's first.
fn glitch_notes(unit: &Unit, segments: &[(String, Record)]) -> Vec<String> {
    segments
        .iter()
        .filter_map(|(name, r)| {
            let g = glitches(unit, r);
            (!g.is_empty()).then(|| {
                let list: Vec<String> = g.iter().map(ToString::to_string).collect();
                format!(
                    "note: {name}: glitches at {}: there the gyro strays from the other gyros (its parity-projected output beyond {GLITCH_Z} robust σ of its own spread; no clean sample of the real flights reaches 8) as a dropout or a transmission error does; rows count from the first sample of {name} (0) and times are the log's; they are kept: cut them from the log to leave them out of the fit",
                    list.join(", ")
                )
            })
        })
        .collect()
}

/// The flag to add when `unit` could not read a log of a built-in unit: a
/// CSV whose header holds a built-in unit's columns, or a ULog file (its
/// `sensor_combined` topic is a triad's).
fn builtin_suggestion(path: &Path, unit: &Unit) -> Option<String> {
    if is_ulog(path) {
        return (unit.name() != "triad")
            .then(|| "; its sensor_combined topic is a triad's: add --unit triad".to_string());
    }
    let file = std::fs::File::open(path).ok()?;
    let first = std::io::BufRead::lines(std::io::BufReader::new(file))
        .next()?
        .ok()?;
    let header: Vec<&str> = first.split(',').map(str::trim).collect();
    // The built-in itself, read from its file or stored in a model file,
    // needs no other unit.
    let name = Unit::builtins_matching(&header)
        .into_iter()
        .find(|n| Unit::builtin(n).ok().as_ref() != Some(unit))?;
    Some(format!(
        "; the log has the columns of built-in unit {name}: add --unit {name}"
    ))
}

/// The records of a model's unit, segments at least two windows long.
pub fn records_of(m: &UnitModel, data: &[PathBuf]) -> Result<Read> {
    let window = m.inner().preprocess().window.length();
    read_records(data, m.unit(), 2 * window)
}

/// Named records as the loop's named signals.
pub fn signals(records: &[(String, Record)]) -> Result<Vec<(String, Signals)>> {
    records
        .iter()
        .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
        .collect()
}

/// Named signals as the loop borrows them.
pub fn borrowed(named: &[(String, Signals)]) -> Vec<(String, &Signals)> {
    named.iter().map(|(n, s)| (n.clone(), s)).collect()
}

/// The unit's plug-in with its calibration file (either format, checked
/// against the unit) and rate reference.
pub fn sensor(unit: Unit, calib: Option<&Path>, reference: RateReference) -> Result<UnitSensor> {
    reference.check()?;
    let calibration = match calib {
        Some(p) => {
            let c = load_calibration(p)?;
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

/// A redundant unit (one with parity residues) given no rate reference,
/// on records one of which turns, is fitted in parity: its rate reference
/// becomes the unit's own least-squares rate ([`RateReference::Parity`]).
/// Returns the one line saying so and what that cannot observe.
pub fn parity_in_motion(sensor: &mut UnitSensor, records: &[(String, Record)]) -> Option<String> {
    if sensor.rate_reference != RateReference::None || sensor.unit.residue_names().is_empty() {
        return None;
    }
    let (name, std) = records
        .iter()
        .find_map(|(n, r)| turning(&sensor.unit, r).map(|s| (n, s)))?;
    sensor.rate_reference = RateReference::Parity;
    Some(format!(
        "note: {name}: the unit turns (its rate varies by {std:.2} deg/s over 1-s averages) and no rate reference is given, so it is fitted in parity: {PARITY_NOTE}"
    ))
}

/// Refuses records on which the gyro errors are not observable: a moving
/// unit without a rate reference (each target would be the motion).
pub fn check_observable(sensor: &UnitSensor, records: &[(String, Record)]) -> Result<()> {
    if sensor.rate_reference != RateReference::None {
        return Ok(());
    }
    for (name, r) in records {
        if let Some(rate_std_deg_s) = turning(&sensor.unit, r) {
            let redundant = if sensor.unit.gyros().len() > 3 {
                "; or judge this redundant unit by its parity residues (dtg-vib residues), which the motion does not enter".to_string()
            } else {
                "; or use a redundant unit (four or more gyros), whose parity residues the motion does not enter".to_string()
            };
            return Err(UnitSensorError::Moving {
                record: name.clone(),
                rate_std_deg_s,
                max_deg_s: MOVING_RATE_STD_DEG_S,
                redundant,
            }
            .into());
        }
    }
    Ok(())
}

/// The note that a unit of three gyros has no parity residue, where one
/// would be shown; its channels are judged against the rate reference only
/// when there is one.
pub fn no_residue_note(unit: &Unit, reference: &RateReference) -> Option<String> {
    unit.residue_names().is_empty().then(|| {
        format!(
            "note: the unit '{}' has {} gyros: nothing is redundant, so it has no parity residue; its channels are judged {} (rms before and after per channel)",
            unit.name(),
            unit.gyros().len(),
            judged(reference)
        )
    })
}

/// How a unit without parity residues is judged, by its rate reference.
pub fn judged(reference: &RateReference) -> &'static str {
    match reference.is_true_rate() {
        true => "against the rate reference",
        false => {
            "by their own outputs (no rate reference: each channel's constant rate stays in its bias)"
        }
    }
}

/// Records of `unit` as one CSV in its column names and units: one header,
/// then every record's rows (a log's segments, one after the other); with
/// the number of data rows.
pub fn unit_csv<'a>(
    records: impl IntoIterator<Item = (&'a str, &'a Record)>,
    unit: &Unit,
) -> Result<(Vec<u8>, usize)> {
    let mut text: Vec<u8> = Vec::new();
    let mut rows = 0;
    for (k, (name, r)) in records.into_iter().enumerate() {
        rows += r.len();
        let mut part = Vec::new();
        r.write_with_unit(&mut part, name, unit)?;
        // One header: later records continue the first's columns.
        let header_end = match k {
            0 => 0,
            _ => part.iter().position(|&b| b == b'\n').map_or(0, |i| i + 1),
        };
        text.extend_from_slice(&part[header_end..]);
    }
    Ok((text, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// "Judged against the rate reference" only when there is one (issue
    /// 34 §4): a triad with a table rate is; without, or in parity, it is
    /// judged by its own outputs.
    #[test]
    fn against_the_rate_reference_only_with_one() {
        let triad = Unit::builtin("triad").unwrap();
        let table = RateReference::Table {
            rate_deg_s: [0.0, 0.0, 10.0],
        };
        let with = no_residue_note(&triad, &table).unwrap();
        assert!(
            with.ends_with("judged against the rate reference (rms before and after per channel)"),
            "{with}"
        );
        for r in [RateReference::None, RateReference::Parity] {
            let without = no_residue_note(&triad, &r).unwrap();
            assert!(
                !without.contains("rate reference (rms")
                    && without.contains("by their own outputs"),
                "{without}"
            );
        }
        assert!(no_residue_note(&Unit::builtin("tetra").unwrap(), &table).is_none());
    }
}
