//! The report of a fitted model: the paper's figures (Figs. 3, 5, 6, 7),
//! residue spectra, before/after bars and the page that shows them with the
//! numbers. One file per section of the page; this one gathers the context
//! they share, draws every figure in parallel and assembles the page.

mod before_after;
mod channels;
mod diagnosis;
mod fit;
mod headline;
mod histogram;
mod paper_figures;
mod residues;
mod summary;

use super::{Drawn, Provenance, fmt, save_all};
use crate::allan::AllanAnalysis;
use crate::apply::Applied;
use crate::error::DtgVibError;
use crate::model::{ChannelScores, CompensationModel};
use crate::parity::ResidueStats;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use plot::{Figure, HtmlReport, Section};
use serde::Serialize;
use std::path::{Path, PathBuf};

pub use diagnosis::DiagnosisExtra;
pub use histogram::NoiseFloor;

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
struct Ctx<'a> {
    model: &'a CompensationModel,
    applied: &'a Applied,
    record: &'a Record,
    baseline: Option<Baseline<'a>>,
    /// Scores on this record (not the fit-time ones: the record may be another).
    scores: Vec<ChannelScores>,
    /// The baseline's scores on this record.
    base_scores: Option<Vec<ChannelScores>>,
    /// Residue rms before/after on the validation rows.
    stats: Vec<ResidueStats>,
    /// The channel the single-channel figures show.
    show: Channel,
    /// The thrust-axis acceleration's column name.
    thrust: String,
    /// The record's noise floor, when known.
    noise_floor: Option<&'a NoiseFloor<'a>>,
}

impl<'a> Ctx<'a> {
    fn new(
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
    fn baseline(&self) -> Option<(&Baseline<'a>, &[ChannelScores])> {
        self.baseline.as_ref().zip(self.base_scores.as_deref())
    }

    /// The times of `rows`.
    fn rows_t(&self, rows: &[usize]) -> Vec<f64> {
        rows.iter().map(|&r| self.applied.residues.t[r]).collect()
    }
}

fn pick(v: &[f64], rows: &[usize]) -> Vec<f64> {
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

/// Draws the figures into `dir` and returns the page (not yet written:
/// [`HtmlReport::write`] it into `dir`, or into a parent of `dir`, whence its
/// figure links still resolve) with the summary; `index` is `dir/index.html`.
pub fn build_report(
    model: &CompensationModel,
    applied: &Applied,
    record: &Record,
    source: &str,
    baseline: Option<Baseline<'_>>,
    extras: &ReportExtras<'_>,
    dir: &Path,
) -> Result<(ReportSummary, HtmlReport), DtgVibError> {
    let ctx = Ctx::new(
        model,
        applied,
        record,
        baseline,
        extras.noise_floor.as_ref(),
    );
    let mut figs: Vec<(Figure, &'static str)> = paper_figures::figures(&ctx)?;
    figs.extend(residues::figures(&ctx));
    figs.push(before_after::figure(&ctx));
    figs.push(fit::figure(&ctx));
    figs.push(histogram::figure(&ctx));
    if let Some(a) = extras.allan {
        figs.extend(super::allan::figures(a));
    }
    let drawn: Drawn = save_all(figs, dir)?;

    // Top to bottom as a test engineer reads it (issue 14 §2): the summary,
    // measured against predicted, where it fails and the diagnosis, Allan
    // deviation, the spectra, the residual against the noise floor; then the
    // channel models, the before/after bars and the paper's figures.
    let mut page = HtmlReport::new("DTG vibration-error compensation");
    for p in headline::paragraphs(&ctx, extras, source) {
        page = page.summary(p);
    }
    page = page
        .section(summary::section(&ctx, extras))
        .section(fit::section(&drawn));
    if let Some(d) = &extras.diagnosis {
        for sec in diagnosis::sections(d) {
            page = page.section(sec);
        }
    }
    if let Some(a) = extras.allan {
        page = page.section(
            Section::new("Allan deviation before and after")
                .text(super::allan::summary(a, source))
                .text("The tables and figures follow: gyro channels, then parity residues."),
        );
        for sec in super::allan::sections(a, &drawn) {
            page = page.section(sec);
        }
    }
    page = page
        .section(residues::section(&ctx, &drawn))
        .section(histogram::section(&ctx, &drawn))
        .section(channels::section(&ctx))
        .section(before_after::section(&ctx, &drawn))
        .section(paper_figures::section(&drawn));
    Ok((
        ReportSummary {
            index: dir.join("index.html"),
            residues: ctx.stats,
            channels: ctx.scores,
        },
        page,
    ))
}
