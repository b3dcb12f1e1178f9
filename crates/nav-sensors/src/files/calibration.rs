//! The paper's ground calibration format (JSON): DTG tables by channel,
//! accelerometer tables by axis. Compensation is the unit calibration's
//! ([`UnitCalibration::compensate`]).

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

pub use super::error::CalibrationFileError;
pub use super::unit_calibration::{GyroCoefficients, UnitCalibration, UnitCalibrationError};
use crate::accel::AccelCoefficients;
use crate::dtg::{DtgCoefficients, DtgTerm};
use crate::geometry::{Axis, Channel};

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
}
