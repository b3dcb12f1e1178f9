//! The test record: time, six gyro outputs, three accelerometer outputs and
//! any extra numeric columns (for example `temp`).
//!
//! This module holds the record itself (validated series, accessors,
//! slicing); [`RecordError`] lists what can be wrong with one, and the CSV
//! format (header `t,X,X1,Y,Y1,Z,Z1,ax,ay,az` then the extra columns; t in
//! s, gyro outputs in deg/h, accelerations in g along the cluster axes) is
//! read and written in `csv.rs`. What the physics makes of a record (the
//! accelerations in a channel's frame, a DTG term's regressor, the parity
//! residues) is in [`crate::regressors`].

mod csv;
mod error;

pub use error::RecordError;

use std::ops::Range;

pub use crate::geometry::Axis;
use crate::geometry::Channel;

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
