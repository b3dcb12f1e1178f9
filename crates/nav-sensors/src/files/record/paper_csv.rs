//! The record's CSV format: header `t,X,X1,Y,Y1,Z,Z1,ax,ay,az` then the
//! extra columns, one row per sample; t in s, gyro outputs in deg/h,
//! accelerations in g along the cluster axes. Reading validates (missing
//! columns, text or non-finite cells, time base) with file:line:column
//! errors; writing gives the shortest round-trip form of every number, so
//! the same record always gives the same bytes.

use std::io::{Read, Write};
use std::path::Path;

use tabular::NumericTable;

use super::error::RecordError;
use super::time::check_time;
use super::{Record, SENSOR_COLUMNS};
use crate::geometry::{Axis, Channel};

impl Record {
    /// Reads and validates a record CSV.
    ///
    /// ```
    /// use nav_sensors::sim::{simulate_unit, Scenario};
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-read-csv");
    /// let paper = nav_sensors::unit::Unit::paper();
    /// simulate_unit(&paper, &Scenario { duration_s: 1.0, ..Default::default() }).unwrap().write_dir(&dir).unwrap();
    /// let rec = nav_sensors::record::Record::read_csv(dir.join("record.csv")).unwrap();
    /// assert_eq!(rec.len(), 50);
    /// ```
    pub fn read_csv(path: impl AsRef<Path>) -> Result<Self, RecordError> {
        Self::from_table(NumericTable::read(path)?)
    }

    /// Reads and validates record CSV text; `name` labels errors.
    ///
    /// ```
    /// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,0,0,0,0,0,0,0,0,1\n0.02,0,0,0,0,0,0,0,0,1\n";
    /// let rec = nav_sensors::record::Record::from_reader(csv.as_bytes(), "mem.csv").unwrap();
    /// assert!(rec.extra_names().is_empty());
    /// ```
    pub fn from_reader<R: Read>(reader: R, name: &str) -> Result<Self, RecordError> {
        Self::from_table(NumericTable::from_reader(reader, name)?)
    }

    /// The record of a table parsed straight into numbers (a 1M-row record
    /// holds its 88 MB of columns, not 600 MB of cell text).
    fn from_table(mut table: NumericTable) -> Result<Self, RecordError> {
        let file = table.file().to_string();
        for name in std::iter::once("t").chain(SENSOR_COLUMNS) {
            if !table.has_column(name) {
                return Err(RecordError::MissingColumn {
                    file,
                    name: name.to_string(),
                    header: table.header().to_vec(),
                });
            }
        }
        if table.len() < 2 {
            return Err(RecordError::TooShort {
                file,
                rows: table.len(),
            });
        }
        // Check in header order so the first bad cell reported is the
        // leftmost bad column's.
        let header = table.header().to_vec();
        for name in &header {
            table.column(name)?;
        }
        let mut columns: Vec<(String, Vec<f64>)> = Vec::with_capacity(header.len());
        for name in header {
            let c = table.take_column(&name)?;
            columns.push((name, c));
        }
        let mut take = |name: &str| -> Vec<f64> {
            let k = columns
                .iter()
                .position(|(n, _)| n == name)
                .expect("checked above");
            std::mem::take(&mut columns[k].1)
        };
        let t = take("t");
        let t_column = table.column_index("t")? + 1;
        check_time(&t, &file, |i| table.line_of_row(i), t_column)?;
        let gyro = Channel::ALL
            .map(|c| (c.name().to_string(), take(c.name())))
            .to_vec();
        let accel = Axis::ALL
            .map(|a| (a.column().to_string(), take(a.column())))
            .to_vec();
        let extra = columns
            .into_iter()
            .filter(|(n, _)| n != "t" && !SENSOR_COLUMNS.contains(&n.as_str()))
            .collect();
        Self::assemble(t, gyro, accel, extra, None)
    }

    /// Writes the record as CSV (numbers in shortest round-trip form, so the
    /// same record always gives the same bytes).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let path = std::env::temp_dir().join("nav-sensors-doc-record.csv");
    /// rec.write_csv(&path).unwrap();
    /// assert_eq!(nav_sensors::record::Record::read_csv(&path).unwrap(), rec);
    /// ```
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<(), RecordError> {
        let (names, cols) = self.columns();
        tabular::write_csv(path, &names, &cols)?;
        Ok(())
    }

    /// Writes the CSV to any writer; `name` labels errors.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let mut out = Vec::new();
    /// rec.write_to(&mut out, "mem").unwrap();
    /// assert!(out.starts_with(b"t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n"));
    /// ```
    pub fn write_to<W: Write>(&self, out: &mut W, name: &str) -> Result<(), RecordError> {
        let (names, cols) = self.columns();
        tabular::write_csv_to(out, name, &names, &cols)?;
        Ok(())
    }

    pub(crate) fn columns(&self) -> (Vec<&str>, Vec<&[f64]>) {
        let mut names: Vec<&str> = vec!["t"];
        let mut cols: Vec<&[f64]> = vec![&self.t];
        for (n, v) in self.gyro_names.iter().zip(&self.gyro) {
            names.push(n);
            cols.push(v);
        }
        for (n, v) in self.accel_names.iter().zip(&self.accel) {
            names.push(n);
            cols.push(v);
        }
        for (n, v) in &self.extra {
            names.push(n);
            cols.push(v);
        }
        (names, cols)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n";

    fn rows(n: usize) -> Vec<String> {
        (0..n)
            .map(|i| format!("{},1,2,3,4,5,6,0,0,1,25", i as f64 * 0.02))
            .collect()
    }

    fn read(text: &str) -> Result<Record, RecordError> {
        Record::from_reader(text.as_bytes(), "rec.csv")
    }

    fn with(rows: &[String]) -> String {
        format!("{HEADER}{}\n", rows.join("\n"))
    }

    #[test]
    fn missing_column_names_file_and_column() {
        let text = "t,X,X1,Y,Y1,Z,Z1,ax,az\n0,1,1,1,1,1,1,0,1\n0.02,1,1,1,1,1,1,0,1\n";
        let err = read(text).unwrap_err();
        assert!(
            matches!(&err, RecordError::MissingColumn { name, .. } if name == "ay"),
            "{err}"
        );
        assert!(
            err.to_string()
                .starts_with("rec.csv:1: missing column 'ay'"),
            "{err}"
        );
    }

    #[test]
    fn text_cell_names_line_and_column() {
        let mut r = rows(5);
        r[2] = "0.04,1,2,3,4,5,6,0,zero,1,25".into();
        let err = read(&with(&r)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "rec.csv:4:9: column 'ay': 'zero' is not a number"
        );
    }

    #[test]
    fn nan_names_line_and_column() {
        let mut r = rows(5);
        r[3] = "0.06,1,2,3,NaN,5,6,0,0,1,25".into();
        let err = read(&with(&r)).unwrap_err();
        assert_eq!(
            err.to_string(),
            "rec.csv:5:5: column 'Y1': 'NaN' is not finite"
        );
    }

    #[test]
    fn non_increasing_time_names_line_and_column() {
        let mut r = rows(5);
        r[3] = "0.04,1,2,3,4,5,6,0,0,1,25".into();
        let err = read(&with(&r)).unwrap_err();
        assert!(
            matches!(
                err,
                RecordError::NotIncreasing {
                    line: 5,
                    column: 1,
                    ..
                }
            ),
            "{err}"
        );
        assert!(
            err.to_string()
                .starts_with("rec.csv:5:1: time 0.04 s does not increase")
        );
    }

    #[test]
    fn irregular_interval_names_line_and_column() {
        // A dropped sample: t jumps by two intervals between rows 3 and 4.
        let r: Vec<String> = [0, 1, 2, 4, 5, 6, 7, 8, 9, 10]
            .iter()
            .map(|&i| format!("{},1,2,3,4,5,6,0,0,1,25", i as f64 * 0.02))
            .collect();
        let err = read(&with(&r)).unwrap_err();
        assert!(
            matches!(
                err,
                RecordError::IrregularInterval {
                    line: 5,
                    column: 1,
                    ..
                }
            ),
            "{err}"
        );
        // Timestamps rounded to 5 decimals are fine.
        let ok: Vec<String> = (0..50)
            .map(|i| format!("{:.5},1,2,3,4,5,6,0,0,1,25", i as f64 / 30.0))
            .collect();
        assert!(read(&with(&ok)).is_ok());
    }

    #[test]
    fn too_short_is_an_error() {
        let err = read(&with(&rows(1))).unwrap_err();
        assert!(
            matches!(err, RecordError::TooShort { rows: 1, .. }),
            "{err}"
        );
    }

    #[test]
    fn write_then_read_is_exact() {
        let r = read(&with(&rows(7))).unwrap();
        let mut a = Vec::new();
        r.write_to(&mut a, "mem").unwrap();
        let back = Record::from_reader(a.as_slice(), "mem").unwrap();
        assert_eq!(back, r);
        assert!(
            String::from_utf8(a)
                .unwrap()
                .starts_with("t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n")
        );
    }
}
