//! `dtg-vib check`: does a model hold on a record it was not fitted on?

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::apply::Applied;
use dtg_vib::model::CompensationModel;
use nav_sensors::record::Record;
use std::path::PathBuf;

use super::parse::parse_share;
use super::report::{guard_report, model_report};
use super::residues::print_residues_on;
use super::terms;

/// The flags of `check`.
#[derive(Args)]
pub struct CheckArgs {
    /// Model file from `fit`.
    #[arg(long)]
    model: PathBuf,
    /// A record the model was not fitted on (CSV).
    #[arg(long)]
    data: PathBuf,
    /// Warn when more than this share of the windows lies outside the training range.
    #[arg(long = "outside-threshold", default_value_t = dtg_vib::check::DEFAULT_OUTSIDE_THRESHOLD, value_parser = parse_share, allow_hyphen_values = true)]
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
    let unit_model = super::unit::model_unit(&model, unit.as_deref())?;
    guard_report(
        report.as_deref(),
        &[("--model", Some(&model)), ("--data", Some(&data))],
    )?;
    if let Some(m) = unit_model {
        let page = report.as_deref().map(|dir| (model.as_path(), dir));
        return super::unit::apply::check(&m, &data, outside_threshold, json, page, progress);
    }
    let m = CompensationModel::load(&model)?;
    let record = Record::read_csv(&data)?;
    progress.say("applying the model");
    let (c, page) = match &report {
        // The report needs the split rows too: apply once, with them.
        Some(dir) => {
            let applied = Applied::new(&m, &record)?;
            let c = dtg_vib::check::check_applied(&m, &applied, outside_threshold)?;
            progress.say("drawing figures");
            let summary = model_report((&m, &model), (&record, &data), &applied, None, dir)?;
            (c, Some(summary.index))
        }
        None => (dtg_vib::check::check(&m, &record, outside_threshold)?, None),
    };
    progress.clear();
    if json {
        println!("{}", serde_json::to_string(&c)?);
    } else {
        print_check(&c);
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

fn print_check(c: &dtg_vib::check::TransferCheck) {
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
            ch.channel.name(),
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
        .map(|ch| ch.channel.name())
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
    print_residues_on(&c.residues, "every row");
    if let Some(r) = &c.residues_unfaded {
        let pooled = |rms: fn(&dtg_vib::parity::ResidueStats) -> f64| {
            (r.iter().map(|s| rms(s).powi(2)).sum::<f64>() / r.len().max(1) as f64).sqrt()
        };
        println!(
            "no fade: pooled residue rms after {:.4} deg/h (the model as fitted, everywhere)",
            pooled(|s| s.rms_after)
        );
    }
}
