//! The ground calibration handed to the user (JSON), and compensation of a
//! record with it.

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

pub use super::error::CalibrationFileError;
use super::record::Record;
pub use super::unit_calibration::{GyroCoefficients, UnitCalibration, UnitCalibrationError};
use crate::accel::{AccelCoefficients, compensate_triad};
use crate::dtg::{DtgCoefficients, DtgInput, DtgTerm, within_interval_covariance};
use crate::geometry::{Axis, Channel, ChannelFrame, least_squares_rate};

/// Ground-calibrated coefficients: per gyro channel the DTG terms that ground
/// calibration determines (bias, scale factor, misalignment, g-sensitive,
/// anisoelastic, anisoinertia — `temp` and `rect_2n` are always zero), per
/// axis the accelerometer coefficients. Nothing about noise.
///
/// ```
/// use nav_sensors::calibration::Calibration;
/// use nav_sensors::dtg::DtgCoefficients;
/// use nav_sensors::geometry::Channel;
/// let mut cal = Calibration::ideal();
/// cal.gyros.insert(Channel::Z, DtgCoefficients { bias_deg_h: 2.0, ..Default::default() });
/// let json = cal.to_json();
/// assert_eq!(Calibration::from_json(&json, "mem").unwrap(), cal);
/// assert_eq!(cal.gyro(Channel::X).bias_deg_h, 0.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Calibration {
    /// File format version ([`Calibration::FORMAT_VERSION`]).
    pub format_version: u32,
    /// DTG coefficients per channel (a missing channel: all zero).
    pub gyros: BTreeMap<Channel, DtgCoefficients>,
    /// Accelerometer coefficients per axis (a missing axis: all zero).
    pub accels: BTreeMap<Axis, AccelCoefficients>,
}

impl Calibration {
    /// The format version written and read.
    ///
    /// ```
    /// assert_eq!(nav_sensors::calibration::Calibration::ideal().format_version,
    ///     nav_sensors::calibration::Calibration::FORMAT_VERSION);
    /// ```
    pub const FORMAT_VERSION: u32 = 1;

    /// A calibration of ideal sensors (compensation changes nothing).
    ///
    /// ```
    /// let cal = nav_sensors::calibration::Calibration::ideal();
    /// assert!(cal.gyros.is_empty() && cal.accels.is_empty());
    /// ```
    pub fn ideal() -> Self {
        Self {
            format_version: Self::FORMAT_VERSION,
            gyros: BTreeMap::new(),
            accels: BTreeMap::new(),
        }
    }

    /// One channel's coefficients, with the terms calibration never covers
    /// (`temp`, `rect_2n`) zeroed.
    ///
    /// ```
    /// use nav_sensors::calibration::Calibration;
    /// use nav_sensors::dtg::DtgCoefficients;
    /// use nav_sensors::geometry::Channel;
    /// let mut cal = Calibration::ideal();
    /// cal.gyros.insert(Channel::Y, DtgCoefficients { temp_deg_h_per_c: 0.1, bias_deg_h: 1.0, ..Default::default() });
    /// let c = cal.gyro(Channel::Y);
    /// assert_eq!((c.bias_deg_h, c.temp_deg_h_per_c), (1.0, 0.0));
    /// ```
    pub fn gyro(&self, channel: Channel) -> DtgCoefficients {
        self.gyros
            .get(&channel)
            .copied()
            .unwrap_or_default()
            .without(&[DtgTerm::Temp, DtgTerm::Rect2N])
    }

    /// One accelerometer's coefficients.
    ///
    /// ```
    /// use nav_sensors::calibration::Calibration;
    /// assert_eq!(Calibration::ideal().accel(nav_sensors::geometry::Axis::Z).bias_ug, 0.0);
    /// ```
    pub fn accel(&self, axis: Axis) -> AccelCoefficients {
        self.accels.get(&axis).copied().unwrap_or_default()
    }

    /// Parses calibration JSON; `path` labels errors.
    ///
    /// ```
    /// let cal = nav_sensors::calibration::Calibration::from_json(
    ///     r#"{"format_version": 1, "gyros": {"Z": {"bias_deg_h": 2.0}}, "accels": {}}"#, "c.json").unwrap();
    /// assert_eq!(cal.gyro(nav_sensors::geometry::Channel::Z).bias_deg_h, 2.0);
    /// ```
    pub fn from_json(text: &str, path: &str) -> Result<Self, CalibrationFileError> {
        super::io::parse_versioned(
            text,
            path,
            |c: &Self| c.format_version,
            Self::FORMAT_VERSION,
        )
    }

    /// Reads a calibration JSON file.
    ///
    /// ```
    /// use nav_sensors::calibration::Calibration;
    /// let path = std::env::temp_dir().join("nav-sensors-doc-cal-load.json");
    /// Calibration::ideal().save(&path).unwrap();
    /// assert_eq!(Calibration::load(&path).unwrap(), Calibration::ideal());
    /// assert!(Calibration::load("/no/such/file.json").is_err());
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, CalibrationFileError> {
        super::io::load_with(path.as_ref(), super::io::calibration_io, Self::from_json)
    }

    /// The calibration as pretty JSON (deterministic: maps are ordered).
    ///
    /// ```
    /// let json = nav_sensors::calibration::Calibration::ideal().to_json();
    /// assert!(json.contains("\"format_version\": 1"));
    /// ```
    pub fn to_json(&self) -> String {
        super::io::pretty(self)
    }

    /// Writes the calibration as a JSON file.
    ///
    /// ```
    /// let path = std::env::temp_dir().join("nav-sensors-doc-cal-save.json");
    /// nav_sensors::calibration::Calibration::ideal().save(&path).unwrap();
    /// assert!(path.exists());
    /// ```
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), CalibrationFileError> {
        super::io::save_calibration(self, path.as_ref())
    }

    /// Compensates a record with these coefficients, as a user can at the
    /// 50-Hz output rate: first the accelerometers (static inverse, the
    /// three axes jointly), then every gyro channel with the inverse DTG
    /// model, using the compensated accelerations resolved into that
    /// channel's (I, O, S) frame and the other-axis rates from the
    /// least-squares rate of the six channels (two passes: raw, then
    /// compensated). `temp` and `rect_2n` are not compensated (ground
    /// calibration does not cover them). Extra columns pass through.
    ///
    /// ```
    /// use nav_sensors::calibration::Calibration;
    /// use nav_sensors::dtg::DtgCoefficients;
    /// use nav_sensors::geometry::{ideal_outputs, Channel};
    /// use nav_sensors::record::Record;
    /// let w = nalgebra::Vector3::new(14.9, 0.0, 2.2);
    /// let mut m = ideal_outputs(&w);
    /// m[Channel::Z.index()] += 1.5 + 0.8 * 1.0; // bias + g_I·(1 g)
    /// let gyro = std::array::from_fn(|k| vec![m[k]; 3]);
    /// let rec = Record::new(vec![0.02, 0.04, 0.06], gyro, [vec![0.0; 3], vec![0.0; 3], vec![1.0; 3]], vec![]).unwrap();
    /// let mut cal = Calibration::ideal();
    /// cal.gyros.insert(Channel::Z, DtgCoefficients { bias_deg_h: 1.5, g_i_deg_h_g: 0.8, ..Default::default() });
    /// let out = cal.compensate(&rec);
    /// assert!((out.gyro(Channel::Z)[0] - 2.2).abs() < 1e-12);
    /// ```
    pub fn compensate(&self, record: &Record) -> Record {
        let n = record.len();
        let accel = self.compensate_accel(record);
        let frames = ChannelFrame::all();
        // The gyro output holds the interval mean of each g² product; the
        // product of the accelerometers' interval means misses the
        // within-interval covariance, estimated from neighbouring means.
        let means: Vec<Vector3<f64>> = (0..n)
            .map(|i| Vector3::new(accel[0][i], accel[1][i], accel[2][i]))
            .collect();
        let covariance = within_interval_covariance(&means);
        let gyro_coefficients = Channel::ALL.map(|c| self.gyro(c));
        let mut gyro: [Vec<f64>; 6] =
            std::array::from_fn(|k| record.gyro(Channel::ALL[k]).to_vec());
        for _pass in 0..2 {
            let mut next: [Vec<f64>; 6] = std::array::from_fn(|_| Vec::with_capacity(n));
            for i in 0..n {
                let current: [f64; 6] = std::array::from_fn(|k| gyro[k][i]);
                let rate = least_squares_rate(&current);
                let f = Vector3::new(accel[0][i], accel[1][i], accel[2][i]);
                for (k, frame) in frames.iter().enumerate() {
                    let x =
                        DtgInput::resolved(frame, &rate, &f).with_covariance(frame, &covariance[i]);
                    let measured = record.gyro(frame.channel)[i];
                    next[k].push(gyro_coefficients[k].compensate_deg_h(measured, &x));
                }
            }
            gyro = next;
        }
        record.with_gyro(gyro).with_accel(accel)
    }

    /// The accelerometer triad of `record` compensated (x, y, z, in g), as
    /// [`Calibration::compensate`] gives it, without the gyros: what reads
    /// only the specific force (the window's axes) need not pay for the
    /// gyro model.
    ///
    /// ```
    /// use nav_sensors::accel::AccelCoefficients;
    /// use nav_sensors::calibration::Calibration;
    /// use nav_sensors::geometry::Axis;
    /// use nav_sensors::record::Record;
    /// let rec = Record::new(vec![0.02, 0.04], std::array::from_fn(|_| vec![0.0; 2]),
    ///     [vec![0.1; 2], vec![0.0; 2], vec![1.0; 2]], vec![]).unwrap();
    /// let mut cal = Calibration::ideal();
    /// cal.accels.insert(Axis::Z, AccelCoefficients { bias_ug: 500.0, ..Default::default() });
    /// let full = cal.compensate(&rec);
    /// let accel = cal.compensate_accel(&rec);
    /// for a in Axis::ALL {
    ///     assert_eq!(accel[a.index()], full.accel(a));
    /// }
    /// ```
    pub fn compensate_accel(&self, record: &Record) -> [Vec<f64>; 3] {
        let n = record.len();
        let coefficients = Axis::ALL.map(|a| self.accel(a));
        let mut accel: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(n));
        for i in 0..n {
            let a = compensate_triad(&coefficients, &record.accel_sample(i));
            for k in 0..3 {
                accel[k].push(a[k]);
            }
        }
        accel
    }
}
