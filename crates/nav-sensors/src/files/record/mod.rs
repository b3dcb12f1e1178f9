//! The test record: time, six gyro outputs, three accelerometer outputs and
//! any extra numeric columns (for example `temp`).
//!
//! This module holds the record itself (validated series, accessors,
//! slicing); [`RecordError`] lists what can be wrong with one, and the CSV
//! format (header `t,X,X1,Y,Y1,Z,Z1,ax,ay,az` then the extra columns; t in
//! s, gyro outputs in deg/h, accelerations in g along the cluster axes) is
//! read and written in `paper_csv.rs`. What the physics makes of a record (the
//! accelerations in a channel's frame, a DTG term's regressor, the parity
//! residues) is in [`crate::regressors`].

mod csv;
mod declared_units;
mod error;
mod glitches;
mod paper_csv;
mod time;
mod ulog_log;

pub use csv::UnitRecords;
pub use declared_units::{
    DeclaredUnitWarning, GYRO_DENSITY_SPAN_DEG_H_RT_HZ, TILT_EXPLAINED, TiltMisses,
    declared_unit_warnings, tilt_misses,
};
pub use error::RecordError;
pub use glitches::{GLITCH_NEIGHBOUR_Z, GLITCH_Z, Glitch, glitch_scores, glitches};
pub use time::{GAP_FACTOR, Gap, INTERVAL_TOLERANCE, TimeReport};
pub use ulog_log::is_ulog;

use std::ops::Range;

pub use crate::geometry::Axis;
use crate::geometry::Channel;
use time::{check_time, check_time_allowing_jitter};

/// The nine sensor columns every record of the paper's unit has, after `t`.
///
/// ```
/// assert_eq!(nav_sensors::record::SENSOR_COLUMNS[8], "az");
/// ```
pub const SENSOR_COLUMNS: [&str; 9] = ["X", "X1", "Y", "Y1", "Z", "Z1", "ax", "ay", "az"];

/// A validated test record: time (s), the gyros' outputs (deg/h), the
/// accelerometers' outputs (g) and any extra numeric columns (one of which
/// a unit may name its temperature column), each series named.
///
/// A record names its sensors as its unit does ([`Record::from_series`],
/// [`Record::read_with_unit`]; the paper's unit's are the six channels X,
/// X1, Y, Y1, Z, Z1 and the accelerometers ax, ay, az, [`Record::new`],
/// [`Record::read_csv`]) and is read by index or name.
///
/// ```
/// use nav_sensors::record::Record;
/// let csv = "t,X,X1,Y,Y1,Z,Z1,ax,ay,az,temp\n\
///            0.00,1,2,3,4,5,6,0,0,1,25.0\n\
///            0.02,1,2,3,4,5,6,0,0,1,25.1\n\
///            0.04,1,2,3,4,5,6,0,0,1,25.2\n";
/// let r = Record::from_reader(csv.as_bytes(), "inline.csv").unwrap();
/// assert_eq!(r.len(), 3);
/// assert!((r.dt() - 0.02).abs() < 1e-15);
/// assert_eq!(r.gyro_named("Y1").unwrap(), &[4.0, 4.0, 4.0]);
/// assert_eq!(r.accel_at(2), &[1.0, 1.0, 1.0]);
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
    gyro_names: Vec<String>,
    gyro: Vec<Vec<f64>>,
    accel_names: Vec<String>,
    accel: Vec<Vec<f64>>,
    extra: Vec<(String, Vec<f64>)>,
    /// The extra column that holds the unit's temperature, when it names one.
    temperature: Option<String>,
}

/// Named series, in order.
type Named = Vec<(String, Vec<f64>)>;

impl Record {
    /// A record of the paper's unit from its series (time in s, gyro outputs
    /// in deg/h in [`Channel::ALL`] order, accelerations in g along x, y, z,
    /// extra named columns). Checks lengths, at least two samples, strictly
    /// increasing time and a constant interval; errors name the file
    /// `"<memory>"`.
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
        let gyros = Channel::ALL
            .iter()
            .zip(gyro)
            .map(|(c, v)| (c.name().to_string(), v))
            .collect();
        let accels = Axis::ALL
            .iter()
            .zip(accel)
            .map(|(a, v)| (a.column().to_string(), v))
            .collect();
        let r = Self::assemble(t, gyros, accels, extra, None)?;
        check_time(&r.t, "<memory>", |i| i as u64 + 2, 1)?;
        Ok(r)
    }

    /// A record of any unit from named series: time (s), gyro outputs
    /// (deg/h) and accelerometer outputs (g) in the unit's order, extra
    /// columns, and the name of the extra column holding temperature (°C),
    /// if any. Checks lengths, unique names, at least two samples and
    /// strictly increasing time; jitter is accepted but a gap (a step over
    /// [`GAP_FACTOR`] × the median) is refused: split the series first
    /// (the unit reader does, [`Record::read_with_unit`]).
    ///
    /// ```
    /// use nav_sensors::record::Record;
    /// let t = vec![0.0, 0.011, 0.019, 0.03];
    /// let g = |v: f64| vec![v; 4];
    /// let rec = Record::from_series(t,
    ///     vec![("g1".into(), g(1.0)), ("g2".into(), g(2.0)), ("g3".into(), g(3.0)), ("g4".into(), g(4.0))],
    ///     vec![("ax".into(), g(0.0)), ("ay".into(), g(0.0)), ("az".into(), g(1.0))],
    ///     vec![("temp".into(), g(25.0))], Some("temp".into())).unwrap();
    /// assert_eq!(rec.gyro_names(), ["g1", "g2", "g3", "g4"]);
    /// assert_eq!(rec.gyro_named("g3").unwrap()[0], 3.0);
    /// assert_eq!(rec.temperature().unwrap()[0], 25.0);
    /// ```
    pub fn from_series(
        t: Vec<f64>,
        gyros: Named,
        accels: Named,
        extra: Named,
        temperature: Option<String>,
    ) -> Result<Self, RecordError> {
        let r = Self::assemble(t, gyros, accels, extra, temperature)?;
        check_time_allowing_jitter(&r.t, "<memory>", |i| i as u64 + 2, 1)?;
        Ok(r)
    }

    /// Checks lengths and names (not time) and builds the record.
    fn assemble(
        t: Vec<f64>,
        gyros: Named,
        accels: Named,
        extra: Named,
        temperature: Option<String>,
    ) -> Result<Self, RecordError> {
        let n = t.len();
        let all = gyros.iter().chain(&accels).chain(&extra);
        for (name, v) in all.clone() {
            if v.len() != n {
                return Err(RecordError::LengthMismatch {
                    name: name.clone(),
                    len: v.len(),
                    expected: n,
                });
            }
        }
        let sensors = gyros.len() + accels.len();
        let names: Vec<&str> = all.map(|(n, _)| n.as_str()).collect();
        for (k, name) in names.iter().enumerate() {
            if *name == "t" || names[..k].contains(name) {
                return Err(if k < sensors {
                    RecordError::DuplicateName {
                        name: name.to_string(),
                    }
                } else {
                    RecordError::BadExtraName {
                        name: name.to_string(),
                    }
                });
            }
        }
        if let Some(name) = &temperature
            && !extra.iter().any(|(n, _)| n == name)
        {
            return Err(RecordError::NoTemperature { name: name.clone() });
        }
        let (gyro_names, gyro) = gyros.into_iter().unzip();
        let (accel_names, accel) = accels.into_iter().unzip();
        Ok(Self {
            t,
            gyro_names,
            gyro,
            accel_names,
            accel,
            extra,
            temperature,
        })
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

    /// The gyros' names, in the unit's order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro_names()[1], "X1");
    /// ```
    pub fn gyro_names(&self) -> &[String] {
        &self.gyro_names
    }

    /// The accelerometers' names, in the unit's order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel_names(), ["ax", "ay", "az"]);
    /// ```
    pub fn accel_names(&self) -> &[String] {
        &self.accel_names
    }

    /// Gyro `k`'s outputs (unit order), deg/h.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro_at(5), &[5.0, 5.0, 5.0]);
    /// ```
    #[track_caller]
    pub fn gyro_at(&self, k: usize) -> &[f64] {
        &self.gyro[k]
    }

    /// Accelerometer `k`'s outputs (unit order), g.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel_at(2), &[1.0, 1.0, 1.0]);
    /// ```
    #[track_caller]
    pub fn accel_at(&self, k: usize) -> &[f64] {
        &self.accel[k]
    }

    /// A gyro's outputs by name, deg/h.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro_named("Y").unwrap()[0], 2.0);
    /// assert!(rec.gyro_named("gx").is_none());
    /// ```
    pub fn gyro_named(&self, name: &str) -> Option<&[f64]> {
        let k = self.gyro_names.iter().position(|n| n == name)?;
        Some(&self.gyro[k])
    }

    /// An accelerometer's outputs by name, g.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel_named("az").unwrap()[0], 1.0);
    /// ```
    pub fn accel_named(&self, name: &str) -> Option<&[f64]> {
        let k = self.accel_names.iter().position(|n| n == name)?;
        Some(&self.accel[k])
    }

    /// The temperature column (°C) when the record's unit names one; `None`
    /// otherwise (a `temp` column of the paper's format is an extra column:
    /// [`Record::extra`]).
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert!(rec.temperature().is_none());
    /// assert!(rec.extra("temp").is_some());
    /// ```
    pub fn temperature(&self) -> Option<&[f64]> {
        self.extra(self.temperature.as_deref()?)
    }

    /// The name of the temperature column, when the unit names one.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert!(rec.temperature_name().is_none());
    /// ```
    pub fn temperature_name(&self) -> Option<&str> {
        self.temperature.as_deref()
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

    /// Every gyro's output at sample `i`, in the unit's order, deg/h.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.gyro_row(1).len(), 6);
    /// ```
    #[track_caller]
    pub fn gyro_row(&self, i: usize) -> Vec<f64> {
        self.gyro.iter().map(|g| g[i]).collect()
    }

    /// Every accelerometer's output at sample `i`, in the unit's order, g.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// assert_eq!(rec.accel_row(0), [0.0, 0.0, 1.0]);
    /// ```
    #[track_caller]
    pub fn accel_row(&self, i: usize) -> Vec<f64> {
        self.accel.iter().map(|a| a[i]).collect()
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
        let cut = |v: &Vec<f64>| v[range.clone()].to_vec();
        Record {
            t: cut(&self.t),
            gyro: self.gyro.iter().map(cut).collect(),
            accel: self.accel.iter().map(cut).collect(),
            extra: self
                .extra
                .iter()
                .map(|(n, v)| (n.clone(), cut(v)))
                .collect(),
            ..self.empty_like()
        }
    }

    /// The names and flags of this record without its series.
    fn empty_like(&self) -> Record {
        Record {
            t: Vec::new(),
            gyro_names: self.gyro_names.clone(),
            gyro: Vec::new(),
            accel_names: self.accel_names.clone(),
            accel: Vec::new(),
            extra: Vec::new(),
            temperature: self.temperature.clone(),
        }
    }

    /// A copy with new gyro outputs, one series per gyro in the unit's order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let zero = rec.with_gyro_series(vec![vec![0.0; 3]; 6]);
    /// assert_eq!(zero.gyro_at(0), &[0.0; 3]);
    /// ```
    #[track_caller]
    pub fn with_gyro_series(&self, gyro: Vec<Vec<f64>>) -> Record {
        assert!(
            gyro.len() == self.gyro.len() && gyro.iter().all(|g| g.len() == self.len()),
            "one series per gyro, one value per sample"
        );
        Record {
            gyro,
            ..self.clone()
        }
    }

    /// A copy with new accelerometer outputs, one series per accelerometer
    /// in the unit's order.
    ///
    /// ```
    /// let rec = nav_sensors::record::Record::new(vec![0.02, 0.04, 0.06], std::array::from_fn(|k| vec![k as f64; 3]),
    ///     [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![("temp".into(), vec![25.0, 25.1, 25.2])]).unwrap();
    /// let moved = rec.with_accel_series(vec![vec![0.5; 3], vec![0.0; 3], vec![1.0; 3]]);
    /// assert_eq!(moved.accel_at(0)[0], 0.5);
    /// ```
    #[track_caller]
    pub fn with_accel_series(&self, accel: Vec<Vec<f64>>) -> Record {
        assert!(
            accel.len() == self.accel.len() && accel.iter().all(|a| a.len() == self.len()),
            "one series per accelerometer, one value per sample"
        );
        Record {
            accel,
            ..self.clone()
        }
    }
}
