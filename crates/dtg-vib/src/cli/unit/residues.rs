//! `residues --unit`: the parity residues P0, P1, … (V·m, V from the
//! unit's H) of every sample, and with a model of the unit the compensated
//! ones; fault detection (four gyros or more) and isolation (five or more)
//! on them; a unit of three gyros has none, and says so.

use anyhow::{Result, bail};
use cli_support::progress::Progress;
use dtg_vib::unit_sensor::fdi::{self, FdiSetting, FdiSummary};
use dtg_vib::unit_sensor::{UnitModel, gyros_before_after, residues_of};
use nav_sensors::unit::Unit;
use serde::Serialize;
use std::path::Path;

/// What fault detection is told: σ per sample (read from the record when
/// absent) and the false-alarm probability per test.
#[derive(Debug, Clone, Copy)]
pub struct FdiOptions {
    /// `--fdi-sigma`, deg/h.
    pub sigma: Option<f64>,
    /// `--fdi-false-alarm`.
    pub false_alarm: f64,
}

/// One residue's rms in `residues --json`.
#[derive(Serialize)]
struct ResidueJson<'a> {
    residue: &'a str,
    rms_before_deg_h: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    rms_after_deg_h: Option<f64>,
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

/// Writes t and the residues (and, with a model, `P*_comp`) of every
/// segment, and prints each residue's rms before and after and what fault
/// detection found (or all of it as one JSON object).
pub fn residues(
    unit: &Unit,
    model: Option<&UnitModel>,
    data: &Path,
    out: &Path,
    options: FdiOptions,
    json: bool,
    progress: Progress,
) -> Result<()> {
    if unit.residue_names().is_empty() {
        bail!(
            "the unit '{}' ({}) has {} gyros: nothing is redundant, so it has no parity residue and no fault detection; judge its channels against a rate reference instead (dtg-vib fit --unit … --table-rate or --earth-rate, then dtg-vib check)",
            unit.name(),
            unit.file(),
            unit.gyros().len()
        );
    }
    let min = model.map_or(2, |m| 2 * m.inner().preprocess().window.length());
    let read = super::read_records(&[data.to_path_buf()], unit, min)?;
    progress.say("computing the parity residues");
    let names = unit.residue_names();
    let n = unit.gyros().len();
    let mut t = Vec::new();
    let (before, after) = match model {
        Some(m) => {
            let g = gyros_before_after(m, &read.records)?;
            t = g.t;
            (g.before, Some(g.after))
        }
        None => {
            let mut b = vec![Vec::new(); n];
            for (_, r) in &read.records {
                t.extend_from_slice(r.t());
                for (k, g) in b.iter_mut().enumerate() {
                    g.extend_from_slice(r.gyro_at(k));
                }
            }
            (b, None)
        }
    };
    let pb = residues_of(unit, &before);
    let pa = after.as_ref().map(|a| residues_of(unit, a));
    // Set up before anything is written: a threshold that overflows is the
    // flags' fault, said with them.
    let (test, setting) = fdi::setting(unit, options.sigma, options.false_alarm, &pb)
        .map_err(|e| {
            anyhow::anyhow!(
                "fault detection with --fdi-sigma {} and --fdi-false-alarm {:e}: {e}: give a noise level and false-alarm probability whose threshold σ·√q is a finite positive number (e.g. --fdi-sigma 0.1 --fdi-false-alarm 1e-3)",
                options
                    .sigma
                    .map_or("(read from the record)".to_string(), |v| format!("{v:e}")),
                options.false_alarm
            )
        })?;
    let mut header: Vec<String> = vec!["t".into()];
    header.extend(names.iter().cloned());
    let mut columns: Vec<&[f64]> = vec![&t];
    columns.extend(pb.iter().map(Vec::as_slice));
    if let Some(pa) = &pa {
        header.extend(names.iter().map(|n| format!("{n}_comp")));
        columns.extend(pa.iter().map(Vec::as_slice));
    }
    let h: Vec<&str> = header.iter().map(String::as_str).collect();
    tabular::write_csv(out, &h, &columns)?;
    let found_before = fdi::run(unit, &test, &before);
    let found_after = after.as_ref().map(|a| fdi::run(unit, &test, a));
    drop(progress);
    read.say_notes();
    let rows: Vec<ResidueJson<'_>> = names
        .iter()
        .enumerate()
        .map(|(k, n)| ResidueJson {
            residue: n,
            rms_before_deg_h: stats::rms(&pb[k]),
            rms_after_deg_h: pa.as_ref().map(|p| stats::rms(&p[k])),
        })
        .collect();
    if json {
        let v = serde_json::json!({
            "unit": unit.name(),
            "samples": t.len(),
            "residues": rows,
            "fdi": FdiJson {
                setting: &setting,
                before: &found_before,
                after: found_after.as_ref(),
            },
        });
        println!("{v}");
        eprintln!("wrote {}", out.display());
        return Ok(());
    }
    println!(
        "residue  rms before  {}(deg/h, every sample)",
        if model.is_some() { "rms after  " } else { "" }
    );
    for r in &rows {
        match r.rms_after_deg_h {
            Some(a) => println!("{:>7}  {:>10.4}  {a:>9.4}", r.residue, r.rms_before_deg_h),
            None => println!("{:>7}  {:>10.4}", r.residue, r.rms_before_deg_h),
        }
    }
    println!(
        "fault detection: ‖p‖ > {:.4} deg/h per sample, false-alarm probability {:.0e} under white noise of σ = {:.4} deg/h ({})",
        setting.threshold_deg_h,
        setting.false_alarm_probability,
        setting.sigma_deg_h,
        match setting.sigma_source {
            fdi::SigmaSource::Given => "--fdi-sigma",
            fdi::SigmaSource::Estimated => "read from the record; --fdi-sigma to state it",
        }
    );
    println!("{}", fdi::line("as logged", &found_before, &setting));
    if let Some(a) = &found_after {
        println!("{}", fdi::line("compensated", a, &setting));
    }
    eprintln!("wrote {}", out.display());
    Ok(())
}
