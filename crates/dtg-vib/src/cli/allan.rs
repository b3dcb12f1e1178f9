//! `dtg-vib allan`: overlapping Allan deviation and IEEE 952 noise terms of
//! every channel and residue, before and after a model. The work is
//! [`dtg_vib::commands::allan`]'s; here the flags and the printing.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::numfmt::short;
use std::path::PathBuf;

use super::report::guard_report;
use dtg_vib::commands::allan::{DEFAULT_CONFIDENCE, allan};
use dtg_vib::commands::records::{no_residue_note, read_records, unit_and_min};
use dtg_vib::unit_sensor::{RateReference, UnitModel};

/// The flags of `allan`.
#[derive(Args)]
pub struct AllanArgs {
    /// Test record (CSV; of a log with time gaps, the longest segment
    /// between them: an average never spans a gap).
    #[arg(long)]
    data: PathBuf,
    /// Model file from `fit`: adds the curves after its compensation.
    #[arg(long)]
    model: Option<PathBuf>,
    /// Two-sided confidence level of the intervals.
    #[arg(long, default_value_t = DEFAULT_CONFIDENCE)]
    confidence: f64,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Write the log-log figures and index.html into this directory.
    #[arg(long)]
    report: Option<PathBuf>,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// (it stores its unit).
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
    let m = model.as_deref().map(UnitModel::load).transpose()?;
    let shown = model.as_deref().map(|p| p.display().to_string());
    let (unit, min) = unit_and_min(
        m.as_ref(),
        shown.as_deref().unwrap_or_default(),
        unit.as_deref(),
    )?;
    guard_report(
        report.as_deref(),
        &[("--data", Some(&data)), ("--model", model.as_deref())],
    )?;
    let read = read_records(std::slice::from_ref(&data), &unit, min)?;
    progress.say("computing Allan deviations");
    let r = allan(&unit, m.as_ref(), &read, confidence)?;
    if let Some(w) = &r.warning {
        progress.clear();
        eprintln!("warning: {w}");
    }
    let (name, a) = (&r.segment, &r.analysis);
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            Some(dtg_vib::report::write_allan_report(a, name, dir)?)
        }
        None => None,
    };
    progress.clear();
    read.say_notes();
    if json {
        println!("{}", r.to_json());
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    let tau = &a.channels[0].before.points;
    println!(
        "Overlapping Allan deviation of {name}{}: {} samples from sample {}{}, τ = {} to {} s; {:.1}% intervals",
        match r.segments {
            1 => "",
            _ => " (the longest segment between time gaps)",
        },
        a.samples,
        a.first_sample,
        first_sample_why(a.first_sample),
        short(tau.first().map_or(0.0, |p| p.tau_s)),
        short(tau.last().map_or(0.0, |p| p.tau_s)),
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
    if let Some(note) = no_residue_note(
        &unit,
        m.as_ref()
            .map_or(&RateReference::None, |m| &m.inner().sensor().rate_reference),
    ) {
        println!("{note}");
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
