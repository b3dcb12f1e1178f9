//! `dtg-vib residues`: the unit's parity residues (the paper's K0..K5 of
//! eq. 6, another unit's P0, … = V·m) of every sample, and with a model the
//! pre-processed and compensated ones; fault detection (four gyros or more)
//! and isolation (five or more) on them; the residue tables other commands
//! print. A unit of three gyros has none, and says so. The work is
//! [`dtg_vib::commands::residues`]'s; here the flags and the printing.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::commands::residues::{Residues, refuse_without_residues, residues};
use dtg_vib::unit_sensor::fdi;
use dtg_vib::unit_sensor::{ResidueStats, pooled};
use std::path::PathBuf;

use dtg_vib::commands::records::{read_records, unit_and_min};
use dtg_vib::unit_sensor::UnitModel;

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

/// Writes the residues and prints their rms before and after and what
/// fault detection found (or all of it as one JSON object).
pub fn run(a: ResiduesArgs, progress: Progress) -> Result<()> {
    let model = a.model.as_deref().map(UnitModel::load).transpose()?;
    let shown = a.model.as_deref().map(|p| p.display().to_string());
    let (unit, min) = unit_and_min(
        model.as_ref(),
        shown.as_deref().unwrap_or_default(),
        a.unit.as_deref(),
    )?;
    outfile::guard_file(
        "--out",
        &a.out,
        &[("--data", Some(&a.data)), ("--model", a.model.as_deref())],
    )?;
    refuse_without_residues(&unit)?;
    let read = read_records(std::slice::from_ref(&a.data), &unit, min)?;
    progress.say("computing the parity residues");
    // Everything is computed (and a flag refused) before anything is written.
    let r = residues(&unit, model.as_ref(), &read, a.fdi_sigma, a.fdi_false_alarm)?;
    let (header, columns) = r.columns();
    let h: Vec<&str> = header.iter().map(String::as_str).collect();
    tabular::write_csv(&a.out, &h, &columns)?;
    drop(progress);
    read.say_notes();
    if a.json {
        println!("{}", r.to_json()?);
        eprintln!("wrote {}", a.out.display());
        return Ok(());
    }
    if let Some(val) = &r.validation {
        print_residues(val);
    }
    print_every_sample(&r);
    eprintln!("wrote {}", a.out.display());
    Ok(())
}

/// Each residue's rms over every sample, as logged and (with a model) as
/// `compensate` writes the gyros, and the fault-detection lines.
fn print_every_sample(r: &Residues) {
    let (rows, setting) = (&r.rms, &r.setting);
    let with_after = rows.iter().any(|r| r.rms_after_deg_h.is_some());
    println!(
        "residue  rms before  {}(deg/h, every sample)",
        if with_after { "rms after  " } else { "" }
    );
    for row in rows {
        match row.rms_after_deg_h {
            Some(a) => println!(
                "{:>7}  {:>10.4}  {a:>9.4}",
                row.residue, row.rms_before_deg_h
            ),
            None => println!("{:>7}  {:>10.4}", row.residue, row.rms_before_deg_h),
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
    println!("{}", fdi::line("as logged", &r.found_before, setting));
    if let Some(a) = &r.found_after {
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
