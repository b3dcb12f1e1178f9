//! The loop as `dtg-vib explain` runs it: fit, diagnose, add every
//! suggested effect, refit, until nothing new is suggested.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

use super::fit_args::{FitArgs, FitRecipe};
use super::records::{borrowed, signals};
use super::thresholds::Thresholds;
use crate::unit_sensor::UnitModel;

/// The loop's rounds and its final model.
pub struct Explained {
    /// The rounds in order, each with its diagnosis.
    pub rounds: Vec<sysid::explain::Round<String, nav_sensors::geometry::Axis>>,
    /// Whether the loop stopped because nothing new was suggested (false: the round limit).
    pub converged: bool,
    /// The final model, as `--out` saves it.
    pub model: UnitModel,
    /// Seconds the loop took.
    pub seconds: f64,
}

/// The flags of `explain`: a fit's, the diagnosis thresholds and the loop's own.
#[derive(Args)]
pub struct ExplainArgs {
    #[command(flatten)]
    pub fit: FitArgs,
    #[command(flatten)]
    pub thresholds: Thresholds,
    /// Most fits to make (the first one included).
    #[arg(long = "max-rounds", default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=50))]
    pub max_rounds: u64,
    /// Write the final model's diagnosis figures and index.html into this directory.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// The fit flag `explain` cannot honour, refused with why and what to do
/// instead: its rounds judge effects on the model's own split.
pub fn explain_takes(f: &FitArgs) -> Result<()> {
    if f.cv.is_some() {
        anyhow::bail!(
            "explain does not take --cv: each round judges effects on the model's own split; run dtg-vib fit --cv records with the effects explain added (--add-effect CHANNEL=ID) to see each record predicted by a model of the others"
        );
    }
    Ok(())
}

/// Runs the loop on the recipe's records, at most `max_rounds` fits; the
/// last diagnosis tries a longer window only when `reported` (its page is
/// the one place that finding shows: the trial refits every channel).
pub fn explain(
    recipe: &FitRecipe,
    (thresholds, reported): (Thresholds, bool),
    max_rounds: u64,
    progress: &(dyn Fn(sysid::explain::ExplainStage<String>) + Sync),
) -> Result<Explained> {
    let named = signals(&recipe.read.records)?;
    let start = std::time::Instant::now();
    let diagnose = sysid::diagnose::DiagnoseOptions {
        try_settings: reported,
        ..thresholds.options()
    };
    let e = sysid::explain::explain(
        &recipe.sensor,
        &borrowed(&named),
        &recipe.options,
        &diagnose,
        max_rounds as usize,
        progress,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(Explained {
        rounds: e.rounds,
        converged: e.converged,
        model: UnitModel::of(recipe.with_window(e.model)),
        seconds,
    })
}
