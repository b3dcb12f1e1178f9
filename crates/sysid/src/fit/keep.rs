//! Each channel keeps its network only where it removes variation.
//!
//! A network fitted to a channel that holds little but noise, or that
//! cannot see what moves the channel on some of its records, predicts
//! structure that is not there: on the campaign's x and y runs the
//! three-run model's networks of Y, Y1 and Z1 read a_z alone, and what they
//! predict from a_z's 1% transverse vibration there (the shape of two
//! Gaussians between rest and the z run's levels) runs against what the x
//! or y vibration does to those channels, which they cannot see: they added
//! 2.5–3.4% to the channels' spread on the very runs they were fitted on
//! (docs/campaign.md §6). So after the fit (and the choice of input and
//! smoother), each channel is judged on its validation rows of every record
//! in turn: where its compensated output varies more about its own mean than
//! what the bias and effects alone leave, or its validation rms is not below
//! the bias-only one,
//! the channel's network is shrunk to zero (its weights solved again
//! against a constant: the bias and the effects, which carry units and
//! intervals, stay). The model file keeps the centres, so every reader
//! (compensate, check, the onboard tables, the C export) reads it as before.

use super::choice::MIN_ADEV_ROWS;
use crate::error::SysidError;
use crate::model::{ChannelModel, Model};
use crate::prepared::Prepared;
use crate::sensor::Sensor;
use faer::{Mat, Par};
use rbf::{CentreSelection, ParamGuard, RbfParams, WidthRule};

/// [`keep_networks`] on the records as the model reads them (a choice may
/// have taken another input than `prepared`'s), the model rescored and the
/// shrunk channels named in its choice report.
pub(super) fn apply<S: Sensor>(
    model: Model<S>,
    prepared: &Prepared<S>,
    train: &[usize],
    val: &[usize],
) -> Result<Model<S>, SysidError> {
    let input = model.preprocess().input;
    let other;
    let p = if prepared.preprocess().input == input {
        prepared
    } else {
        other = prepared.with_input(input)?;
        &other
    };
    let (mut model, dropped) = keep_networks(model, p, train, val)?;
    if dropped.is_empty() {
        return Ok(model);
    }
    super::choice::rescore(&mut model, p, train, val)?;
    if let Some(mut report) = model.choice().cloned() {
        report.networks_shrunk = dropped
            .iter()
            .map(|d| format!("{}: {}", model.channels()[d.channel].channel(), d.reason))
            .collect();
        model.set_choice(report);
    }
    Ok(model)
}

/// Why a channel's network was shrunk to zero, for the fit's report.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Dropped {
    /// The channel's index.
    pub(super) channel: usize,
    /// The record (or `validation rows`) where it added variation, and the
    /// ratio of the spread after to the spread before there.
    pub(super) reason: String,
}

/// The model with the networks that add variation on some record's
/// validation rows (or do not lower the validation rms) shrunk to zero, and
/// which were.
pub(super) fn keep_networks<S: Sensor>(
    model: Model<S>,
    prepared: &Prepared<S>,
    train: &[usize],
    val: &[usize],
) -> Result<(Model<S>, Vec<Dropped>), SysidError> {
    let predicted = model.predict(prepared)?;
    let records = prepared.record_rows();
    let mut dropped = Vec::new();
    for (k, c) in model.channels().iter().enumerate() {
        let y = prepared.target(k);
        let s = crate::model::score(y, &predicted[k], train, val);
        // Before: what the bias and effects leave, so an effect that adds
        // variation is not laid at the network's door.
        let z = prepared.effect_matrix(k, c.effects())?;
        let theta = c.effect_coefficients();
        let effects = |r: usize| (0..theta.len()).map(|j| z[(r, j)] * theta[j]).sum::<f64>();
        let reason = if s.val_rms >= s.val_rms_bias_only {
            Some(format!(
                "validation rms {:.4} not below the bias-only {:.4}",
                s.val_rms, s.val_rms_bias_only
            ))
        } else {
            records.iter().find_map(|(name, range)| {
                let rows: Vec<usize> = val.iter().copied().filter(|r| range.contains(r)).collect();
                if rows.len() < MIN_ADEV_ROWS {
                    return None;
                }
                let before: Vec<f64> = rows.iter().map(|&r| y[r] - effects(r)).collect();
                let after: Vec<f64> = rows.iter().map(|&r| y[r] - predicted[k][r]).collect();
                let ratio = spread(&after) / spread(&before);
                (ratio > 1.0).then(|| {
                    let at = if name.is_empty() { "the record" } else { name };
                    format!("spread after {ratio:.4}× before on {at}'s validation rows")
                })
            })
        };
        if let Some(reason) = reason {
            dropped.push(Dropped { channel: k, reason });
        }
    }
    if dropped.is_empty() {
        return Ok((model, dropped));
    }
    let mut parts = model.into_parts();
    for d in &dropped {
        let k = d.channel;
        parts.channels[k] =
            without_network(prepared, &parts.channels[k], k, train, &parts.settings)?;
        if let Some(range) = parts
            .operating_points
            .as_mut()
            .and_then(|o| o.range.as_mut())
        {
            range.network_mean[k] = 0.0;
        }
    }
    let model = Model::from_parts(parts).map_err(|reason| SysidError::InvalidOption {
        name: "fitted model",
        value: reason,
        reason: "shrinking a network gave an inconsistent model (a bug: please report it)",
    })?;
    Ok((model, dropped))
}

/// The standard deviation of `v` (about its mean).
fn spread(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len().max(1) as f64;
    (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len().max(1) as f64).sqrt()
}

/// Channel `k`'s model with its network's weights solved against a
/// constant (so they are zero to rounding) and its bias the training rows'
/// mean of what the effects leave; centres, width, effects and their
/// coefficients as they were.
fn without_network<S: Sensor>(
    prepared: &Prepared<S>,
    c: &crate::model::ChannelModelOf<S>,
    k: usize,
    train: &[usize],
    settings: &crate::recipe::FitSettings,
) -> Result<crate::model::ChannelModelOf<S>, SysidError> {
    let y = prepared.target(k);
    let z = prepared.effect_matrix(k, c.effects())?;
    let theta = c.effect_coefficients();
    let left = |r: usize| y[r] - (0..theta.len()).map(|j| z[(r, j)] * theta[j]).sum::<f64>();
    let bias = train.iter().map(|&r| left(r)).sum::<f64>() / train.len().max(1) as f64;
    let fail = |source| SysidError::Fit {
        channel: c.channel().to_string(),
        source,
    };
    let params = RbfParams::new()
        .kernel(settings.kernel)
        .centres(CentreSelection::Given(c.rbf().centres()))
        .width(WidthRule::Fixed(c.width()))
        .ridge(settings.ridge)
        .seed(settings.seed)
        .parallelism(Par::Seq)
        .check()
        .map_err(|e| fail(e.into()))?;
    let x = prepared.window_view();
    let d = x.ncols();
    let rbf = params
        .fit_given_streaming(train.len(), d, 0, 1, |start, mut xb, _, mut yb| {
            for i in 0..xb.nrows() {
                let row = train[start + i];
                for j in 0..d {
                    xb[(i, j)] = x[(row, j)];
                }
                yb[(i, 0)] = bias;
            }
        })
        .map_err(fail)?;
    let theta = Mat::from_fn(theta.len(), 1, |j, _| theta[j]);
    Ok(ChannelModel::new(
        c.channel(),
        c.effects().to_vec(),
        c.width(),
        rbf.with_linear(theta.as_ref()),
        *c.scores(),
        c.coefficients().map(<[_]>::to_vec).unwrap_or_default(),
    ))
}
