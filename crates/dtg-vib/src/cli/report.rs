//! `dtg-vib report`: the figures and index.html of a model on a record
//! (also written by `check --report`), and what they show in numbers: the
//! residues, each channel against a baseline, fault detection.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::unit_page::{Page, Parity, Written, write_page};
use dtg_vib::unit_sensor::fdi;
use dtg_vib::unit_sensor::{Applied, UnitModel};
use nav_sensors::record::Record;
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
    if let (Some(b), Some(path)) = (&base, &baseline)
        && b.unit() != m.unit()
    {
        anyhow::bail!(
            "--baseline {}: fitted with the unit '{}', the model with '{}': a baseline must be a model of the same unit",
            path.display(),
            b.unit().name(),
            m.unit().name()
        );
    }
    let read = records_of(&m, std::slice::from_ref(&data))?;
    progress.say("applying the model");
    let records = read.borrowed();
    let applied = Applied::new(&m, &records)?;
    let base_applied = match &base {
        Some(b) => Some(Applied::new(b, &records)?),
        None => None,
    };
    progress.say("drawing figures");
    let files = [data.clone()];
    let baseline_page = base.as_ref().zip(baseline.as_deref());
    let Written { index, parity, .. } =
        model_page(&m, &model, &read.records, &files, baseline_page, &out)?;
    drop(progress);
    read.say_notes();
    if !m.unit().residue_names().is_empty() {
        print_residues(&applied.validation_residues());
    }
    if let Some(ba) = &base_applied {
        print_baseline_table(&m, ba, &applied);
    }
    print_parity(&m, &parity);
    println!("report: {}", index.display());
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

/// The page of a model on records with the files' provenance: `report`
/// and `check --report`.
pub fn model_page(
    m: &UnitModel,
    model: &Path,
    records: &[(String, Record)],
    data: &[PathBuf],
    baseline: Option<(&UnitModel, &Path)>,
    dir: &Path,
) -> Result<Written> {
    let page = Page {
        baseline,
        ..Page::new(model, data)
    };
    Ok(write_page(m, records, page, dir)?)
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
