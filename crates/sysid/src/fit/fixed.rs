//! One fit of a recipe as it is: its input and smoother, on given training
//! and validation rows, every channel's effects and network, scored, with
//! the operating points and training range the model keeps. The choice of
//! input and smoother ([`super::input_choice`]) runs it once per input.

use super::batched;
use super::channel::{
    ChannelFit, channel_predictions, gather, inner_folds_fit, refit_weights, scored, windows_vary,
};
use super::memo::channel_fits::Records;
use super::network::selection_stride;
use super::partial;
use super::progress::{FitStage, Progress};
use super::shared;
use crate::error::SysidError;
use crate::inference::Coefficient;
use crate::model::{ChannelModelOf, Model, ModelParts, channel_network_means};
use crate::operating::OperatingPoints;
use crate::operating::fade::rest_rows;
use crate::operating::range::TrainingRange;
use crate::prepared::Prepared;
use crate::recipe::Recipe;
use crate::sensor::Sensor;
use faer::MatRef;
use rayon::prelude::*;

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
    Stored(&'a [Vec<Coefficient>]),
}

impl Coef<'_> {
    /// Channel `channel`'s stored coefficients, when there is one for each
    /// of its `n_effects` effects.
    pub(super) fn stored(&self, channel: usize, n_effects: usize) -> Option<&[Coefficient]> {
        match self {
            Coef::Stored(all) => all
                .get(channel)
                .filter(|c| c.len() == n_effects && n_effects > 0)
                .map(Vec::as_slice),
            _ => None,
        }
    }
}

/// The recipe fitted with its input, without rescoring for a smoother.
pub(super) fn fit_rows_fixed<S: Sensor>(
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
pub(super) fn fit_rows_predicting<S: Sensor>(
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
    // Each group of channels that read the same windows is fitted on a view
    // of them, not a copy: only the rows a fit works on are gathered (all
    // training rows, or the selection subsample).
    let groups = prepared.window_groups();
    for (members, x) in &groups {
        windows_vary(*x, &train, recipe.preprocess.window.signals_of(members[0]))?;
    }
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
    let known = |k: usize| coef.stored(k, recipe.effects_of(k).len());
    let mut fits: Vec<ChannelFit<S>> = Vec::with_capacity(channels.len());
    for (members, x) in groups {
        let x_theta = raw.as_ref().map_or(x, |p| p.window_view(members[0]));
        let rows = (train.as_slice(), fit_on.as_slice(), theta_rows.as_slice());
        let group = (prepared, members.as_slice());
        fits.extend(fit_group(group, (x, x_theta), rows, recipe, &known)?);
    }
    fits.sort_by_key(|f| f.channel);
    channels
        .iter()
        .for_each(|c| progress(FitStage::ChannelDone(c.clone())));
    let yhat = channel_predictions(prepared, &fits);
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
    let rest = rest_rows(prepared, length, &train)?;
    let means = channel_network_means::<S>(&fitted, prepared, &rest);
    operating_points.range = Some(TrainingRange::from_training(
        prepared, length, &train, &others, means,
    )?);
    let operating_points = Some(operating_points);
    let model = Model::from_parts(ModelParts {
        sensor: prepared.sensor().clone(),
        preprocess: recipe.preprocess.clone(),
        dt_s: prepared.calibrated().dt(),
        median_dt_s: Some(median_interval(prepared)),
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

/// The channels `channels` (those that read the windows `x`; `x_theta`
/// their raw windows) fitted on rows `fit_on` of `train`, effects'
/// coefficients on `theta_rows` (or `known(k)`), in the order of
/// `channels`: on a subsample, each network's weights solved again on
/// every training row.
fn fit_group<'a, S: Sensor>(
    (prepared, channels): (&Prepared<S>, &[usize]),
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    (train, fit_on, theta_rows): (&[usize], &[usize], &[usize]),
    recipe: &Recipe<S::Effect>,
    known: &(dyn Fn(usize) -> Option<&'a [Coefficient]> + Sync),
) -> Result<Vec<ChannelFit<S>>, SysidError> {
    let settings = &recipe.settings;
    let x_fit = gather(x, fit_on);
    let remembered = (!settings.shared_centres)
        .then(|| Records::of(prepared, (x, x_theta)))
        .flatten();
    let rows = (fit_on, theta_rows);
    let group = (prepared, channels);
    let fits: Vec<ChannelFit<S>> = match settings.shared_centres {
        true => shared::fit_channels_shared(group, (x, x_theta), &x_fit, rows, recipe, known)?,
        // Each channel's own network, their candidate columns computed once.
        false => {
            batched::fit_channels(remembered, group, (x, x_theta), &x_fit, rows, recipe, known)?
        }
    };
    drop(x_fit);
    // On a subsample, the weights are solved again on every training row,
    // over row blocks (memory independent of the number of rows), before
    // the channel is scored: for channels that share centres, in one solve.
    match (fit_on.len() == train.len(), settings.shared_centres) {
        (true, _) => Ok(fits),
        (false, true) => shared::refit_weights_shared(prepared, x, train, fits, settings),
        (false, false) => fits
            .into_par_iter()
            .map(|f| refit_weights(prepared, x, train, f, settings))
            .collect(),
    }
}

/// The records' median sample interval, s, or their mean where the two
/// agree within 1e-9 (an evenly sampled record, whose median steps differ
/// from the span's mean in the last bits only): a model file then stores
/// the one interval, and reads back equal.
fn median_interval<S: Sensor>(prepared: &Prepared<S>) -> f64 {
    let (mean, median) = (prepared.calibrated().dt(), prepared.median_dt());
    if (median - mean).abs() <= 1e-9 * mean {
        mean
    } else {
        median
    }
}
