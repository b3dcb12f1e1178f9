//! The page of a model of the paper's own plug-in (a [`CompensationModel`]
//! applied as [`Applied`]): the one page ([`super::compensation`]) of the
//! paper's unit, its inputs read off the paper's types. Transitional: it
//! goes once `demo`, `report` and `check --report` build the paper's page
//! from its unit model through [`crate::unit_page::write_page`].

use super::compensation::{Evaluated, ReportExtras, build_page, parity_on_samples};
use crate::allan::AllanAnalysis;
use crate::apply::Applied;
use crate::error::DtgVibError;
use crate::model::{ChannelScores, CompensationModel};
use crate::parity::ResidueStats;
use crate::unit_sensor::fdi::DEFAULT_FALSE_ALARM;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use plot::HtmlReport;
use serde::Serialize;
use std::path::{Path, PathBuf};

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

/// What a report wrote and the numbers it shows.
#[derive(Debug, Clone, Serialize)]
pub struct ReportSummary {
    /// The report page.
    pub index: PathBuf,
    /// Residue rms before/after on the validation rows.
    pub residues: Vec<ResidueStats>,
    /// Each channel's scores on this record, in X, X1, Y, Y1, Z, Z1 order.
    pub channels: Vec<ChannelScores>,
}

/// Writes the figures and `index.html` into `dir`.
///
/// `source` names the record on the page (its file name, or "simulated").
pub fn write_report(
    model: &CompensationModel,
    applied: &Applied,
    record: &Record,
    source: &str,
    baseline: Option<Baseline<'_>>,
    dir: &Path,
) -> Result<ReportSummary, DtgVibError> {
    let extras = ReportExtras::default();
    let (summary, page) = build_report(model, applied, record, source, baseline, &extras, dir)?;
    page.write(dir)?;
    Ok(summary)
}

fn evaluated<'a>(
    model: &'a CompensationModel,
    applied: &'a Applied,
) -> Evaluated<'a, crate::paper_unit::PaperUnit> {
    Evaluated {
        model: model.inner(),
        prepared: applied.prepared.inner(),
        predicted: &applied.predicted[..],
        train: &applied.train,
        val: &applied.val,
    }
}

/// Draws the figures into `dir` and returns the page (not yet written:
/// [`HtmlReport::write`] it into `dir`, or into a parent of `dir`, whence its
/// figure links still resolve) with the summary; `index` is `dir/index.html`.
/// The residues and fault detection on every sample (as logged and
/// compensated) and, unless
/// `extras` has it, the Allan analysis of the record are made here.
pub fn build_report(
    model: &CompensationModel,
    applied: &Applied,
    record: &Record,
    source: &str,
    baseline: Option<Baseline<'_>>,
    extras: &ReportExtras<'_>,
    dir: &Path,
) -> Result<(ReportSummary, HtmlReport), DtgVibError> {
    let unit = Unit::paper();
    let first = applied.prepared.first_sample();
    let compensated = applied.compensated_record();
    let before: Vec<Vec<f64>> = Channel::ALL
        .iter()
        .map(|c| record.gyro(*c)[first..].to_vec())
        .collect();
    let after: Vec<Vec<f64>> = Channel::ALL
        .iter()
        .map(|c| compensated.gyro(*c).to_vec())
        .collect();
    let parity = parity_on_samples(&unit, &before, &after, None, DEFAULT_FALSE_ALARM);
    // Too short a record for an Allan curve has none worth drawing.
    let own_allan = match extras.allan {
        Some(_) => None,
        None => AllanAnalysis::new(record, Some(model), 0.683).ok(),
    };
    let all = ReportExtras {
        provenance: extras.provenance,
        allan: extras.allan.or(own_allan.as_ref()),
        links: extras.links.clone(),
        diagnosis: extras.diagnosis.clone(),
        noise_floor: extras.noise_floor.clone(),
        parity: extras.parity.or(Some(&parity)),
        lead: extras.lead.clone(),
    };
    let base = baseline.as_ref().map(|b| evaluated(b.model, b.applied));
    let (page, _) = build_page(
        &unit,
        &evaluated(model, applied),
        base.as_ref()
            .zip(baseline.as_ref())
            .map(|(e, b)| (b.label, e)),
        &[record],
        source,
        &all,
        dir,
    )?;
    Ok((
        ReportSummary {
            index: dir.join("index.html"),
            residues: applied.validation_residues(),
            channels: Channel::ALL.map(|c| applied.scores(c)).to_vec(),
        },
        page,
    ))
}
