//! `dtg-vib report`: the figures and index.html of a model on a record
//! (also written by `check --report`).

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::apply::Applied;
use dtg_vib::model::CompensationModel;
use dtg_vib::report::{Baseline, Provenance, ReportExtras, build_report};
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};

use super::residues::print_residues;

/// The flags of `report`.
#[derive(Args)]
pub struct ReportArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// An earlier model of the same record, to show each channel's error before and after.
    #[arg(long)]
    baseline: Option<PathBuf>,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
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
    let unit_model = super::unit::model_unit(&model, unit.as_deref())?;
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
    if let Some(m) = unit_model {
        return super::unit::report::report(&m, &model, &data, baseline.as_deref(), &out, progress);
    }
    let m = CompensationModel::load(&model)?;
    let record = Record::read_csv(&data)?;
    progress.say("applying the model");
    let applied = Applied::new(&m, &record)?;
    let base = match &baseline {
        Some(b) => {
            let bm = CompensationModel::load(b)?;
            let ba = Applied::new(&bm, &record)?;
            Some((bm, ba, b.as_path()))
        }
        None => None,
    };
    progress.say("drawing figures");
    let summary = model_report(
        (&m, &model),
        (&record, &data),
        &applied,
        base.as_ref().map(|(bm, ba, path)| (bm, ba, *path)),
        &out,
    )?;
    drop(progress);
    print_residues(&summary.residues);
    if let Some((_, ba, _)) = &base {
        print_baseline_table(ba, &summary.channels);
    }
    println!("report: {}", summary.index.display());
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

/// The report of a model on a record, with the files' provenance: `report`
/// and `check --report`.
pub fn model_report(
    (m, model): (&CompensationModel, &PathBuf),
    (record, data): (&Record, &PathBuf),
    applied: &Applied,
    baseline: Option<(&CompensationModel, &Applied, &std::path::Path)>,
    dir: &std::path::Path,
) -> Result<dtg_vib::report::ReportSummary> {
    let mut files = vec![("model", model.clone()), ("data", data.clone())];
    files.extend(baseline.map(|(_, _, b)| ("baseline model", b.to_path_buf())));
    let provenance = Provenance::of_this_process(files);
    let extras = ReportExtras {
        provenance: Some(&provenance),
        ..ReportExtras::default()
    };
    let (summary, page) = build_report(
        m,
        applied,
        record,
        &data.display().to_string(),
        baseline.map(|(model, applied, _)| Baseline {
            label: "baseline",
            model,
            applied,
        }),
        &extras,
        dir,
    )?;
    page.write(dir)?;
    Ok(summary)
}

/// Each channel's validation rms under the baseline and this model.
fn print_baseline_table(base: &Applied, this: &[dtg_vib::model::ChannelScores]) {
    println!("channel  val rms baseline  val rms this model  (deg/h)  change");
    for (c, s) in nav_sensors::geometry::Channel::ALL.into_iter().zip(this) {
        let b = base.scores(c).val_rms;
        println!(
            "{:>7}  {:>16.4}  {:>18.4}  {:>15}",
            c.name(),
            b,
            s.val_rms,
            format!("{:+.1}%", 100.0 * (s.val_rms / b - 1.0))
        );
    }
}
