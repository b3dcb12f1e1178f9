//! The diagnosis report: measured against predicted, the residual against
//! its top candidates, residual spectra against a white floor, the
//! correlation tests with their bands, and the ERR ranking. One file per
//! section of the page; this one draws every figure in parallel and
//! assembles the page.

pub(in crate::report) mod channel;
mod figures;
pub(in crate::report) mod overview;
pub(in crate::report) mod reading;

use crate::diagnose::Diagnosis;
use crate::error::DtgVibError;
use crate::report::common::{Drawn, save_all};
use plot::HtmlReport;
use std::fmt::Display;
use std::path::{Path, PathBuf};

pub use reading::ChannelWording;

/// Writes the diagnosis figures and `index.html` into `dir`; `min_err` is
/// the suggestion threshold drawn on the ERR charts.
pub fn write_diagnosis_report(
    diag: &Diagnosis,
    min_err: f64,
    dir: &Path,
) -> Result<PathBuf, DtgVibError> {
    write_diagnosis_report_of(
        diag,
        min_err,
        &ChannelWording::of_unit(&nav_sensors::unit::Unit::paper()),
        dir,
    )
}

/// [`write_diagnosis_report`] for the diagnosis of any unit's channels,
/// its channels and candidates described by `wording`.
pub fn write_diagnosis_report_of<C: Display>(
    diag: &sysid::diagnose::Diagnosis<C, nav_sensors::geometry::Axis>,
    min_err: f64,
    wording: &ChannelWording,
    dir: &Path,
) -> Result<PathBuf, DtgVibError> {
    let mut figs = figures::figures(diag, min_err);
    figs.push(overview::figure(diag));
    let drawn: Drawn = save_all(figs, dir)?;

    let mut page = HtmlReport::new("Diagnosis: what the model is missing")
        .summary(overview::summary(diag))
        .section(overview::section(diag, &drawn))
        .section(reading::section(diag, min_err, wording));
    for c in &diag.channels {
        page = page.section(channel::section(c));
    }
    page = page.section(figures::section(&drawn, min_err));
    Ok(page.write(dir)?)
}
