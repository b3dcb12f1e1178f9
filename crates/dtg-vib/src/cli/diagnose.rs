//! `dtg-vib diagnose`: what a model is missing, ranked on its records.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::explain::diagnose_records;
use dtg_vib::model::CompensationModel;
use dtg_vib::report::write_diagnosis_report;
use nav_sensors::record::Record;
use std::path::{Path, PathBuf};

use super::findings::print_diagnosis;
use super::fit_args::once_each;
use super::report::guard_report;
use super::thresholds::Thresholds;

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
    let unit_model = super::unit::model_unit(&model, unit.as_deref())?;
    let inputs: Vec<(&str, Option<&Path>)> = std::iter::once(("--model", Some(model.as_path())))
        .chain(data.iter().map(|d| ("--data", Some(d.as_path()))))
        .collect();
    guard_report(report.as_deref(), &inputs)?;
    if let Some(m) = unit_model {
        return super::unit::apply::diagnose(
            &m,
            &data,
            json,
            &thresholds.options(),
            report.as_deref(),
            progress,
        );
    }
    once_each(&data)?;
    let m = CompensationModel::load(&model)?;
    let records = data
        .iter()
        .map(|d| Ok((d.display().to_string(), Record::read_csv(d)?)))
        .collect::<Result<Vec<(String, Record)>>>()?;
    let named: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    progress.say("diagnosing (the model's mirror is fitted on its validation rows)");
    let options = thresholds.options();
    let d = diagnose_records(&m, &named, &options)?;
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(write_diagnosis_report(&d, options.rank.min_err(), dir)?)
        }
        None => None,
    };
    drop(progress);
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
