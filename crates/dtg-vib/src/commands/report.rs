//! A report as `dtg-vib report` writes it: the figures and index.html of a
//! model on a record (also `check --report`'s), with a baseline model of
//! the same unit where one is given, and the numbers the command prints
//! (the residues on the validation rows, each channel against the
//! baseline, the residues on every sample and fault detection).

use anyhow::{Result, bail};
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};

use super::records::Read;
use crate::page::{Page, Written, write_page};
use crate::unit_sensor::{Applied, UnitModel};

/// Who asks for a page besides the command line: the call the provenance
/// names and the folder of inputs staged from memory (see [`Page`]).
#[derive(Default)]
pub struct Caller<'a> {
    pub command: Option<String>,
    pub staged: Option<&'a Path>,
}

/// The page of a model on records with the files' provenance: `report`
/// and `check --report`.
pub fn model_page(
    m: &UnitModel,
    model: &Path,
    records: &[(String, Record)],
    data: &[PathBuf],
    baseline: Option<(&UnitModel, &Path)>,
    dir: &Path,
    caller: Caller<'_>,
) -> Result<Written> {
    let page = Page {
        baseline,
        command: caller.command,
        staged: caller.staged,
        ..Page::new(model, data)
    };
    Ok(write_page(m, records, page, dir)?)
}

/// What `report` wrote and the numbers it prints.
pub struct Reported {
    pub written: Written,
    /// The model applied to the records, with its split.
    pub applied: Applied,
    /// The baseline applied to them.
    pub baseline: Option<Applied>,
}

/// Writes the report of `m` (read from `model`) on `read` (the records of
/// the files `data`, read with [`super::records::records_of`]) into `out`,
/// against `baseline` (a model of the same unit, and its file). The
/// caller has guarded `out` (`outfile::guard_dir`): never over an input.
pub fn report(
    m: &UnitModel,
    model: &Path,
    read: &Read,
    data: &[PathBuf],
    baseline: Option<(&UnitModel, &Path)>,
    out: &Path,
    caller: Caller<'_>,
) -> Result<Reported> {
    if let Some((b, path)) = baseline
        && b.unit() != m.unit()
    {
        bail!(
            "--baseline {}: fitted with the unit '{}', the model with '{}': a baseline must be a model of the same unit",
            path.display(),
            b.unit().name(),
            m.unit().name()
        );
    }
    let records = read.borrowed();
    let applied = Applied::new(m, &records)?;
    let base_applied = match baseline {
        Some((b, _)) => Some(Applied::new(b, &records)?),
        None => None,
    };
    let written = model_page(m, model, &read.records, data, baseline, out, caller)?;
    Ok(Reported {
        written,
        applied,
        baseline: base_applied,
    })
}
