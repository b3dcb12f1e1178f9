//! The paper's truth file format ([`crate::unit::FileFormat::Paper`]):
//! channels keyed `X` … `Z1` with untagged DTG tables, residues `K0` …
//! `K5`, no `unit` key. What the built-in `paper` unit's simulation writes
//! and what [`super::UnitTruth`] reads as the paper unit's truth; the
//! definitions of its numbers are [`super::UnitChannelTruth`]'s.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::scenario::Scenario;
use super::truth::{UnitChannelTruth, UnitCollinear, UnitHiddenTruth, UnitTruth};
use crate::dtg::{DtgCoefficients, DtgTerm};
use crate::files::calibration::GyroCoefficients;
use crate::geometry::{Channel, Residue};
use crate::unit::Unit;

/// A hidden effect with what it contributes to the record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct HiddenTruth {
    /// The channel.
    pub(crate) channel: Channel,
    /// The term (stable id).
    pub(crate) term: DtgTerm,
    /// Its true coefficient, in `unit`.
    pub(crate) coefficient: f64,
    /// The coefficient's unit.
    pub(crate) unit: String,
    /// IEEE Std 813 name.
    pub(crate) description: String,
    /// Standard deviation at 50 Hz of the part of the effect a model of the
    /// record can see (coefficient × regressor from the 50-Hz accelerations or
    /// the `temp` column), deg/h.
    pub(crate) rms_deg_h: f64,
    /// `rms_deg_h / noise_floor_deg_h` of the channel.
    pub(crate) ratio_to_noise_floor: f64,
}

/// Two candidate regressors of a channel that are nearly collinear on this
/// record (|correlation| > 0.95 at the output rate): a diagnosis cannot tell
/// them apart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Collinear {
    /// First term.
    pub(crate) a: DtgTerm,
    /// Second term.
    pub(crate) b: DtgTerm,
    /// Correlation of their 50-Hz regressors.
    pub(crate) correlation: f64,
}

/// Per-channel truth and error budget at the output rate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct ChannelTruth {
    /// The true coefficients.
    pub(crate) coefficients: DtgCoefficients,
    /// The rms (about the mean) at the output rate of everything no model of
    /// the record can predict: sensor noise (ARW, bias instability,
    /// quantisation), the true angular motion (fixture rocking) about I, and
    /// every term's high-rate effect minus its least-squares conditional
    /// expectation given the vibration level and the 50-Hz accelerations
    /// (local linear and quadratic features). See docs/nav-sensors.md §8.
    pub(crate) noise_floor_deg_h: f64,
    /// The floor of format version 1: the high-rate effects minus their
    /// expectation given the vibration level only (`Σ k_term·g²`). Above
    /// `noise_floor_deg_h` by what the neighbouring 50-Hz accelerations
    /// reveal of the within-interval motion (0 when read from a version-1 file).
    #[serde(default)]
    pub(crate) level_only_noise_floor_deg_h: f64,
    /// Sensor noise alone (ARW, bias instability, quantisation), rms about the mean, deg/h.
    pub(crate) noise_rms_deg_h: f64,
    /// True rocking rate about I averaged per interval, rms, deg/h.
    pub(crate) motion_rms_deg_h: f64,
    /// What compensation with the TRUE coefficients at the output rate leaves
    /// (vibration rectification and high-rate mismatch), rms about zero, deg/h.
    pub(crate) unmodelled_rms_deg_h: f64,
    /// Its expectation given the level, `Σ k_term · g(t)²`, rms about zero, deg/h.
    pub(crate) rectification_expected_rms_deg_h: f64,
    /// Its least-squares conditional expectation given the level and the
    /// 50-Hz accelerations (what the floor subtracts), rms about zero, deg/h
    /// (0 when read from a version-1 file).
    #[serde(default)]
    pub(crate) predictable_rms_deg_h: f64,
    /// Per term, the expected unmodelled drift at full level (0 dB) `k_term`,
    /// deg/h (terms with |k| < 1e-4 deg/h omitted).
    pub(crate) rectification_at_full_level_deg_h: BTreeMap<DtgTerm, f64>,
    /// What compensation with the TRUE coefficients at the output rate
    /// leaves in all (noise, motion and unmodelled), rms about zero, deg/h.
    pub(crate) after_true_compensation_rms_deg_h: f64,
    /// Standard deviation of what the calibration errors leave, as seen
    /// through the 50-Hz regressors, deg/h (hidden effects excluded).
    pub(crate) calibration_error_rms_deg_h: f64,
    /// Candidate pairs (g_*, gg_*) that are nearly collinear on this record.
    pub(crate) collinear: Vec<Collinear>,
}

/// The simulator's truth file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Truth {
    /// File format version ([`Truth::FORMAT_VERSION`]).
    pub(crate) format_version: u32,
    /// The scenario simulated (every coefficient, noise and environment parameter).
    pub(crate) scenario: Scenario,
    /// Earth rate in the cluster frame, deg/h (at rest: at t = 0 when the
    /// scenario has a motion profile).
    pub(crate) earth_rate_cluster_deg_h: [f64; 3],
    /// Specific force of the stationary unit in the cluster frame, g (at
    /// rest: at t = 0 when the scenario has a motion profile).
    pub(crate) gravity_cluster_g: [f64; 3],
    /// Effects present in the truth and zeroed in the calibration.
    pub(crate) hidden: Vec<HiddenTruth>,
    /// Per-channel truth and error budget.
    pub(crate) channels: BTreeMap<Channel, ChannelTruth>,
    /// Per residue (eq. 6), the noise floor propagated through the residue
    /// (same definition as the channels'), deg/h.
    pub(crate) residue_noise_floor_deg_h: BTreeMap<Residue, f64>,
    /// Per residue, what compensation with the true coefficients at 50 Hz
    /// leaves (noise and unmodelled vibration effects; true motion cancels),
    /// rms about zero, deg/h: the paper's "before" after a perfect ground
    /// calibration.
    pub(crate) residue_after_true_compensation_rms_deg_h: BTreeMap<Residue, f64>,
}

impl Truth {
    /// The format version written: version 2 conditions the noise floor on
    /// the 50-Hz accelerations as well as the level (version 1's floor is
    /// kept as `level_only_noise_floor_deg_h`).
    pub(crate) const FORMAT_VERSION: u32 = 2;

    /// The truth as pretty JSON (deterministic).
    pub(crate) fn to_json(&self) -> String {
        crate::files::io::pretty(self)
    }
}

/// The paper's truth as the paper unit's: channels in the unit's order
/// (X … Z1) under their names, DTG coefficients tagged `dtg`, term and
/// residue names as strings, every number as it is.
impl From<Truth> for UnitTruth {
    fn from(t: Truth) -> Self {
        let named = |m: BTreeMap<Residue, f64>| -> BTreeMap<String, f64> {
            m.into_iter()
                .map(|(r, v)| (r.name().to_string(), v))
                .collect()
        };
        let channels = Channel::ALL
            .iter()
            .filter_map(|c| t.channels.get(c).map(|ct| (c, ct)))
            .map(|(c, ct)| UnitChannelTruth {
                channel: c.name().to_string(),
                coefficients: GyroCoefficients::Dtg(ct.coefficients),
                noise_floor_deg_h: ct.noise_floor_deg_h,
                noise_rms_deg_h: ct.noise_rms_deg_h,
                motion_rms_deg_h: ct.motion_rms_deg_h,
                unmodelled_rms_deg_h: ct.unmodelled_rms_deg_h,
                predictable_rms_deg_h: ct.predictable_rms_deg_h,
                after_true_compensation_rms_deg_h: ct.after_true_compensation_rms_deg_h,
                level_only_noise_floor_deg_h: ct.level_only_noise_floor_deg_h,
                rectification_expected_rms_deg_h: ct.rectification_expected_rms_deg_h,
                rectification_at_full_level_deg_h: ct
                    .rectification_at_full_level_deg_h
                    .iter()
                    .map(|(term, v)| (term.id().to_string(), *v))
                    .collect(),
                calibration_error_rms_deg_h: ct.calibration_error_rms_deg_h,
                collinear: ct
                    .collinear
                    .iter()
                    .map(|p| UnitCollinear {
                        a: p.a.id().to_string(),
                        b: p.b.id().to_string(),
                        correlation: p.correlation,
                    })
                    .collect(),
            })
            .collect();
        UnitTruth {
            format_version: Self::FORMAT_VERSION,
            unit: Unit::paper(),
            scenario: t.scenario,
            earth_rate_cluster_deg_h: t.earth_rate_cluster_deg_h,
            gravity_cluster_g: t.gravity_cluster_g,
            hidden: t
                .hidden
                .into_iter()
                .map(|h| UnitHiddenTruth {
                    channel: h.channel.name().to_string(),
                    term: h.term.id().to_string(),
                    coefficient: h.coefficient,
                    unit: h.unit,
                    description: h.description,
                    rms_deg_h: h.rms_deg_h,
                    ratio_to_noise_floor: h.ratio_to_noise_floor,
                })
                .collect(),
            not_applied: Vec::new(),
            channels,
            residue_noise_floor_deg_h: named(t.residue_noise_floor_deg_h),
            residue_after_true_compensation_rms_deg_h: named(
                t.residue_after_true_compensation_rms_deg_h,
            ),
        }
    }
}

/// The paper unit's truth in the paper's format (the file the built-in
/// `paper` writes, [`crate::unit::FileFormat::Paper`]): the inverse of
/// [`UnitTruth::from`] a [`Truth`], every number as it is. `None` when a
/// name is not the paper's (a channel, term or residue of another unit).
impl UnitTruth {
    pub(crate) fn to_paper(&self) -> Option<Truth> {
        let by_name = |m: &BTreeMap<String, f64>| -> Option<BTreeMap<Residue, f64>> {
            m.iter().map(|(r, v)| Some((r.parse().ok()?, *v))).collect()
        };
        let mut channels = BTreeMap::new();
        for ct in &self.channels {
            let GyroCoefficients::Dtg(coefficients) = ct.coefficients else {
                return None;
            };
            let channel: Channel = ct.channel.parse().ok()?;
            let truth = ChannelTruth {
                coefficients,
                noise_floor_deg_h: ct.noise_floor_deg_h,
                level_only_noise_floor_deg_h: ct.level_only_noise_floor_deg_h,
                noise_rms_deg_h: ct.noise_rms_deg_h,
                motion_rms_deg_h: ct.motion_rms_deg_h,
                unmodelled_rms_deg_h: ct.unmodelled_rms_deg_h,
                rectification_expected_rms_deg_h: ct.rectification_expected_rms_deg_h,
                predictable_rms_deg_h: ct.predictable_rms_deg_h,
                rectification_at_full_level_deg_h: ct
                    .rectification_at_full_level_deg_h
                    .iter()
                    .map(|(term, v)| Some((term.parse().ok()?, *v)))
                    .collect::<Option<_>>()?,
                after_true_compensation_rms_deg_h: ct.after_true_compensation_rms_deg_h,
                calibration_error_rms_deg_h: ct.calibration_error_rms_deg_h,
                collinear: ct
                    .collinear
                    .iter()
                    .map(|p| {
                        Some(Collinear {
                            a: p.a.parse().ok()?,
                            b: p.b.parse().ok()?,
                            correlation: p.correlation,
                        })
                    })
                    .collect::<Option<_>>()?,
            };
            channels.insert(channel, truth);
        }
        let hidden = self
            .hidden
            .iter()
            .map(|h| {
                Some(HiddenTruth {
                    channel: h.channel.parse().ok()?,
                    term: h.term.parse().ok()?,
                    coefficient: h.coefficient,
                    unit: h.unit.clone(),
                    description: h.description.clone(),
                    rms_deg_h: h.rms_deg_h,
                    ratio_to_noise_floor: h.ratio_to_noise_floor,
                })
            })
            .collect::<Option<_>>()?;
        Some(Truth {
            format_version: Truth::FORMAT_VERSION,
            scenario: self.scenario.clone(),
            earth_rate_cluster_deg_h: self.earth_rate_cluster_deg_h,
            gravity_cluster_g: self.gravity_cluster_g,
            hidden,
            channels,
            residue_noise_floor_deg_h: by_name(&self.residue_noise_floor_deg_h)?,
            residue_after_true_compensation_rms_deg_h: by_name(
                &self.residue_after_true_compensation_rms_deg_h,
            )?,
        })
    }
}
