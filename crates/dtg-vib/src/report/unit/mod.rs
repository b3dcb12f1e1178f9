//! The report of a unit's model on records of any unit (not the paper's,
//! whose page is [`super::paper`]): per channel measured against predicted
//! with rms before and after, the effects found with their 95% intervals
//! and units, the parity residues P0, … with fault detection (or, for a
//! unit of three gyros, why there is none), and the Allan figure. One file
//! per section; this one draws the figures in parallel and assembles the
//! page.

mod channels;
mod parity;

use super::common::{Drawn, save_all};
use super::provenance::Provenance;
use crate::allan::AllanAnalysis;
use crate::error::DtgVibError;
use crate::unit_sensor::UnitApplied;
use crate::unit_sensor::fdi::{FdiSetting, FdiSummary};
use nav_sensors::unit::Unit;
use plot::{HtmlReport, Section};
use std::path::{Path, PathBuf};

/// One parity residue's rms before and after, deg/h.
#[derive(Debug, Clone, PartialEq)]
pub struct ResidueRms {
    /// `P0`, `P1`, …
    pub name: String,
    /// Rms before compensation (the record as logged).
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
    /// `(what was tested, summary)`, e.g. `("calibrated", …)`.
    pub found: Vec<(String, FdiSummary)>,
}

/// What a unit's page shows.
pub struct UnitReport<'a> {
    /// The unit.
    pub unit: &'a Unit,
    /// The record(s), as the page names them.
    pub source: &'a str,
    /// The model on the record(s).
    pub applied: &'a UnitApplied,
    /// A baseline model on the same record(s), with its label.
    pub baseline: Option<(&'a str, &'a UnitApplied)>,
    /// The parity residues (empty for three gyros).
    pub residues: Vec<ResidueRms>,
    /// Fault detection, for four gyros or more.
    pub fdi: Option<FdiShown>,
    /// The Allan analysis, if made.
    pub allan: Option<&'a AllanAnalysis>,
    /// Where the report came from.
    pub provenance: Option<&'a Provenance>,
    /// Paragraphs the caller puts first (the demo's story).
    pub lead: Vec<String>,
    /// Other pages to link, `(path, text)` (relative paths resolve from
    /// this page's directory when written).
    pub links: Vec<(PathBuf, String)>,
}

/// Writes the figures and `index.html` of a unit's report into `dir`.
pub fn write_unit_report(r: &UnitReport<'_>, dir: &Path) -> Result<PathBuf, DtgVibError> {
    Ok(build_unit_report(r, dir)?.write(dir)?)
}

/// Draws the figures of a unit's report into `dir` and returns the page,
/// not yet written: write it into `dir`, or into another directory, whence
/// its figure links still resolve.
pub fn build_unit_report(r: &UnitReport<'_>, dir: &Path) -> Result<HtmlReport, DtgVibError> {
    let mut figs = channels::figures(r);
    if let Some(a) = r.allan {
        figs.extend(super::allan::figures(a));
    }
    let drawn: Drawn = save_all(figs, dir)?;
    let mut page = HtmlReport::new(format!("Sensor-unit compensation: {}", r.unit.name()));
    for p in &r.lead {
        page = page.summary(p.clone());
    }
    page = page.summary(channels::summary(r));
    page = page.summary(parity::summary(r));
    if !r.links.is_empty() {
        let mut s = Section::new("Other pages");
        for (path, text) in &r.links {
            s = s.link(path.clone(), text.clone());
        }
        page = page.section(s);
    }
    page = page
        .section(channels::section(r, &drawn))
        .section(channels::effects_section(r))
        .section(parity::section(r));
    if let Some(a) = r.allan {
        page = page.section(
            Section::new("Allan deviation before and after")
                .text(super::allan::summary(a, r.source))
                .text(match a.residues.is_empty() {
                    true => "The table and figure of the gyro channels follow (a unit of three gyros has no parity residue).",
                    false => "The tables and figures follow: gyro channels, then parity residues.",
                }),
        );
        for sec in super::allan::sections(a, &drawn) {
            page = page.section(sec);
        }
    }
    if let Some(p) = r.provenance {
        page = page.section(Section::new("Provenance").table(p.table()));
    }
    page = page.section(Section::new("Colours").text(super::common::colours::LEGEND));
    Ok(page)
}
