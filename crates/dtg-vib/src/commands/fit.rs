//! A fit as `dtg-vib fit` makes it: every channel of the unit fitted on the
//! recipe's records, with the window's signals the records chose and the
//! records' names, and each record's validation rms (with `--cv records`,
//! each validated by a model fitted on the others).

use anyhow::Result;

use super::fit_args::FitRecipe;
use super::records::{borrowed, signals};
use crate::unit_sensor::UnitModel;

/// A fitted model and what the fit measured.
pub struct Fitted {
    /// The model, as `--out` saves it.
    pub model: UnitModel,
    /// Each channel's validation rms per record: with several records, or
    /// with `--cv records` (leave one record out).
    pub per_record: Option<Vec<Vec<sysid::fit::RecordScore>>>,
    /// Seconds the fit took.
    pub seconds: f64,
}

/// Fits the recipe's records; `cv` leaves each record out in turn.
/// `progress` hears the loop's stages, and `"leaving one record out"`.
pub fn fit(
    recipe: &FitRecipe,
    cv: bool,
    progress: sysid::fit::Progress<'_, String>,
    say: &dyn Fn(&str),
) -> Result<Fitted> {
    let FitRecipe {
        sensor,
        options,
        read,
        ..
    } = recipe;
    let named = signals(&read.records)?;
    let start = std::time::Instant::now();
    let (model, prepared) = sysid::fit_records(sensor, &borrowed(&named), options, progress)?;
    let mut model = recipe.with_window(model);
    if read.records.len() > 1 {
        model = model.with_records(read.records.iter().map(|(n, _)| n.clone()).collect());
    }
    let per_record = match cv {
        true => {
            say("leaving one record out");
            Some(sysid::fit::leave_one_record_out(&prepared, options)?)
        }
        false if read.records.len() > 1 => Some(sysid::fit::record_scores(&model, &prepared)?),
        false => None,
    };
    Ok(Fitted {
        model: UnitModel::of(model),
        per_record,
        seconds: start.elapsed().as_secs_f64(),
    })
}
