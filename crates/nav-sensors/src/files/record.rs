//! The test record: time, six gyro outputs, three accelerometer outputs and
//! any extra numeric columns (for example `temp`), as CSV.
//!
//! Header `t,X,X1,Y,Y1,Z,Z1,ax,ay,az` then the extra columns; t in s, gyro
//! outputs in deg/h, accelerations in g along the cluster axes.

use std::io::{Read, Write};
use std::ops::Range;
use std::path::Path;

use tabular::{Table, TableError};

use crate::dtg::{DtgInput, DtgTerm};
pub use crate::geometry::Axis;
use crate::geometry::{Channel, ChannelFrame, residues};

/// Relative tolerance on the sample interval: every `t[i] − t[i−1]` must be
/// within `1e-3·dt` of the median interval `dt`. That accepts timestamps
/// rounded to 5 decimals at 50 Hz (≤ 1e-5 s error in a difference, 5e-4·dt)
/// or stored in single precision over a 100-s test, and still rejects any
/// dropped or repeated sample (a 100% deviation) or a 1% clock glitch.
///
/// ```
/// assert!(nav_sensors::record::INTERVAL_TOLERANCE < 0.01);
/// ```
pub const INTERVAL_TOLERANCE: f64 = 1e-3;

/// The nine sensor columns every record has, after `t`.
///
/// ```
/// assert_eq!(nav_sensors::record::SENSOR_COLUMNS[8], "az");
/// ```
pub const SENSOR_COLUMNS: [&str; 9] = ["X", "X1", "Y", "Y1", "Z", "Z1", "ax", "ay", "az"];

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
    /// [`INTERVAL_TOLERANCE`] (relative).
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
    /// Series of different lengths given to [`Record::new`].
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
}

/// A validated test record.
///
/// ```
/// use nav_sensors::record::{Axis, Record};
/// use nav_sensors::geometry::Channel;
/// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n\
///            0.00,1,2,3,4,5,6,0,0,1,25.0\n\
///            0.02,1,2,3,4,5,6,0,0,1,25.1\n\
///            0.04,1,2,3,4,5,6,0,0,1,25.2\n";
/// let r = Record::from_reader(csv.as_bytes(), "inline.csv").unwrap();
/// assert_eq!(r.len(), 3);
/// assert!((r.dt() - 0.02).abs() < 1e-15);
/// assert_eq!(r.gyro(Channel::Y1), &[4.0, 4.0, 4.0]);
/// assert_eq!(r.accel(Axis::Z), &[1.0, 1.0, 1.0]);
/// assert_eq!(r.extra("temp").unwrap()[2], 25.2);
/// assert_eq!(r.extra_names(), vec!["temp"]);
/// assert_eq!(r.slice(1..3).t(), &[0.02, 0.04]);
///
/// let bad = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,1,1,1,1,1,1,0,0,1\n0.02,1,1,1,1,1,1,0,0,oops\n";
/// let err = Record::from_reader(bad.as_bytes(), "bad.csv").unwrap_err();
/// assert_eq!(err.to_string(), "bad.csv:3:10: column 'az': 'oops' is not a number");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    t: Vec<f64>,
    gyro: [Vec<f64>; 6],
    accel: [Vec<f64>; 3],
    extra: Vec<(String, Vec<f64>)>,
}

impl Record {
    /// A record from its series (time in s, gyro outputs in deg/h in
    /// [`Channel::ALL`] order, accelerations in g along x, y, z, extra named
    /// columns). Checks lengths, at least two samples, strictly increasing
    /// time and a constant interval; errors name the file `"<memory>"`.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.len(), 3);
    /// let bad = nav_sensors::record::Record::new(vec![0.0, 0.0], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.0; 2], vec![0.0; 2], vec![0.0; 2]], vec![]);
    /// assert!(bad.is_err());
    /// ```
    pub fn new(
        t: Vec<f64>,
        gyro: [Vec<f64>; 6],
        accel: [Vec<f64>; 3],
        extra: Vec<(String, Vec<f64>)>,
    ) -> Result<Self, RecordError> {
        let n = t.len();
        let lengths = Channel::ALL
            .iter()
            .map(|c| (c.name().to_string(), gyro[c.index()].len()))
            .chain(
                Axis::ALL
                    .iter()
                    .map(|a| (a.column().to_string(), accel[a.index()].len())),
            )
            .chain(extra.iter().map(|(name, v)| (name.clone(), v.len())));
        for (name, len) in lengths {
            if len != n {
                return Err(RecordError::LengthMismatch {
                    name,
                    len,
                    expected: n,
                });
            }
        }
        for (k, (name, _)) in extra.iter().enumerate() {
            let reserved = name == "t" || SENSOR_COLUMNS.contains(&name.as_str());
            if reserved || extra[..k].iter().any(|(n, _)| n == name) {
                return Err(RecordError::BadExtraName { name: name.clone() });
            }
        }
        check_time(&t, "<memory>", |i| i as u64 + 2, 1)?;
        Ok(Self {
            t,
            gyro,
            accel,
            extra,
        })
    }

    /// Reads and validates a record CSV.
    ///
    /// ```
    /// use nav_sensors::sim::{simulate, Scenario};
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-read-csv");
    /// simulate(&Scenario { duration_s: 1.0, ..Default::default() }).unwrap().write_dir(&dir).unwrap();
    /// let rec = nav_sensors::record::Record::read_csv(dir.join("record.csv")).unwrap();
    /// assert_eq!(rec.len(), 50);
    /// ```
    pub fn read_csv(path: impl AsRef<Path>) -> Result<Self, RecordError> {
        Self::from_table(&Table::read(path)?)
    }

    /// Reads and validates record CSV text; `name` labels errors.
    ///
    /// ```
    /// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az\n0,0,0,0,0,0,0,0,0,1\n0.02,0,0,0,0,0,0,0,0,1\n";
    /// let rec = nav_sensors::record::Record::from_reader(csv.as_bytes(), "mem.csv").unwrap();
    /// assert!(rec.extra_names().is_empty());
    /// ```
    pub fn from_reader<R: Read>(reader: R, name: &str) -> Result<Self, RecordError> {
        Self::from_table(&Table::from_reader(reader, name)?)
    }

    fn from_table(table: &Table) -> Result<Self, RecordError> {
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
        // Parse in header order so the first bad cell reported is the
        // leftmost bad column.
        let mut columns: Vec<(String, Vec<f64>)> = Vec::with_capacity(table.header().len());
        for name in table.header() {
            columns.push((name.clone(), table.numeric(name)?));
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
        let gyro = Channel::ALL.map(|c| take(c.name()));
        let accel = Axis::ALL.map(|a| take(a.column()));
        let extra = columns
            .into_iter()
            .filter(|(n, _)| n != "t" && !SENSOR_COLUMNS.contains(&n.as_str()))
            .collect();
        Ok(Self {
            t,
            gyro,
            accel,
            extra,
        })
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
        for c in Channel::ALL {
            names.push(c.name());
            cols.push(&self.gyro[c.index()]);
        }
        for a in Axis::ALL {
            names.push(a.column());
            cols.push(&self.accel[a.index()]);
        }
        for (n, v) in &self.extra {
            names.push(n);
            cols.push(v);
        }
        (names, cols)
    }

    /// Number of samples.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.len(), 3);
    /// ```
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Always false for a valid record (at least two samples); kept for API symmetry.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert!(!rec.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Time, s.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.t()[0], 0.02);
    /// ```
    pub fn t(&self) -> &[f64] {
        &self.t
    }

    /// Mean sample interval, s.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert!((rec.dt() - 0.02).abs() < 1e-15);
    /// ```
    pub fn dt(&self) -> f64 {
        (self.t[self.t.len() - 1] - self.t[0]) / (self.t.len() - 1) as f64
    }

    /// One gyro channel's outputs, deg/h.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro(nav_sensors::geometry::Channel::X1), &[1.0, 1.0, 1.0]);
    /// ```
    pub fn gyro(&self, channel: Channel) -> &[f64] {
        &self.gyro[channel.index()]
    }

    /// One accelerometer's outputs, g.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel(nav_sensors::record::Axis::Z), &[1.0, 1.0, 1.0]);
    /// ```
    pub fn accel(&self, axis: Axis) -> &[f64] {
        &self.accel[axis.index()]
    }

    /// An extra column by name.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.extra("temp").unwrap()[1], 25.1);
    /// assert!(rec.extra("pressure").is_none());
    /// ```
    pub fn extra(&self, name: &str) -> Option<&[f64]> {
        self.extra
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// The extra columns' names, in file order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.extra_names(), vec!["temp"]);
    /// ```
    pub fn extra_names(&self) -> Vec<&str> {
        self.extra.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The six gyro outputs at sample `i`, in [`Channel::ALL`] order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro_sample(0), [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    /// ```
    #[track_caller]
    pub fn gyro_sample(&self, i: usize) -> [f64; 6] {
        std::array::from_fn(|k| self.gyro[k][i])
    }

    /// The three accelerations at sample `i`, g.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel_sample(2), nalgebra::Vector3::new(0.0, 0.0, 1.0));
    /// ```
    #[track_caller]
    pub fn accel_sample(&self, i: usize) -> nalgebra::Vector3<f64> {
        nalgebra::Vector3::new(self.accel[0][i], self.accel[1][i], self.accel[2][i])
    }

    /// The accelerations resolved into a channel's frame: `[a_I, a_O, a_S]`
    /// series, g (eq. 2 for every sample).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::Channel;
    /// let r = Record::new(vec![0.0, 0.02], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.0; 2], vec![0.0; 2], vec![1.0; 2]], vec![]).unwrap();
    /// let [a_i, _, a_s] = r.frame_accel(Channel::X1);
    /// let h = 0.5f64.sqrt();
    /// assert!((a_i[0] + h).abs() < 1e-15 && (a_s[0] + h).abs() < 1e-15);
    /// ```
    pub fn frame_accel(&self, channel: Channel) -> [Vec<f64>; 3] {
        let frame = ChannelFrame::of(channel);
        let mut out: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(self.len()));
        for i in 0..self.len() {
            let r = frame.resolve(&self.accel_sample(i));
            out[0].push(r.i);
            out[1].push(r.o);
            out[2].push(r.s);
        }
        out
    }

    /// A DTG term's regressor at every sample for a channel (the effect
    /// column of `term`, in deg/h per coefficient unit), from the record's
    /// accelerations resolved into the channel's frame and a constant
    /// reference rate in the cluster frame (deg/h; e.g. Earth rate, or zero).
    /// `None` for `temp` and `rect_2n`, which the accelerations do not give
    /// (use the `temp` column for the former).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::Channel;
    /// use nav_sensors::dtg::DtgTerm;
    /// let r = Record::new(vec![0.0, 0.02], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.0; 2], vec![0.0; 2], vec![1.0, 3.0]], vec![]).unwrap();
    /// let w = nalgebra::Vector3::zeros();
    /// assert_eq!(r.term_regressor(Channel::Z, DtgTerm::GgII, &w).unwrap(), vec![1.0, 9.0]);
    /// assert!(r.term_regressor(Channel::Z, DtgTerm::Temp, &w).is_none());
    /// ```
    pub fn term_regressor(
        &self,
        channel: Channel,
        term: DtgTerm,
        rate_cluster_deg_h: &nalgebra::Vector3<f64>,
    ) -> Option<Vec<f64>> {
        if matches!(term, DtgTerm::Temp | DtgTerm::Rect2N) {
            return None;
        }
        let frame = ChannelFrame::of(channel);
        Some(
            (0..self.len())
                .map(|i| {
                    term.regressor(&DtgInput::resolved(
                        &frame,
                        rate_cluster_deg_h,
                        &self.accel_sample(i),
                    ))
                })
                .collect(),
        )
    }

    /// The six parity residues K0..K5 (eq. 6) at every sample, deg/h.
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// use nav_sensors::geometry::{ideal_outputs, Residue};
    /// let m = ideal_outputs(&nalgebra::Vector3::new(13.0, 0.0, 7.5));
    /// let gyro = std::array::from_fn(|k| vec![m[k]; 2]);
    /// let r = Record::new(vec![0.0, 0.02], gyro, [vec![0.0; 2], vec![0.0; 2], vec![1.0; 2]], vec![]).unwrap();
    /// assert!(r.residues()[Residue::K4.index()][1].abs() < 1e-12);
    /// ```
    pub fn residues(&self) -> [Vec<f64>; 6] {
        let mut out: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(self.len()));
        for i in 0..self.len() {
            for (k, v) in residues(&self.gyro_sample(i)).into_iter().enumerate() {
                out[k].push(v);
            }
        }
        out
    }

    /// The samples in `range` (time values kept as they are).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let tail = rec.slice(1..3);
    /// assert_eq!((tail.len(), tail.t()[0]), (2, 0.04));
    /// ```
    #[track_caller]
    pub fn slice(&self, range: Range<usize>) -> Record {
        assert!(
            range.end <= self.len() && range.len() >= 2,
            "slice {range:?} of a {}-sample record must keep at least 2 samples",
            self.len()
        );
        Record {
            t: self.t[range.clone()].to_vec(),
            gyro: std::array::from_fn(|k| self.gyro[k][range.clone()].to_vec()),
            accel: std::array::from_fn(|k| self.accel[k][range.clone()].to_vec()),
            extra: self
                .extra
                .iter()
                .map(|(n, v)| (n.clone(), v[range.clone()].to_vec()))
                .collect(),
        }
    }

    /// A copy with new gyro outputs (same time base and other columns).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let zero = rec.with_gyro(std::array::from_fn(|_| vec![0.0; 3]));
    /// assert_eq!(zero.gyro(nav_sensors::geometry::Channel::Z1), &[0.0; 3]);
    /// ```
    #[track_caller]
    pub fn with_gyro(&self, gyro: [Vec<f64>; 6]) -> Record {
        assert!(
            gyro.iter().all(|g| g.len() == self.len()),
            "one value per sample"
        );
        Record {
            gyro,
            ..self.clone()
        }
    }

    /// A copy with new accelerometer outputs.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let moved = rec.with_accel([vec![0.5; 3], vec![0.0; 3], vec![1.0; 3]]);
    /// assert_eq!(moved.accel(nav_sensors::record::Axis::X)[0], 0.5);
    /// ```
    #[track_caller]
    pub fn with_accel(&self, accel: [Vec<f64>; 3]) -> Record {
        assert!(
            accel.iter().all(|a| a.len() == self.len()),
            "one value per sample"
        );
        Record {
            accel,
            ..self.clone()
        }
    }
}

/// Checks at least two samples, strictly increasing time and a constant
/// interval; `line(i)` gives the file line of sample i.
fn check_time(
    t: &[f64],
    file: &str,
    line: impl Fn(usize) -> u64,
    column: usize,
) -> Result<(), RecordError> {
    if t.len() < 2 {
        return Err(RecordError::TooShort {
            file: file.to_string(),
            rows: t.len(),
        });
    }
    for i in 1..t.len() {
        if t[i].partial_cmp(&t[i - 1]) != Some(std::cmp::Ordering::Greater) {
            return Err(RecordError::NotIncreasing {
                file: file.to_string(),
                line: line(i),
                column,
                previous: t[i - 1],
                t: t[i],
            });
        }
    }
    // The median interval, so the row reported is the irregular one (a
    // dropped sample would pull a mean interval away from every other row).
    let mut intervals: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let mid = intervals.len() / 2;
    let expected = *intervals
        .select_nth_unstable_by(mid, |a, b| a.total_cmp(b))
        .1;
    for i in 1..t.len() {
        let interval = t[i] - t[i - 1];
        if (interval - expected).abs() > INTERVAL_TOLERANCE * expected {
            return Err(RecordError::IrregularInterval {
                file: file.to_string(),
                line: line(i),
                column,
                interval,
                expected,
                tolerance: INTERVAL_TOLERANCE,
            });
        }
    }
    Ok(())
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
