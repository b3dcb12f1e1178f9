//! `dtg-vib explain`: the whole loop (fit, diagnose, add what it suggests,
//! refit) and the rounds it made.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::explain::ExplainStage;
use dtg_vib::report::write_diagnosis_report;
use nav_sensors::calibration::Calibration;
use nav_sensors::record::Record;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::findings::print_rounds;
use super::fit::{FitReport, print_fit, with_window_signals};
use super::fit_args::{FitArgs, fit_inputs, fit_options, read_records, window_signals};
use super::report::guard_report;
use super::thresholds::Thresholds;

/// The flags of `explain`: a fit's, the diagnosis thresholds and the loop's own.
#[derive(Args)]
pub struct ExplainArgs {
    #[command(flatten)]
    fit: FitArgs,
    #[command(flatten)]
    thresholds: Thresholds,
    /// Most fits to make (the first one included).
    #[arg(long = "max-rounds", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
    max_rounds: u64,
    /// Write the final model's diagnosis figures and index.html into this directory.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// The fit flag `explain` cannot honour, refused with why and what to do
/// instead: its rounds judge effects on the model's own split.
fn explain_takes(f: &FitArgs) -> Result<()> {
    if f.cv.is_some() {
        anyhow::bail!(
            "explain does not take --cv: each round judges effects on the model's own split; run dtg-vib fit --cv records with the effects explain added (--add-effect CHANNEL=ID) to see each record predicted by a model of the others"
        );
    }
    Ok(())
}

/// Runs the loop, saves the final model and prints the rounds.
pub fn run(a: ExplainArgs, progress: Progress) -> Result<()> {
    let f = &a.fit;
    if let Some(unit) = super::unit::chosen(f.unit.as_deref())? {
        explain_takes(f)?;
        guard_report(a.report.as_deref(), &fit_inputs(f))?;
        return super::unit::fit::explain(
            f,
            unit,
            &a.thresholds.options(),
            a.max_rounds as usize,
            a.report.as_deref(),
            progress,
        );
    }
    outfile::guard_file("--out", &f.out, &fit_inputs(f))?;
    guard_report(a.report.as_deref(), &fit_inputs(f))?;
    explain_takes(f)?;
    let mut options = fit_options(f)?;
    let records = read_records(f)?;
    let named: Vec<(String, &Record)> = records.iter().map(|(n, r)| (n.clone(), r)).collect();
    let calibration = f.calib.as_ref().map(Calibration::load).transpose()?;
    let window = window_signals(f, &mut options.preprocess.window, || {
        Ok(dtg_vib::fit::choose_window_signals(
            &named,
            calibration.as_ref(),
        )?)
    })?;
    let diagnose_options = a.thresholds.options();
    let start = std::time::Instant::now();
    let fitted = AtomicUsize::new(0);
    let mut e = dtg_vib::explain::explain_records(
        &named,
        calibration.as_ref(),
        &options,
        &diagnose_options,
        a.max_rounds as usize,
        &|stage| show_stage(&progress, &fitted, stage),
    )?;
    let seconds = start.elapsed().as_secs_f64();
    e.model = with_window_signals(e.model, window);
    e.model.save(&f.out)?;
    let page = match &a.report {
        Some(dir) => {
            progress.say("drawing figures");
            let last = &e.rounds.last().expect("at least one round").diagnosis;
            Some(write_diagnosis_report(
                last,
                diagnose_options.rank.min_err(),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    if f.json {
        let report = ExplainReport {
            rounds: &e.rounds,
            converged: e.converged,
            final_fit: FitReport::new(&e.model, seconds),
        };
        println!("{}", serde_json::to_string(&report)?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    print_rounds(&e.rounds, e.converged, a.max_rounds);
    print_fit(&e.model);
    if let Some(w) = e
        .model
        .inner()
        .choice()
        .and_then(|c| c.window_signals.as_ref())
    {
        println!("{}", w.line());
    }
    println!("model: {} ({:.1} s)", f.out.display(), seconds);
    if let Some(p) = &page {
        println!("report: {}", p.display());
    }
    Ok(())
}

/// A round's steps as lines that stay on the terminal (a round over several
/// records takes tens of seconds), and the current one on the spinner;
/// `fitted` counts the round's channels, which finish in any order.
fn show_stage(progress: &Progress, fitted: &AtomicUsize, stage: ExplainStage) {
    match stage {
        ExplainStage::Fitting(n) => {
            fitted.store(0, Ordering::Relaxed);
            progress.line(format!("round {n}: fitting the six channels"));
            progress.say(format!("round {n}: fitting"));
        }
        ExplainStage::ChannelFitted(n, ch) => {
            let k = fitted.fetch_add(1, Ordering::Relaxed) + 1;
            progress.line(format!("round {n}: {} fitted ({k} of 6)", ch.name()));
        }
        ExplainStage::Diagnosing(n) => {
            progress.line(format!(
                "round {n}: diagnosing (the model's mirror, then every candidate effect)"
            ));
            progress.say(format!("round {n}: diagnosing"));
        }
    }
}

/// `explain --json`: every round, whether the loop converged, and the final fit
/// as `fit --json` writes it.
#[derive(serde::Serialize)]
struct ExplainReport<'a> {
    rounds: &'a [dtg_vib::explain::Round],
    converged: bool,
    #[serde(rename = "final")]
    final_fit: FitReport,
}
