//! The report of a model of any unit on its record(s), one page for every
//! unit: the summary with what is left and what got worse, measured against
//! predicted, where it fails and the diagnosis, the Allan deviation of
//! channels and residues, the parity residues with their spectra and fault
//! detection (or, for three gyros, why there are none), the residual
//! against the noise floor, the channel models and the effects found,
//! before and after, and the paper's figures. One file per section; this
//! one draws every figure in parallel and assembles the page.

mod before_after;
mod channels;
mod ctx;
mod diagnosis;
mod fdi;
mod fit;
mod headline;
mod histogram;
mod inputs;
mod paper_figures;
mod residues;
mod summary;

use crate::error::DtgVibError;
use crate::report::common::{Drawn, save_all};
use crate::report::diagnosis::ChannelWording;
use ctx::Ctx;
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use plot::{Figure, HtmlReport, Section};
use std::fmt::Display;
use std::path::Path;
use sysid::{ChannelScores, Sensor};

pub use fdi::parity_on_samples;
pub use inputs::{
    DiagnosisExtra, Evaluated, FdiShown, NoiseFloor, Parity, ReportExtras, ResidueRms,
};

/// The numbers the page shows that a command prints too.
#[derive(Debug, Clone, PartialEq)]
pub struct PageNumbers {
    /// Each residue's rms before and after on the validation rows of the
    /// pre-processed outputs (none for three gyros).
    pub residues: Vec<ResidueRms>,
    /// Each channel's name and scores on these rows, in the unit's order.
    pub channels: Vec<(String, ChannelScores)>,
}

/// Draws the figures of the page of `on` (a model of `unit` applied to
/// the `raw` record(s), named `source` on the page), against a `baseline`
/// (its label and it on the same records), into `dir`, and returns the page
/// (not yet written: [`HtmlReport::write`] it into `dir`, or into a parent
/// of `dir`, whence its figure links still resolve) with its numbers.
pub fn build_page<S: Sensor, C: Display>(
    unit: &Unit,
    on: &Evaluated<'_, S>,
    baseline: Option<(&str, &Evaluated<'_, S>)>,
    raw: &[&Record],
    source: &str,
    extras: &ReportExtras<'_, C>,
    dir: &Path,
) -> Result<(HtmlReport, PageNumbers), DtgVibError> {
    let ctx = Ctx::new(unit, on, baseline, raw, extras.noise_floor.as_ref());
    let mut figs: Vec<(Figure, &'static str)> = paper_figures::figures(&ctx);
    figs.extend(residues::figures(&ctx));
    figs.push(before_after::figure(&ctx));
    figs.push(fit::figure(&ctx));
    figs.push(histogram::figure(&ctx));
    if let Some(a) = extras.allan {
        figs.extend(super::allan::figures(a));
    }
    let drawn: Drawn = save_all(figs, dir)?;
    let page = assemble(&ctx, extras, source, &drawn);
    let numbers = PageNumbers {
        residues: ctx.stats.clone(),
        channels: ctx
            .channels
            .iter()
            .map(|c| (c.name.clone(), c.scores))
            .collect(),
    };
    Ok((page, numbers))
}

/// The page, top to bottom as a test engineer reads it (issue 14 §2): the
/// summary, measured against predicted, where it fails and the diagnosis,
/// Allan deviation, the residues with their spectra and fault detection,
/// the residual against the noise floor; then the channel models, the
/// effects found, the before/after bars and the paper's figures.
fn assemble<C: Display>(
    ctx: &Ctx<'_>,
    extras: &ReportExtras<'_, C>,
    source: &str,
    drawn: &Drawn,
) -> HtmlReport {
    let mut page = HtmlReport::new(format!("Vibration-error compensation: {}", ctx.unit.name()));
    for p in headline::paragraphs(ctx, extras, source) {
        page = page.summary(p);
    }
    page = page
        .section(summary::section(ctx, extras))
        .section(fit::section(drawn));
    if let Some(d) = &extras.diagnosis {
        for sec in diagnosis::sections(d, &ChannelWording::of_unit(ctx.unit)) {
            page = page.section(sec);
        }
    }
    if let Some(a) = extras.allan {
        page = page.section(
            Section::new("Allan deviation before and after")
                .text(super::allan::summary(a, source))
                .text(if a.residues.is_empty() {
                    "The table and figure of the gyro channels follow (a unit of three gyros has no parity residue)."
                } else {
                    "The tables and figures follow: gyro channels, then parity residues."
                }),
        );
        for sec in super::allan::sections(a, drawn) {
            page = page.section(sec);
        }
    }
    page.section(residues::section(ctx, extras, drawn))
        .section(histogram::section(ctx, drawn))
        .section(channels::section(ctx))
        .section(channels::effects_section(ctx))
        .section(before_after::section(ctx, drawn))
        .section(paper_figures::section(ctx, drawn))
}
