//! `residues --unit`: the parity residues P0, P1, … (V·m, V from the
//! unit's H) of every sample, and with a model of the unit the compensated
//! ones; a unit of three gyros has none, and says so.

use anyhow::{Result, bail};
use cli_support::progress::Progress;
use dtg_vib::unit_sensor::{UnitModel, to_signals};
use nav_sensors::record::Record;
use nav_sensors::unit::Unit;
use std::path::Path;

/// Per residue, its series over a record's samples.
fn residue_series(unit: &Unit, r: &Record) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::with_capacity(r.len()); unit.residue_names().len()];
    for i in 0..r.len() {
        for (o, v) in out.iter_mut().zip(unit.residues(&r.gyro_row(i))) {
            o.push(v);
        }
    }
    out
}

fn rms(x: &[f64]) -> f64 {
    stats::rms(x)
}

/// Writes t and the residues (and, with a model, `P*_comp`) of every
/// segment, and prints each residue's rms before and after.
pub fn residues(
    unit: &Unit,
    model: Option<&UnitModel>,
    data: &Path,
    out: &Path,
    progress: Progress,
) -> Result<()> {
    if unit.residue_names().is_empty() {
        bail!(
            "the unit '{}' ({}) has {} gyros: nothing is redundant, so it has no parity residue; judge its channels against a rate reference instead (dtg-vib fit --unit … --table-rate or --earth-rate, then dtg-vib check)",
            unit.name(),
            unit.file(),
            unit.gyros().len()
        );
    }
    let min = model.map_or(2, |m| 2 * m.inner().preprocess().window.length());
    let read = super::read_records(&[data.to_path_buf()], unit, min)?;
    let records = &read.records;
    progress.say("computing the parity residues");
    let names = unit.residue_names();
    let mut header: Vec<String> = vec!["t".into()];
    header.extend(names.iter().cloned());
    if model.is_some() {
        header.extend(names.iter().map(|n| format!("{n}_comp")));
    }
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); header.len()];
    for (_, r) in records {
        let (base, after) = match model {
            Some(m) => {
                let c = super::apply::compensated(m, &to_signals(r)?)?;
                let first = r.len() - c.len();
                (r.slice(first..r.len()), Some(residue_series(unit, &c)))
            }
            None => (r.clone(), None),
        };
        columns[0].extend_from_slice(base.t());
        for (k, s) in residue_series(unit, &base).into_iter().enumerate() {
            columns[1 + k].extend(s);
        }
        if let Some(after) = after {
            for (k, s) in after.into_iter().enumerate() {
                columns[1 + names.len() + k].extend(s);
            }
        }
    }
    let h: Vec<&str> = header.iter().map(String::as_str).collect();
    let c: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
    tabular::write_csv(out, &h, &c)?;
    drop(progress);
    read.say_notes();
    println!(
        "residue  rms before  {}(deg/h, every sample)",
        if model.is_some() { "rms after  " } else { "" }
    );
    for (k, n) in names.iter().enumerate() {
        let before = rms(&columns[1 + k]);
        match model {
            Some(_) => println!(
                "{n:>7}  {before:>10.4}  {:>9.4}",
                rms(&columns[1 + names.len() + k])
            ),
            None => println!("{n:>7}  {before:>10.4}"),
        }
    }
    eprintln!("wrote {}", out.display());
    Ok(())
}
