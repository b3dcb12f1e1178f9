//! `dtg-vib explain`: the whole loop (fit, diagnose, add what it suggests,
//! refit) and the rounds it made.

use anyhow::Result;
use cli_support::progress::Progress;
use dtg_vib::commands::explain::{Explained, explain, explain_takes};
use dtg_vib::report::{ChannelWording, write_diagnosis_report_of};
use std::sync::atomic::{AtomicUsize, Ordering};
use sysid::explain::ExplainStage;

pub use dtg_vib::commands::explain::ExplainArgs;

use super::findings::print_rounds;
use super::fit::{FitReport, print_fit_channels, print_frequency_responses};
use super::report::guard_report;
use dtg_vib::commands::fit_args::{FitRecipe, fit_inputs};

/// Runs the loop, saves the final model and prints the rounds.
pub fn run(a: ExplainArgs, progress: Progress) -> Result<()> {
    let f = &a.fit;
    outfile::guard_file("--out", &f.out, &fit_inputs(f))?;
    guard_report(a.report.as_deref(), &fit_inputs(f))?;
    explain_takes(f)?;
    let recipe = FitRecipe::resolve(f)?;
    let unit = &recipe.sensor.unit;
    let fitted = AtomicUsize::new(0);
    let n = unit.gyros().len();
    let Explained {
        rounds,
        converged,
        model,
        seconds,
    } = explain(
        &recipe,
        (a.thresholds, a.report.is_some()),
        a.max_rounds,
        &|stage| show_stage(&progress, &fitted, n, stage),
    )?;
    model.save(&f.out)?;
    let page = match &a.report {
        Some(dir) => {
            progress.say("drawing figures");
            let last = &rounds.last().expect("at least one round").diagnosis;
            Some(write_diagnosis_report_of(
                last,
                a.thresholds.options().rank.min_err(),
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
            rounds: &rounds,
            converged,
            final_fit: FitReport::of_model(m, seconds),
        };
        println!("{}", serde_json::to_string(&report)?);
        if let Some(p) = &page {
            eprintln!("report: {}", p.display());
        }
        return Ok(());
    }
    println!("unit: {} ({})", unit.name(), unit.file());
    print_rounds(&rounds, converged, a.max_rounds);
    print_fit_channels(m.channels());
    print_frequency_responses(m);
    for w in m.choice().iter().flat_map(|c| &c.window_signals) {
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
