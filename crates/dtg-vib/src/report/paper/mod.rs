//! The report of a fitted model: the paper's figures (Figs. 3, 5, 6, 7),
//! residue spectra, before/after bars and the page that shows them with the
//! numbers. One file per section of the page; this one gathers the context
//! they share, draws every figure in parallel and assembles the page.

mod before_after;
mod channels;
mod ctx;
mod diagnosis;
mod fit;
mod headline;
mod histogram;
mod paper_figures;
mod residues;
mod summary;

use super::common::{Drawn, save_all};
use crate::apply::Applied;
use crate::error::DtgVibError;
use crate::model::{ChannelScores, CompensationModel};
use crate::parity::ResidueStats;
use nav_sensors::record::Record;
use plot::{Figure, HtmlReport, Section};
use serde::Serialize;
use std::path::{Path, PathBuf};

use ctx::Ctx;
pub use ctx::{Baseline, ReportExtras};
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
