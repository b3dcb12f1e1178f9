//! The simulator's truth (JSON): every coefficient and effect used, the
//! scenario, the hidden effects and the per-channel noise floor.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::scenario::Scenario;
use crate::dtg::{DtgCoefficients, DtgTerm};
use crate::geometry::{Channel, Residue};

/// A hidden effect with what it contributes to the record.
///
/// ```
/// use nav_sensors::sim::{simulate, Scenario};
/// let sim = simulate(&Scenario { duration_s: 2.0, ..Scenario::triaxial_hidden() }).unwrap();
/// let h = &sim.truth.hidden[0];
/// assert_eq!((h.channel.name(), h.term.id()), ("Y1", "gg_IS"));
/// assert!(h.rms_deg_h > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HiddenTruth {
    /// The channel.
    pub channel: Channel,
    /// The term (stable id).
    pub term: DtgTerm,
    /// Its true coefficient, in `unit`.
    pub coefficient: f64,
    /// The coefficient's unit.
    pub unit: String,
    /// IEEE Std 813 name.
    pub description: String,
    /// Standard deviation at 50 Hz of the part of the effect a model of the
    /// record can see (coefficient × regressor from the 50-Hz accelerations or
    /// the `temp` column), deg/h.
    pub rms_deg_h: f64,
    /// `rms_deg_h / noise_floor_deg_h` of the channel.
    pub ratio_to_noise_floor: f64,
}

/// Two candidate regressors of a channel that are nearly collinear on this
/// record (|correlation| > 0.95 at the output rate): a diagnosis cannot tell
/// them apart.
///
/// ```
/// use nav_sensors::sim::{simulate, Scenario};
/// let sim = simulate(&Scenario { duration_s: 10.0, ..Scenario::default() }).unwrap();
/// let x = &sim.truth.channels[&nav_sensors::geometry::Channel::X];
/// assert!(x.collinear.iter().all(|p| p.correlation.abs() > 0.95));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Collinear {
    /// First term.
    pub a: DtgTerm,
    /// Second term.
    pub b: DtgTerm,
    /// Correlation of their 50-Hz regressors.
    pub correlation: f64,
}

/// Per-channel truth and error budget at the output rate.
///
/// ```
/// use nav_sensors::sim::{simulate, Scenario};
/// let sim = simulate(&Scenario { duration_s: 2.0, ..Scenario::default() }).unwrap();
/// let z = &sim.truth.channels[&nav_sensors::geometry::Channel::Z];
/// assert!(z.noise_floor_deg_h >= 0.0 && z.noise_rms_deg_h > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelTruth {
    /// The true coefficients.
    pub coefficients: DtgCoefficients,
    /// The rms (about the mean) at the output rate of everything no model of
    /// the record can predict: sensor noise (ARW, bias instability,
    /// quantisation), the true angular motion (fixture rocking) about I, and
    /// every term's high-rate effect minus its least-squares conditional
    /// expectation given the vibration level and the 50-Hz accelerations
    /// (local linear and quadratic features). See docs/nav-sensors.md §8.
    pub noise_floor_deg_h: f64,
    /// The floor of format version 1: the high-rate effects minus their
    /// expectation given the vibration level only (`Σ k_term·g²`). Above
    /// `noise_floor_deg_h` by what the neighbouring 50-Hz accelerations
    /// reveal of the within-interval motion (0 when read from a version-1 file).
    #[serde(default)]
    pub level_only_noise_floor_deg_h: f64,
    /// Sensor noise alone (ARW, bias instability, quantisation), rms about the mean, deg/h.
    pub noise_rms_deg_h: f64,
    /// True rocking rate about I averaged per interval, rms, deg/h.
    pub motion_rms_deg_h: f64,
    /// What compensation with the TRUE coefficients at the output rate leaves
    /// (vibration rectification and high-rate mismatch), rms about zero, deg/h.
    pub unmodelled_rms_deg_h: f64,
    /// Its expectation given the level, `Σ k_term · g(t)²`, rms about zero, deg/h.
    pub rectification_expected_rms_deg_h: f64,
    /// Its least-squares conditional expectation given the level and the
    /// 50-Hz accelerations (what the floor subtracts), rms about zero, deg/h
    /// (0 when read from a version-1 file).
    #[serde(default)]
    pub predictable_rms_deg_h: f64,
    /// Per term, the expected unmodelled drift at full level (0 dB) `k_term`,
    /// deg/h (terms with |k| < 1e-4 deg/h omitted).
    pub rectification_at_full_level_deg_h: BTreeMap<DtgTerm, f64>,
    /// What compensation with the TRUE coefficients at the output rate
    /// leaves in all (noise, motion and unmodelled), rms about zero, deg/h.
    pub after_true_compensation_rms_deg_h: f64,
    /// Standard deviation of what the calibration errors leave, as seen
    /// through the 50-Hz regressors, deg/h (hidden effects excluded).
    pub calibration_error_rms_deg_h: f64,
    /// Candidate pairs (g_*, gg_*) that are nearly collinear on this record.
    pub collinear: Vec<Collinear>,
}

/// The simulator's truth file.
///
/// ```
/// let sim = nav_sensors::sim::simulate(&nav_sensors::sim::Scenario {
///     duration_s: 2.0, ..nav_sensors::sim::Scenario::default()
/// }).unwrap();
/// let json = sim.truth.to_json();
/// let back = nav_sensors::truth::Truth::from_json(&json, "mem").unwrap();
/// assert_eq!(back.channels.len(), 6);
/// assert!(back.channels[&nav_sensors::geometry::Channel::X].noise_floor_deg_h > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Truth {
    /// File format version ([`Truth::FORMAT_VERSION`]).
    pub format_version: u32,
    /// The scenario simulated (every coefficient, noise and environment parameter).
    pub scenario: Scenario,
    /// Earth rate in the cluster frame, deg/h (at rest: at t = 0 when the
    /// scenario has a motion profile).
    pub earth_rate_cluster_deg_h: [f64; 3],
    /// Specific force of the stationary unit in the cluster frame, g (at
    /// rest: at t = 0 when the scenario has a motion profile).
    pub gravity_cluster_g: [f64; 3],
    /// Effects present in the truth and zeroed in the calibration.
    pub hidden: Vec<HiddenTruth>,
    /// Per-channel truth and error budget.
    pub channels: BTreeMap<Channel, ChannelTruth>,
    /// Per residue (eq. 6), the noise floor propagated through the residue
    /// (same definition as the channels'), deg/h.
    pub residue_noise_floor_deg_h: BTreeMap<Residue, f64>,
    /// Per residue, what compensation with the true coefficients at 50 Hz
    /// leaves (noise and unmodelled vibration effects; true motion cancels),
    /// rms about zero, deg/h: the paper's "before" after a perfect ground
    /// calibration.
    pub residue_after_true_compensation_rms_deg_h: BTreeMap<Residue, f64>,
}

/// Reading a truth file failed.
///
/// ```
/// let err = nav_sensors::truth::Truth::from_json("{}", "t.json").unwrap_err();
/// assert!(matches!(err, nav_sensors::truth::TruthFileError::Json { .. }));
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
    /// Parses a truth file of either kind (the paper's [`Truth`] or a unit's
    /// [`super::UnitTruth`]); `path` labels errors.
    pub(crate) fn parse<T: serde::de::DeserializeOwned>(text: &str, path: &str) -> Result<T, Self> {
        serde_json::from_str(text).map_err(|source| TruthFileError::Json {
            path: path.to_string(),
            source,
        })
    }

    /// Reads a truth file of either kind.
    pub(crate) fn load<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, Self> {
        crate::files::io::load_with(
            path,
            |path, source| TruthFileError::Io { path, source },
            |text, path| Self::parse(text, path),
        )
    }
}

impl Truth {
    /// The format version written.
    ///
    /// ```
    /// assert_eq!(nav_sensors::truth::Truth::FORMAT_VERSION, 2);
    /// ```
    ///
    /// Version 2 conditions the noise floor on the 50-Hz accelerations as
    /// well as the level (version 1's floor is kept as
    /// `level_only_noise_floor_deg_h`).
    pub const FORMAT_VERSION: u32 = 2;

    /// The truth as pretty JSON (deterministic).
    ///
    /// ```
    /// let sim = nav_sensors::sim::simulate(&nav_sensors::sim::Scenario {
    ///     duration_s: 1.0, ..Default::default() }).unwrap();
    /// assert!(sim.truth.to_json().contains("noise_floor_deg_h"));
    /// ```
    pub fn to_json(&self) -> String {
        crate::files::io::pretty(self)
    }

    /// Parses truth JSON; `path` labels errors.
    ///
    /// ```
    /// assert!(nav_sensors::truth::Truth::from_json("not json", "t.json").is_err());
    /// ```
    pub fn from_json(text: &str, path: &str) -> Result<Self, TruthFileError> {
        TruthFileError::parse(text, path)
    }

    /// Reads a truth JSON file.
    ///
    /// ```
    /// use nav_sensors::sim::{simulate, Scenario};
    /// let dir = std::env::temp_dir().join("nav-sensors-doc-truth-load");
    /// simulate(&Scenario { duration_s: 1.0, ..Default::default() }).unwrap().write_dir(&dir).unwrap();
    /// let truth = nav_sensors::truth::Truth::load(dir.join("truth.json")).unwrap();
    /// assert_eq!(truth.scenario.duration_s, 1.0);
    /// ```
    pub fn load(path: impl AsRef<Path>) -> Result<Self, TruthFileError> {
        TruthFileError::load(path.as_ref())
    }

    /// The noise floor of one channel, deg/h.
    ///
    /// ```
    /// let sim = nav_sensors::sim::simulate(&nav_sensors::sim::Scenario {
    ///     duration_s: 2.0, ..nav_sensors::sim::Scenario::default()
    /// }).unwrap();
    /// // At least the 50-Hz angle random walk, 60·0.0007/√0.02 = 0.30 deg/h.
    /// assert!(sim.truth.noise_floor_deg_h(nav_sensors::geometry::Channel::Z) > 0.2);
    /// ```
    pub fn noise_floor_deg_h(&self, channel: Channel) -> f64 {
        self.channels[&channel].noise_floor_deg_h
    }
}
