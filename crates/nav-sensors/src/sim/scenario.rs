//! A vibration test described as data (TOML), with a seed.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::motion::MotionProfile;
use super::site::Site;
use super::thermal::Thermal;
use crate::accel::{AccelCoefficients, AccelNoise, ServoLoop};
use crate::dtg::{DtgCoefficients, DtgNoise, DtgTerm};
use crate::geometry::{Axis, Channel};
use crate::rate::RateCoefficients;
use crate::signal::num;
use crate::vibration::{VibrationConfig, VibrationError};

/// The three DTGs: shared dynamics and noise, coefficients per channel.
///
/// ```
/// let g = &nav_sensors::sim::Scenario::default().gyros;
/// assert_eq!(g.spin_hz, 200.0);
/// assert_eq!(g.channels.len(), 6);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GyroSet {
    /// Rotor spin frequency, Hz (2N = twice this).
    pub spin_hz: f64,
    /// Quality factor of the 2N rectification resonance.
    pub rect_2n_q: f64,
    /// Noise, the same model on every channel.
    pub noise: DtgNoise,
    /// Output quantisation: angle per pulse, arcsec (remainder carried to
    /// the next interval); absent for none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pulse_arcsec: Option<f64>,
    /// True coefficients per channel (a missing channel is an ideal one).
    pub channels: BTreeMap<Channel, DtgCoefficients>,
}

/// The accelerometer triad.
///
/// ```
/// let a = &nav_sensors::sim::Scenario::default().accels;
/// assert_eq!(a.servo.natural_hz, 800.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AccelSet {
    /// Servo-loop dynamics (the same on every axis).
    #[serde(default)]
    pub servo: ServoLoop,
    /// Noise.
    #[serde(default)]
    pub noise: AccelNoise,
    /// True coefficients per axis (a missing axis is an ideal one).
    #[serde(default)]
    pub axes: BTreeMap<Axis, AccelCoefficients>,
}

/// Errors of the ground calibration handed to the user: each calibrated
/// coefficient is `truth·(1 + relative·n₁) + absolute·n₂` with n₁, n₂
/// independent standard normal draws (seeded). Values are 1σ.
///
/// ```
/// let e: nav_sensors::sim::CalibrationError = toml::from_str("relative = 0.05").unwrap();
/// assert_eq!(e.relative, 0.05);
/// assert_eq!(e.bias_deg_h, nav_sensors::sim::CalibrationError::default().bias_deg_h);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CalibrationError {
    /// Relative error of every calibrated coefficient (1σ, fraction).
    pub relative: f64,
    /// DTG bias, deg/h.
    pub bias_deg_h: f64,
    /// DTG scale factor, ppm.
    pub scale_factor_ppm: f64,
    /// DTG misalignments, µrad.
    pub misalignment_urad: f64,
    /// DTG g-sensitive drifts, deg/h/g.
    pub g_deg_h_g: f64,
    /// DTG anisoelastic drifts, deg/h/g².
    pub gg_deg_h_g2: f64,
    /// DTG anisoinertia, deg/h/(deg/s)².
    pub ai_deg_h_per_deg_s2: f64,
    /// Accelerometer bias, µg.
    pub accel_bias_ug: f64,
    /// Accelerometer scale factor, ppm.
    pub accel_scale_factor_ppm: f64,
    /// Accelerometer K2, µg/g².
    pub accel_k2_ug_per_g2: f64,
    /// Accelerometer misalignments, µrad.
    pub accel_misalignment_urad: f64,
}

impl Default for CalibrationError {
    /// Small, as after a good multi-position and centrifuge calibration:
    /// 1% relative plus 0.02 deg/h, 20 ppm, 20 µrad, 0.01 deg/h/g,
    /// 0.002 deg/h/g², 0.002 deg/h/(deg/s)²; accelerometers 20 µg, 20 ppm,
    /// 1 µg/g², 10 µrad.
    fn default() -> Self {
        Self {
            relative: 0.01,
            bias_deg_h: 0.02,
            scale_factor_ppm: 20.0,
            misalignment_urad: 20.0,
            g_deg_h_g: 0.01,
            gg_deg_h_g2: 0.002,
            ai_deg_h_per_deg_s2: 0.002,
            accel_bias_ug: 20.0,
            accel_scale_factor_ppm: 20.0,
            accel_k2_ug_per_g2: 1.0,
            accel_misalignment_urad: 10.0,
        }
    }
}

impl CalibrationError {
    /// No calibration error at all (the calibration equals the truth on
    /// every calibrated term).
    ///
    /// ```
    /// assert_eq!(nav_sensors::sim::CalibrationError::none().relative, 0.0);
    /// ```
    pub fn none() -> Self {
        Self {
            relative: 0.0,
            bias_deg_h: 0.0,
            scale_factor_ppm: 0.0,
            misalignment_urad: 0.0,
            g_deg_h_g: 0.0,
            gg_deg_h_g2: 0.0,
            ai_deg_h_per_deg_s2: 0.0,
            accel_bias_ug: 0.0,
            accel_scale_factor_ppm: 0.0,
            accel_k2_ug_per_g2: 0.0,
            accel_misalignment_urad: 0.0,
        }
    }

    /// The absolute 1σ for a DTG term (zero for terms calibration does not cover).
    ///
    /// ```
    /// use nav_sensors::dtg::DtgTerm;
    /// let e = nav_sensors::sim::CalibrationError::default();
    /// assert_eq!(e.absolute_for(DtgTerm::GgIS), e.gg_deg_h_g2);
    /// assert_eq!(e.absolute_for(DtgTerm::Temp), 0.0);
    /// ```
    pub fn absolute_for(&self, term: DtgTerm) -> f64 {
        match term {
            DtgTerm::Bias => self.bias_deg_h,
            DtgTerm::ScaleFactor => self.scale_factor_ppm,
            DtgTerm::MisalignmentO | DtgTerm::MisalignmentS => self.misalignment_urad,
            DtgTerm::GI | DtgTerm::GO | DtgTerm::GS => self.g_deg_h_g,
            DtgTerm::GgII
            | DtgTerm::GgOO
            | DtgTerm::GgSS
            | DtgTerm::GgIO
            | DtgTerm::GgIS
            | DtgTerm::GgOS => self.gg_deg_h_g2,
            DtgTerm::AiIO | DtgTerm::AiIS | DtgTerm::AiOS => self.ai_deg_h_per_deg_s2,
            DtgTerm::Temp | DtgTerm::Rect2N => 0.0,
        }
    }

    /// The absolute 1σ for a rate-gyro term: the DTG's bias, scale-factor,
    /// g-sensitive and g²-sensitive errors for their rate-gyro counterparts
    /// (zero for `temp`).
    ///
    /// ```
    /// use nav_sensors::rate::RateTerm;
    /// let e = nav_sensors::sim::CalibrationError::default();
    /// assert_eq!(e.absolute_for_rate(RateTerm::GY), e.g_deg_h_g);
    /// assert_eq!(e.absolute_for_rate(RateTerm::Temp), 0.0);
    /// ```
    pub fn absolute_for_rate(&self, term: crate::rate::RateTerm) -> f64 {
        use crate::rate::RateTerm as T;
        match term {
            T::Bias => self.bias_deg_h,
            T::ScaleFactor => self.scale_factor_ppm,
            T::GX | T::GY | T::GZ => self.g_deg_h_g,
            T::GgXx | T::GgYy | T::GgZz | T::GgXy | T::GgXz | T::GgYz => self.gg_deg_h_g2,
            T::Temp => 0.0,
        }
    }
}

/// An effect present in the truth and zeroed in the calibration handed to
/// the user: what the application's diagnosis must find.
///
/// ```
/// let h: nav_sensors::sim::HiddenEffect = toml::from_str("channel = \"Y1\"\nterm = \"gg_IS\"").unwrap();
/// assert_eq!(h.term, nav_sensors::dtg::DtgTerm::GgIS);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HiddenEffect {
    /// The channel.
    pub channel: Channel,
    /// The term, by stable id.
    pub term: DtgTerm,
}

/// The gyros of a unit other than the paper's (simulated with
/// [`crate::sim::simulate_unit`]): true coefficients by channel name, in the
/// table of the channel's model, and the hidden effects by channel name and
/// term id. A channel listed nowhere is an ideal gyro, except that a `dtg`
/// channel named like one of the paper's takes `gyros.channels` (so the
/// paper's unit reads the scenario's paper tables).
///
/// ```
/// let text = "[rate.g2]\ng_y_deg_h_g = 0.5\n[[hidden]]\nchannel = \"g2\"\nterm = \"g_y\"\n";
/// let u: nav_sensors::sim::UnitGyros = toml::from_str(text).unwrap();
/// assert_eq!(u.rate["g2"].g_y_deg_h_g, 0.5);
/// assert_eq!(u.hidden[0].to_string(), "g2=g_y");
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitGyros {
    /// Rate-gyro coefficients by channel name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub rate: BTreeMap<String, RateCoefficients>,
    /// DTG coefficients by channel name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub dtg: BTreeMap<String, DtgCoefficients>,
    /// Effects present in the truth and zeroed in the calibration.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hidden: Vec<UnitHiddenEffect>,
}

impl UnitGyros {
    /// Whether nothing is given (the scenario then writes no `[unit]` table).
    ///
    /// ```
    /// assert!(nav_sensors::sim::UnitGyros::default().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.rate.is_empty() && self.dtg.is_empty() && self.hidden.is_empty()
    }
}

/// A hidden effect of a unit's channel: the channel's name and a term id of
/// its model (`g2=g_y` for a rate gyro, `Y1=gg_IS` for a DTG channel).
///
/// ```
/// let h: nav_sensors::sim::UnitHiddenEffect = "gx2 = g_x".parse().unwrap();
/// assert_eq!((h.channel.as_str(), h.term.as_str()), ("gx2", "g_x"));
/// assert!("gx2".parse::<nav_sensors::sim::UnitHiddenEffect>().is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitHiddenEffect {
    /// The channel's name.
    pub channel: String,
    /// The term id.
    pub term: String,
}

impl std::fmt::Display for UnitHiddenEffect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}={}", self.channel, self.term)
    }
}

impl std::str::FromStr for UnitHiddenEffect {
    type Err = String;
    /// `CHANNEL=ID`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.split_once('=') {
            Some((c, t)) if !c.trim().is_empty() && !t.trim().is_empty() => Ok(Self {
                channel: c.trim().to_string(),
                term: t.trim().to_string(),
            }),
            _ => Err(format!("'{s}': expected CHANNEL=ID, e.g. g2=g_y")),
        }
    }
}

/// A complete vibration test.
///
/// `Scenario::default()` is the paper's test ([`Scenario::paper_z_random`]).
///
/// ```
/// use nav_sensors::sim::Scenario;
/// let s = Scenario::default();
/// let text = s.to_toml().unwrap();
/// assert_eq!(Scenario::from_toml(&text, "inline").unwrap(), s);
/// assert_eq!(s.output_samples(), 5000);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Short name.
    pub name: String,
    /// What the test is for.
    #[serde(default)]
    pub description: String,
    /// Seed of every random draw; the same seed gives byte-identical files.
    pub seed: u64,
    /// Test length, s.
    pub duration_s: f64,
    /// Rate at which physics and error models run, Hz (≥ 4 kHz so the
    /// 2000-Hz band is represented).
    pub internal_rate_hz: f64,
    /// Rate of the instruments' outputs, Hz (a divisor of the internal rate).
    pub output_rate_hz: f64,
    /// Latitude and orientation.
    pub site: Site,
    /// The shaker.
    pub vibration: VibrationConfig,
    /// A flight-like motion of the unit (attitude, turns, speed; see
    /// [`MotionProfile`]); absent for a unit fixed on the shaker table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<MotionProfile>,
    /// Temperature.
    pub thermal: Thermal,
    /// The gyros.
    pub gyros: GyroSet,
    /// The accelerometers.
    pub accels: AccelSet,
    /// Errors of the ground calibration handed to the user.
    #[serde(default)]
    pub calibration_error: CalibrationError,
    /// Effects present in the truth but zeroed in the calibration.
    #[serde(default)]
    pub hidden: Vec<HiddenEffect>,
    /// The gyros of a unit other than the paper's (absent for the paper's).
    #[serde(default, skip_serializing_if = "UnitGyros::is_empty")]
    pub unit: UnitGyros,
}

/// What is wrong with a scenario.
///
/// ```
/// use nav_sensors::sim::{Scenario, ScenarioError};
/// let err = Scenario::from_toml("seed = 1", "s.toml").unwrap_err();
/// assert!(matches!(err, ScenarioError::Parse { .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// A number that is NaN or infinite (TOML spells them `nan` and `inf`).
    #[error("{field} = {value}: every number in a scenario must be finite")]
    NotFinite {
        /// Dotted path of the field, e.g. `gyros.channels.Y1.gg_is`.
        field: String,
        /// The value.
        value: f64,
    },
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The TOML does not describe a scenario (the message has line and column).
    #[error("{file}: {message}")]
    Parse {
        /// The file.
        file: String,
        /// The parser's message, with the location.
        message: String,
    },
    /// Serialising failed.
    #[error("cannot write scenario as TOML: {0}")]
    Serialize(String),
    /// A rate, duration or parameter out of range.
    #[error("{field} = {}: {requirement}", num(*value))]
    OutOfRange {
        /// The field's path.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// The cluster's x and z directions are not perpendicular.
    #[error("orientation: x {x:?} and z {z:?} are not perpendicular")]
    Orientation {
        /// x direction.
        x: super::site::Direction,
        /// z direction.
        z: super::site::Direction,
    },
    /// The vibration description is invalid.
    #[error("vibration: {0}")]
    Vibration(#[from] VibrationError),
    /// A hidden effect whose truth coefficient is zero (nothing to find).
    #[error("hidden effect {channel}/{term}: its truth coefficient is zero")]
    HiddenIsZero {
        /// Channel.
        channel: Channel,
        /// Term.
        term: DtgTerm,
    },
    /// A `[unit]` entry that does not fit the unit simulated: a channel the
    /// unit lacks, a table of the other model, an unknown term id, or a
    /// hidden effect whose truth coefficient is zero.
    #[error("{key}: {problem}")]
    Unit {
        /// The scenario key, e.g. `unit.rate.g5` or `unit.hidden[0]`.
        key: String,
        /// What is wrong, and with which unit file.
        problem: String,
    },
}

impl Default for Scenario {
    fn default() -> Self {
        Self::paper_z_random()
    }
}

impl Scenario {
    /// Parses a scenario from TOML text; `file` labels errors.
    ///
    /// ```
    /// let text = nav_sensors::sim::Scenario::triaxial_clean().to_toml().unwrap();
    /// let s = nav_sensors::sim::Scenario::from_toml(&text, "inline").unwrap();
    /// assert_eq!(s.name, "triaxial_clean");
    /// ```
    pub fn from_toml(text: &str, file: &str) -> Result<Self, ScenarioError> {
        toml::from_str(text).map_err(|e| ScenarioError::Parse {
            file: file.to_string(),
            message: e.to_string(),
        })
    }

    /// Reads a scenario TOML file.
    ///
    /// ```
    /// let path = std::env::temp_dir().join("nav-sensors-doc-scenario-load.toml");
    /// nav_sensors::sim::Scenario::default().save(&path).unwrap();
    /// assert_eq!(nav_sensors::sim::Scenario::load(&path).unwrap(), nav_sensors::sim::Scenario::default());
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, ScenarioError> {
        crate::files::io::load_with(
            path.as_ref(),
            |path, source| ScenarioError::Io { path, source },
            Self::from_toml,
        )
    }

    /// The scenario as TOML text.
    ///
    /// ```
    /// let text = nav_sensors::sim::Scenario::default().to_toml().unwrap();
    /// assert!(text.contains("[gyros.channels.Z1]"));
    /// ```
    pub fn to_toml(&self) -> Result<String, ScenarioError> {
        toml::to_string(self).map_err(|e| ScenarioError::Serialize(e.to_string()))
    }

    /// Writes the scenario as a TOML file.
    ///
    /// ```
    /// let path = std::env::temp_dir().join("nav-sensors-doc-scenario-save.toml");
    /// nav_sensors::sim::Scenario::default().save(&path).unwrap();
    /// assert!(std::fs::read_to_string(&path).unwrap().starts_with("name = "));
    /// ```
    pub fn save(&self, path: impl AsRef<Path>) -> Result<(), ScenarioError> {
        let path = path.as_ref();
        outfile::write_bytes(path, self.to_toml()?).map_err(|source| ScenarioError::Io {
            path: path.display().to_string(),
            source,
        })
    }

    /// The most internal-rate samples a scenario may ask for (2^26: about
    /// 5 GiB of simulator memory, 4.6 hours at 4 kHz).
    ///
    /// ```
    /// let mut s = nav_sensors::sim::Scenario::default();
    /// s.duration_s = 1e9;
    /// assert!(s.validate().unwrap_err().to_string().contains("2^26"));
    /// ```
    pub const MAX_INTERNAL_SAMPLES: usize = 1 << 26;

    /// Number of output samples, `round(duration·output rate)`.
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario { duration_s: 2.0, ..Default::default() };
    /// assert_eq!(s.output_samples(), 100);
    /// ```
    pub fn output_samples(&self) -> usize {
        (self.duration_s * self.output_rate_hz).round() as usize
    }

    /// Internal samples per output interval.
    ///
    /// ```
    /// assert_eq!(nav_sensors::sim::Scenario::default().oversampling(), 80);
    /// ```
    pub fn oversampling(&self) -> usize {
        (self.internal_rate_hz / self.output_rate_hz).round() as usize
    }

    /// The true coefficients of a channel (zero when not listed).
    ///
    /// ```
    /// use nav_sensors::geometry::Channel;
    /// let mut s = nav_sensors::sim::Scenario::default();
    /// s.gyros.channels.remove(&Channel::X);
    /// assert_eq!(s.gyro(Channel::X).bias_deg_h, 0.0);
    /// ```
    pub fn gyro(&self, channel: Channel) -> DtgCoefficients {
        self.gyros
            .channels
            .get(&channel)
            .copied()
            .unwrap_or_default()
    }

    /// The true coefficients of an accelerometer (zero when not listed).
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario::default();
    /// assert_eq!(s.accel(nav_sensors::geometry::Axis::Z).bias_ug, 140.0);
    /// ```
    pub fn accel(&self, axis: Axis) -> AccelCoefficients {
        self.accels.axes.get(&axis).copied().unwrap_or_default()
    }

    /// Checks every range the simulator relies on.
    ///
    /// ```
    /// let s = nav_sensors::sim::Scenario { internal_rate_hz: 1000.0, ..Default::default() };
    /// assert!(s.validate().is_err());
    /// assert!(nav_sensors::sim::Scenario::default().validate().is_ok());
    /// ```
    pub fn validate(&self) -> Result<(), ScenarioError> {
        self.check_timing()?;
        self.check_sensors()?;
        self.check_noise()?;
        let range = check_range;
        range(
            "site.latitude_deg",
            self.site.latitude_deg,
            self.site.latitude_deg.abs() <= 90.0,
            "must be from -90 to 90 degrees",
        )?;
        if let Ok(value) = toml::Value::try_from(self)
            && let Some((field, value)) = first_non_finite(&value, "")
        {
            return Err(ScenarioError::NotFinite { field, value });
        }
        if self.site.orientation.axes_enu().is_none() {
            return Err(ScenarioError::Orientation {
                x: self.site.orientation.x,
                z: self.site.orientation.z,
            });
        }
        self.vibration.validate(self.internal_rate_hz)?;
        if let Some(m) = &self.motion {
            m.validate()?;
        }
        for h in &self.hidden {
            if self.gyro(h.channel).get(h.term) == 0.0 {
                return Err(ScenarioError::HiddenIsZero {
                    channel: h.channel,
                    term: h.term,
                });
            }
        }
        Ok(())
    }

    /// The rates and the length: a whole number of internal samples per
    /// output sample, at least two output samples, and memory the machine has.
    fn check_timing(&self) -> Result<(), ScenarioError> {
        let range = check_range;
        range(
            "output_rate_hz",
            self.output_rate_hz,
            self.output_rate_hz > 0.0,
            "must be positive",
        )?;
        range(
            "internal_rate_hz",
            self.internal_rate_hz,
            self.internal_rate_hz >= 4000.0,
            "must be at least 4000 Hz so the 2000-Hz band is represented",
        )?;
        let ratio = self.internal_rate_hz / self.output_rate_hz;
        range(
            "internal_rate_hz",
            self.internal_rate_hz,
            // At least once: an output rate above the internal one (1e308)
            // rounded the ratio to 0 and left the synthesis no samples.
            ratio >= 1.0 && (ratio - ratio.round()).abs() < 1e-9,
            "must be a whole multiple (1 or more) of output_rate_hz",
        )?;
        range(
            "duration_s",
            self.duration_s,
            self.output_samples() >= 2,
            "must give at least two output samples",
        )?;
        // The simulator holds the internal-rate histories in memory, about
        // 80 bytes per internal sample (310 MiB for 1000 s at 4 kHz): refuse
        // what would exhaust the machine instead of aborting in the allocator.
        range(
            "duration_s",
            self.duration_s,
            (self.output_samples() as f64) * (self.oversampling() as f64)
                <= Self::MAX_INTERNAL_SAMPLES as f64,
            "with internal_rate_hz gives more than 2^26 internal samples (about 5 GiB of memory; 4.6 h at 4 kHz): split a longer test into several scenarios",
        )?;
        Ok(())
    }

    /// The sensors' dynamics: spin, 2N resonance, pulse size, the
    /// accelerometers' servo loop and the thermal lag.
    fn check_sensors(&self) -> Result<(), ScenarioError> {
        let range = check_range;
        let s = &self.accels.servo;
        range(
            "gyros.spin_hz",
            self.gyros.spin_hz,
            self.gyros.spin_hz > 0.0 && 2.0 * self.gyros.spin_hz < 0.5 * self.internal_rate_hz,
            "must be positive with 2N below the internal Nyquist frequency",
        )?;
        range(
            "gyros.rect_2n_q",
            self.gyros.rect_2n_q,
            self.gyros.rect_2n_q > 0.0,
            "must be positive",
        )?;
        if let Some(q) = self.gyros.pulse_arcsec {
            range("gyros.pulse_arcsec", q, q > 0.0, "must be positive")?;
        }
        range(
            "accels.servo.natural_hz",
            s.natural_hz,
            s.natural_hz > 0.0 && s.natural_hz < 0.5 * self.internal_rate_hz,
            "must be positive and below the internal Nyquist frequency",
        )?;
        range(
            "accels.servo.damping",
            s.damping,
            s.damping > 0.0,
            "must be positive",
        )?;
        range(
            "thermal.time_constant_s",
            self.thermal.time_constant_s,
            self.thermal.time_constant_s >= 0.0,
            "must not be negative",
        )?;
        Ok(())
    }

    /// The noise levels: none negative, and a correlation time where there
    /// is bias instability.
    fn check_noise(&self) -> Result<(), ScenarioError> {
        let range = check_range;
        for (field, v) in [
            (
                "gyros.noise.arw_deg_per_rt_h",
                self.gyros.noise.arw_deg_per_rt_h,
            ),
            (
                "gyros.noise.bias_instability_deg_h",
                self.gyros.noise.bias_instability_deg_h,
            ),
            (
                "gyros.noise.rrw_deg_h_per_rt_h",
                self.gyros.noise.rrw_deg_h_per_rt_h,
            ),
            (
                "accels.noise.density_ug_per_rt_hz",
                self.accels.noise.density_ug_per_rt_hz,
            ),
            ("thermal.sensor_noise_c", self.thermal.sensor_noise_c),
        ] {
            range(field, v, v >= 0.0, "must not be negative")?;
        }
        if self.gyros.noise.bias_instability_deg_h > 0.0 {
            range(
                "gyros.noise.bias_instability_tau_s",
                self.gyros.noise.bias_instability_tau_s,
                self.gyros.noise.bias_instability_tau_s > 0.0,
                "must be positive when there is bias instability",
            )?;
        }
        Ok(())
    }
}

/// `Ok` when `ok` holds and `value` is finite, else the
/// [`ScenarioError::OutOfRange`] that names the field and the requirement.
pub(crate) fn check_range(
    field: &'static str,
    value: f64,
    ok: bool,
    requirement: &'static str,
) -> Result<(), ScenarioError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(ScenarioError::OutOfRange {
            field,
            value,
            requirement,
        })
    }
}

/// The first NaN or infinite number in a TOML tree, with its dotted path.
fn first_non_finite(v: &toml::Value, path: &str) -> Option<(String, f64)> {
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        }
    };
    match v {
        toml::Value::Float(f) if !f.is_finite() => Some((path.to_string(), *f)),
        toml::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_non_finite(x, &format!("{path}[{i}]"))),
        toml::Value::Table(t) => t.iter().find_map(|(k, x)| first_non_finite(x, &join(k))),
        _ => None,
    }
}
