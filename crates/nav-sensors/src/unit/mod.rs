//! The sensor unit as data: a unit file names the record's columns, the
//! units they are logged in, and every gyro and accelerometer with its axes
//! in the unit frame. Geometry (the measurement matrix H, the least-squares
//! rate, the parity residues) follows from the gyros' input axes
//! ([`Unit::measurement_matrix`], [`Unit::parity_matrix`]).
//!
//! The paper's unit is one file among others (`units/paper.toml`, built in
//! as `paper`); `triad`, `tetra` and `dual-triad` are built in too. Their
//! one source is the workspace's `units/` folder, embedded at build time.
//! The keys are a contract (docs/formats.md, "Unit file").
//!
//! ```
//! use nav_sensors::unit::{GyroModel, Unit};
//! let text = r#"
//! name = "two IMUs"
//! [columns]
//! time = "t_us"
//! time_scale = 1e-6
//! [units]
//! rate = "rad/s"
//! specific_force = "m/s^2"
//! [[gyro]]
//! name = "G1"
//! model = "rate"
//! input = [0.0, 0.0, 2.0]
//! [[gyro]]
//! name = "G2"
//! model = "rate"
//! input = [1.0, 0.0, 0.0]
//! [[gyro]]
//! name = "G3"
//! model = "rate"
//! input = [0.0, 1.0, 0.0]
//! [[accel]]
//! name = "ax"
//! input = [1.0, 0.0, 0.0]
//! [[accel]]
//! name = "ay"
//! input = [0.0, 1.0, 0.0]
//! [[accel]]
//! name = "az"
//! input = [0.0, 0.0, 1.0]
//! "#;
//! let unit = Unit::from_toml(text, "imu.toml").unwrap();
//! assert_eq!(unit.gyro_names(), ["G1", "G2", "G3"]);
//! assert_eq!(unit.gyros()[0].input, nalgebra::Vector3::new(0.0, 0.0, 1.0)); // normalised
//! assert_eq!(unit.gyros()[0].model, GyroModel::Rate);
//! assert_eq!(unit.columns().time_scale, 1e-6);
//! assert!((unit.units().rate.to_deg_h() - 3600.0 * 180.0 / std::f64::consts::PI).abs() < 1e-9);
//! assert!(unit.residue_names().is_empty()); // three gyros: no parity residue
//! ```

mod error;
mod file;
mod geometry;
mod term;
mod ulog_table;

pub use error::UnitError;
pub use geometry::UnitGeometry;
pub use term::{GyroTerm, Sensed};

use std::fmt;
use std::path::Path;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::geometry::{Channel, DtgAxes, dtg_frame, input_axis};

/// How far from perpendicular (cosine of the angle, after normalising) a
/// `dtg` gyro's input, spin and output axes may be: 1e-6 (0.2 arcsec),
/// above what a file writing axes to 7 significant digits can reach and far
/// below any real DTG's build tolerance.
///
/// ```
/// assert_eq!(nav_sensors::unit::PERPENDICULAR_TOLERANCE, 1e-6);
/// ```
pub const PERPENDICULAR_TOLERANCE: f64 = 1e-6;

/// How far a named residue may be from cancelling the rate: each component
/// of Σ weight·input axis within 1e-6 of Σ |weight| (the tolerance of
/// [`PERPENDICULAR_TOLERANCE`], for weights and axes written to 7
/// significant digits; eq. 6's weights written to the last bit cancel to
/// 1e-16).
///
/// ```
/// assert_eq!(nav_sensors::unit::RESIDUE_TOLERANCE, 1e-6);
/// ```
pub const RESIDUE_TOLERANCE: f64 = 1e-6;

/// One g in m/s² (the standard acceleration of gravity, used to convert
/// `m/s^2` columns to g).
///
/// ```
/// assert_eq!(nav_sensors::unit::STANDARD_GRAVITY_M_S2, 9.80665);
/// ```
pub const STANDARD_GRAVITY_M_S2: f64 = 9.80665;

/// The unit the gyro columns are logged in (`[units] rate`). Inside, every
/// rate is deg/h.
///
/// ```
/// use nav_sensors::unit::RateUnit;
/// let u: RateUnit = serde_json::from_str("\"deg/s\"").unwrap();
/// assert_eq!(u, RateUnit::DegPerSecond);
/// assert_eq!(u.to_deg_h(), 3600.0);
/// assert_eq!(u.to_string(), "deg/s");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum RateUnit {
    /// `deg/h`.
    #[default]
    #[serde(rename = "deg/h")]
    DegPerHour,
    /// `deg/s`.
    #[serde(rename = "deg/s")]
    DegPerSecond,
    /// `rad/s`.
    #[serde(rename = "rad/s")]
    RadPerSecond,
}

impl RateUnit {
    /// The factor from this unit to deg/h.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::RateUnit::DegPerHour.to_deg_h(), 1.0);
    /// ```
    pub fn to_deg_h(self) -> f64 {
        match self {
            RateUnit::DegPerHour => 1.0,
            RateUnit::DegPerSecond => 3600.0,
            RateUnit::RadPerSecond => 3600.0 * 180.0 / std::f64::consts::PI,
        }
    }

    /// The name as written in a unit file.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::RateUnit::RadPerSecond.name(), "rad/s");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            RateUnit::DegPerHour => "deg/h",
            RateUnit::DegPerSecond => "deg/s",
            RateUnit::RadPerSecond => "rad/s",
        }
    }
}

impl fmt::Display for RateUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The unit the accelerometer columns are logged in (`[units]
/// specific_force`). Inside, every specific force is g (9.80665 m/s²).
///
/// ```
/// use nav_sensors::unit::SpecificForceUnit;
/// let u: SpecificForceUnit = serde_json::from_str("\"m/s^2\"").unwrap();
/// assert_eq!(u.to_g(), 1.0 / 9.80665);
/// assert_eq!(SpecificForceUnit::G.to_g(), 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum SpecificForceUnit {
    /// `g`.
    #[default]
    #[serde(rename = "g")]
    G,
    /// `m/s^2` (also read as `m/s²`).
    #[serde(rename = "m/s^2", alias = "m/s²")]
    MetresPerSecond2,
}

impl SpecificForceUnit {
    /// The factor from this unit to g.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::SpecificForceUnit::G.to_g(), 1.0);
    /// ```
    pub fn to_g(self) -> f64 {
        match self {
            SpecificForceUnit::G => 1.0,
            SpecificForceUnit::MetresPerSecond2 => 1.0 / STANDARD_GRAVITY_M_S2,
        }
    }

    /// The name as written in a unit file.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::SpecificForceUnit::MetresPerSecond2.name(), "m/s^2");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            SpecificForceUnit::G => "g",
            SpecificForceUnit::MetresPerSecond2 => "m/s^2",
        }
    }
}

impl fmt::Display for SpecificForceUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// `[columns]`: the time column (and its scale to seconds) and the optional
/// temperature column. Every other numeric column a record has beyond the
/// sensors' is an extra column (`col:NAME`).
///
/// ```
/// let c = &nav_sensors::unit::Unit::builtin("triad").unwrap();
/// assert_eq!(c.columns().time, "t");
/// assert_eq!(c.columns().time_scale, 1.0);
/// assert!(c.columns().temperature.is_none());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Columns {
    /// The time column's name.
    pub time: String,
    /// Seconds per time-column unit (1e-6 for microseconds).
    pub time_scale: f64,
    /// The temperature column (°C), when the unit names one.
    pub temperature: Option<String>,
}

/// `[units]`: what the gyro and accelerometer columns are logged in.
///
/// ```
/// use nav_sensors::unit::{RateUnit, SpecificForceUnit, Unit};
/// let u = Unit::builtin("triad").unwrap();
/// assert_eq!(u.units().rate, RateUnit::DegPerSecond);
/// assert_eq!(u.units().specific_force, SpecificForceUnit::MetresPerSecond2);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Units {
    /// The gyro columns' unit.
    pub rate: RateUnit,
    /// The accelerometer columns' unit.
    pub specific_force: SpecificForceUnit,
}

/// A gyro's error model.
///
/// ```
/// use nav_sensors::unit::{GyroModel, Unit};
/// let paper = Unit::paper();
/// assert!(matches!(paper.gyros()[0].model, GyroModel::Dtg { .. }));
/// assert_eq!(Unit::builtin("tetra").unwrap().gyros()[0].model, GyroModel::Rate);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GyroModel {
    /// `"rate"`: a single-axis rate gyro (MEMS/CVG, IEEE Std 1431; FOG,
    /// IEEE Std 952), error model [`crate::rate`] in the unit frame.
    Rate,
    /// `"dtg"`: one input axis of a two-axis DTG (IEEE Std 813), error
    /// model [`crate::dtg`] in its own input, output and spin axes.
    Dtg {
        /// The rotor's spin axis S (unit vector, unit frame).
        spin: Vector3<f64>,
        /// The channel's output axis O (the DTG's other input axis, signed
        /// as the error model uses it).
        output: Vector3<f64>,
    },
}

impl GyroModel {
    /// The name as written in a unit file (`rate`, `dtg`).
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::GyroModel::Rate.name(), "rate");
    /// ```
    pub fn name(&self) -> &'static str {
        match self {
            GyroModel::Rate => "rate",
            GyroModel::Dtg { .. } => "dtg",
        }
    }
}

/// One `[[gyro]]`: the channel's name (its record column, and its name in
/// flags, JSON keys and reports), its input axis and model.
///
/// ```
/// let u = nav_sensors::unit::Unit::paper();
/// let x1 = &u.gyros()[1];
/// assert_eq!(x1.name, "X1");
/// let axes = x1.dtg_axes().unwrap();
/// assert_eq!(axes.output, nalgebra::Vector3::new(1.0, 0.0, 0.0)); // X's input axis
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Gyro {
    /// The name.
    pub name: String,
    /// The input axis I (unit vector, unit frame).
    pub input: Vector3<f64>,
    /// The error model (with a DTG's spin and output axes).
    pub model: GyroModel,
    /// The IMU it belongs to (`imu = "NAME"`), when the unit groups its
    /// sensors into IMUs.
    pub imu: Option<String>,
}

impl Gyro {
    /// A `dtg` gyro's (I, O, S) axes; `None` for a rate gyro.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// assert!(u.gyros()[0].dtg_axes().is_none());
    /// ```
    pub fn dtg_axes(&self) -> Option<DtgAxes> {
        match self.model {
            GyroModel::Rate => None,
            GyroModel::Dtg { spin, output } => Some(DtgAxes {
                input: self.input,
                output,
                spin,
            }),
        }
    }
}

/// One `[[accel]]`: the accelerometer's name (its record column) and input
/// axis.
///
/// ```
/// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// assert_eq!(u.accels()[2].name, "az");
/// assert_eq!(u.accels()[2].input, nalgebra::Vector3::new(0.0, 0.0, 1.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Accelerometer {
    /// The name.
    pub name: String,
    /// The input axis (unit vector, unit frame).
    pub input: Vector3<f64>,
    /// The IMU it belongs to (`imu = "NAME"`), when the unit groups its
    /// sensors into IMUs.
    pub imu: Option<String>,
}

/// One `[[residue]]`: a parity residue the unit file names, with its
/// weight on each gyro's output (gyro order). A unit that names residues
/// reports them (the paper's K0–K5 of eq. 6); one that names none reports
/// the rows of its orthonormal parity matrix as P0, P1, ….
///
/// ```
/// let u = nav_sensors::unit::Unit::paper();
/// let k0 = &u.named_residues()[0];
/// assert_eq!(k0.name, "K0");
/// // K0 = X + Z + √2·Y1 (eq. 6)
/// assert_eq!(k0.weights, [1.0, 0.0, 0.0, std::f64::consts::SQRT_2, 1.0, 0.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct NamedResidue {
    /// The name (a column of residue files, a key of JSON outputs).
    pub name: String,
    /// The weight on each gyro's output, in the unit's gyro order.
    pub weights: Vec<f64>,
}

/// A validated sensor unit (see the module documentation). Built only by
/// reading a unit file ([`Unit::from_toml`], [`Unit::load`],
/// [`Unit::builtin`], [`Unit::resolve`]), so every unit holds the rules of
/// the contract. Serialises as the unit file's keys (a fitted model stores
/// the unit it was fitted with).
///
/// ```
/// use nav_sensors::unit::Unit;
/// let tetra = Unit::builtin("tetra").unwrap();
/// assert_eq!(tetra.gyros().len(), 4);
/// assert_eq!(tetra.residue_names(), ["P0"]);
/// let back = Unit::from_toml(&tetra.to_toml(), "copy.toml").unwrap();
/// assert_eq!(back, tetra);
/// let json = serde_json::to_string(&tetra).unwrap();
/// assert_eq!(serde_json::from_str::<Unit>(&json).unwrap(), tetra);
/// ```
#[derive(Debug, Clone)]
pub struct Unit {
    name: String,
    columns: Columns,
    units: Units,
    gyros: Vec<Gyro>,
    accels: Vec<Accelerometer>,
    residues: Vec<NamedResidue>,
    /// The `[ulog]` table, when the file has one.
    ulog: Option<ulog::UlogTable>,
    file: String,
    file_format: FileFormat,
    paper_geometry: bool,
    geometry: UnitGeometry,
}

/// The formats a unit's simulated test is written in ([`Unit::file_format`]).
/// Data of the built-in units' table, not a key of the unit file: the
/// built-in `paper` keeps writing the files every release before units
/// wrote, so scripts reading them go on working; every other unit, a copy
/// of the paper's file included, writes the unit formats.
///
/// ```
/// use nav_sensors::unit::{FileFormat, Unit};
/// assert_eq!(Unit::paper().file_format(), FileFormat::Paper);
/// assert_eq!(Unit::builtin("tetra").unwrap().file_format(), FileFormat::Unit);
/// let copy = Unit::from_toml(Unit::builtin_toml("paper").unwrap(), "copy.toml").unwrap();
/// assert_eq!(copy.file_format(), FileFormat::Unit);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FileFormat {
    /// The record in the unit's column names and units, the calibration
    /// and truth keyed by its sensors' names, and the unit file beside them
    /// (docs/formats.md, "Unit calibration JSON").
    #[default]
    Unit,
    /// The paper's formats (docs/formats.md): the calibration's DTG tables
    /// without `model` and its accelerometers by axis, the truth by
    /// channel, and the per-sample noise components (`components.csv`).
    Paper,
}

/// Equal when every key of the file is equal (the file it came from aside).
impl PartialEq for Unit {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.columns == other.columns
            && self.units == other.units
            && self.gyros == other.gyros
            && self.accels == other.accels
            && self.residues == other.residues
            && self.ulog == other.ulog
    }
}

/// The built-in units, embedded from the workspace's `units/` folder (their
/// one source: the file a user copies is what `--unit NAME` runs), with the
/// formats their simulated files are written in.
const BUILTIN: [(&str, &str, FileFormat); 4] = [
    (
        "paper",
        include_str!("../../../../units/paper.toml"),
        FileFormat::Paper,
    ),
    (
        "triad",
        include_str!("../../../../units/triad.toml"),
        FileFormat::Unit,
    ),
    (
        "tetra",
        include_str!("../../../../units/tetra.toml"),
        FileFormat::Unit,
    ),
    (
        "dual-triad",
        include_str!("../../../../units/dual-triad.toml"),
        FileFormat::Unit,
    ),
];

impl Unit {
    /// The built-in units' names.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::BUILTIN_NAMES, ["paper", "triad", "tetra", "dual-triad"]);
    /// ```
    pub const BUILTIN_NAMES: [&'static str; 4] = ["paper", "triad", "tetra", "dual-triad"];

    /// Parses and validates a unit file's text; `file` names it in errors.
    ///
    /// ```
    /// let text = nav_sensors::unit::Unit::builtin_toml("triad").unwrap();
    /// let u = nav_sensors::unit::Unit::from_toml(text, "triad.toml").unwrap();
    /// assert_eq!(u.gyro_names(), ["gx", "gy", "gz"]);
    /// ```
    pub fn from_toml(text: &str, file: &str) -> Result<Self, UnitError> {
        file::UnitFile::parse(text, file)?.validate(file)
    }

    /// Reads and validates a unit file.
    ///
    /// ```
    /// let path = std::env::temp_dir().join("nav-sensors-doc-unit.toml");
    /// std::fs::write(&path, nav_sensors::unit::Unit::builtin_toml("tetra").unwrap()).unwrap();
    /// assert_eq!(nav_sensors::unit::Unit::load(&path).unwrap().gyros().len(), 4);
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, UnitError> {
        crate::files::io::load_with(
            path.as_ref(),
            |path, source| UnitError::Io { path, source },
            Self::from_toml,
        )
    }

    /// A built-in unit by name ([`Unit::BUILTIN_NAMES`]).
    ///
    /// ```
    /// let err = nav_sensors::unit::Unit::builtin("quad").unwrap_err();
    /// assert_eq!(err.to_string(), "unknown unit 'quad' (built-in: paper, triad, tetra, dual-triad; or give a FILE.toml)");
    /// ```
    pub fn builtin(name: &str) -> Result<Self, UnitError> {
        let (_, text, file_format) =
            BUILTIN.iter().find(|(n, _, _)| *n == name).ok_or_else(|| {
                UnitError::UnknownBuiltin {
                    given: name.to_string(),
                    valid: Self::BUILTIN_NAMES.to_vec(),
                }
            })?;
        let mut unit = Self::from_toml(text, &format!("units/{name}.toml"))?;
        unit.file_format = *file_format;
        Ok(unit)
    }

    /// The built-in units whose columns a record's header has (the time
    /// column and every gyro and accelerometer), the most sensors first: a
    /// record given without `--unit` whose header is not the paper's gets
    /// the suggestion `--unit NAME` of the first.
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// assert_eq!(Unit::builtins_matching(&["t", "gx", "gy", "gz", "ax", "ay", "az", "temp"]), ["triad"]);
    /// let dual = ["t", "gx", "gy", "gz", "gx2", "gy2", "gz2", "ax", "ay", "az"];
    /// assert_eq!(Unit::builtins_matching(&dual), ["dual-triad", "triad"]);
    /// assert!(Unit::builtins_matching(&["time", "a", "b"]).is_empty());
    /// ```
    pub fn builtins_matching(header: &[&str]) -> Vec<&'static str> {
        let mut found: Vec<(usize, &'static str)> = Self::BUILTIN_NAMES
            .into_iter()
            .filter_map(|name| {
                let unit = Self::builtin(name).ok()?;
                let mut needed = unit.gyro_names();
                needed.extend(unit.accel_names());
                let sensors = needed.len();
                needed.push(&unit.columns.time);
                needed
                    .iter()
                    .all(|c| header.contains(c))
                    .then_some((sensors, name))
            })
            .collect();
        found.sort_by_key(|&(sensors, _)| std::cmp::Reverse(sensors));
        found.into_iter().map(|(_, name)| name).collect()
    }

    /// A built-in unit's file text (what `units/NAME.toml` holds).
    ///
    /// ```
    /// assert!(nav_sensors::unit::Unit::builtin_toml("paper").unwrap().contains("name = \"X1\""));
    /// assert!(nav_sensors::unit::Unit::builtin_toml("nope").is_none());
    /// ```
    pub fn builtin_toml(name: &str) -> Option<&'static str> {
        BUILTIN
            .iter()
            .find(|(n, _, _)| *n == name)
            .map(|(_, t, _)| *t)
    }

    /// The paper's unit (the default of every command).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::paper();
    /// assert_eq!(u.gyro_names(), ["X", "X1", "Y", "Y1", "Z", "Z1"]);
    /// assert!(u.has_paper_geometry());
    /// ```
    pub fn paper() -> Self {
        Self::builtin("paper").expect("the embedded paper unit is valid (tested)")
    }

    /// `--unit ARG`: a file when `ARG` ends in `.toml` or holds a path
    /// separator, else a built-in name.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::resolve("triad").unwrap().gyros().len(), 3);
    /// assert!(nav_sensors::unit::Unit::resolve("no/such/unit.toml").is_err());
    /// ```
    pub fn resolve(arg: &str) -> Result<Self, UnitError> {
        if arg.ends_with(".toml") || arg.contains('/') || arg.contains('\\') {
            Self::load(arg)
        } else {
            Self::builtin(arg)
        }
    }

    /// The unit written as a unit file (the contract's keys).
    ///
    /// ```
    /// let text = nav_sensors::unit::Unit::paper().to_toml();
    /// assert!(text.contains("[[gyro]]") && text.contains("model = \"dtg\""));
    /// ```
    pub fn to_toml(&self) -> String {
        toml::to_string(&file::UnitFile::from(self)).expect("plain data serialises")
    }

    /// Assembles a validated unit and derives its geometry (`imus`: the
    /// IMUs whose accelerometers span 3-D, with their indices).
    #[allow(clippy::too_many_arguments)]
    fn assemble(
        name: String,
        columns: Columns,
        units: Units,
        gyros: Vec<Gyro>,
        accels: Vec<Accelerometer>,
        residues: Vec<NamedResidue>,
        imus: Vec<(String, Vec<usize>)>,
        ulog: Option<ulog::UlogTable>,
        file: String,
    ) -> Self {
        let paper_geometry = paper_geometry(&gyros);
        let geometry = UnitGeometry::new(&gyros, &accels, &residues, imus);
        Self {
            name,
            columns,
            units,
            gyros,
            accels,
            residues,
            ulog,
            file,
            file_format: FileFormat::Unit,
            paper_geometry,
            geometry,
        }
    }

    /// The free-text name shown in reports.
    ///
    /// ```
    /// assert!(nav_sensors::unit::Unit::builtin("tetra").unwrap().name().starts_with("tetra"));
    /// ```
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Where the unit was read from (`units/NAME.toml` for a built-in), for messages.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::builtin("triad").unwrap().file(), "units/triad.toml");
    /// ```
    pub fn file(&self) -> &str {
        &self.file
    }

    /// The unit, with `file` as where messages say it was read from: a
    /// unit stored in a model file is named by that file (its keys read
    /// as `<stored unit>` until then).
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let u = u.with_file("the unit stored in m.json");
    /// assert_eq!(u.file(), "the unit stored in m.json");
    /// ```
    pub fn with_file(mut self, file: impl Into<String>) -> Self {
        self.file = file.into();
        self
    }

    /// `[columns]`.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::paper().columns().time, "t");
    /// ```
    pub fn columns(&self) -> &Columns {
        &self.columns
    }

    /// `[units]`.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::paper().units().rate.name(), "deg/h");
    /// ```
    pub fn units(&self) -> &Units {
        &self.units
    }

    /// The gyros in file order (the order of every per-channel vector).
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::builtin("dual-triad").unwrap().gyros().len(), 6);
    /// ```
    pub fn gyros(&self) -> &[Gyro] {
        &self.gyros
    }

    /// The accelerometers in file order.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::paper().accels().len(), 3);
    /// ```
    pub fn accels(&self) -> &[Accelerometer] {
        &self.accels
    }

    /// The residues the unit file names (`[[residue]]`), in file order;
    /// empty when it names none.
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// assert_eq!(Unit::paper().named_residues().len(), 6);
    /// assert!(Unit::builtin("tetra").unwrap().named_residues().is_empty());
    /// ```
    pub fn named_residues(&self) -> &[NamedResidue] {
        &self.residues
    }

    /// The physical unit of a record column the unit reads as an extra
    /// column (an effect's regressor): `°C` for the unit's temperature
    /// column whatever it is called (`board_temp`, `T_imu`), and for the
    /// paper format's `temp`; `None` for a column the unit says nothing of
    /// (its effect is then "per unit of" the column).
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// let toml = Unit::builtin_toml("triad").unwrap().replace("time = \"t\"", "time = \"t\"\ntemperature = \"board_temp\"");
    /// let unit = Unit::from_toml(&toml, "u.toml").unwrap();
    /// assert_eq!(unit.column_unit("board_temp"), Some("°C"));
    /// assert_eq!(Unit::paper().column_unit("temp"), Some("°C"));
    /// assert_eq!(unit.column_unit("baro"), None);
    /// ```
    pub fn column_unit(&self, column: &str) -> Option<&'static str> {
        let temperature = self.columns.temperature.as_deref();
        (temperature == Some(column) || (temperature.is_none() && column == "temp")).then_some("°C")
    }

    /// The `[ulog]` table the unit file gives, if any.
    ///
    /// ```
    /// assert!(nav_sensors::unit::Unit::builtin("triad").unwrap().declared_ulog_table().is_none());
    /// ```
    pub fn declared_ulog_table(&self) -> Option<&ulog::UlogTable> {
        self.ulog.as_ref()
    }

    /// Where each column comes from in a PX4 ULog file: the unit file's
    /// `[ulog]` table, or for a triad whose gyros and accelerometers lie
    /// on +x, +y, +z (and no temperature column) PX4's `sensor_combined`;
    /// `None` for any other unit without a table.
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// let t = Unit::builtin("triad").unwrap().ulog_table().unwrap();
    /// assert_eq!(t.columns["gy"].field, "gyro_rad[1]");
    /// assert_eq!(t.columns["az"].field, "accelerometer_m_s2[2]");
    /// assert!(Unit::builtin("tetra").unwrap().ulog_table().is_none());
    /// ```
    pub fn ulog_table(&self) -> Option<ulog::UlogTable> {
        match &self.ulog {
            Some(t) => Some(t.clone()),
            None => {
                let gyros: Vec<_> = self
                    .gyros
                    .iter()
                    .map(|g| (g.name.as_str(), g.input))
                    .collect();
                let accels: Vec<_> = self
                    .accels
                    .iter()
                    .map(|a| (a.name.as_str(), a.input))
                    .collect();
                ulog_table::default_table(self.columns.temperature.as_deref(), &gyros, &accels)
            }
        }
    }

    /// The gyro channels' names, in file order.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::builtin("tetra").unwrap().gyro_names(), ["g1", "g2", "g3", "g4"]);
    /// ```
    pub fn gyro_names(&self) -> Vec<&str> {
        self.gyros.iter().map(|g| g.name.as_str()).collect()
    }

    /// The accelerometers' names, in file order.
    ///
    /// ```
    /// assert_eq!(nav_sensors::unit::Unit::paper().accel_names(), ["ax", "ay", "az"]);
    /// ```
    pub fn accel_names(&self) -> Vec<&str> {
        self.accels.iter().map(|a| a.name.as_str()).collect()
    }

    /// The IMUs the unit groups its sensors into (`imu` keys), in order of
    /// first appearance (gyros, then accelerometers); empty when it groups
    /// none.
    ///
    /// ```
    /// let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../units/multi-imu.toml")).unwrap();
    /// let u = nav_sensors::unit::Unit::from_toml(&text, "units/multi-imu.toml").unwrap();
    /// assert_eq!(u.imu_names(), ["imu1", "imu2", "imu3"]);
    /// assert!(nav_sensors::unit::Unit::paper().imu_names().is_empty());
    /// ```
    pub fn imu_names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        let all = self.gyros.iter().map(|g| &g.imu);
        for imu in all.chain(self.accels.iter().map(|a| &a.imu)).flatten() {
            if !names.contains(&imu.as_str()) {
                names.push(imu);
            }
        }
        names
    }

    /// The accelerometers gyro `k` reads by default: its IMU's (in unit
    /// order), or every accelerometer when it names no IMU.
    ///
    /// ```
    /// let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../units/multi-imu.toml")).unwrap();
    /// let u = nav_sensors::unit::Unit::from_toml(&text, "units/multi-imu.toml").unwrap();
    /// assert_eq!(u.imu_accel_names(4), ["a2x", "a2y", "a2z"]); // g2y
    /// assert_eq!(nav_sensors::unit::Unit::paper().imu_accel_names(0), ["ax", "ay", "az"]);
    /// ```
    #[track_caller]
    pub fn imu_accel_names(&self, k: usize) -> Vec<&str> {
        let imu = &self.gyros[k].imu;
        self.accels
            .iter()
            .filter(|a| imu.is_none() || a.imu == *imu)
            .map(|a| a.name.as_str())
            .collect()
    }

    /// The position of a gyro channel by name.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
    /// assert_eq!(u.gyro_index("gx2"), Some(3));
    /// assert_eq!(u.gyro_index("X"), None);
    /// ```
    pub fn gyro_index(&self, name: &str) -> Option<usize> {
        self.gyros.iter().position(|g| g.name == name)
    }

    /// Whether the gyros are the paper's six channels (names X, X1, Y, Y1,
    /// Z, Z1 in that order, `dtg`, with eq. 4's input axes and the paper's
    /// spin and output axes to the last bit). Nothing in the geometry
    /// depends on it (the residues K0–K5 are `units/paper.toml`'s data).
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// assert!(Unit::paper().has_paper_geometry());
    /// assert!(!Unit::builtin("triad").unwrap().has_paper_geometry());
    /// ```
    pub fn has_paper_geometry(&self) -> bool {
        self.paper_geometry
    }

    /// The formats its simulated files are written in (the built-in
    /// units' table; a unit read from a file writes the unit formats).
    ///
    /// ```
    /// use nav_sensors::unit::{FileFormat, Unit};
    /// assert_eq!(Unit::builtin("triad").unwrap().file_format(), FileFormat::Unit);
    /// ```
    pub fn file_format(&self) -> FileFormat {
        self.file_format
    }

    /// The derived geometry (H, least squares, parity).
    ///
    /// ```
    /// let g = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// assert_eq!(g.geometry().measurement_matrix().nrows(), 4);
    /// ```
    pub fn geometry(&self) -> &UnitGeometry {
        &self.geometry
    }

    /// The n×3 measurement matrix H: row k is gyro k's input axis.
    ///
    /// ```
    /// let h = nav_sensors::unit::Unit::builtin("tetra").unwrap().measurement_matrix().clone();
    /// let hth = h.transpose() * &h;
    /// assert!((hth - nalgebra::DMatrix::<f64>::identity(3, 3) * (4.0 / 3.0)).norm() < 1e-12);
    /// ```
    pub fn measurement_matrix(&self) -> &nalgebra::DMatrix<f64> {
        self.geometry.measurement_matrix()
    }

    /// The orthonormal parity matrix V ((n − 3)×n): `V·H = 0`, `V·Vᵀ = I`.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
    /// let v = u.parity_matrix();
    /// assert_eq!(v.shape(), (3, 6));
    /// assert!((v * u.measurement_matrix()).norm() < 1e-12);
    /// ```
    pub fn parity_matrix(&self) -> &nalgebra::DMatrix<f64> {
        self.geometry.parity_matrix()
    }

    /// The residues' names: those the unit file names (`[[residue]]`: the
    /// paper's K0–K5), else `P0`, `P1`, … (one per row of V), none for a
    /// unit of three gyros.
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// assert_eq!(Unit::paper().residue_names(), ["K0", "K1", "K2", "K3", "K4", "K5"]);
    /// assert_eq!(Unit::builtin("dual-triad").unwrap().residue_names(), ["P0", "P1", "P2"]);
    /// ```
    pub fn residue_names(&self) -> &[String] {
        self.geometry.residue_names()
    }

    /// The residues of one sample of gyro outputs (file order, any rate
    /// unit): the named residues' weights times `m` (for the paper, eq. 6),
    /// `V·m` when the unit names none, and an empty vector for three gyros
    /// (nothing is redundant; judge them against a rate reference instead).
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// let u = Unit::builtin("tetra").unwrap();
    /// let m: Vec<f64> = u.gyros().iter().map(|g| g.input.dot(&nalgebra::Vector3::new(5.0, -2.0, 9.0))).collect();
    /// assert!(u.residues(&m)[0].abs() < 1e-12);
    /// assert!(Unit::builtin("triad").unwrap().residues(&[1.0, 2.0, 3.0]).is_empty());
    /// ```
    #[track_caller]
    pub fn residues(&self, m: &[f64]) -> Vec<f64> {
        self.geometry.residues(m)
    }

    /// The parity vector `V·m` of one sample (gyro order, any rate unit):
    /// orthonormal components whatever residues the unit names, so that
    /// independent channel noise σ gives components of σ each (what fault
    /// detection and a noise estimate need; the named residues, such as
    /// eq. 6's, are neither orthogonal nor of unit norm).
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// let u = Unit::paper();
    /// let p = u.parity_vector(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    /// assert_eq!(p.len(), 3);
    /// // A fault on X reaches the parity space with ‖v_X‖² = 1 − h_Xᵀ(HᵀH)⁻¹h_X.
    /// let leverage = u.geometry().least_squares_operator().column(0).dot(&u.measurement_matrix().row(0).transpose());
    /// assert!((p.iter().map(|v| v * v).sum::<f64>() - (1.0 - leverage)).abs() < 1e-12);
    /// ```
    #[track_caller]
    pub fn parity_vector(&self, m: &[f64]) -> Vec<f64> {
        self.geometry.parity_vector(m)
    }

    /// The least-squares rate `(HᵀH)⁻¹Hᵀm` of one sample (H's
    /// pseudo-inverse by SVD), same unit as `m`.
    ///
    /// ```
    /// use nav_sensors::unit::Unit;
    /// let u = Unit::builtin("dual-triad").unwrap();
    /// let w = nalgebra::Vector3::new(10.0, -3.0, 7.0);
    /// let m: Vec<f64> = u.gyros().iter().map(|g| g.input.dot(&w)).collect();
    /// assert!((u.least_squares_rate(&m) - w).norm() < 1e-12);
    /// ```
    #[track_caller]
    pub fn least_squares_rate(&self, m: &[f64]) -> Vector3<f64> {
        self.geometry.least_squares_rate(m)
    }

    /// The specific force in the unit frame from one sample of the
    /// accelerometers (file order), g: the outputs themselves when the
    /// accelerometers lie on the unit axes, their least-squares combination
    /// otherwise.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// assert_eq!(u.specific_force(&[0.1, 0.2, 1.0]), nalgebra::Vector3::new(0.1, 0.2, 1.0));
    /// ```
    #[track_caller]
    pub fn specific_force(&self, a: &[f64]) -> Vector3<f64> {
        self.geometry.specific_force(a)
    }

    /// One IMU's specific force in the unit frame, g, from one sample of
    /// every accelerometer (unit order): that IMU's accelerometers alone,
    /// as [`Unit::specific_force`] combines them. `None` for a name that is
    /// no IMU's or an IMU whose accelerometers do not span 3-D.
    ///
    /// ```
    /// let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../units/multi-imu.toml")).unwrap();
    /// let u = nav_sensors::unit::Unit::from_toml(&text, "units/multi-imu.toml").unwrap();
    /// let a = [0.0, 0.0, 1.0, 0.0, 0.0, 1.2, 0.0, 0.0, 1.1];
    /// assert_eq!(u.imu_specific_force("imu2", &a).unwrap().z, 1.2);
    /// assert!((u.specific_force(&a).z - 1.1).abs() < 1e-12); // the unit's: the three triads' mean
    /// assert!(u.imu_specific_force("imu4", &a).is_none());
    /// ```
    #[track_caller]
    pub fn imu_specific_force(&self, imu: &str, a: &[f64]) -> Option<Vector3<f64>> {
        self.geometry.imu_specific_force(imu, a)
    }

    /// The specific force gyro `k` senses, g: its IMU's
    /// ([`Unit::imu_specific_force`]), or the unit's when it names no IMU.
    ///
    /// ```
    /// let u = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// assert_eq!(u.gyro_specific_force(0, &[0.1, 0.2, 1.0]), u.specific_force(&[0.1, 0.2, 1.0]));
    /// ```
    #[track_caller]
    pub fn gyro_specific_force(&self, k: usize, a: &[f64]) -> Vector3<f64> {
        match &self.gyros[k].imu {
            Some(imu) => self
                .imu_specific_force(imu, a)
                .expect("a gyro's IMU spans 3-D (validated)"),
            None => self.specific_force(a),
        }
    }
}

impl Serialize for Unit {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        file::UnitFile::from(self).serialize(s)
    }
}

impl<'de> Deserialize<'de> for Unit {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let f = file::UnitFile::deserialize(d)?;
        f.validate("<stored unit>")
            .map_err(serde::de::Error::custom)
    }
}

/// Names X..Z1 in order, `dtg`, with today's frames to the last bit.
fn paper_geometry(gyros: &[Gyro]) -> bool {
    gyros.len() == 6
        && gyros.iter().zip(Channel::ALL).all(|(g, c)| {
            let frame = crate::geometry::ChannelFrame::of(c);
            let bits = |a: &Vector3<f64>, b: &Vector3<f64>| {
                a.iter()
                    .zip(b.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            };
            g.name == c.name()
                && bits(&g.input, &input_axis(c))
                && match g.model {
                    GyroModel::Dtg { spin, output } => {
                        bits(&spin, &frame.spin)
                            && bits(&output, &frame.other)
                            && bits(&spin, &dtg_frame(c.dtg()).row(2).transpose())
                    }
                    GyroModel::Rate => false,
                }
        })
}

#[cfg(test)]
mod tests;
