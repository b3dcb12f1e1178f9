//! The ground calibration of any unit (JSON), and compensation of a record
//! of that unit with it. Keyed by the unit's channel and accelerometer
//! names, each gyro table saying its model. The paper's calibration format
//! (DTG tables without `model`, accelerometers by axis `x`, `y`, `z`), as a
//! file or embedded in a paper model file written before, reads as the
//! paper unit's calibration.

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

pub use super::error::CalibrationFileError;
use super::paper_calibration::PaperCalibration;
use super::record::Record;
use crate::accel::{AccelCoefficients, compensate_triad};
use crate::dtg::{DtgCoefficients, within_interval_covariance};
use crate::geometry::{Axis, Channel};
use crate::rate::RateCoefficients;
use crate::unit::{GyroModel, Sensed, Unit};

/// One gyro's coefficients, tagged with its model (`"model": "rate"` or
/// `"dtg"` in the file).
///
/// ```
/// use nav_sensors::calibration::GyroCoefficients;
/// use nav_sensors::rate::RateCoefficients;
/// let c = GyroCoefficients::Rate(RateCoefficients { bias_deg_h: 1.5, ..Default::default() });
/// let json = serde_json::to_string(&c).unwrap();
/// assert!(json.starts_with("{\"model\":\"rate\",\"bias_deg_h\":1.5"));
/// assert_eq!(serde_json::from_str::<GyroCoefficients>(&json).unwrap(), c);
/// assert!(serde_json::from_str::<GyroCoefficients>("{\"model\":\"rate\",\"g_I_deg_h_g\":1}").is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "lowercase")]
pub enum GyroCoefficients {
    /// A rate gyro's table.
    Rate(RateCoefficients),
    /// A DTG channel's table.
    Dtg(DtgCoefficients),
}

impl GyroCoefficients {
    /// Zero coefficients of a gyro's model (an ideal gyro).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let z = nav_sensors::calibration::GyroCoefficients::zero(&u.gyros()[0].model);
    /// assert!(matches!(z, nav_sensors::calibration::GyroCoefficients::Rate(_)));
    /// ```
    pub fn zero(model: &GyroModel) -> Self {
        match model {
            GyroModel::Rate => GyroCoefficients::Rate(RateCoefficients::default()),
            GyroModel::Dtg { .. } => GyroCoefficients::Dtg(DtgCoefficients::default()),
        }
    }

    /// The coefficients in the model's term order.
    ///
    /// ```
    /// let c = nav_sensors::calibration::GyroCoefficients::Rate(Default::default());
    /// assert_eq!(c.to_vec().len(), 12);
    /// ```
    pub fn to_vec(&self) -> Vec<f64> {
        match self {
            GyroCoefficients::Rate(c) => c.to_array().to_vec(),
            GyroCoefficients::Dtg(c) => c.to_array().to_vec(),
        }
    }

    /// The model's name (`rate`, `dtg`).
    ///
    /// ```
    /// assert_eq!(nav_sensors::calibration::GyroCoefficients::Dtg(Default::default()).model(), "dtg");
    /// ```
    pub fn model(&self) -> &'static str {
        match self {
            GyroCoefficients::Rate(_) => "rate",
            GyroCoefficients::Dtg(_) => "dtg",
        }
    }

    /// The inverse model: the rate about the input axis (deg/h) that gives
    /// `measured_deg_h` for what the gyro senses otherwise.
    fn compensate(&self, unit: &Unit, channel: usize, measured_deg_h: f64, s: &Sensed) -> f64 {
        let gyro = &unit.gyros()[channel];
        match (self, gyro.dtg_input(s), gyro.rate_input(s)) {
            (GyroCoefficients::Dtg(c), Some(x), _) => c.compensate_deg_h(measured_deg_h, &x),
            (GyroCoefficients::Rate(c), _, Some(x)) => c.compensate_deg_h(measured_deg_h, &x),
            // Checked against the unit before compensating.
            _ => measured_deg_h,
        }
    }
}

/// What is wrong with using a unit calibration on a unit.
///
/// ```
/// use nav_sensors::calibration::{UnitCalibration, UnitCalibrationError};
/// let triad = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let mut cal = UnitCalibration::ideal(&triad);
/// cal.gyros.insert("gq".into(), cal.gyros["gx"]);
/// let err = cal.check(&triad).unwrap_err();
/// assert_eq!(err.to_string(), "the calibration has gyro 'gq', which units/triad.toml does not");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitCalibrationError {
    /// A gyro or accelerometer name the unit does not have.
    #[error("the calibration has {what} '{name}', which {unit_file} does not")]
    Unknown {
        /// "gyro" or "accelerometer".
        what: &'static str,
        /// The name.
        name: String,
        /// The unit file.
        unit_file: String,
    },
    /// A calibration of a built-in unit's gyros (every name and model)
    /// given with another unit.
    #[error(
        "the calibration is of the built-in unit '{builtin}' (gyros {}: --unit {builtin}), but {unit_file} has gyros {}: give a unit calibration with a table per gyro of that unit, each saying its \"model\" (docs/formats.md, \"Unit calibration JSON\"; `dtg-vib calibrate --unit` writes one)",
        builtin_gyros.join(", "),
        unit_gyros.join(", ")
    )]
    OtherBuiltin {
        /// The built-in unit whose gyros the calibration names.
        builtin: String,
        /// Its gyros.
        builtin_gyros: Vec<String>,
        /// The unit file.
        unit_file: String,
        /// The unit's gyros.
        unit_gyros: Vec<String>,
    },
    /// A gyro's table of the other model.
    #[error("gyro '{name}': the calibration has a \"{given}\" table, {unit_file} says \"{model}\"")]
    Model {
        /// The gyro.
        name: String,
        /// The model of the table.
        given: &'static str,
        /// The unit's model.
        model: &'static str,
        /// The unit file.
        unit_file: String,
    },
    /// The record's sensors are not the unit's.
    #[error("the record's gyros ({}) are not those of {unit_file}", record.join(", "))]
    Record {
        /// The record's gyro names.
        record: Vec<String>,
        /// The unit file.
        unit_file: String,
    },
}

/// The ground calibration of a unit's gyros (by name, each with its model)
/// and accelerometers (by name; the pendulous model of
/// [`crate::accel::AccelCoefficients`], used for accelerometers on the unit
/// axes). Terms ground calibration does not cover are zero.
///
/// ```
/// use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
/// use nav_sensors::rate::RateCoefficients;
/// let tetra = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let mut cal = UnitCalibration::ideal(&tetra);
/// cal.gyros.insert("g2".into(), GyroCoefficients::Rate(RateCoefficients { bias_deg_h: 2.0, ..Default::default() }));
/// let back = UnitCalibration::from_json(&cal.to_json(), "mem").unwrap();
/// assert_eq!(back, cal);
/// ```
///
/// The paper's calibration format reads as the paper unit's calibration
/// (each channel's DTG table under its name, each axis's accelerometer
/// under its column, every value as it is):
///
/// ```
/// use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
/// let paper = r#"{"format_version": 1, "gyros": {"Z": {"bias_deg_h": 2.0}}, "accels": {"z": {"bias_ug": 50.0}}}"#;
/// let cal = UnitCalibration::from_json(paper, "c.json").unwrap();
/// assert!(matches!(cal.gyros["Z"], GyroCoefficients::Dtg(t) if t.bias_deg_h == 2.0));
/// assert_eq!(cal.accels["az"].bias_ug, 50.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, try_from = "CalibrationFile")]
pub struct UnitCalibration {
    /// File format version ([`UnitCalibration::FORMAT_VERSION`]).
    pub format_version: u32,
    /// Gyro coefficients by channel name.
    pub gyros: BTreeMap<String, GyroCoefficients>,
    /// Accelerometer coefficients by name.
    pub accels: BTreeMap<String, AccelCoefficients>,
}

impl UnitCalibration {
    /// The format version written and read.
    ///
    /// ```
    /// assert_eq!(nav_sensors::calibration::UnitCalibration::FORMAT_VERSION, 1);
    /// ```
    pub const FORMAT_VERSION: u32 = 1;

    /// A calibration of ideal sensors of a unit (every table zero).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
    /// assert_eq!(nav_sensors::calibration::UnitCalibration::ideal(&u).gyros.len(), 6);
    /// ```
    pub fn ideal(unit: &Unit) -> Self {
        Self {
            format_version: Self::FORMAT_VERSION,
            gyros: unit
                .gyros()
                .iter()
                .map(|g| (g.name.clone(), GyroCoefficients::zero(&g.model)))
                .collect(),
            accels: unit
                .accels()
                .iter()
                .map(|a| (a.name.clone(), AccelCoefficients::default()))
                .collect(),
        }
    }

    /// Parses calibration JSON; `path` labels errors.
    ///
    /// ```
    /// assert!(nav_sensors::calibration::UnitCalibration::from_json("{}", "c.json").is_err());
    /// ```
    pub fn from_json(text: &str, path: &str) -> Result<Self, CalibrationFileError> {
        super::io::parse_versioned(
            text,
            path,
            |c: &Self| c.format_version,
            Self::FORMAT_VERSION,
        )
    }

    /// Reads a calibration file.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let path = std::env::temp_dir().join("nav-sensors-doc-unit-cal.json");
    /// let cal = nav_sensors::calibration::UnitCalibration::ideal(&u);
    /// cal.save(&path).unwrap();
    /// assert_eq!(nav_sensors::calibration::UnitCalibration::load(&path).unwrap(), cal);
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, CalibrationFileError> {
        super::io::load_with(path.as_ref(), super::io::calibration_io, Self::from_json)
    }

    /// The calibration as pretty JSON (deterministic).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// assert!(nav_sensors::calibration::UnitCalibration::ideal(&u).to_json().contains("\"model\": \"rate\""));
    /// ```
    pub fn to_json(&self) -> String {
        super::io::pretty(self)
    }

    /// Writes the calibration file atomically.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let path = std::env::temp_dir().join("nav-sensors-doc-unit-cal-save.json");
    /// nav_sensors::calibration::UnitCalibration::ideal(&u).save(&path).unwrap();
    /// assert!(path.exists());
    /// ```
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), CalibrationFileError> {
        super::io::save_calibration(self, path.as_ref())
    }

    /// Checks the calibration against a unit: every name is the unit's and
    /// every gyro table is of the gyro's model (a sensor the calibration
    /// omits is ideal).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert!(nav_sensors::calibration::UnitCalibration::ideal(&u).check(&u).is_ok());
    /// ```
    pub fn check(&self, unit: &Unit) -> Result<(), UnitCalibrationError> {
        for (name, c) in &self.gyros {
            let Some(k) = unit.gyro_index(name) else {
                if let Some((builtin, of)) = self.builtin_unit() {
                    return Err(UnitCalibrationError::OtherBuiltin {
                        builtin: builtin.to_string(),
                        builtin_gyros: of.gyro_names().iter().map(|n| n.to_string()).collect(),
                        unit_file: unit.file().to_string(),
                        unit_gyros: unit.gyro_names().iter().map(|n| n.to_string()).collect(),
                    });
                }
                return Err(UnitCalibrationError::Unknown {
                    what: "gyro",
                    name: name.clone(),
                    unit_file: unit.file().to_string(),
                });
            };
            let model = unit.gyros()[k].model.name();
            if c.model() != model {
                return Err(UnitCalibrationError::Model {
                    name: name.clone(),
                    given: c.model(),
                    model,
                    unit_file: unit.file().to_string(),
                });
            }
        }
        if let Some(name) = self
            .accels
            .keys()
            .find(|n| !unit.accel_names().contains(&n.as_str()))
        {
            return Err(UnitCalibrationError::Unknown {
                what: "accelerometer",
                name: name.clone(),
                unit_file: unit.file().to_string(),
            });
        }
        Ok(())
    }

    /// The built-in unit whose gyros these tables are (every name, and each
    /// table of that gyro's model), if one is: a calibration given with the
    /// wrong unit is then told which unit it belongs to.
    fn builtin_unit(&self) -> Option<(&'static str, Unit)> {
        Unit::BUILTIN_NAMES.into_iter().find_map(|name| {
            let u = Unit::builtin(name).ok()?;
            let same = u.gyros().len() == self.gyros.len()
                && u.gyros().iter().all(|g| {
                    self.gyros
                        .get(&g.name)
                        .is_some_and(|c| c.model() == g.model.name())
                });
            same.then_some((name, u))
        })
    }

    /// Compensates a record of the unit, at its output rate: first the
    /// accelerometers (static inverse of the three jointly, when they lie
    /// on the unit axes; others pass through), then every gyro with its
    /// model's inverse, using the compensated specific force (with its
    /// within-interval covariance estimated from neighbouring means, as the
    /// gyro outputs hold interval means of g² products) and the
    /// least-squares rate of all gyros (two passes: raw, then compensated).
    /// `temp` is not compensated (ground calibration does not cover it).
    ///
    /// ```
    /// use nav_sensors::calibration::{GyroCoefficients, UnitCalibration};
    /// use nav_sensors::rate::RateCoefficients;
    /// use nav_sensors::record::Record;
    /// let triad = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let mut cal = UnitCalibration::ideal(&triad);
    /// cal.gyros.insert("gz".into(), GyroCoefficients::Rate(RateCoefficients { bias_deg_h: 1.5, g_z_deg_h_g: 0.8, ..Default::default() }));
    /// let g = |v: f64| vec![v; 3];
    /// let rec = Record::from_series(vec![0.0, 0.02, 0.04],
    ///     vec![("gx".into(), g(0.0)), ("gy".into(), g(0.0)), ("gz".into(), g(10.0 + 1.5 + 0.8))],
    ///     vec![("ax".into(), g(0.0)), ("ay".into(), g(0.0)), ("az".into(), g(1.0))], vec![], None).unwrap();
    /// let out = cal.compensate(&triad, &rec).unwrap();
    /// assert!((out.gyro_named("gz").unwrap()[1] - 10.0).abs() < 1e-12);
    /// ```
    pub fn compensate(&self, unit: &Unit, record: &Record) -> Result<Record, UnitCalibrationError> {
        self.check(unit)?;
        let same = |have: &[String], want: Vec<&str>| have.iter().map(String::as_str).eq(want);
        if !same(record.gyro_names(), unit.gyro_names())
            || !same(record.accel_names(), unit.accel_names())
        {
            return Err(UnitCalibrationError::Record {
                record: record.gyro_names().to_vec(),
                unit_file: unit.file().to_string(),
            });
        }
        let n = record.len();
        let accel = self.compensate_accels(unit, record);
        // One sample's outputs in a buffer reused from sample to sample (an
        // allocation a sample showed in the demo's profile).
        let mut row = vec![0.0; accel.len()];
        let force: Vec<Vector3<f64>> = (0..n)
            .map(|i| {
                row.iter_mut().zip(&accel).for_each(|(r, a)| *r = a[i]);
                unit.specific_force(&row)
            })
            .collect();
        let covariance = within_interval_covariance(&force);
        let coefficients: Vec<GyroCoefficients> = unit
            .gyros()
            .iter()
            .map(|g| {
                self.gyros
                    .get(&g.name)
                    .copied()
                    .unwrap_or(GyroCoefficients::zero(&g.model))
            })
            .collect();
        let channels = unit.gyros().len();
        let mut gyro: Vec<Vec<f64>> = (0..channels).map(|k| record.gyro_at(k).to_vec()).collect();
        let mut current = vec![0.0; channels];
        for _pass in 0..2 {
            let mut next: Vec<Vec<f64>> = (0..channels).map(|_| Vec::with_capacity(n)).collect();
            for i in 0..n {
                current.iter_mut().zip(&gyro).for_each(|(c, g)| *c = g[i]);
                let sensed = Sensed {
                    rate_deg_h: unit.least_squares_rate(&current),
                    specific_force_g: force[i],
                    specific_force_cov_g2: covariance[i],
                    ..Sensed::default()
                };
                for (k, c) in coefficients.iter().enumerate() {
                    next[k].push(c.compensate(unit, k, record.gyro_at(k)[i], &sensed));
                }
            }
            gyro = next;
        }
        Ok(record.with_gyro_series(gyro).with_accel_series(accel))
    }

    /// The accelerometers compensated, IMU by IMU (the accelerometers
    /// naming no IMU are one group): the static inverse of a group's three
    /// jointly when they are the unit axes x, y, z (in any order), else
    /// their outputs unchanged.
    pub fn compensate_accels(&self, unit: &Unit, record: &Record) -> Vec<Vec<f64>> {
        let mut out: Vec<Vec<f64>> = (0..unit.accels().len())
            .map(|k| record.accel_at(k).to_vec())
            .collect();
        let mut groups: Vec<&Option<String>> = Vec::new();
        for a in unit.accels() {
            if !groups.contains(&&a.imu) {
                groups.push(&a.imu);
            }
        }
        for imu in groups {
            let members: Vec<usize> = (0..unit.accels().len())
                .filter(|&k| unit.accels()[k].imu == *imu)
                .collect();
            if let Some(by_axis) = triad(unit, &members) {
                self.compensate_accel_triad(unit, by_axis, &mut out);
            }
        }
        out
    }

    /// Replaces the outputs of the triad `by_axis` (accelerometer indices
    /// on x, y, z) by their static inverse.
    fn compensate_accel_triad(&self, unit: &Unit, by_axis: [usize; 3], out: &mut [Vec<f64>]) {
        let coefficients = by_axis.map(|k| {
            self.accels
                .get(&unit.accels()[k].name)
                .copied()
                .unwrap_or_default()
        });
        let n = out[by_axis[0]].len();
        let mut compensated: [Vec<f64>; 3] = std::array::from_fn(|_| Vec::with_capacity(n));
        // i indexes the triad's three columns at once.
        #[allow(clippy::needless_range_loop)]
        for i in 0..n {
            let m = Vector3::from(by_axis.map(|k| out[k][i]));
            let a = compensate_triad(&coefficients, &m);
            for (c, v) in compensated.iter_mut().zip(a.iter()) {
                c.push(*v);
            }
        }
        for (k, c) in by_axis.into_iter().zip(compensated) {
            out[k] = c;
        }
    }
}

/// The accelerometers `members` (indices) on x, y, z, when they are
/// exactly the three unit axes, one each.
fn triad(unit: &Unit, members: &[usize]) -> Option<[usize; 3]> {
    if members.len() != 3 {
        return None;
    }
    let on = |k: usize, x: Axis| unit.accels()[k].input == x.unit_vector();
    let by_axis = Axis::ALL.map(|x| members.iter().copied().find(|&k| on(k, x)));
    let [Some(x), Some(y), Some(z)] = by_axis else {
        return None;
    };
    Some([x, y, z])
}

impl UnitCalibration {
    /// The paper unit's calibration in the paper's format (the file the
    /// built-in `paper` writes, [`crate::unit::FileFormat::Paper`]), every
    /// value as it is: the inverse of reading that format. `None` when a
    /// table is not a DTG channel of the paper's or an accelerometer `ax`,
    /// `ay`, `az`.
    pub(crate) fn to_paper(&self) -> Option<PaperCalibration> {
        let gyros = self
            .gyros
            .iter()
            .map(|(name, c)| match c {
                GyroCoefficients::Dtg(t) => Some((name.parse::<Channel>().ok()?, *t)),
                GyroCoefficients::Rate(_) => None,
            })
            .collect::<Option<_>>()?;
        let accels = self
            .accels
            .iter()
            .map(|(name, t)| {
                let axis = Axis::ALL.into_iter().find(|a| a.column() == name)?;
                Some((axis, *t))
            })
            .collect::<Option<_>>()?;
        Some(PaperCalibration {
            format_version: PaperCalibration::FORMAT_VERSION,
            gyros,
            accels,
        })
    }
}

/// A calibration file as read: the unit format, or the paper's (gyro
/// tables without `model`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CalibrationFile {
    format_version: u32,
    gyros: BTreeMap<String, GyroTable>,
    accels: BTreeMap<String, AccelCoefficients>,
}

/// One gyro table as read: tagged with its model, or the paper's DTG table
/// (no `model` key).
enum GyroTable {
    Tagged(GyroCoefficients),
    Paper(DtgCoefficients),
}

impl<'de> Deserialize<'de> for GyroTable {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = serde_json::Value::deserialize(d)?;
        if v.get("model").is_some() {
            return GyroCoefficients::deserialize(v)
                .map(GyroTable::Tagged)
                .map_err(D::Error::custom);
        }
        DtgCoefficients::deserialize(v)
            .map(GyroTable::Paper)
            .map_err(|e| {
                D::Error::custom(format!(
                    "{e} (a gyro table without \"model\" is read as the paper's DTG table; a unit's table says \"model\": \"rate\" or \"dtg\")"
                ))
            })
    }
}

impl TryFrom<CalibrationFile> for UnitCalibration {
    type Error = String;

    fn try_from(f: CalibrationFile) -> Result<Self, String> {
        let paper = f
            .gyros
            .values()
            .filter(|t| matches!(t, GyroTable::Paper(_)))
            .count();
        if paper == 0 {
            let gyros = f
                .gyros
                .into_iter()
                .map(|(name, t)| match t {
                    GyroTable::Tagged(c) => (name, c),
                    GyroTable::Paper(_) => unreachable!("counted"),
                })
                .collect();
            return Ok(Self {
                format_version: f.format_version,
                gyros,
                accels: f.accels,
            });
        }
        if paper != f.gyros.len() {
            return Err("some gyro tables say their \"model\" and some do not: a unit calibration's tables all do, the paper's format's none".into());
        }
        let mut gyros = BTreeMap::new();
        for (name, t) in f.gyros {
            let GyroTable::Paper(t) = t else {
                unreachable!("all counted")
            };
            if !Channel::ALL.iter().any(|c| c.name() == name) {
                return Err(format!(
                    "gyro '{name}' has no \"model\": a table without one is the paper's calibration format, whose gyros are X, X1, Y, Y1, Z, Z1; give each table of a unit's calibration \"model\": \"rate\" or \"dtg\""
                ));
            }
            gyros.insert(name, GyroCoefficients::Dtg(t));
        }
        let mut accels = BTreeMap::new();
        for (axis, t) in f.accels {
            let Some(a) = Axis::ALL.into_iter().find(|a| a.name() == axis) else {
                return Err(format!(
                    "accelerometer '{axis}' in the paper's calibration format, whose accelerometers are its axes x, y, z"
                ));
            };
            accels.insert(a.column().to_string(), t);
        }
        Ok(Self {
            format_version: f.format_version,
            gyros,
            accels,
        })
    }
}
