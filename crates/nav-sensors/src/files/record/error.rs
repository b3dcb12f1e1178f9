//! Everything that can be wrong with a record.

use tabular::TableError;

/// Everything that can be wrong with a record. File-based variants name the
/// file, the 1-based line (the header is line 1) and the 1-based column.
///
/// ```
/// use nav_sensors::record::{Record, RecordError};
/// let err = Record::from_reader("t,X\n0,1\n".as_bytes(), "r.csv").unwrap_err();
/// assert!(matches!(err, RecordError::MissingColumn { .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// Reading the CSV failed: I/O, malformed CSV, a text cell or a
    /// non-finite number (file:line:column), or a duplicate column.
    #[error(transparent)]
    Table(#[from] TableError),
    /// A required column is missing from the header.
    #[error("{file}:1: missing column '{name}' (the header has: {})", header.join(", "))]
    MissingColumn {
        /// File name.
        file: String,
        /// The missing column.
        name: String,
        /// The header as read.
        header: Vec<String>,
    },
    /// Fewer than two data rows (no sample interval).
    #[error("{file}: {rows} data row(s); a record needs at least 2")]
    TooShort {
        /// File name.
        file: String,
        /// Number of data rows.
        rows: usize,
    },
    /// Time does not strictly increase.
    #[error(
        "{file}:{line}:{column}: time {t} s does not increase on the previous row's {previous} s"
    )]
    NotIncreasing {
        /// File name.
        file: String,
        /// Line of the offending row.
        line: u64,
        /// Column of `t`.
        column: usize,
        /// The previous time, s.
        previous: f64,
        /// This row's time, s.
        t: f64,
    },
    /// A sample interval differs from the median interval by more than
    /// [`INTERVAL_TOLERANCE`](super::INTERVAL_TOLERANCE) (relative).
    #[error(
        "{file}:{line}:{column}: sample interval {interval} s differs from the record's {expected} s (relative tolerance {tolerance})"
    )]
    IrregularInterval {
        /// File name.
        file: String,
        /// Line of the row that ends the interval.
        line: u64,
        /// Column of `t`.
        column: usize,
        /// This interval, s.
        interval: f64,
        /// The median interval, s.
        expected: f64,
        /// The relative tolerance used.
        tolerance: f64,
    },
    /// Series of different lengths given to [`Record::new`](super::Record::new).
    #[error("series '{name}' has {len} samples, expected {expected}")]
    LengthMismatch {
        /// Series name.
        name: String,
        /// Its length.
        len: usize,
        /// The time series' length.
        expected: usize,
    },
    /// An extra column named like a sensor column or `t`, or twice.
    #[error("extra column name '{name}' is reserved or repeated")]
    BadExtraName {
        /// The name.
        name: String,
    },
    /// A sensor column name given twice to [`Record::from_series`](super::Record::from_series).
    #[error("column name '{name}' is given twice")]
    DuplicateName {
        /// The name.
        name: String,
    },
    /// The temperature column named is not among the extra columns.
    #[error("temperature column '{name}' is not among the extra columns")]
    NoTemperature {
        /// The name.
        name: String,
    },
    /// A step longer than [`GAP_FACTOR`](super::GAP_FACTOR) × the median in
    /// one record (split the series at its gaps first).
    #[error(
        "{file}:{line}:{column}: a gap of {step} s (the median step is {median} s): split the record at its gaps"
    )]
    Gap {
        /// File name.
        file: String,
        /// Line of the row after the gap.
        line: u64,
        /// Column of the time.
        column: usize,
        /// The step, s.
        step: f64,
        /// The median step, s.
        median: f64,
    },
    /// A column the unit file names is not in the record.
    #[error("{file}:1: no column '{name}' ({key} in {unit_file}); the header has: {}", header.join(", "))]
    MissingUnitColumn {
        /// The record's file name.
        file: String,
        /// The missing column.
        name: String,
        /// The unit file's key naming it, e.g. `gyro[2].name`.
        key: String,
        /// The unit file.
        unit_file: String,
        /// The header as read.
        header: Vec<String>,
    },
    /// A column named like a gyro or accelerometer that the unit file does
    /// not list (a sensor forgotten in the unit file would otherwise be
    /// taken for an extra column and fitted as an effect).
    #[error(
        "{file}:1: column '{name}' looks like a gyro or accelerometer but {unit_file} names no such sensor: add it to the unit file or rename the column"
    )]
    SensorLikeColumn {
        /// The record's file name.
        file: String,
        /// The column.
        name: String,
        /// The unit file.
        unit_file: String,
    },
    /// A record written in a unit's format whose sensors are not the unit's.
    #[error("the record's sensors ({}) are not those of {unit_file}", sensors.join(", "))]
    NotOfUnit {
        /// The unit file.
        unit_file: String,
        /// The record's gyro and accelerometer names.
        sensors: Vec<String>,
    },
    /// A PX4 ULog file that could not be read (boxed: its errors are large).
    #[error(transparent)]
    Ulog(Box<ulog::UlogError>),
    /// A PX4 ULog file read with a unit that says nothing of where its
    /// columns are in a ULog (no `[ulog]` table, and not a triad on x, y, z).
    #[error(
        "{file}: a PX4 ULog file, but {unit_file} has no [ulog] table saying which topic and field fills each of its columns; add one (docs/formats.md, \"[ulog]\") or convert the log to CSV"
    )]
    NoUlogTable {
        /// The log.
        file: String,
        /// The unit file.
        unit_file: String,
    },
}

impl From<ulog::UlogError> for RecordError {
    fn from(e: ulog::UlogError) -> Self {
        RecordError::Ulog(Box::new(e))
    }
}
