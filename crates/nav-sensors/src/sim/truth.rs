//! The truth of a simulation of any unit (JSON): the unit, the scenario,
//! every channel's true coefficients and error budget, the hidden effects
//! and the residue noise floors. The paper's truth file format (no `unit`
//! key, `super::paper_truth`) reads as the paper unit's truth.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::paper_truth::Truth;
use super::scenario::Scenario;
use crate::files::calibration::GyroCoefficients;
use crate::unit::Unit;

/// A hidden effect of a unit's channel with what it contributes.
///
/// ```
/// use nav_sensors::sim::{simulate_unit, Scenario, UnitHiddenEffect};
/// use nav_sensors::rate::RateCoefficients;
/// let unit = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let mut s = Scenario { duration_s: 2.0, ..Scenario::triaxial_clean() };
/// s.unit.rate.insert("g2".into(), RateCoefficients { g_y_deg_h_g: 1.5, ..Default::default() });
/// s.unit.hidden.push("g2=g_y".parse().unwrap());
/// let sim = simulate_unit(&unit, &s).unwrap();
/// let h = &sim.truth.hidden[0];
/// assert_eq!((h.channel.as_str(), h.term.as_str(), h.coefficient), ("g2", "g_y", 1.5));
/// assert_eq!(h.unit, "deg/h/g");
/// assert!(h.rms_deg_h > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitHiddenTruth {
    /// The channel.
    pub channel: String,
    /// The term id.
    pub term: String,
    /// Its true coefficient, in `unit`.
    pub coefficient: f64,
    /// The coefficient's unit.
    pub unit: String,
    /// IEEE name of the term.
    pub description: String,
    /// Standard deviation at the output rate of the part of the effect a
    /// model of the record can see (coefficient × regressor from the
    /// record's accelerations or temperature), deg/h.
    pub rms_deg_h: f64,
    /// `rms_deg_h / noise_floor_deg_h` of the channel.
    pub ratio_to_noise_floor: f64,
}

/// Two candidate terms of a channel whose regressors are nearly collinear
/// on the record (|correlation| > 0.95 at the output rate): a diagnosis
/// cannot tell them apart.
///
/// ```
/// let unit = nav_sensors::unit::Unit::builtin("tetra").unwrap();
/// let sim = nav_sensors::sim::simulate_unit(&unit, &nav_sensors::sim::Scenario { duration_s: 4.0, ..Default::default() }).unwrap();
/// assert!(sim.truth.channels[0].collinear.iter().all(|p| p.correlation.abs() > 0.95 && p.a != p.b));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitCollinear {
    /// First term's id.
    pub a: String,
    /// Second term's id.
    pub b: String,
    /// Correlation of their regressors at the output rate.
    pub correlation: f64,
}

/// One channel's truth and error budget at the output rate (the noise
/// floor's definition: docs/nav-sensors.md §8). The fields after
/// `after_true_compensation_rms_deg_h` read as zero or empty from a file
/// written before they were (unit truth files of 5b6a72d).
///
/// ```
/// let unit = nav_sensors::unit::Unit::builtin("triad").unwrap();
/// let s = nav_sensors::sim::Scenario { duration_s: 2.0, ..Default::default() };
/// let sim = nav_sensors::sim::simulate_unit(&unit, &s).unwrap();
/// let gz = &sim.truth.channels[2];
/// assert_eq!(gz.channel, "gz");
/// assert!(gz.noise_floor_deg_h >= gz.noise_rms_deg_h * 0.5);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitChannelTruth {
    /// The channel's name.
    pub channel: String,
    /// The true coefficients (with the model).
    pub coefficients: GyroCoefficients,
    /// The rms about the mean of everything no model of the record can
    /// predict (noise, rocking about I, unpredictable rectification), deg/h.
    pub noise_floor_deg_h: f64,
    /// Sensor noise alone (ARW, bias instability, rate random walk,
    /// quantisation), rms about the mean, deg/h.
    pub noise_rms_deg_h: f64,
    /// True rocking rate about I averaged per interval, rms, deg/h.
    pub motion_rms_deg_h: f64,
    /// What compensation with the true coefficients at the output rate
    /// leaves of the deterministic terms (rectification within intervals),
    /// rms about zero, deg/h.
    pub unmodelled_rms_deg_h: f64,
    /// The part of it a model given the level and the output-rate
    /// accelerations predicts, rms about zero, deg/h.
    pub predictable_rms_deg_h: f64,
    /// Noise, motion and unmodelled together, rms about zero, deg/h.
    pub after_true_compensation_rms_deg_h: f64,
    /// The floor given the vibration level only (`Σ k_term·g²` subtracted),
    /// deg/h.
    #[serde(default)]
    pub level_only_noise_floor_deg_h: f64,
    /// The unmodelled part's expectation given the level, `Σ k_term·g(t)²`,
    /// rms about zero, deg/h.
    #[serde(default)]
    pub rectification_expected_rms_deg_h: f64,
    /// Per term id, the expected unmodelled drift at full level (0 dB)
    /// `k_term`, deg/h (terms with |k| < 1e-4 deg/h omitted).
    #[serde(default)]
    pub rectification_at_full_level_deg_h: BTreeMap<String, f64>,
    /// Standard deviation of what the calibration errors leave, as seen
    /// through the regressors at the output rate, deg/h (hidden effects
    /// excluded).
    #[serde(default)]
    pub calibration_error_rms_deg_h: f64,
    /// Candidate pairs of specific-force terms nearly collinear on this record.
    #[serde(default)]
    pub collinear: Vec<UnitCollinear>,
}

/// The truth file of a simulation of any unit.
///
/// ```
/// let unit = nav_sensors::unit::Unit::builtin("dual-triad").unwrap();
/// let s = nav_sensors::sim::Scenario { duration_s: 2.0, ..Default::default() };
/// let sim = nav_sensors::sim::simulate_unit(&unit, &s).unwrap();
/// let back = nav_sensors::sim::UnitTruth::from_json(&sim.truth.to_json(), "mem").unwrap();
/// assert_eq!((back.unit, back.scenario), (unit, sim.truth.scenario.clone()));
/// assert_eq!(back.residue_noise_floor_deg_h.len(), 3); // P0, P1, P2
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnitTruth {
    /// File format version ([`UnitTruth::FORMAT_VERSION`]).
    pub format_version: u32,
    /// The unit simulated (the unit file's keys).
    pub unit: Unit,
    /// The scenario simulated.
    pub scenario: Scenario,
    /// Earth rate in the unit frame, deg/h (at t = 0 in motion).
    pub earth_rate_cluster_deg_h: [f64; 3],
    /// Specific force of the stationary unit, g (at t = 0 in motion).
    pub gravity_cluster_g: [f64; 3],
    /// Effects present in the truth and zeroed in the calibration.
    pub hidden: Vec<UnitHiddenTruth>,
    /// Entries of the scenario's paper-unit tables (`hidden`) that name a
    /// channel this unit does not have, and were therefore not simulated.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_applied: Vec<String>,
    /// Per channel, in the unit's order.
    pub channels: Vec<UnitChannelTruth>,
    /// Per residue (the unit file's named residues, such as the paper's
    /// K0–K5, else `P0`…; none for three gyros), the noise floor through
    /// the residue, deg/h.
    pub residue_noise_floor_deg_h: BTreeMap<String, f64>,
    /// Per residue, what compensation with the true coefficients at the
    /// output rate leaves (noise and unmodelled vibration effects; true
    /// motion cancels), rms about zero, deg/h (empty from a file written
    /// before it was).
    #[serde(default)]
    pub residue_after_true_compensation_rms_deg_h: BTreeMap<String, f64>,
}

impl UnitTruth {
    /// The format version written.
    ///
    /// ```
    /// assert_eq!(nav_sensors::sim::UnitTruth::FORMAT_VERSION, 1);
    /// ```
    pub const FORMAT_VERSION: u32 = 1;

    /// The truth as pretty JSON (deterministic).
    ///
    /// ```
    /// let unit = nav_sensors::unit::Unit::builtin("triad").unwrap();
    /// let sim = nav_sensors::sim::simulate_unit(&unit, &nav_sensors::sim::Scenario { duration_s: 1.0, ..Default::default() }).unwrap();
    /// assert!(sim.truth.to_json().contains("\"noise_floor_deg_h\""));
    /// ```
    pub fn to_json(&self) -> String {
        crate::files::io::pretty(self)
    }

    /// Parses truth JSON, of a unit or the paper's format (no `unit` key:
    /// read as the paper unit's truth); `path` labels errors.
    ///
    /// ```
    /// use nav_sensors::sim::{simulate_unit, Scenario, UnitTruth};
    /// use nav_sensors::unit::Unit;
    /// assert!(UnitTruth::from_json("{}", "t.json").is_err());
    /// let sim = simulate_unit(&Unit::paper(), &Scenario { duration_s: 1.0, ..Default::default() }).unwrap();
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-paper-truth");
    /// sim.write_dir(&dir).unwrap();
    /// let json = std::fs::read_to_string(dir.join("truth.json")).unwrap();
    /// assert!(!json.contains("\"unit\""));
    /// let read = UnitTruth::from_json(&json, "truth.json").unwrap();
    /// assert_eq!((&read.unit, &read.scenario), (&Unit::paper(), &sim.truth.scenario));
    /// assert_eq!(read.channels[5].channel, "Z1");
    /// ```
    pub fn from_json(text: &str, path: &str) -> Result<Self, TruthFileError> {
        /// Only whether the file names its unit.
        #[derive(Deserialize)]
        struct Probe {
            unit: Option<serde::de::IgnoredAny>,
        }
        match serde_json::from_str::<Probe>(text) {
            Ok(Probe { unit: None }) => TruthFileError::parse::<Truth>(text, path).map(Self::from),
            _ => TruthFileError::parse(text, path),
        }
    }

    /// Reads a truth JSON file.
    ///
    /// ```
    /// let unit = nav_sensors::unit::Unit::builtin("tetra").unwrap();
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-unit-truth");
    /// nav_sensors::sim::simulate_unit(&unit, &nav_sensors::sim::Scenario { duration_s: 1.0, ..Default::default() })
    ///     .unwrap().write_dir(&dir).unwrap();
    /// assert_eq!(nav_sensors::sim::UnitTruth::load(dir.join("truth.json")).unwrap().unit, unit);
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, TruthFileError> {
        crate::files::io::load_with(
            path.as_ref(),
            |path, source| TruthFileError::Io { path, source },
            Self::from_json,
        )
    }
}

/// Reading a truth file failed.
///
/// ```
/// let err = nav_sensors::sim::UnitTruth::from_json("{}", "t.json").unwrap_err();
/// assert!(matches!(err, nav_sensors::sim::TruthFileError::Json { .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum TruthFileError {
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: std::io::Error,
    },
    /// The JSON does not describe a truth file.
    #[error("{path}: {source}")]
    Json {
        /// The file.
        path: String,
        /// The cause.
        #[source]
        source: serde_json::Error,
    },
}

impl TruthFileError {
    /// Parses a truth file of either format (the paper's or a unit's);
    /// `path` labels errors.
    pub(crate) fn parse<T: serde::de::DeserializeOwned>(text: &str, path: &str) -> Result<T, Self> {
        serde_json::from_str(text).map_err(|source| TruthFileError::Json {
            path: path.to_string(),
            source,
        })
    }
}
