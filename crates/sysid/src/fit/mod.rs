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
mod choice;
mod digest;
mod input_sample;
mod judged;
mod keep;
mod keep_bi;
mod memo;
mod network;
mod partial;
mod shared;
mod theta_memo;

use crate::error::SysidError;
use crate::model::{ChannelModelOf, Model, ModelParts};
use crate::operating::OperatingPoints;
use crate::operating::range::TrainingRange;
use crate::prepared::Prepared;
use crate::recipe::{FitOptions, Recipe};
use crate::sensor::Sensor;
use crate::signals::Signals;
use crate::split::{by_record_rows, split_rows};
use channel::{
    ChannelFit, gather, inner_folds_fit, predictions, refit_weights, scored, windows_vary,
};
use rayon::prelude::*;
use serde::Serialize;

pub use choice::{
    ADEV_CONFIDENCE, Candidate, ChoiceReport, InputSample, MIN_ADEV_ROWS, ModelChoice,
    SMALLER_INPUT_TOLERANCE, SharedCentresTrial,
};
pub use input_sample::SHARED_CENTRES_TOLERANCE;
pub(crate) use keep::fixed_report;
pub use partial::MIN_BLOCK_ROWS;
pub(crate) use partial::{cross_fitted_theta, raw_windows, theta_rows};

/// Which stage of a fit is running, for progress display.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitStage<C> {
    /// Reading and pre-processing the records.
    Preparing,
    /// One channel's cross-validation and fit finished.
    ChannelDone(C),
}

/// A fit's progress callback.
pub type Progress<'a, C> = &'a (dyn Fn(FitStage<C>) + Sync);

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
/// the sensor, with its calibration, comes from `prepared`).
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
        &options.recipe,
        (&train, &val),
        Coef::AllRows,
        progress,
    )?;
    model.set_validated_on(options.validate_on.clone());
    Ok(model)
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
/// samples, split within each record: the trial the diagnosis's advice on a
/// slow residual rests on.
pub fn refit_with_window<S: Sensor>(
    model: &Model<S>,
    records: &[(String, &Signals)],
    length: usize,
) -> Result<Model<S>, SysidError> {
    let mut recipe = model.recipe();
    let signals = recipe.preprocess.window.signals().to_vec();
    recipe.preprocess.window = crate::WindowSpec::new(signals, length)?;
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
            &options.recipe,
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

/// Which rows estimate the effects' coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Coef<'a> {
    /// Training and validation rows of every record given: the estimate
    /// the diagnosis makes (cross-fitted partialling over the whole
    /// record), so the model stores one estimate of each coefficient, not a
    /// noisier one from half the rows. A few coefficients estimated on the
    /// validation rows barely flatter the validation rms; the network, which
    /// could, still sees only the training rows.
    AllRows,
    /// Training rows only: where the validation rows judge a transfer
    /// (leaving a record out).
    TrainingRows,
    /// Each channel's coefficients already estimated on every row (a
    /// model's, for its mirror), in the channel order; a channel without
    /// them (no effects, or none estimated) is estimated as with `AllRows`.
    Stored(&'a [Vec<crate::inference::Coefficient>]),
}

impl Coef<'_> {
    /// Channel `channel`'s stored coefficients, when there is one for each
    /// of its `n_effects` effects.
    fn stored(&self, channel: usize, n_effects: usize) -> Option<&[crate::inference::Coefficient]> {
        match self {
            Coef::Stored(all) => all
                .get(channel)
                .filter(|c| c.len() == n_effects && n_effects > 0)
                .map(Vec::as_slice),
            _ => None,
        }
    }
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
        Some(c) => choice::fit_choosing(prepared, recipe, c, (train, val), coef, progress)?,
        None => {
            let mut model = fit_rows_fixed(prepared, recipe, (train, val), coef, progress)?;
            if recipe.preprocess.smoother.is_some() {
                choice::rescore(&mut model, prepared, train, val)?;
            }
            model
        }
    };
    keep::apply(model, prepared, train, val)
}

/// [`fit_rows`] with the recipe's input and without rescoring for a smoother.
fn fit_rows_fixed<S: Sensor>(
    prepared: &Prepared<S>,
    recipe: &Recipe<S::Effect>,
    rows: (&[usize], &[usize]),
    coef: Coef<'_>,
    progress: Progress<'_, S::Channel>,
) -> Result<Model<S>, SysidError> {
    fit_rows_predicting(prepared, recipe, rows, coef, progress).map(|(model, _)| model)
}

/// [`fit_rows_fixed`], with the model's unsmoothed predictions on every row
/// of `prepared` (per channel), which scored it.
fn fit_rows_predicting<S: Sensor>(
    prepared: &Prepared<S>,
    recipe: &Recipe<S::Effect>,
    (train, val): (&[usize], &[usize]),
    coef: Coef<'_>,
    progress: Progress<'_, S::Channel>,
) -> Result<(Model<S>, Vec<Vec<f64>>), SysidError> {
    debug_assert_eq!(prepared.preprocess(), &recipe.preprocess);
    let settings = &recipe.settings;
    let channels = prepared.sensor().channels();
    let (train, val) = (train.to_vec(), val.to_vec());
    // A view of the prepared windows, not a copy: only the rows a fit works
    // on are gathered (all training rows, or the selection subsample).
    let x = prepared.window_view();
    windows_vary(x, &train, recipe.preprocess.window.signals())?;
    let stride = selection_stride(train.len());
    let sel: Vec<usize> = train.iter().step_by(stride).copied().collect();
    inner_folds_fit(prepared, sel.len(), settings.inner_folds)?;
    let fit_on = if stride > 1 { &sel } else { &train };
    let theta_rows: Vec<usize> = match coef {
        Coef::AllRows | Coef::Stored(_) => partial::theta_rows(&train, &val),
        Coef::TrainingRows => fit_on.clone(),
    };
    // The effects are partialled out with the raw windows whatever the
    // input (one estimate of each coefficient, whichever input the choice
    // takes); they are prepared only when some channel cross-fits.
    let cross_fits = (0..channels.len()).any(|k| {
        let n = recipe.effects_of(k).len();
        n > 0 && coef.stored(k, n).is_none()
    });
    let raw = match cross_fits {
        true => partial::raw_windows(prepared)?,
        false => None,
    };
    let x_theta = raw.as_ref().map_or(x, |p| p.window_view());
    let x_fit = gather(x, fit_on);
    let remembered = (!settings.shared_centres)
        .then(|| memo::Records::of(prepared, (x, x_theta)))
        .flatten();
    let known = |k: usize| coef.stored(k, recipe.effects_of(k).len());
    let rows = (fit_on.as_slice(), theta_rows.as_slice());
    let fits: Vec<ChannelFit<S>> = match settings.shared_centres {
        true => shared::fit_channels_shared(prepared, (x, x_theta), &x_fit, rows, recipe, &known)?,
        // Each channel's own network, their candidate columns computed once.
        false => batched::fit_channels(
            remembered,
            prepared,
            (x, x_theta),
            &x_fit,
            rows,
            recipe,
            &known,
        )?,
    };
    channels
        .iter()
        .for_each(|c| progress(FitStage::ChannelDone(c.clone())));
    drop(x_fit);
    // On a subsample, the weights are solved again on every training row,
    // over row blocks (memory independent of the number of rows), before
    // the channel is scored: for channels that share centres, in one solve.
    let fits = match (stride, settings.shared_centres) {
        (1, _) => fits,
        (_, true) => shared::refit_weights_shared(prepared, x, &train, fits, settings)?,
        (_, false) => fits
            .into_par_iter()
            .map(|f| refit_weights(prepared, x, &train, f, settings))
            .collect::<Result<_, _>>()?,
    };
    let yhat = predictions(&fits, x);
    let fitted: Vec<ChannelModelOf<S>> = fits
        .into_iter()
        .zip(&yhat)
        .map(|(f, y)| scored(prepared, &train, &val, f, y))
        .collect::<Result<_, _>>()?;
    let length = recipe.preprocess.window.length();
    let mut operating_points = OperatingPoints::from_training(prepared, length, &train, &val)?;
    // The range's tolerance is measured on every row that did not train
    // (validation and the gaps): the records fitted on stay inside, to the bit.
    let mut trained = vec![false; prepared.rows()];
    train.iter().for_each(|&r| trained[r] = true);
    let others: Vec<usize> = (0..prepared.rows()).filter(|&r| !trained[r]).collect();
    // The network at rest: where a record that starts outside holds it.
    let rest = crate::operating::fade::rest_rows(prepared, length, &train)?;
    let means = crate::operating::fade::network_means::<S>(&fitted, x, &rest);
    operating_points.range = Some(TrainingRange::from_training(
        prepared, length, &train, &others, means,
    )?);
    let operating_points = Some(operating_points);
    let model = Model::from_parts(ModelParts {
        sensor: prepared.sensor().clone(),
        preprocess: recipe.preprocess.clone(),
        dt_s: prepared.calibrated().dt(),
        split: recipe.split,
        channels: fitted,
        settings: settings.clone(),
        records: Vec::new(),
        validated_on: None,
        operating_points,
        choice: None,
    })
    .map_err(|reason| SysidError::InvalidOption {
        name: "fitted model",
        value: reason,
        reason: "a fit gave an inconsistent model (a bug: please report it)",
    })?;
    Ok((model, yhat))
}

/// Training windows above which cross-validation and centre selection run on
/// every `selection_stride`-th of them; the weights are still solved on all.
/// Their cost is rows × candidates per fold and channel: 1.6 GB a channel at
/// 500,000 rows, where a 1M-row record needed 6 GB and over 5 minutes. On
/// the 1M-sample record of docs/performance.md, 25,000 selection rows
/// instead of 50,000 took the fit from 52 s to 33 s with every channel's
/// validation rms within 1% (0.6% lower to 0.1% higher); 10,000 took 22 s
/// but raised Z1's by 1.5%.
pub const MAX_SELECTION_ROWS: usize = 25_000;

/// The stride of the training windows that choose centres and width: 1 up to
/// [`MAX_SELECTION_ROWS`]. A stride keeps time order, so the blocked folds'
/// leakage gap of g rows spans g·stride samples, never fewer than needed.
///
/// ```
/// assert_eq!(sysid::fit::selection_stride(25_000), 1);
/// assert_eq!(sysid::fit::selection_stride(500_000), 20);
/// ```
pub fn selection_stride(n_train: usize) -> usize {
    n_train.div_ceil(MAX_SELECTION_ROWS).max(1)
}
