//! `dtg-vib diagnose`: what a model is missing, ranked on its records.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::report::{ChannelWording, write_diagnosis_report_of};
use std::path::{Path, PathBuf};

use super::findings::print_diagnosis;
use super::report::guard_report;
use dtg_vib::commands::records::{once_each, open_model, records_of};
use dtg_vib::commands::thresholds::Thresholds;

/// The flags of `diagnose`.
#[derive(Args)]
pub struct DiagnoseArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// The test record it was fitted on; repeat for the records of a
    /// model fitted on several (candidates are ranked on all of them).
    #[arg(long, required = true)]
    data: Vec<PathBuf>,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Write figures and index.html into this directory.
    #[arg(long)]
    report: Option<PathBuf>,
    #[command(flatten)]
    thresholds: Thresholds,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
    #[arg(long)]
    unit: Option<String>,
}

/// Diagnoses the model on its records and prints (or writes as JSON) the findings.
pub fn run(a: DiagnoseArgs, progress: Progress) -> Result<()> {
    let DiagnoseArgs {
        model,
        data,
        json,
        report,
        thresholds,
        unit,
    } = a;
    // A record given twice is refused before the model is read.
    once_each(&data)?;
    let m = open_model(&model, unit.as_deref())?;
    let inputs: Vec<(&str, Option<&Path>)> = std::iter::once(("--model", Some(model.as_path())))
        .chain(data.iter().map(|d| ("--data", Some(d.as_path()))))
        .collect();
    guard_report(report.as_deref(), &inputs)?;
    let read = records_of(&m, &data)?;
    progress.say("diagnosing (the model's mirror is fitted on its validation rows)");
    let d = dtg_vib::commands::diagnose::diagnose(&m, &read, thresholds)?;
    let options = thresholds.options();
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            let wording = ChannelWording::of_unit(m.unit());
            Some(write_diagnosis_report_of(
                &d,
                options.rank.min_err(),
                &wording,
                dir,
            )?)
        }
        None => None,
    };
    drop(progress);
    read.say_notes();
    if json {
        // stdout holds the one JSON object; the page goes to stderr.
        println!("{}", serde_json::to_string(&d)?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
    } else {
        print_diagnosis(&d);
        if let Some(p) = &page {
            println!("report: {}", p.display());
        }
    }
    Ok(())
}
