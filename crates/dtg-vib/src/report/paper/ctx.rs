//! What every section of the paper's report reads: the model, its
//! application to the record, a baseline to compare with, and what else
//! is known of the record.

use super::diagnosis::DiagnosisExtra;
use super::histogram::NoiseFloor;
use crate::allan::AllanAnalysis;
use crate::apply::Applied;
use crate::model::{ChannelScores, CompensationModel};
use crate::parity::ResidueStats;
use crate::report::provenance::Provenance;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use std::path::PathBuf;

/// A previous model of the same record, to show each channel's error before
/// and after (e.g. before and after adding an effect).
pub struct Baseline<'a> {
    /// Its name in the report (e.g. "baseline").
    pub label: &'a str,
    /// The model.
    pub model: &'a CompensationModel,
    /// It applied to the same record.
    pub applied: &'a Applied,
}

/// What a report shows beyond the model and the record, when known.
#[derive(Default)]
pub struct ReportExtras<'a> {
    /// Where the report came from (files with SHA-256, command line).
    pub provenance: Option<&'a Provenance>,
    /// The Allan deviation before and after, drawn and tabled on the page.
    pub allan: Option<&'a AllanAnalysis>,
    /// Other pages to link from the summary: `(path, text)`.
    pub links: Vec<(PathBuf, String)>,
    /// A diagnosis of the model: where it fails and what it misses, in
    /// short on the page, linking its own page.
    pub diagnosis: Option<DiagnosisExtra<'a>>,
    /// The record's noise floor, when known (a simulation's truth): the
    /// residual histogram is drawn against it.
    pub noise_floor: Option<NoiseFloor<'a>>,
}

/// What every section of the page reads.
pub(super) struct Ctx<'a> {
    pub(super) model: &'a CompensationModel,
    pub(super) applied: &'a Applied,
    pub(super) record: &'a Record,
    pub(super) baseline: Option<Baseline<'a>>,
    /// Scores on this record (not the fit-time ones: the record may be another).
    pub(super) scores: Vec<ChannelScores>,
    /// The baseline's scores on this record.
    pub(super) base_scores: Option<Vec<ChannelScores>>,
    /// Residue rms before/after on the validation rows.
    pub(super) stats: Vec<ResidueStats>,
    /// The channel the single-channel figures show.
    pub(super) show: Channel,
    /// The thrust-axis acceleration's column name.
    pub(super) thrust: String,
    /// The record's noise floor, when known.
    pub(super) noise_floor: Option<&'a NoiseFloor<'a>>,
}

impl<'a> Ctx<'a> {
    pub(super) fn new(
        model: &'a CompensationModel,
        applied: &'a Applied,
        record: &'a Record,
        baseline: Option<Baseline<'a>>,
        noise_floor: Option<&'a NoiseFloor<'a>>,
    ) -> Self {
        let scores: Vec<ChannelScores> = Channel::ALL.map(|c| applied.scores(c)).to_vec();
        let base_scores = baseline
            .as_ref()
            .map(|b| Channel::ALL.map(|c| b.applied.scores(c)).to_vec());
        let show = showcase(&scores);
        let thrust = model
            .preprocess()
            .window
            .signals()
            .first()
            .cloned()
            .unwrap_or_else(|| "az".into());
        Ctx {
            model,
            applied,
            record,
            baseline,
            scores,
            base_scores,
            stats: applied.validation_residues(),
            show,
            thrust,
            noise_floor,
        }
    }

    /// The baseline with its scores, when there is one.
    pub(super) fn baseline(&self) -> Option<(&Baseline<'a>, &[ChannelScores])> {
        self.baseline.as_ref().zip(self.base_scores.as_deref())
    }

    /// The times of `rows`.
    pub(super) fn rows_t(&self, rows: &[usize]) -> Vec<f64> {
        rows.iter().map(|&r| self.applied.residues.t[r]).collect()
    }
}

pub(super) fn pick(v: &[f64], rows: &[usize]) -> Vec<f64> {
    rows.iter().map(|&r| v[r]).collect()
}

/// The channel whose validation residual fell most against a bias-only model:
/// the one the paper's single-channel figures show.
fn showcase(scores: &[ChannelScores]) -> Channel {
    Channel::ALL
        .into_iter()
        .zip(scores)
        .max_by(|(_, a), (_, b)| {
            let g = |s: &ChannelScores| s.val_rms_bias_only / s.val_rms;
            g(a).total_cmp(&g(b))
        })
        .map_or(Channel::X, |(c, _)| c)
}
