//! The parity residues as `dtg-vib residues` gives them: every sample's
//! residues (the paper's K0..K5 of eq. 6, another unit's P0, … = V·m) as
//! logged and, with a model, pre-processed, compensated and as `compensate`
//! writes the gyros; their rms; fault detection (four gyros or more) and
//! isolation (five or more) on them. A unit of three gyros has none, and
//! is refused saying so.

use anyhow::{Result, anyhow, bail};
use nav_sensors::unit::Unit;
use serde::Serialize;

use super::records::Read;
use crate::unit_sensor::fdi::{self, FdiSetting, FdiSummary};
use crate::unit_sensor::{Applied, ResidueSeries, ResidueStats, UnitModel, residues_of};

/// One residue's rms in `residues --json`.
#[derive(Debug, Clone, Serialize)]
pub struct ResidueRms {
    pub residue: String,
    pub rms_before_deg_h: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_after_deg_h: Option<f64>,
}

/// Fault detection in `residues --json`.
#[derive(Serialize)]
struct FdiJson<'a> {
    #[serde(flatten)]
    setting: &'a FdiSetting,
    before: &'a FdiSummary,
    #[serde(skip_serializing_if = "Option::is_none")]
    after: Option<&'a FdiSummary>,
}

/// What `residues` computes: per row its time and the residues of the
/// gyros as logged (`before`) and as compensated (`after`, with a model),
/// the pre-processed outputs' residues before and after the prediction
/// (`pre_comp`), the validation rows' table, each residue's rms and what
/// fault detection found.
pub struct Residues {
    pub unit: Unit,
    pub t: Vec<f64>,
    pub before: Vec<Vec<f64>>,
    pub after: Option<Vec<Vec<f64>>>,
    pub pre_comp: Option<ResidueSeries>,
    pub validation: Option<Vec<ResidueStats>>,
    pub rms: Vec<ResidueRms>,
    pub setting: FdiSetting,
    pub found_before: FdiSummary,
    pub found_after: Option<FdiSummary>,
}

/// The gyros of every segment: as logged (without a model), or from its
/// first full window on as logged and with the model's compensation, with
/// the pre-processed residues and the validation rows' table.
type Gyros = (
    Vec<f64>,
    Vec<Vec<f64>>,
    Option<Vec<Vec<f64>>>,
    Option<ResidueSeries>,
    Option<Vec<ResidueStats>>,
);

fn gyros(unit: &Unit, model: Option<&UnitModel>, read: &Read) -> Result<Gyros> {
    let n = unit.gyros().len();
    let Some(m) = model else {
        let mut t = Vec::new();
        let mut before = vec![Vec::new(); n];
        for (_, r) in &read.records {
            t.extend_from_slice(r.t());
            for (k, g) in before.iter_mut().enumerate() {
                g.extend_from_slice(r.gyro_at(k));
            }
        }
        return Ok((t, before, None, None, None));
    };
    let applied = Applied::unsplit(m, &read.borrowed())?;
    let first = applied.prepared.first_sample();
    let mut before = vec![Vec::new(); n];
    for (_, r) in &read.records {
        for (k, g) in before.iter_mut().enumerate() {
            g.extend_from_slice(&r.gyro_at(k)[first..]);
        }
    }
    let mut after = vec![Vec::new(); n];
    for c in applied.compensated()? {
        for (k, g) in after.iter_mut().enumerate() {
            g.extend_from_slice(c.gyro_at(k));
        }
    }
    let residues = applied.residues();
    // The validation rows of the model's split, if these records have them.
    let validation = match m.inner().rows(&applied.prepared) {
        Ok((_, val)) => Some(residues.stats(&val)),
        Err(_) => None,
    };
    Ok((
        residues.t.clone(),
        before,
        Some(after),
        Some(residues),
        validation,
    ))
}

/// A unit of three gyros has no residue: refused in one line saying what
/// judges its channels instead.
pub fn refuse_without_residues(unit: &Unit) -> Result<()> {
    if unit.residue_names().is_empty() {
        bail!(
            "the unit '{}' ({}) has {} gyros: nothing is redundant, so it has no parity residue and no fault detection; judge its channels against a rate reference instead (dtg-vib fit --unit … --table-rate or --earth-rate, then dtg-vib check)",
            unit.name(),
            unit.file(),
            unit.gyros().len()
        );
    }
    Ok(())
}

/// The residues of `unit` on `read` (with the model's compensation where
/// one is given: `unit` is then the model's), fault detection with the
/// gyros' white noise `fdi_sigma` per sample (deg/h; None: read from the
/// record) and false-alarm probability `fdi_false_alarm` per sample.
pub fn residues(
    unit: &Unit,
    model: Option<&UnitModel>,
    read: &Read,
    fdi_sigma: Option<f64>,
    fdi_false_alarm: f64,
) -> Result<Residues> {
    refuse_without_residues(unit)?;
    let (t, before, after, pre_comp, validation) = gyros(unit, model, read)?;
    let pb = residues_of(unit, &before);
    let pa = after.as_ref().map(|a| residues_of(unit, a));
    // A threshold that overflows is the flags' fault, said with them.
    let (test, setting) = fdi::setting(unit, fdi_sigma, fdi_false_alarm, &before).map_err(|e| {
        anyhow!(
            "fault detection with --fdi-sigma {} and --fdi-false-alarm {:e}: {e}: give a noise level and false-alarm probability whose threshold σ·√q is a finite positive number (e.g. --fdi-sigma 0.1 --fdi-false-alarm 1e-3)",
            fdi_sigma.map_or("(read from the record)".to_string(), |v| format!("{v:e}")),
            fdi_false_alarm
        )
    })?;
    let found_before = fdi::run(unit, &test, &before);
    let found_after = after.as_ref().map(|g| fdi::run(unit, &test, g));
    let rms = unit
        .residue_names()
        .iter()
        .enumerate()
        .map(|(k, n)| ResidueRms {
            residue: n.clone(),
            rms_before_deg_h: stats::rms(&pb[k]),
            rms_after_deg_h: pa.as_ref().map(|p| stats::rms(&p[k])),
        })
        .collect();
    Ok(Residues {
        unit: unit.clone(),
        t,
        before: pb,
        after: pa,
        pre_comp,
        validation,
        rms,
        setting,
        found_before,
        found_after,
    })
}

impl Residues {
    /// The columns `residues --out` writes: `t`, the residues as logged,
    /// and with a model `R_pre`, `R_comp` and `R_out` for each residue R.
    pub fn columns(&self) -> (Vec<String>, Vec<&[f64]>) {
        let names = self.unit.residue_names();
        let mut header: Vec<String> = vec!["t".into()];
        header.extend(names.iter().cloned());
        let mut columns: Vec<&[f64]> = vec![&self.t];
        columns.extend(self.before.iter().map(Vec::as_slice));
        if let Some(r) = &self.pre_comp {
            header.extend(names.iter().map(|n| format!("{n}_pre")));
            columns.extend(r.before.iter().map(Vec::as_slice));
            header.extend(names.iter().map(|n| format!("{n}_comp")));
            columns.extend(r.after.iter().map(Vec::as_slice));
        }
        if let Some(pa) = &self.after {
            header.extend(names.iter().map(|n| format!("{n}_out")));
            columns.extend(pa.iter().map(Vec::as_slice));
        }
        (header, columns)
    }

    /// `residues --json`'s object.
    pub fn to_json(&self) -> Result<serde_json::Value> {
        let mut v = serde_json::json!({
            "unit": self.unit.name(),
            "samples": self.t.len(),
            "residues": self.rms,
            "fdi": FdiJson {
                setting: &self.setting,
                before: &self.found_before,
                after: self.found_after.as_ref(),
            },
        });
        if let Some(val) = &self.validation {
            v["validation"] = serde_json::to_value(val)?;
        }
        Ok(v)
    }
}
