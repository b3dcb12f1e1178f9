//! A unit's records as the loop's named signals (gyros, accelerometers,
//! extra columns, in that order), and a log read with a unit as named
//! segments: a gap splits the log, and each segment is then one record of
//! several (no window, filter or fold crosses a gap).

use super::error::UnitSensorError;
use nav_sensors::record::{Record, TimeReport};
use nav_sensors::unit::Unit;
use std::path::Path;
use sysid::Signals;

/// A record of any unit as named signals.
///
/// ```
/// let unit = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let csv = "t,gx,gy,gz,ax,ay,az,temp\n0,1,0,0,0,0,9.8,20\n0.01,1,0,0,0,0,9.8,20\n";
/// let rec = &nav_sensors::record::Record::from_reader_with_unit(csv.as_bytes(), "l.csv", &unit).unwrap().records[0];
/// let s = dtg_vib::unit_sensor::to_signals(rec).unwrap();
/// assert_eq!(s.names(), ["gx", "gy", "gz", "ax", "ay", "az", "temp"]);
/// assert_eq!(s.column("gx").unwrap()[0], 3600.0);
/// let back = dtg_vib::unit_sensor::to_record(&unit, &s).unwrap();
/// assert_eq!(&back, rec);
/// ```
pub fn to_signals(record: &Record) -> Result<Signals, UnitSensorError> {
    let gyros = record
        .gyro_names()
        .iter()
        .enumerate()
        .map(|(k, n)| (n.clone(), record.gyro_at(k).to_vec()));
    let accels = record
        .accel_names()
        .iter()
        .enumerate()
        .map(|(k, n)| (n.clone(), record.accel_at(k).to_vec()));
    let extra = record
        .extra_names()
        .into_iter()
        .map(|n| (n.to_string(), record.extra(n).unwrap_or(&[]).to_vec()));
    Ok(Signals::new(
        record.t().to_vec(),
        gyros.chain(accels).chain(extra).collect(),
    )?)
}

/// Named signals of a unit as its record (the unit's sensors, then every
/// other column as an extra one).
pub fn to_record(unit: &Unit, signals: &Signals) -> Result<Record, UnitSensorError> {
    let take = |n: &str| -> Result<(String, Vec<f64>), UnitSensorError> {
        let v = signals
            .column(n)
            .ok_or_else(|| UnitSensorError::MissingColumn {
                name: n.to_string(),
                unit_file: unit.file().to_string(),
                columns: signals.names().iter().map(|c| c.to_string()).collect(),
            })?;
        Ok((n.to_string(), v.to_vec()))
    };
    let gyros = unit
        .gyro_names()
        .iter()
        .map(|n| take(n))
        .collect::<Result<Vec<_>, _>>()?;
    let accels = unit
        .accel_names()
        .iter()
        .map(|n| take(n))
        .collect::<Result<Vec<_>, _>>()?;
    let own = |n: &str| unit.gyro_names().contains(&n) || unit.accel_names().contains(&n);
    let extra = signals
        .columns()
        .iter()
        .filter(|(n, _)| !own(n))
        .cloned()
        .collect();
    let temperature = unit
        .columns()
        .temperature
        .clone()
        .filter(|t| signals.column(t).is_some());
    Ok(Record::from_series(
        signals.t().to_vec(),
        gyros,
        accels,
        extra,
        temperature,
    )?)
}

/// A log read with a unit: its segments, named for errors and scores, and
/// what its time column showed.
#[derive(Debug, Clone)]
pub struct UnitRecord {
    /// The segments in time order: (name, record). One segment is named
    /// by the file; several as `FILE#k` (from 1).
    pub segments: Vec<(String, Record)>,
    /// The time column's median step, jitter and gaps.
    pub time: TimeReport,
    /// Segments too short to keep (fewer than `min_samples`), dropped.
    pub dropped_segments: usize,
}

impl UnitRecord {
    /// A line saying how the log was split, or `None` for a log in one
    /// piece.
    pub fn gaps_notice(&self, file: &str) -> Option<String> {
        let largest = self.time.largest_gap_s()?;
        let mut dropped = Vec::new();
        if self.time.dropped_samples > 0 {
            dropped.push(format!(
                "{} isolated sample(s) between gaps dropped",
                self.time.dropped_samples
            ));
        }
        if self.dropped_segments > 0 {
            dropped.push(format!(
                "{} segment(s) shorter than two windows dropped",
                self.dropped_segments
            ));
        }
        Some(format!(
            "note: {file}: {} gap(s) in the time column (largest {largest:.3} s, a step over {} × the median {:.4} s): {} segment(s), each treated as a record of its own{}",
            self.time.gaps.len(),
            nav_sensors::record::GAP_FACTOR,
            self.time.median_step_s,
            self.segments.len(),
            dropped.iter().map(|d| format!("; {d}")).collect::<String>()
        ))
    }
}

/// Reads a log with a unit ([`Record::read_with_unit`]) and names its
/// segments; segments shorter than `min_samples` are dropped (a window or
/// a filter cannot run on them) and counted.
pub fn read_unit_records(
    path: &Path,
    unit: &Unit,
    min_samples: usize,
) -> Result<UnitRecord, UnitSensorError> {
    let read = Record::read_with_unit(path, unit)?;
    let file = path.display().to_string();
    let n = read.records.len();
    let total = n;
    let longest = read.records.iter().map(Record::len).max().unwrap_or(0);
    let segments: Vec<(String, Record)> = read
        .records
        .into_iter()
        .enumerate()
        .filter(|(_, r)| r.len() >= min_samples)
        .map(|(k, r)| {
            let name = if total == 1 {
                file.clone()
            } else {
                format!("{file}#{}", k + 1)
            };
            (name, r)
        })
        .collect();
    let dropped_segments = n - segments.len();
    if segments.is_empty() {
        return Err(UnitSensorError::TooShort {
            file,
            segments: n,
            longest,
            min_samples,
        });
    }
    Ok(UnitRecord {
        segments,
        time: read.time,
        dropped_segments,
    })
}
