//! Fitting a sensor's channel models: physical effects and an RBF on the
//! input windows, fitted together, with the width and the number of
//! centres chosen by blocked cross-validation inside the training rows.
//!
//! Together, not in stages: the effect columns (e.g. a gyro's g_I ∝ a_z)
//! and the RBF features (functions of the a_z window) are correlated, and a
//! staged fit would hand the shared part to whichever stage runs first. The
//! effects' coefficients come from cross-fitted partialling out
//! ([`partial`]), the network is fitted on what they leave, and the OLS
//! engine takes any forced columns first, so the centres explain only what
//! the physics does not.
//!
//! This is also the layer the diagnosis asks for the fits it needs and does
//! not make itself: the model's [`mirror`] and a [`refit_with_window`].

mod batched;
mod channel;
mod fixed;
mod input_choice;
mod input_sample;
mod keep;
mod memo;
mod network;
mod partial;
mod progress;
mod shared;

use crate::error::SysidError;
use crate::model::Model;
use crate::prepared::Prepared;
use crate::recipe::{FitOptions, Recipe};
use crate::sensor::Sensor;
use crate::signals::Signals;
use crate::split::{by_record_rows, split_rows};
use fixed::{Coef, fit_rows_fixed};
use serde::Serialize;
use std::borrow::Cow;

pub use input_choice::{
    ADEV_CONFIDENCE, Candidate, ChoiceReport, InputSample, MIN_ADEV_ROWS, ModelChoice,
    SMALLER_INPUT_TOLERANCE, SharedCentresTrial,
};
pub use input_sample::SHARED_CENTRES_TOLERANCE;
pub use memo::digest::{Digest, Digester, Store};
pub use network::{MAX_SELECTION_ROWS, selection_stride};
pub use partial::MIN_BLOCK_ROWS;
pub(crate) use partial::{cross_fitted_theta, raw_windows, theta_rows};
pub use progress::{FitStage, Progress};

/// Fits every channel of `sensor` on one raw record.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.effects[0] = vec![sysid::example::Slope];
/// options.recipe.settings.max_centres = 5;
/// let model = sysid::fit(&Line, &line_record(3000, 2.0, 1), &options, &|_| {})?;
/// let slope = &model.channel(0).coefficients().unwrap()[0];
/// assert!(slope.covers(2.0), "{slope:?}");
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn fit<S: Sensor>(
    sensor: &S,
    record: &Signals,
    options: &FitOptions<S::Effect>,
    progress: Progress<'_, S::Channel>,
) -> Result<Model<S>, SysidError> {
    options.recipe.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new(sensor, record, &options.recipe.preprocess)?;
    fit_prepared(&prepared, options, progress)
}

/// [`fit`] on records already prepared (with `options.recipe.preprocess`;
/// the sensor, with its calibration, comes from `prepared`, and so do the
/// window's signals when the recipe left them to the records: the model
/// then reports their choice).
pub fn fit_prepared<S: Sensor>(
    prepared: &Prepared<S>,
    options: &FitOptions<S::Effect>,
    progress: Progress<'_, S::Channel>,
) -> Result<Model<S>, SysidError> {
    options.recipe.settings.check()?;
    let (train, val) = match &options.validate_on {
        Some(name) => by_record_rows(prepared, name)?,
        None => split_rows(prepared, options.recipe.split)?,
    };
    let mut model = fit_rows(
        prepared,
        &as_prepared(&options.recipe, prepared),
        (&train, &val),
        Coef::AllRows,
        progress,
    )?;
    model.set_validated_on(options.validate_on.clone());
    if !prepared.window_choice().is_empty() {
        model = model.with_window_signals(prepared.window_choice().to_vec());
    }
    Ok(model)
}

/// `recipe` with the window's signals `prepared` chose, where it left them
/// to the records ([`crate::window::WindowSignals::Auto`]).
fn as_prepared<'r, E: Clone>(
    recipe: &'r Recipe<E>,
    prepared_with: &Prepared<impl Sensor>,
) -> Cow<'r, Recipe<E>> {
    if !recipe.preprocess.window.is_auto() {
        return Cow::Borrowed(recipe);
    }
    let mut named = recipe.clone();
    named.preprocess.window = prepared_with.preprocess().window.clone();
    Cow::Owned(named)
}

/// [`fit`] on several records, each prepared on its own (filters and
/// windows never cross a boundary) and named for errors and scores.
pub fn fit_records<S: Sensor>(
    sensor: &S,
    records: &[(String, &Signals)],
    options: &FitOptions<S::Effect>,
    progress: Progress<'_, S::Channel>,
) -> Result<(Model<S>, Prepared<S>), SysidError> {
    options.recipe.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new_many(sensor, records, &options.recipe.preprocess)?;
    let mut model = fit_prepared(&prepared, options, progress)?;
    model.set_records(record_names(records));
    // The records as the model reads them (a choice may have taken another input).
    let input = model.preprocess().input;
    let prepared = match prepared.preprocess().input == input {
        true => prepared,
        false => prepared.with_input(input)?,
    };
    Ok((model, prepared))
}

/// The names a model or diagnosis keeps of its records: none for one
/// record (its file is said where it is given), every one of several.
pub(crate) fn record_names(records: &[(String, &Signals)]) -> Vec<String> {
    match records.len() {
        1 => Vec::new(),
        _ => records.iter().map(|(n, _)| n.clone()).collect(),
    }
}

/// The model's mirror, which the diagnosis's cross-fit reads: its recipe
/// trained on its validation rows of `prepared` (the records it was fitted
/// on, prepared by [`Model::prepare_many`]) and validated on its training
/// rows, so that between the model and its mirror every row has a
/// prediction from a model that did not see it.
pub fn mirror<S: Sensor>(model: &Model<S>, prepared: &Prepared<S>) -> Result<Model<S>, SysidError> {
    let (train, val) = model.rows(prepared)?;
    // The model's own input and smoother, not a choice of its own.
    let mut recipe = model.recipe();
    recipe.settings.choice = None;
    // The effects' coefficients are the model's: the same rows cross-fitted
    // the same way would give the same numbers (one estimate of each), so
    // the mirror fits only its networks.
    let stored: Vec<Vec<crate::inference::Coefficient>> = model
        .channels()
        .iter()
        .map(|c| c.coefficients().map(<[_]>::to_vec).unwrap_or_default())
        .collect();
    // The mirror trains on the validation rows: a short record's folds are
    // too few there, not on the training rows the message would name.
    fit_rows(
        prepared,
        &recipe,
        (&val, &train),
        Coef::Stored(&stored),
        &|_| {},
    )
    .map_err(|e| match e {
        SysidError::InnerFoldsEmpty {
            folds,
            n_train,
            gap,
            window,
            filter_memory,
        } => SysidError::MirrorFoldsEmpty {
            folds,
            n_val: n_train,
            gap,
            window,
            filter_memory,
        },
        e => e,
    })
}

/// `model`'s recipe fitted again on `records` with windows of `length`
/// samples, split within each record, on the input the model's choice took
/// (its smoother chosen again): the trial the diagnosis's advice on a slow
/// residual rests on.
pub fn refit_with_window<S: Sensor>(
    model: &Model<S>,
    records: &[(String, &Signals)],
    length: usize,
) -> Result<Model<S>, SysidError> {
    let mut recipe = model.recipe();
    // The input the model's choice took on these records: the trial varies
    // the window alone (its smoother is still chosen). Fitting every input
    // again cost more than the rest of the loop (the raw input of a
    // 150-sample window over three axes is 450 columns).
    if let Some(choice) = recipe.settings.choice.as_mut() {
        choice.inputs = vec![recipe.preprocess.input];
    }
    recipe.preprocess.window = recipe.preprocess.window.with_length(length)?;
    let prepared = Prepared::new_many(model.sensor(), records, &recipe.preprocess)?;
    let (train, val) = split_rows(&prepared, recipe.split)?;
    let mut trial = fit_rows(&prepared, &recipe, (&train, &val), Coef::AllRows, &|_| {})?;
    trial.set_records(record_names(records));
    Ok(trial)
}

/// One record's validation rms of one channel, in the target's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordScore {
    /// The record's name (its file).
    pub file: String,
    /// Rms of target − model on the record's validation rows.
    pub val_rms: f64,
}

/// Each channel's validation rms on each record of `prepared`, for the
/// validation rows the model was fitted with (the sensor's channel order);
/// a record without validation rows (it only trained) is left out.
pub fn record_scores<S: Sensor>(
    model: &Model<S>,
    prepared: &Prepared<S>,
) -> Result<Vec<Vec<RecordScore>>, SysidError> {
    let val = match model.validated_on() {
        // A by-record fit validated on one whole record: asked of data without
        // it, that is an error naming the record, not another split.
        Some(name) => by_record_rows(prepared, name)?.1,
        None => model.rows(prepared)?.1,
    };
    let predicted = model.predict(prepared)?;
    Ok((0..model.channels().len())
        .map(|k| {
            let y = prepared.target(k);
            prepared
                .record_rows()
                .into_iter()
                .filter_map(|(name, range)| {
                    let rows: Vec<usize> =
                        val.iter().copied().filter(|r| range.contains(r)).collect();
                    (!rows.is_empty()).then(|| RecordScore {
                        file: name.to_string(),
                        val_rms: stats::rms(
                            &rows
                                .iter()
                                .map(|&r| y[r] - predicted[k][r])
                                .collect::<Vec<_>>(),
                        ),
                    })
                })
                .collect()
        })
        .collect())
}

/// Leave one record out: each record validated, whole, by a model fitted
/// on the others; each channel's rms per record.
pub fn leave_one_record_out<S: Sensor>(
    prepared: &Prepared<S>,
    options: &FitOptions<S::Effect>,
) -> Result<Vec<Vec<RecordScore>>, SysidError> {
    let mut out: Vec<Vec<RecordScore>> = vec![Vec::new(); prepared.sensor().channels().len()];
    for (name, _) in prepared.record_rows() {
        let (train, val) = by_record_rows(prepared, name)?;
        // The left-out record judges the model: its rows estimate nothing,
        // not even the effects' coefficients.
        let m = fit_rows(
            prepared,
            &as_prepared(&options.recipe, prepared),
            (&train, &val),
            Coef::TrainingRows,
            &|_| {},
        )
        .map_err(|e| SysidError::InRecord {
            record: format!("leaving out {name}"),
            source: Box::new(e),
        })?;
        for (k, c) in m.channels().iter().enumerate() {
            out[k].push(RecordScore {
                file: name.to_string(),
                val_rms: c.scores().val_rms,
            });
        }
    }
    Ok(out)
}

/// A recipe fitted on explicit training and validation rows of data
/// prepared with its pre-processing (the mirror trains on a model's
/// validation rows; leaving a record out trains on the others): with its
/// settings' choice of input and smoother if it has one, else as it is.
fn fit_rows<S: Sensor>(
    prepared: &Prepared<S>,
    recipe: &Recipe<S::Effect>,
    (train, val): (&[usize], &[usize]),
    coef: Coef<'_>,
    progress: Progress<'_, S::Channel>,
) -> Result<Model<S>, SysidError> {
    let model = match &recipe.settings.choice {
        Some(c) => input_choice::fit_choosing(prepared, recipe, c, (train, val), coef, progress)?,
        None => {
            let mut model = fit_rows_fixed(prepared, recipe, (train, val), coef, progress)?;
            if recipe.preprocess.smoother.is_some() {
                input_choice::rescore(&mut model, prepared, train, val)?;
            }
            model
        }
    };
    keep::apply(model, prepared, train, val)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::example::{Line, line_record};

    /// The default recipe names no signal: the records choose among the
    /// sensor's operating signals when they are prepared, the model's
    /// window names what they chose, and its report says why; a window
    /// named by the recipe is taken as it is, with nothing to report.
    #[test]
    fn the_default_window_is_chosen_from_the_records() {
        let rec = line_record(2000, 1.0, 3);
        let mut options = FitOptions::<crate::example::Slope>::new(1);
        assert!(options.recipe.preprocess.window.is_auto());
        options.recipe.preprocess.filter = None;
        options.recipe.settings.max_centres = 5;
        let (model, prepared) =
            fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {}).unwrap();
        assert_eq!(model.preprocess().window.signals(), ["u"]);
        assert_eq!(model.preprocess().window.length(), 50);
        assert_eq!(prepared.preprocess().window, model.preprocess().window);
        let chosen = model.choice().and_then(|c| c.window_signals.first());
        assert_eq!(chosen.map(|c| c.taken.clone()), Some(vec!["u".to_string()]));
        // The model's recipe names the signals: a refit chooses nothing again.
        assert!(!model.recipe().preprocess.window.is_auto());

        options.recipe.preprocess.window =
            crate::window::WindowSpec::new(vec!["u".into()], 50).unwrap();
        let (named, _) = fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {}).unwrap();
        assert!(named.choice().is_none_or(|c| c.window_signals.is_empty()));
        assert_eq!(named.channel(0).scores(), model.channel(0).scores());
    }
}
