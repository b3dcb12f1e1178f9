//! `dtg-vib allan`: overlapping Allan deviation and IEEE 952 noise terms of
//! every channel and residue, before and after a model.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::model::CompensationModel;
use nav_sensors::record::Record;
use std::path::PathBuf;

use super::report::guard_report;

/// The flags of `allan`.
#[derive(Args)]
pub struct AllanArgs {
    /// Test record (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Model file from `fit`: adds the curves after its compensation.
    #[arg(long)]
    model: Option<PathBuf>,
    /// Two-sided confidence level of the intervals.
    #[arg(long, default_value_t = 0.683)]
    confidence: f64,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Write the log-log figures and index.html into this directory.
    #[arg(long)]
    report: Option<PathBuf>,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
    #[arg(long)]
    unit: Option<String>,
}

/// Computes the deviations and prints (or writes as JSON) the noise terms.
pub fn run(a: AllanArgs, progress: Progress) -> Result<()> {
    let AllanArgs {
        data,
        model,
        confidence,
        json,
        report,
        unit,
    } = a;
    let unit_model = match &model {
        Some(m) => super::unit::model_unit(m, unit.as_deref())?,
        None => None,
    };
    let chosen = match &unit_model {
        Some(m) => Some(m.unit().clone()),
        None if model.is_none() => super::unit::chosen(unit.as_deref())?,
        None => None,
    };
    guard_report(
        report.as_deref(),
        &[("--data", Some(&data)), ("--model", model.as_deref())],
    )?;
    if let Some(u) = chosen {
        let run = super::unit::allan::AllanRun {
            model: unit_model.as_ref(),
            confidence,
            json,
            report: report.as_deref(),
        };
        return super::unit::allan::allan(&u, &data, run, progress);
    }
    let record = Record::read_csv(&data)?;
    let m = model.as_ref().map(CompensationModel::load).transpose()?;
    progress.say("computing Allan deviations");
    let a = dtg_vib::allan::AllanAnalysis::new(&record, m.as_ref(), confidence)?;
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(dtg_vib::report::write_allan_report(
                &a,
                &data.display().to_string(),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    if json {
        println!("{}", serde_json::to_string(&a.to_json())?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    let tau = &a.channels[0].before.points;
    println!(
        "Overlapping Allan deviation of {}: {} samples from sample {}{}, τ = {} to {} s; {:.1}% intervals",
        data.display(),
        a.samples,
        a.first_sample,
        first_sample_why(a.first_sample),
        tau.first().map_or(0.0, |p| p.tau_s),
        tau.last().map_or(0.0, |p| p.tau_s),
        100.0 * a.confidence
    );
    let text = dtg_vib::allan::term_text;
    let mut unresolved = false;
    for (what, pick) in [
        (
            "angle random walk (deg/√h)",
            (|t| &t.arw) as fn(&nav_sensors::noise::NoiseTerms) -> &nav_sensors::noise::NoiseTerm,
        ),
        ("bias instability (deg/h)", |t| &t.bias_instability),
        ("rate random walk (deg/h/√h)", |t| &t.rrw),
    ] {
        println!("{what:<27} {:<40} after", "before");
        for s in a.channels.iter().chain(&a.residues) {
            let (before, after) = (
                text(pick(&s.terms_before)),
                s.terms_after.as_ref().map_or("—".into(), |t| text(pick(t))),
            );
            unresolved |= before.contains("not resolved") || after.contains("not resolved");
            println!("{:>27} {before:<40} {after}", s.name);
        }
    }
    if unresolved {
        println!("{NOT_RESOLVED}");
    }
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}

/// Why the analysis starts at `first` (0-based), where it does not start
/// at the record's first sample: rows before the model's first full window
/// have no compensation, and before and after must cover the same samples.
fn first_sample_why(first: usize) -> &'static str {
    match first {
        0 => "",
        _ => {
            " (the first with a full window of the model: before and after cover the same samples)"
        }
    }
}

/// What "< bound (not resolved)" in the tables says.
const NOT_RESOLVED: &str = "< bound (not resolved): the curve shows no region of this term's slope; the bound is the largest value every τ still allows";
