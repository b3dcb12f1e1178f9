//! `diagnose`, `check` and `compensate` with a model of a unit other than
//! the paper's: the records read with the model's unit, in segments.

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::report::{Wording, write_diagnosis_report_of};
use dtg_vib::unit_sensor::{UnitModel, compensated};
use std::path::{Path, PathBuf};

use super::{Read, borrowed, read_records, signals};

/// The records of a model's unit, segments at least two windows long.
pub(super) fn records_of(m: &UnitModel, data: &[PathBuf]) -> Result<Read> {
    let window = m.inner().preprocess().window.length();
    read_records(data, m.unit(), 2 * window)
}

/// `diagnose` of a unit's model, and with `report` its diagnosis page.
pub fn diagnose(
    m: &UnitModel,
    data: &[PathBuf],
    json: bool,
    options: &sysid::diagnose::DiagnoseOptions,
    report: Option<&Path>,
    progress: Progress,
) -> Result<()> {
    let read = records_of(m, data)?;
    super::check_observable(m.inner().sensor(), &read.records)?;
    let named = signals(&read.records)?;
    progress.say("diagnosing (the model's mirror is fitted on its validation rows)");
    let d = sysid::explain::diagnose_records(m.inner(), &borrowed(&named), options)?;
    let page = match report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(write_diagnosis_report_of(
                &d,
                options.rank.min_err(),
                &Wording::of_unit(m.unit()),
                dir,
            )?)
        }
        None => None,
    };
    drop(progress);
    read.say_notes();
    if json {
        println!("{}", serde_json::to_string(&d)?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    super::super::findings::print_diagnosis(&d);
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}

/// `check` of a unit's model on a record (all its segments together), and
/// with `report` (the model's file and the page's directory) the unit's page.
pub fn check(
    m: &UnitModel,
    data: &Path,
    outside_threshold: f64,
    json: bool,
    report: Option<(&Path, &Path)>,
    progress: Progress,
) -> Result<()> {
    let read = records_of(m, &[data.to_path_buf()])?;
    super::check_observable(m.inner().sensor(), &read.records)?;
    let named = signals(&read.records)?;
    progress.say("applying the model");
    let prepared = m.inner().prepare_many(&borrowed(&named))?;
    let predicted = m.inner().predict(&prepared)?;
    let c = sysid::check::transfer(m.inner(), &prepared, &predicted, outside_threshold)?;
    let page = match report {
        Some((model, dir)) => {
            progress.say("drawing figures");
            let data = [data.to_path_buf()];
            let page = dtg_vib::unit_page::Page::new(model, &data);
            Some(dtg_vib::unit_page::write_page(m, &read.records, page, dir)?.index)
        }
        None => None,
    };
    drop(progress);
    read.say_notes();
    if json {
        let mut v = serde_json::to_value(&c)?;
        v["unit"] = serde_json::Value::String(m.unit().name().to_string());
        println!("{v}");
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    println!(
        "channel  rms before  rms after  mean after  fit %  (deg/h, {} windows)",
        c.windows
    );
    for ch in &c.channels {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}  {:>10.4}  {:>5.1}",
            ch.channel, ch.rms_before, ch.rms_after, ch.mean_after, ch.fit_percent
        );
    }
    if let Some(f) = c.outside_fraction {
        println!(
            "outside the training range: {:.1}% of the windows",
            100.0 * f
        );
    }
    if let Some(w) = &c.warning {
        println!("warning: {w}");
    }
    if let Some(note) = super::no_residue_note(m.unit()) {
        println!("{note}");
    }
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}

/// `compensate` with a unit's model: every segment compensated, written
/// in the unit's column names and units, one after the other.
pub fn compensate(m: &UnitModel, data: &Path, out: &Path, progress: Progress) -> Result<()> {
    let read = records_of(m, &[data.to_path_buf()])?;
    let named = signals(&read.records)?;
    progress.say("compensating");
    let mut text: Vec<u8> = Vec::new();
    let mut rows = 0;
    for (k, (name, s)) in named.iter().enumerate() {
        let r = compensated(m, s)?;
        rows += r.len();
        let mut part = Vec::new();
        r.write_with_unit(&mut part, name, m.unit())?;
        let body = match k {
            0 => &part[..],
            _ => {
                let header_end = part.iter().position(|&b| b == b'\n').map_or(0, |i| i + 1);
                &part[header_end..]
            }
        };
        text.extend_from_slice(body);
    }
    outfile::write_bytes(out, text).map_err(|e| anyhow::anyhow!("{}: {e}", out.display()))?;
    drop(progress);
    read.say_notes();
    eprintln!(
        "wrote {} ({rows} rows in the unit's names and units, from {} segment(s); each segment's first samples have no full window)",
        out.display(),
        named.len()
    );
    Ok(())
}
