//! `dtg-vib explain`: the whole loop (fit, diagnose, add what it suggests,
//! refit) and the rounds it made.

use anyhow::Result;
use clap::Args;
use cli_support::progress::Progress;
use dtg_vib::report::{ChannelWording, write_diagnosis_report_of};
use dtg_vib::unit_sensor::UnitModel;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use sysid::explain::ExplainStage;

use super::findings::print_rounds;
use super::fit::{FitReport, print_fit_channels};
use super::fit_args::{FitArgs, FitRecipe, fit_inputs};
use super::records::{borrowed, signals};
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
    outfile::guard_file("--out", &f.out, &fit_inputs(f))?;
    guard_report(a.report.as_deref(), &fit_inputs(f))?;
    explain_takes(f)?;
    let recipe = FitRecipe::resolve(f)?;
    let unit = &recipe.sensor.unit;
    let named = signals(&recipe.read.records)?;
    let diagnose_options = a.thresholds.options();
    let start = std::time::Instant::now();
    let fitted = AtomicUsize::new(0);
    let n = unit.gyros().len();
    let e = sysid::explain::explain(
        &recipe.sensor,
        &borrowed(&named),
        &recipe.options,
        &diagnose_options,
        a.max_rounds as usize,
        &|stage| show_stage(&progress, &fitted, n, stage),
    )?;
    let seconds = start.elapsed().as_secs_f64();
    let model = UnitModel::of(recipe.with_window(e.model));
    model.save(&f.out)?;
    let page = match &a.report {
        Some(dir) => {
            progress.say("drawing figures");
            let last = &e.rounds.last().expect("at least one round").diagnosis;
            Some(write_diagnosis_report_of(
                last,
                diagnose_options.rank.min_err(),
                &ChannelWording::of_unit(unit),
                dir,
            )?)
        }
        None => None,
    };
    progress.clear();
    recipe.read.say_notes();
    let m = model.inner();
    if f.json {
        let report = ExplainReport {
            unit: unit.name(),
            rounds: &e.rounds,
            converged: e.converged,
            final_fit: FitReport::of_model(m, seconds),
        };
        println!("{}", serde_json::to_string(&report)?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    println!("unit: {} ({})", unit.name(), unit.file());
    print_rounds(&e.rounds, e.converged, a.max_rounds);
    print_fit_channels(m.channels());
    if let Some(w) = m.choice().and_then(|c| c.window_signals.as_ref()) {
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
/// `fitted` counts the round's channels (of `n`), which finish in any order.
fn show_stage(progress: &Progress, fitted: &AtomicUsize, n: usize, stage: ExplainStage<String>) {
    match stage {
        ExplainStage::Fitting(r) => {
            fitted.store(0, Ordering::Relaxed);
            progress.line(format!("round {r}: fitting the {n} channels"));
            progress.say(format!("round {r}: fitting"));
        }
        ExplainStage::ChannelFitted(r, ch) => {
            let k = fitted.fetch_add(1, Ordering::Relaxed) + 1;
            progress.line(format!("round {r}: {ch} fitted ({k} of {n})"));
        }
        ExplainStage::Diagnosing(r) => {
            progress.line(format!(
                "round {r}: diagnosing (the model's mirror, then every candidate effect)"
            ));
            progress.say(format!("round {r}: diagnosing"));
        }
    }
}

/// `explain --json`: every round, whether the loop converged, and the final fit
/// as `fit --json` writes it.
#[derive(serde::Serialize)]
struct ExplainReport<'a> {
    unit: &'a str,
    rounds: &'a [sysid::explain::Round<String, nav_sensors::geometry::Axis>],
    converged: bool,
    #[serde(rename = "final")]
    final_fit: FitReport,
}
