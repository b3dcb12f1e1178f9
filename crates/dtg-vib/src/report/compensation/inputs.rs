//! What the page is built from: a model of any unit applied to its
//! record(s) (the loop's model, preparation and prediction), and what else
//! is known — a diagnosis, the Allan analysis, fault detection, the noise
//! floor, where it came from and the pages it links.

use crate::allan::AllanAnalysis;
use crate::report::provenance::Provenance;
use crate::unit_sensor::fdi::{FdiSetting, FdiSummary};
use nav_sensors::geometry::Channel;
use std::path::PathBuf;
use sysid::Sensor;
use sysid::diagnose::Diagnosis;

/// A model applied to its record(s): what the page reads of it.
pub struct Evaluated<'a, S: Sensor> {
    /// The model.
    pub model: &'a sysid::Model<S>,
    /// The record(s) prepared as its training data were.
    pub prepared: &'a sysid::Prepared<S>,
    /// Per channel and row, the predicted error of the pre-processed
    /// (filtered) output, deg/h: the network part faded outside the
    /// training range (a causal model's: the onboard evaluator's).
    pub predicted: &'a [Vec<f64>],
    /// Training rows of the model's split (empty when the split does not
    /// fit the record: then every row is a validation row).
    pub train: &'a [usize],
    /// Validation rows.
    pub val: &'a [usize],
}

/// What no model of the record can predict, per channel, when it is known.
#[derive(Debug, Clone)]
pub struct NoiseFloor<'a> {
    /// Per channel (the unit's gyro order), the floor at every sample of
    /// the record, deg/h (a simulation's `X_floor` … components).
    pub per_sample: Vec<&'a [f64]>,
    /// Where it comes from, in words (shown on the page).
    pub source: String,
}

/// A diagnosis to summarise on the page (channels of type `C`).
#[derive(Debug, Clone)]
pub struct DiagnosisExtra<'a, C = Channel> {
    /// The diagnosis.
    pub diagnosis: &'a Diagnosis<C, nav_sensors::geometry::Axis>,
    /// Of which model, in words ("this model", "the baseline model").
    pub of: String,
    /// The ERR a suggestion needs (`RankOptions::min_err`).
    pub min_err: f64,
    /// Its full page (`write_diagnosis_report`'s index.html).
    pub page: PathBuf,
}

/// One parity residue's rms before and after, deg/h.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidueRms {
    /// `K0`, `P0`, … as the unit names it.
    pub name: String,
    /// Rms before compensation.
    pub before: f64,
    /// Rms after, with a model.
    pub after: Option<f64>,
}

/// Fault detection on the record: the test as stated and what it found,
/// before and (with a model) after compensation.
#[derive(Debug, Clone, PartialEq)]
pub struct FdiShown {
    /// The test.
    pub setting: FdiSetting,
    /// `(what was tested, summary)`, e.g. `("as logged", …)`.
    pub found: Vec<(String, FdiSummary)>,
}

/// The parity residues on every sample of the record as logged and as
/// compensated (what `residues` writes), and fault detection on them.
#[derive(Debug, Clone, PartialEq)]
pub struct Parity {
    /// Each residue's rms as logged and compensated (none for three gyros).
    pub residues: Vec<ResidueRms>,
    /// Fault detection (four gyros or more).
    pub fdi: Option<FdiShown>,
}

/// What a page shows beyond the model and the record(s), when known
/// (diagnosed channels of type `C`).
pub struct ReportExtras<'a, C = Channel> {
    /// Where the report came from (files with SHA-256, command line).
    pub provenance: Option<&'a Provenance>,
    /// The Allan deviation before and after, drawn and tabled on the page.
    pub allan: Option<&'a AllanAnalysis>,
    /// Other pages to link from the summary: `(path, text)`.
    pub links: Vec<(PathBuf, String)>,
    /// A diagnosis of the model: where it fails and what it misses, in
    /// short on the page, linking its own page.
    pub diagnosis: Option<DiagnosisExtra<'a, C>>,
    /// The record's noise floor, when known (a simulation's truth): the
    /// residual histogram is drawn against it.
    pub noise_floor: Option<NoiseFloor<'a>>,
    /// The parity residues on every sample as logged and compensated, with
    /// fault detection.
    pub parity: Option<&'a Parity>,
    /// Paragraphs the caller puts first (the demo's story).
    pub lead: Vec<String>,
}

impl<C> Default for ReportExtras<'_, C> {
    fn default() -> Self {
        Self {
            provenance: None,
            allan: None,
            links: Vec::new(),
            diagnosis: None,
            noise_floor: None,
            parity: None,
            lead: Vec::new(),
        }
    }
}
