//! `dtg-vib check`: does a model hold on a record it was not fitted on?

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::unit_sensor::Applied;
use dtg_vib::unit_sensor::check::{DEFAULT_OUTSIDE_THRESHOLD, TransferCheck};
use std::path::PathBuf;

use super::report::guard_report;
use super::residues::print_residues_on;
use super::terms;
use dtg_vib::commands::parse::parse_share;
use dtg_vib::commands::records::{no_residue_note, open_model, records_of};
use dtg_vib::commands::report::{Caller, model_page};

/// The flags of `check`.
#[derive(Args)]
pub struct CheckArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// A record the model was not fitted on (CSV; a log with time gaps is
    /// read in segments, compared together).
    #[arg(long)]
    data: PathBuf,
    /// Warn when more than this share of the windows lies outside the training range.
    #[arg(long = "outside-threshold", default_value_t = DEFAULT_OUTSIDE_THRESHOLD, value_parser = parse_share, allow_hyphen_values = true)]
    outside_threshold: f64,
    /// Print one JSON object on stdout.
    #[arg(long)]
    json: bool,
    /// Also write the model's report on this record (figures and index.html) here.
    #[arg(long)]
    report: Option<PathBuf>,
    /// The sensor unit: a unit file (FILE.toml) or a built-in name (paper,
    /// triad, tetra, dual-triad); default paper. Not needed with a model
    /// fitted on another unit (the model stores it).
    #[arg(long)]
    unit: Option<String>,
}

/// Applies the model to the record and prints (or writes as JSON) how it did.
pub fn run(a: CheckArgs, progress: Progress) -> Result<()> {
    let CheckArgs {
        model,
        data,
        outside_threshold,
        json,
        report,
        unit,
    } = a;
    let m = open_model(&model, unit.as_deref())?;
    guard_report(
        report.as_deref(),
        &[("--model", Some(&model)), ("--data", Some(&data))],
    )?;
    let read = records_of(&m, std::slice::from_ref(&data))?;
    progress.say("applying the model");
    let records = read.borrowed();
    // The report needs the split rows too: apply once, with them.
    let applied = match report {
        Some(_) => Applied::new(&m, &records)?,
        None => Applied::unsplit(&m, &records)?,
    };
    let c = dtg_vib::unit_sensor::check::check(&m, &applied, outside_threshold)?;
    let page = match &report {
        Some(dir) => {
            progress.say("drawing figures");
            let data = [data.clone()];
            Some(
                model_page(
                    &m,
                    &model,
                    &read.records,
                    &data,
                    None,
                    dir,
                    Caller::default(),
                )?
                .index,
            )
        }
        None => None,
    };
    progress.clear();
    read.say_notes();
    if json {
        let mut v = serde_json::to_value(&c)?;
        v["unit"] = serde_json::Value::String(m.unit().name().to_string());
        println!("{v}");
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
    } else {
        print_check(&c);
        if let Some(note) = no_residue_note(m.unit(), &m.inner().sensor().rate_reference) {
            println!("{note}");
        }
        if let Some(p) = page {
            println!("report: {}", p.display());
        }
    }
    if let Some(w) = &c.warning {
        eprintln!("warning: {w}");
    }
    if let Some(n) = &c.note {
        eprintln!("note: {n}");
    }
    Ok(())
}

fn print_check(c: &TransferCheck) {
    let cell = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
    // A model with a training range fades its network part outside it: the
    // figures of the model as fitted follow, for comparison.
    let unfaded = c.channels.iter().any(|ch| ch.rms_after_unfaded.is_some());
    let tail = if unfaded {
        "  │ no fade: rms after  mean after  spread after"
    } else {
        ""
    };
    println!(
        "channel  rms before  rms after  mean after  spread after   fit %   inside  outside{tail}  (deg/h)"
    );
    for ch in &c.channels {
        let no_fade = if unfaded {
            format!(
                "  │          {:>9}  {:>10}  {:>12}",
                cell(ch.rms_after_unfaded),
                cell(ch.mean_after_unfaded),
                cell(ch.spread_after_unfaded)
            )
        } else {
            String::new()
        };
        println!(
            "{:>7}  {:>10.4}  {:>9.4}  {:>10.4}  {:>12.4}  {:>6.1}  {:>7}  {:>7}{no_fade}",
            ch.channel,
            ch.rms_before,
            ch.rms_after,
            ch.mean_after,
            ch.spread_after,
            ch.fit_percent,
            cell(ch.rms_inside),
            cell(ch.rms_outside)
        );
    }
    println!("{}", terms::CHECK_COLUMNS);
    if unfaded {
        println!("{}", terms::CHECK_FADE);
    }
    let worse: Vec<&str> = c
        .channels
        .iter()
        .filter(|ch| ch.fit_percent < 0.0)
        .map(|ch| ch.channel.as_str())
        .collect();
    if let Some(line) = terms::negative_fit(&worse) {
        println!("{line}");
    }
    match c.outside_fraction {
        Some(f) => println!(
            "windows outside the training range: {:.1}% of {}; median distance to the nearest training point {:.2}× the reference distance ({}), outside beyond {}×",
            100.0 * f,
            c.windows,
            c.median_relative_distance.unwrap_or(f64::NAN),
            terms::REFERENCE_DISTANCE,
            dtg_vib::operating::OUTSIDE_FACTOR
        ),
        None => {
            println!("windows outside the training range: unknown (model without operating points)")
        }
    }
    if let (Some(r), Some(w)) = (c.outside_range_fraction, c.fade_weight_mean) {
        println!(
            "windows outside the per-axis range (each axis's mean specific force and vibration level as the training windows spanned them): {:.1}%; network part weight {w:.3} on average (1: the model as fitted)",
            100.0 * r
        );
    }
    if c.residues.is_empty() {
        return;
    }
    print_residues_on(&c.residues, "every row");
    if let Some(r) = &c.residues_unfaded {
        println!(
            "no fade: pooled residue rms after {:.4} deg/h (the model as fitted, everywhere)",
            dtg_vib::unit_sensor::pooled(r, |s| s.rms_after)
        );
    }
}
