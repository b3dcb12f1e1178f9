//! The page of a unit's model on records of its unit, computed and
//! written: the model applied ([`crate::unit_sensor::UnitApplied`]), the
//! parity residues before and after with fault detection, the Allan
//! analysis of the longest segment, and the page
//! ([`crate::report::write_unit_report`]). `report`, `check --report` and
//! `demo --unit` write it.

use crate::allan::AllanAnalysis;
use crate::error::DtgVibError;
use crate::report::{FdiShown, Provenance, ResidueRms, UnitReport, build_unit_report};
use crate::unit_sensor::fdi::{self, DEFAULT_FALSE_ALARM};
use crate::unit_sensor::{UnitApplied, UnitModel, gyros_before_after, residues_of, to_signals};
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};
use sysid::Signals;

/// The parity residues' rms before and after, and fault detection on the
/// record as logged and compensated.
#[derive(Debug, Clone, PartialEq)]
pub struct Parity {
    /// Each residue's rms (none for three gyros).
    pub residues: Vec<ResidueRms>,
    /// Fault detection (four gyros or more).
    pub fdi: Option<FdiShown>,
}

/// The residues and fault detection of `m` on `records` (segments of its
/// unit's logs); σ given or read from the record, false-alarm probability
/// `p_fa` per sample.
pub fn parity(
    m: &UnitModel,
    records: &[(String, Record)],
    sigma: Option<f64>,
    p_fa: f64,
) -> Result<Parity, DtgVibError> {
    let unit = m.unit();
    if unit.residue_names().is_empty() {
        return Ok(Parity {
            residues: Vec::new(),
            fdi: None,
        });
    }
    let g = gyros_before_after(m, records)?;
    let (pb, pa) = (residues_of(unit, &g.before), residues_of(unit, &g.after));
    let residues = unit
        .residue_names()
        .iter()
        .enumerate()
        .map(|(k, n)| ResidueRms {
            name: n.clone(),
            before: stats::rms(&pb[k]),
            after: Some(stats::rms(&pa[k])),
        })
        .collect();
    // A record without noise (σ read as 0) has no threshold: the page
    // shows the residues without the test rather than no page.
    let fdi = fdi::setting(unit, sigma, p_fa, &pb)
        .ok()
        .map(|(test, setting)| FdiShown {
            setting,
            found: vec![
                ("as logged".to_string(), fdi::run(unit, &test, &g.before)),
                ("compensated".to_string(), fdi::run(unit, &test, &g.after)),
            ],
        });
    Ok(Parity { residues, fdi })
}

/// What a unit's page is made of besides the model and its records.
pub struct Page<'a> {
    /// The model file (provenance).
    pub model_path: &'a Path,
    /// The records' files (provenance, and the page's name for them).
    pub data: &'a [PathBuf],
    /// A baseline model and its file.
    pub baseline: Option<(&'a UnitModel, &'a Path)>,
    /// Paragraphs first on the page.
    pub lead: Vec<String>,
    /// Other pages to link.
    pub links: Vec<(PathBuf, String)>,
    /// Another directory to write the page into too (its figures linked
    /// from the page's own directory): the demo's `out/index.html`.
    pub also_into: Option<PathBuf>,
}

/// Writes the page of `m` on `records` (segments of its unit's logs) into
/// `dir`; returns the page and the parity figures it shows.
pub fn write_page(
    m: &UnitModel,
    records: &[(String, Record)],
    page: Page<'_>,
    dir: &Path,
) -> Result<(PathBuf, Parity), DtgVibError> {
    let signals = records
        .iter()
        .map(|(n, r)| Ok((n.clone(), to_signals(r)?)))
        .collect::<Result<Vec<(String, Signals)>, DtgVibError>>()?;
    let named: Vec<(String, &Signals)> = signals.iter().map(|(n, s)| (n.clone(), s)).collect();
    let applied = UnitApplied::new(m, &named)?;
    let base = match page.baseline {
        Some((b, _)) => Some(UnitApplied::new(b, &named)?),
        None => None,
    };
    let parity = parity(m, records, None, DEFAULT_FALSE_ALARM)?;
    // The longest segment's curves; one too short for an Allan curve has
    // none worth drawing, and the page goes without.
    let allan: Option<AllanAnalysis> = records
        .iter()
        .max_by_key(|(_, r)| r.len())
        .and_then(|(_, r)| AllanAnalysis::new(m.unit(), Some(m), r, 0.683).ok());
    let mut files: Vec<(String, PathBuf)> = vec![("model".into(), page.model_path.to_path_buf())];
    files.extend(page.data.iter().map(|d| ("data".to_string(), d.clone())));
    if let Some((_, p)) = page.baseline {
        files.push(("baseline model".into(), p.to_path_buf()));
    }
    let provenance = Provenance::of_this_process(files);
    let source = page
        .data
        .iter()
        .map(|d| d.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let r = UnitReport {
        unit: m.unit(),
        source: &source,
        applied: &applied,
        baseline: base.as_ref().map(|b| ("baseline", b)),
        residues: parity.residues.clone(),
        fdi: parity.fdi.clone(),
        allan: allan.as_ref(),
        provenance: Some(&provenance),
        lead: page.lead,
        links: page.links.clone(),
    };
    let html = build_unit_report(&r, dir)?;
    let index = html.write(dir)?;
    if let Some(other) = &page.also_into {
        html.write(other)?;
    }
    Ok((index, parity))
}
