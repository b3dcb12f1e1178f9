//! Reading a log of any unit: the unit file's column names, its units
//! (gyros to deg/h, specific force to g with 9.80665 m/s² = 1 g, time by
//! `time_scale` to s), jitter accepted and gaps split into segments
//! ([`super::time`]). Every unit's log, the paper's CSV included, is read
//! here: a record of the paper's format gives the values of the paper's
//! strict reader ([`Record::read_csv`]). Writing a record in a unit's names
//! and units is the inverse.

use std::io::Read;
use std::path::Path;

use tabular::NumericTable;

use super::Record;
use super::error::RecordError;
use super::time::TimeReport;
use crate::unit::{RateUnit, SpecificForceUnit, Unit};

/// A log read with a unit: one record per segment between gaps, and what
/// the time column showed.
///
/// ```
/// use nav_sensors::record::Record;
/// use nav_sensors::unit::Unit;
/// let csv = "t,gx,gy,gz,ax,ay,az\n0,1,0,0,0,0,-9.80665\n0.01,1,0,0,0,0,-9.80665\n\
///            0.02,1,0,0,0,0,-9.80665\n0.5,1,0,0,0,0,-9.80665\n0.51,1,0,0,0,0,-9.80665\n";
/// let read = Record::from_reader_with_unit(csv.as_bytes(), "log.csv", &Unit::builtin("triad").unwrap()).unwrap();
/// assert_eq!(read.records.len(), 2);
/// assert_eq!(read.time.gaps.len(), 1);
/// let first = &read.records[0];
/// assert_eq!(first.gyro_named("gx").unwrap()[0], 3600.0); // 1 deg/s in deg/h
/// assert_eq!(first.accel_named("az").unwrap()[0], -1.0); // −9.80665 m/s² in g
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct UnitRecords {
    /// The segments, in time order, each a record of at least two samples.
    pub records: Vec<Record>,
    /// The time column's median step, jitter and gaps.
    pub time: TimeReport,
}

impl Record {
    /// Reads a log with a unit file (see the module documentation).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let path = std::env::temp_dir().join("nav-sensors-doc-unit-log.csv");
    /// std::fs::write(&path, "time_us,a,b,c,d,ax,ay,az\n0,0,0,0,0,0,0,1\n1000,0,0,0,0,0,0,1\n2000,0,0,0,0,0,0,1\n").unwrap();
    /// let unit = Unit::from_toml(&Unit::builtin_toml("tetra").unwrap()
    ///     .replace("time = \"t\"", "time = \"time_us\"\ntime_scale = 1e-6")
    ///     .replace("\"g1\"", "\"a\"").replace("\"g2\"", "\"b\"").replace("\"g3\"", "\"c\"").replace("\"g4\"", "\"d\""), "mine.toml").unwrap();
    /// let read = Record::read_with_unit(&path, &unit).unwrap();
    /// assert!((read.records[0].dt() - 0.001).abs() < 1e-15);
    /// ```
    ///
    /// A PX4 ULog file (told by its first bytes, whatever its name) is read
    /// here too, through the unit's [`Unit::ulog_table`]: the same segments,
    /// conversions and checks as the CSV pyulog would make of it
    /// (`super::ulog_log`).
    pub fn read_with_unit(path: impl AsRef<Path>, unit: &Unit) -> Result<UnitRecords, RecordError> {
        let path = path.as_ref();
        if super::ulog_log::is_ulog(path) {
            return from_table(super::ulog_log::table(path, unit)?, unit, &Scales::px4());
        }
        from_table(NumericTable::read(path)?, unit, &Scales::of(unit))
    }

    /// Reads log text with a unit file; `name` labels errors.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let err = Record::from_reader_with_unit("t,gx,gy,ax,ay,az\n0,0,0,0,0,0\n".as_bytes(), "log.csv",
    ///     &Unit::builtin("triad").unwrap()).unwrap_err();
    /// assert!(err.to_string().starts_with("log.csv:1: no column 'gz' (gyro[2].name in units/triad.toml)"));
    /// ```
    pub fn from_reader_with_unit<R: Read>(
        reader: R,
        name: &str,
        unit: &Unit,
    ) -> Result<UnitRecords, RecordError> {
        from_table(
            NumericTable::from_reader(reader, name)?,
            unit,
            &Scales::of(unit),
        )
    }

    /// Writes the record in a unit's column names and units (time divided
    /// by `time_scale`, rates from deg/h, specific force from g), the form
    /// [`Record::read_with_unit`] reads back. The record's sensors must be
    /// the unit's, in its order.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let triad = Unit::builtin("triad").unwrap();
    /// let g = |v: f64| vec![v; 3];
    /// let rec = Record::from_series(vec![0.0, 0.01, 0.02],
    ///     vec![("gx".into(), g(3600.0)), ("gy".into(), g(0.0)), ("gz".into(), g(0.0))],
    ///     vec![("ax".into(), g(0.0)), ("ay".into(), g(0.0)), ("az".into(), g(1.0))], vec![], None).unwrap();
    /// let mut out = Vec::new();
    /// rec.write_with_unit(&mut out, "mem", &triad).unwrap();
    /// assert!(String::from_utf8(out).unwrap().starts_with("t,gx,gy,gz,ax,ay,az\n0,1,0,0,0,0,9.80665\n"));
    /// ```
    pub fn write_with_unit<W: std::io::Write>(
        &self,
        out: &mut W,
        name: &str,
        unit: &Unit,
    ) -> Result<(), RecordError> {
        let (names, cols) = self.unit_columns(unit)?;
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let cols: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
        tabular::write_csv_to(out, name, &names, &cols)?;
        Ok(())
    }

    /// Writes the record as a CSV file in a unit's names and units
    /// ([`Record::write_with_unit`]), atomically.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::unit::Unit;
    /// let sim = nav_sensors::sim::simulate_unit(&Unit::paper(), &nav_sensors::sim::Scenario { duration_s: 1.0, ..Default::default() }).unwrap();
    /// let path = std::env::temp_dir().join("nav-sensors-doc-write-unit.csv");
    /// sim.record.write_csv_with_unit(&path, &Unit::paper()).unwrap();
    /// assert_eq!(Record::read_csv(&path).unwrap(), sim.record);
    /// ```
    pub fn write_csv_with_unit(
        &self,
        path: impl AsRef<Path>,
        unit: &Unit,
    ) -> Result<(), RecordError> {
        let (names, cols) = self.unit_columns(unit)?;
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let cols: Vec<&[f64]> = cols.iter().map(Vec::as_slice).collect();
        tabular::write_csv(path, &names, &cols)?;
        Ok(())
    }

    /// The columns in a unit's names and units.
    fn unit_columns(&self, unit: &Unit) -> Result<(Vec<String>, Vec<Vec<f64>>), RecordError> {
        let same = |have: &[String], want: Vec<&str>| have.iter().map(String::as_str).eq(want);
        if !same(&self.gyro_names, unit.gyro_names())
            || !same(&self.accel_names, unit.accel_names())
        {
            return Err(RecordError::NotOfUnit {
                unit_file: unit.file().to_string(),
                sensors: self
                    .gyro_names
                    .iter()
                    .chain(&self.accel_names)
                    .cloned()
                    .collect(),
            });
        }
        let scale = |v: &[f64], k: f64| -> Vec<f64> {
            if k == 1.0 {
                v.to_vec()
            } else {
                v.iter().map(|x| x / k).collect()
            }
        };
        let mut names = vec![unit.columns().time.clone()];
        let mut cols = vec![scale(&self.t, unit.columns().time_scale)];
        let rate = unit.units().rate.to_deg_h();
        for (n, v) in self.gyro_names.iter().zip(&self.gyro) {
            names.push(n.clone());
            cols.push(scale(v, rate));
        }
        let force = unit.units().specific_force.to_g();
        for (n, v) in self.accel_names.iter().zip(&self.accel) {
            names.push(n.clone());
            cols.push(scale(v, force));
        }
        for (n, v) in &self.extra {
            names.push(n.clone());
            cols.push(v.clone());
        }
        Ok((names, cols))
    }
}

/// The factors from a log's columns to a record's units: time to s, rates
/// to deg/h, specific force to g.
pub(super) struct Scales {
    pub time: f64,
    pub rate: f64,
    pub force: f64,
}

impl Scales {
    /// A ULog's: PX4's units (s, rad/s, m/s²), whatever the unit's
    /// `[units]` say of its CSV logs.
    fn px4() -> Self {
        Self {
            time: 1.0,
            rate: RateUnit::RadPerSecond.to_deg_h(),
            force: SpecificForceUnit::MetresPerSecond2.to_g(),
        }
    }

    /// The unit file's: `time_scale` and `[units]`, for its CSV logs.
    fn of(unit: &Unit) -> Self {
        Self {
            time: unit.columns().time_scale,
            rate: unit.units().rate.to_deg_h(),
            force: unit.units().specific_force.to_g(),
        }
    }
}

/// Checks a table of a unit's columns and makes its records: the one
/// path of every log format (a CSV's table, or a ULog's, `super::ulog_log`).
pub(super) fn from_table(
    mut table: NumericTable,
    unit: &Unit,
    scales: &Scales,
) -> Result<UnitRecords, RecordError> {
    let file = table.file().to_string();
    let c = unit.columns();
    let mut wanted: Vec<(String, &str)> = vec![("columns.time".into(), c.time.as_str())];
    if let Some(t) = &c.temperature {
        wanted.push(("columns.temperature".into(), t.as_str()));
    }
    for (k, g) in unit.gyros().iter().enumerate() {
        wanted.push((format!("gyro[{k}].name"), g.name.as_str()));
    }
    for (k, a) in unit.accels().iter().enumerate() {
        wanted.push((format!("accel[{k}].name"), a.name.as_str()));
    }
    for (key, name) in &wanted {
        if !table.has_column(name) {
            return Err(RecordError::MissingUnitColumn {
                file,
                name: name.to_string(),
                key: key.clone(),
                unit_file: unit.file().to_string(),
                header: table.header().to_vec(),
            });
        }
    }
    let header = table.header().to_vec();
    let named = |n: &str| wanted.iter().any(|(_, w)| *w == n);
    if let Some(name) = header
        .iter()
        .find(|n| !named(n) && looks_like_sensor(n, unit))
    {
        return Err(RecordError::SensorLikeColumn {
            file,
            name: name.clone(),
            unit_file: unit.file().to_string(),
        });
    }
    if table.len() < 2 {
        return Err(RecordError::TooShort {
            file,
            rows: table.len(),
        });
    }
    // Check in header order so the first bad cell reported is the
    // leftmost bad column's.
    for name in &header {
        table.column(name)?;
    }
    let t_column = table.column_index(&c.time)? + 1;
    let t: Vec<f64> = table
        .take_column(&c.time)?
        .iter()
        .map(|v| v * scales.time)
        .collect();
    super::time::check_increasing(&t, &file, &|i| table.line_of_row(i), t_column)?;
    let mut take_scaled = |name: &str, k: f64| -> Result<(String, Vec<f64>), RecordError> {
        let v = table.take_column(name)?;
        Ok((
            name.to_string(),
            if k == 1.0 {
                v
            } else {
                v.iter().map(|x| x * k).collect()
            },
        ))
    };
    let gyros = unit
        .gyros()
        .iter()
        .map(|g| take_scaled(&g.name, scales.rate))
        .collect::<Result<Vec<_>, _>>()?;
    let accels = unit
        .accels()
        .iter()
        .map(|a| take_scaled(&a.name, scales.force))
        .collect::<Result<Vec<_>, _>>()?;
    let extra = header
        .iter()
        .filter(|n| {
            **n != c.time
                && !unit.gyro_names().contains(&n.as_str())
                && !unit.accel_names().contains(&n.as_str())
        })
        .map(|n| take_scaled(n, 1.0))
        .collect::<Result<Vec<_>, _>>()?;
    let (segments, time) = TimeReport::split(&t);
    if segments.is_empty() {
        return Err(RecordError::TooShort { file, rows: 1 });
    }
    let cut =
        |named: &[(String, Vec<f64>)], r: &std::ops::Range<usize>| -> Vec<(String, Vec<f64>)> {
            named
                .iter()
                .map(|(n, v)| (n.clone(), v[r.clone()].to_vec()))
                .collect()
        };
    let records = segments
        .iter()
        .map(|r| {
            Record::assemble(
                t[r.clone()].to_vec(),
                cut(&gyros, r),
                cut(&accels, r),
                cut(&extra, r),
                c.temperature.clone(),
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(UnitRecords { records, time })
}

/// Whether a column the unit does not name looks like a gyro or
/// accelerometer: its name, lower-cased without `_`, `-` and trailing
/// digits, is one of the unit's sensor names so reduced (`gx2` beside `gx`,
/// `g5` beside `g1`…`g4`), a conventional triad name (`gx`, `g_y`, `wz`,
/// `ay`…), or starts with `gyro` or `acc`.
fn looks_like_sensor(name: &str, unit: &Unit) -> bool {
    let base = |n: &str| {
        n.to_ascii_lowercase()
            .replace(['_', '-'], "")
            .trim_end_matches(|c: char| c.is_ascii_digit())
            .to_string()
    };
    let b = base(name);
    if b.is_empty() {
        return false;
    }
    let conventional = ["gx", "gy", "gz", "ax", "ay", "az", "wx", "wy", "wz"];
    unit.gyro_names()
        .iter()
        .chain(unit.accel_names().iter())
        .any(|n| base(n) == b)
        || conventional.contains(&b.as_str())
        || b.starts_with("gyro")
        || b.starts_with("acc")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triad() -> Unit {
        Unit::builtin("triad").unwrap()
    }

    fn read(text: &str, unit: &Unit) -> Result<UnitRecords, RecordError> {
        Record::from_reader_with_unit(text.as_bytes(), "log.csv", unit)
    }

    fn rows(times: &[f64]) -> String {
        let mut s = String::from("t,gx,gy,gz,ax,ay,az\n");
        for t in times {
            s.push_str(&format!("{t},1,-0.5,0.25,0,0,-9.80665\n"));
        }
        s
    }

    #[test]
    fn units_are_converted_at_the_reader() {
        let r = read(&rows(&[0.0, 0.01, 0.02]), &triad()).unwrap();
        let rec = &r.records[0];
        assert_eq!(rec.gyro_at(0), &[3600.0; 3]);
        assert_eq!(rec.gyro_at(1), &[-1800.0; 3]);
        assert_eq!(rec.accel_at(2), &[-1.0; 3]);
        let rad = Unit::from_toml(
            &Unit::builtin_toml("triad")
                .unwrap()
                .replace("deg/s", "rad/s")
                .replace("m/s^2", "g"),
            "rad.toml",
        )
        .unwrap();
        let r = read(&rows(&[0.0, 0.01]), &rad).unwrap();
        assert!((r.records[0].gyro_at(0)[0] - 3600.0 * 180.0 / std::f64::consts::PI).abs() < 1e-9);
        assert_eq!(r.records[0].accel_at(2)[0], -9.80665);
    }

    #[test]
    fn a_missing_column_names_the_unit_key() {
        let err = read("t,gx,gz,ax,ay,az\n0,0,0,0,0,1\n0.01,0,0,0,0,1\n", &triad()).unwrap_err();
        assert_eq!(
            err.to_string(),
            "log.csv:1: no column 'gy' (gyro[1].name in units/triad.toml); the header has: t, gx, gz, ax, ay, az"
        );
        let with_temp = Unit::from_toml(
            &Unit::builtin_toml("triad")
                .unwrap()
                .replace("time = \"t\"", "time = \"t\"\ntemperature = \"T_imu\""),
            "t.toml",
        )
        .unwrap();
        let err = read(&rows(&[0.0, 0.01]), &with_temp).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("log.csv:1: no column 'T_imu' (columns.temperature in t.toml)"),
            "{err}"
        );
        let ok = read(
            "t,gx,gy,gz,ax,ay,az,T_imu\n0,0,0,0,0,0,1,30\n0.01,0,0,0,0,0,1,30.5\n",
            &with_temp,
        )
        .unwrap();
        assert_eq!(ok.records[0].temperature().unwrap(), &[30.0, 30.5]);
        assert_eq!(ok.records[0].extra_names(), ["T_imu"]);
    }

    #[test]
    fn a_sensor_the_unit_forgot_is_refused() {
        for extra in ["gx2", "g_z", "gyro_x", "accel3", "wz"] {
            let text = rows(&[0.0, 0.01])
                .replacen("az\n", &format!("az,{extra}\n"), 1)
                .replace("-9.80665\n", "-9.80665,0\n");
            let err = read(&text, &triad()).unwrap_err();
            assert_eq!(
                err.to_string(),
                format!(
                    "log.csv:1: column '{extra}' looks like a gyro or accelerometer but units/triad.toml names no such sensor: add it to the unit file or rename the column"
                )
            );
        }
        // Temperature and other columns are extra columns.
        let text = rows(&[0.0, 0.01])
            .replacen("az\n", "az,temp,baro\n", 1)
            .replace("-9.80665\n", "-9.80665,25,1013\n");
        assert_eq!(
            read(&text, &triad()).unwrap().records[0].extra_names(),
            ["temp", "baro"]
        );
    }

    #[test]
    fn time_scale_and_jitter_are_accepted_and_gaps_split() {
        // Jitter up to 3 medians (a dropped sample is 2) is one segment.
        let t = [0.0, 0.010, 0.0195, 0.031, 0.040, 0.060, 0.070, 0.080];
        let r = read(&rows(&t), &triad()).unwrap();
        assert_eq!((r.records.len(), r.time.gaps.len()), (1, 0));
        assert!((r.time.max_step_ratio - 2.0).abs() < 1e-9);
        // A step of more than 3 medians splits; an isolated sample between
        // two gaps is dropped and counted.
        let t = [0.0, 0.01, 0.02, 0.03, 0.2, 0.5, 0.51, 0.52, 0.53];
        let r = read(&rows(&t), &triad()).unwrap();
        assert_eq!(r.records.len(), 2);
        assert_eq!(r.time.gaps.len(), 2);
        assert_eq!(r.time.dropped_samples, 1);
        assert_eq!(r.records[1].t(), &[0.5, 0.51, 0.52, 0.53]);
        assert!((r.time.largest_gap_s().unwrap() - 0.3).abs() < 1e-12);
        // Microseconds.
        let us = Unit::from_toml(
            &Unit::builtin_toml("triad")
                .unwrap()
                .replace("time = \"t\"", "time = \"t\"\ntime_scale = 1e-6"),
            "us.toml",
        )
        .unwrap();
        let r = read(&rows(&[1000.0, 3000.0, 5000.0]), &us).unwrap();
        assert!((r.records[0].dt() - 0.002).abs() < 1e-15);
    }

    #[test]
    fn time_must_increase() {
        let err = read(&rows(&[0.0, 0.01, 0.01, 0.02]), &triad()).unwrap_err();
        assert!(
            matches!(
                err,
                RecordError::NotIncreasing {
                    line: 4,
                    column: 1,
                    ..
                }
            ),
            "{err}"
        );
        let err = read(&rows(&[0.0]), &triad()).unwrap_err();
        assert!(
            matches!(err, RecordError::TooShort { rows: 1, .. }),
            "{err}"
        );
    }

    #[test]
    fn the_paper_unit_reads_through_the_unit_reader_with_the_strict_readers_values() {
        let csv =
            "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n0,1,2,3,4,5,6,0,0,1,25\n0.02,1,2,3,4,5,6,0,0,1,25\n";
        let r = read(csv, &Unit::paper()).unwrap();
        assert_eq!(
            r.records,
            vec![Record::from_reader(csv.as_bytes(), "log.csv").unwrap()]
        );
        assert_eq!(
            r.records[0]
                .gyro_named(crate::geometry::Channel::Y1.name())
                .unwrap()[0],
            4.0
        );
        // The paper's CSV takes the rule of every unit: jitter is accepted
        // (the strict reader refuses it), a gap splits.
        let jitter = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,1,2,3,4,5,6,0,0,1\n0.02,1,2,3,4,5,6,0,0,1\n0.041,1,2,3,4,5,6,0,0,1\n";
        assert!(matches!(
            Record::from_reader(jitter.as_bytes(), "log.csv"),
            Err(RecordError::IrregularInterval { .. })
        ));
        assert_eq!(read(jitter, &Unit::paper()).unwrap().records[0].len(), 3);
        // Errors keep file, line and column.
        let text = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,1,2,3,4,5,6,0,0,1\n0.02,1,2,3,4,5,6,0,zero,1\n";
        assert_eq!(
            read(text, &Unit::paper()).unwrap_err().to_string(),
            "log.csv:3:9: column 'ay': 'zero' is not a number"
        );
        let text = "t,X,X1,Y,Y1,Z,Z1,ax,az\n0,1,2,3,4,5,6,0,1\n0.02,1,2,3,4,5,6,0,1\n";
        assert_eq!(
            read(text, &Unit::paper()).unwrap_err().to_string(),
            "log.csv:1: no column 'ay' (accel[1].name in units/paper.toml); the header has: t, X, X1, Y, Y1, Z, Z1, ax, az"
        );
        let text = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,1,2,3,4,5,6,0,0,1\n0,1,2,3,4,5,6,0,0,1\n";
        assert!(
            read(text, &Unit::paper())
                .unwrap_err()
                .to_string()
                .starts_with("log.csv:3:1: time 0 s does not increase")
        );
    }

    #[test]
    fn writing_in_a_unit_reads_back() {
        let unit = triad();
        let r = read(&rows(&[0.0, 0.01, 0.02]), &unit).unwrap();
        let mut out = Vec::new();
        r.records[0]
            .write_with_unit(&mut out, "mem", &unit)
            .unwrap();
        let back = Record::from_reader_with_unit(out.as_slice(), "mem", &unit).unwrap();
        assert_eq!(back.records, r.records);
        let err = r.records[0]
            .write_with_unit(&mut Vec::new(), "mem", &Unit::paper())
            .unwrap_err();
        assert!(err.to_string().starts_with(
            "the record's sensors (gx, gy, gz, ax, ay, az) are not those of units/paper.toml"
        ));
    }
}
