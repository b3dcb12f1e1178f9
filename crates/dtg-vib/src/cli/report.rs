//! `dtg-vib report`: the figures and index.html of a model on a record
//! (also written by `check --report`), and what they show in numbers: the
//! residues, each channel against a baseline, fault detection. The work is
//! [`dtg_vib::commands::report`]'s; here the flags and the printing.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::commands::report::{Caller, report};
use dtg_vib::page::Parity;
use dtg_vib::unit_sensor::fdi;
use dtg_vib::unit_sensor::{Applied, UnitModel};
use std::path::{Path, PathBuf};

use super::residues::print_residues;
use dtg_vib::commands::records::{no_residue_note, open_model, records_of};

/// The flags of `report`.
#[derive(Args)]
pub struct ReportArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// An earlier model of the same record (and unit), to show each
    /// channel's error before and after.
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); not needed (a model stores its unit), and
    /// refused when it is not the model's.
    #[arg(long)]
    unit: Option<String>,
}

/// Writes the report and prints the residues (and the baseline's table).
pub fn run(a: ReportArgs, progress: Progress) -> Result<()> {
    let ReportArgs {
        model,
        data,
        baseline,
        out,
        unit,
    } = a;
    let m = open_model(&model, unit.as_deref())?;
    outfile::guard_dir(
        "--out",
        &out,
        &["index.html"],
        &[
            ("--model", Some(&model)),
            ("--data", Some(&data)),
            ("--baseline", baseline.as_deref()),
        ],
    )?;
    let base = baseline.as_deref().map(UnitModel::load).transpose()?;
    let read = records_of(&m, std::slice::from_ref(&data))?;
    progress.say("drawing figures");
    let files = [data.clone()];
    let baseline_page = base.as_ref().zip(baseline.as_deref());
    let r = report(
        &m,
        &model,
        &read,
        &files,
        baseline_page,
        &out,
        Caller::default(),
    )?;
    drop(progress);
    read.say_notes();
    if !m.unit().residue_names().is_empty() {
        print_residues(&r.applied.validation_residues());
    }
    if let Some(ba) = &r.baseline {
        print_baseline_table(&m, ba, &r.applied);
    }
    print_parity(&m, &r.written.parity);
    println!("report: {}", r.written.index.display());
    Ok(())
}

/// Refuses, before any work, a `--report DIR` (of `check`, `diagnose`,
/// `explain`, `allan`) whose index.html would be one of the inputs, or that
/// cannot be written.
pub fn guard_report(report: Option<&Path>, inputs: &[(&str, Option<&Path>)]) -> Result<()> {
    if let Some(dir) = report {
        outfile::guard_dir("--report", dir, &["index.html"], inputs)?;
    }
    Ok(())
}

/// Each channel's validation rms under the baseline and this model.
fn print_baseline_table(m: &UnitModel, base: &Applied, this: &Applied) {
    println!("channel  val rms baseline  val rms this model  (deg/h)  change");
    for (k, c) in m.unit().gyro_names().into_iter().enumerate() {
        let (b, s) = (base.scores(k).val_rms, this.scores(k).val_rms);
        println!(
            "{:>7}  {:>16.4}  {:>18.4}  {:>15}",
            c,
            b,
            s,
            format!("{:+.1}%", 100.0 * (s / b - 1.0))
        );
    }
}

/// The residues' rms before and after on every sample (as logged and as
/// `compensate` writes them) and the fault-detection lines, or, for three
/// gyros, that there is no residue.
pub fn print_parity(m: &UnitModel, p: &Parity) {
    if p.residues.is_empty() {
        if let Some(note) = no_residue_note(m.unit(), &m.inner().sensor().rate_reference) {
            println!("{note}");
        }
        return;
    }
    println!("residue  rms before  rms after  (deg/h, every sample)");
    for r in &p.residues {
        println!(
            "{:>7}  {:>10.4}  {:>9.4}",
            r.name,
            r.before,
            r.after.unwrap_or(f64::NAN)
        );
    }
    if let Some(f) = &p.fdi {
        for (what, s) in &f.found {
            println!("{}", fdi::line(what, s, &f.setting));
        }
    }
}
