//! `dtg-vib residues`: the unit's parity residues (the paper's K0..K5 of
//! eq. 6, another unit's P0, … = V·m) of every sample, and with a model the
//! pre-processed and compensated ones; fault detection (four gyros or more)
//! and isolation (five or more) on them; the residue tables other commands
//! print. A unit of three gyros has none, and says so.

use anyhow::{Result, bail};
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::unit_sensor::fdi::{self, FdiSetting, FdiSummary};
use dtg_vib::unit_sensor::{Applied, ResidueSeries, ResidueStats, UnitModel, pooled, residues_of};
use nav_sensors::unit::Unit;
use serde::Serialize;
use std::path::PathBuf;

use dtg_vib::commands::records::{Read, open_model, read_records, unit_of};

/// The flags of `residues`.
#[derive(Args)]
pub struct ResiduesArgs {
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Model file: adds R_pre (calibrated, filtered), R_comp (R_pre less
    /// the predicted errors) and R_out (what `compensate` writes) columns.
    #[arg(long)]
    model: Option<PathBuf>,
    /// Output CSV.
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// (it stores its unit).
    #[arg(long)]
    unit: Option<String>,
    /// Print one JSON object on stdout: the residues' rms and what fault
    /// detection found.
    #[arg(long)]
    json: bool,
    /// Fault detection (units of four gyros or more): the gyros' white
    /// noise per sample, deg/h; default read from the record.
    #[arg(long = "fdi-sigma", value_parser = dtg_vib::commands::parse::parse_sigma)]
    fdi_sigma: Option<f64>,
    /// Fault detection: the false-alarm probability per sample.
    #[arg(long = "fdi-false-alarm", default_value_t = fdi::DEFAULT_FALSE_ALARM, value_parser = dtg_vib::commands::parse::parse_alpha)]
    fdi_false_alarm: f64,
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

/// The series `residues` writes and tests: per row its time, the gyros as
/// logged and (with a model) compensated, and the residues of the
/// pre-processed outputs before and after the prediction with the
/// validation rows' table.
struct Series {
    t: Vec<f64>,
    before: Vec<Vec<f64>>,
    after: Option<Vec<Vec<f64>>>,
    pre_comp: Option<ResidueSeries>,
    validation: Option<Vec<ResidueStats>>,
}

/// Every segment's samples as logged (without a model), or from its first
/// full window on with the model's compensation.
fn series(unit: &Unit, model: Option<&UnitModel>, read: &Read) -> Result<Series> {
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
        return Ok(Series {
            t,
            before,
            after: None,
            pre_comp: None,
            validation: None,
        });
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
    Ok(Series {
        t: residues.t.clone(),
        before,
        after: Some(after),
        pre_comp: Some(residues),
        validation,
    })
}

/// Writes the residues and prints their rms before and after and what
/// fault detection found (or all of it as one JSON object).
pub fn run(a: ResiduesArgs, progress: Progress) -> Result<()> {
    let model = a
        .model
        .as_deref()
        .map(|m| open_model(m, a.unit.as_deref()))
        .transpose()?;
    let unit = match &model {
        Some(m) => m.unit().clone(),
        None => unit_of(a.unit.as_deref())?,
    };
    outfile::guard_file(
        "--out",
        &a.out,
        &[("--data", Some(&a.data)), ("--model", a.model.as_deref())],
    )?;
    refuse_without_residues(&unit)?;
    let min = model
        .as_ref()
        .map_or(2, |m| 2 * m.inner().preprocess().window.length());
    let read = read_records(std::slice::from_ref(&a.data), &unit, min)?;
    progress.say("computing the parity residues");
    let s = series(&unit, model.as_ref(), &read)?;
    let pb = residues_of(&unit, &s.before);
    let pa = s.after.as_ref().map(|a| residues_of(&unit, a));
    // Set up before anything is written: a threshold that overflows is the
    // flags' fault, said with them.
    let (test, setting) = fdi::setting(&unit, a.fdi_sigma, a.fdi_false_alarm, &pb)
        .map_err(|e| {
            anyhow::anyhow!(
                "fault detection with --fdi-sigma {} and --fdi-false-alarm {:e}: {e}: give a noise level and false-alarm probability whose threshold σ·√q is a finite positive number (e.g. --fdi-sigma 0.1 --fdi-false-alarm 1e-3)",
                a.fdi_sigma
                    .map_or("(read from the record)".to_string(), |v| format!("{v:e}")),
                a.fdi_false_alarm
            )
        })?;
    write_csv(&a.out, &unit, &s, &pb, pa.as_deref())?;
    let found_before = fdi::run(&unit, &test, &s.before);
    let found_after = s.after.as_ref().map(|g| fdi::run(&unit, &test, g));
    drop(progress);
    read.say_notes();
    let rows: Vec<ResidueJson<'_>> = unit
        .residue_names()
        .iter()
        .enumerate()
        .map(|(k, n)| ResidueJson {
            residue: n,
            rms_before_deg_h: stats::rms(&pb[k]),
            rms_after_deg_h: pa.as_ref().map(|p| stats::rms(&p[k])),
        })
        .collect();
    if a.json {
        let mut v = serde_json::json!({
            "unit": unit.name(),
            "samples": s.t.len(),
            "residues": rows,
            "fdi": FdiJson {
                setting: &setting,
                before: &found_before,
                after: found_after.as_ref(),
            },
        });
        if let Some(val) = &s.validation {
            v["validation"] = serde_json::to_value(val)?;
        }
        println!("{v}");
        eprintln!("wrote {}", a.out.display());
        return Ok(());
    }
    if let Some(val) = &s.validation {
        print_residues(val);
    }
    print_every_sample(&rows, &setting, &found_before, found_after.as_ref());
    eprintln!("wrote {}", a.out.display());
    Ok(())
}

/// A unit of three gyros has no residue: refused in one line saying what
/// judges its channels instead.
fn refuse_without_residues(unit: &Unit) -> Result<()> {
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

/// `t`, the residues as logged, and with a model `R_pre`, `R_comp` and
/// `R_out` for each residue R.
fn write_csv(
    out: &std::path::Path,
    unit: &Unit,
    s: &Series,
    pb: &[Vec<f64>],
    pa: Option<&[Vec<f64>]>,
) -> Result<()> {
    let names = unit.residue_names();
    let mut header: Vec<String> = vec!["t".into()];
    header.extend(names.iter().cloned());
    let mut columns: Vec<&[f64]> = vec![&s.t];
    columns.extend(pb.iter().map(Vec::as_slice));
    if let Some(r) = &s.pre_comp {
        header.extend(names.iter().map(|n| format!("{n}_pre")));
        columns.extend(r.before.iter().map(Vec::as_slice));
        header.extend(names.iter().map(|n| format!("{n}_comp")));
        columns.extend(r.after.iter().map(Vec::as_slice));
    }
    if let Some(pa) = pa {
        header.extend(names.iter().map(|n| format!("{n}_out")));
        columns.extend(pa.iter().map(Vec::as_slice));
    }
    let h: Vec<&str> = header.iter().map(String::as_str).collect();
    Ok(tabular::write_csv(out, &h, &columns)?)
}

/// Each residue's rms over every sample, as logged and (with a model) as
/// `compensate` writes the gyros, and the fault-detection lines.
fn print_every_sample(
    rows: &[ResidueJson<'_>],
    setting: &FdiSetting,
    before: &FdiSummary,
    after: Option<&FdiSummary>,
) {
    let with_after = rows.iter().any(|r| r.rms_after_deg_h.is_some());
    println!(
        "residue  rms before  {}(deg/h, every sample)",
        if with_after { "rms after  " } else { "" }
    );
    for r in rows {
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
    println!("{}", fdi::line("as logged", before, setting));
    if let Some(a) = after {
        println!("{}", fdi::line("compensated", a, setting));
    }
}

/// The residue table on the validation rows.
pub fn print_residues(stats: &[ResidueStats]) {
    print_residues_on(stats, "validation rows");
}

/// The residue table on the rows `rows` names: each residue's rms before and
/// after and how many times better or worse, then all of them pooled (the
/// rms of the residues together, the one figure a campaign compares models
/// by).
pub fn print_residues_on(stats: &[ResidueStats], rows: &str) {
    println!(
        "residue  rms before  rms after  {:<24}  change",
        format!("(deg/h, {rows})")
    );
    let row = |name: &str, before: f64, after: f64| {
        println!(
            "{name:>7}  {before:>10.4}  {after:>9.4}  {:24}  {}",
            "",
            change(before, after)
        );
    };
    for s in stats {
        row(&s.residue, s.rms_before, s.rms_after);
    }
    row(
        "pooled",
        pooled(stats, |s| s.rms_before),
        pooled(stats, |s| s.rms_after),
    );
}

/// How many times smaller (better) or larger (worse) the rms is after: a
/// ratio below one, printed as such, read as a reduction where it was a
/// sixfold worsening.
///
/// The ratio has two decimals either way, as the reduction had, in six
/// columns so that the "×" of a table's rows line up.
fn change(before: f64, after: f64) -> String {
    let ratio = before / after;
    if !(ratio.is_finite() && ratio > 0.0) {
        format!("{:>6}", "—")
    } else if ratio >= 1.0 {
        format!("{ratio:>6.2}× better")
    } else {
        format!("{:>6.2}× worse", 1.0 / ratio)
    }
}

#[cfg(test)]
mod tests {
    use super::change;

    #[test]
    fn a_change_says_better_or_worse_with_its_factor() {
        assert_eq!(change(4.07, 1.0), "  4.07× better");
        assert_eq!(change(2.3748, 14.5898), "  6.14× worse");
        assert_eq!(change(1.0, 1.0), "  1.00× better");
        // No ratio to give: a dash, never "inf× better".
        assert_eq!(change(1.0, 0.0), "     —");
        assert_eq!(change(0.0, 0.0), "     —");
    }
}
