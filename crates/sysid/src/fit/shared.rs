//! One centre selection for every channel that reads the same input.
//!
//! The channels of one sensor unit see the same vibration through the same
//! windows, so the centres one channel needs are nearly those of the others
//! (on the demo the per-channel selections already picked mostly the same
//! windows). Each channel's effects are partialled out first (cross-fitted
//! θ, as a per-channel fit does), then one cross-validated OLS selection
//! runs on what they leave of every channel together: the engine sums the
//! ERR over the targets, and the grid scores the mean over channels of the
//! validation NMSE (each channel normalised by its own variance, so a noisy
//! channel does not outweigh a quiet one). Each channel keeps its own
//! least-squares weights (a column of the multi-output QR solve), so the
//! model file keeps per-channel networks whose centres and width are equal.
//!
//! One selection instead of one per channel is most of the fit's time on a
//! large record, and an onboard step can compute the kernels once.
//!
//! A channel whose effects cannot be cross-fitted (blocks too short) is
//! fitted alone, effects and network jointly, as before.

use super::channel::{ChannelFit, check_effects, fit_channel, gather, name};
use super::network::fit_network;
use super::partial::{coefficients, cross_fitted_theta};
use crate::error::SysidError;
use crate::inference::Coefficient;
use crate::prepared::Prepared;
use crate::recipe::{FitSettings, Recipe};
use crate::sensor::{Effect, Sensor};
use crate::split::leakage_gap;
use faer::{Mat, MatRef, Par};
use rayon::prelude::*;
use rbf::{CentreSelection, ParamGuard, RbfParams, WidthRule};

/// A channel before the shared network: its effects' columns and, when it
/// has effects, their cross-fitted coefficients; or its whole fit when it
/// has to be fitted alone.
enum Partialled<S: Sensor> {
    Shared {
        channel: usize,
        effects: Vec<S::Effect>,
        z: Mat<f64>,
        theta: Vec<f64>,
        coefficients: Vec<Coefficient>,
    },
    Alone(Box<ChannelFit<S>>),
}

/// The channels `channels` of `recipe` (those that read the windows `x`)
/// fitted with one centre selection on the windows `x_fit` (rows `fit_on`
/// of `x`), effects' coefficients estimated on `theta_rows` of the raw
/// windows `x_theta` (as a per-channel fit estimates them); in the order
/// of `channels`.
pub(super) fn fit_channels_shared<'a, S: Sensor>(
    (prepared, channels): (&Prepared<S>, &[usize]),
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    x_fit: &Mat<f64>,
    (fit_on, theta_rows): (&[usize], &[usize]),
    recipe: &Recipe<S::Effect>,
    known: &(dyn Fn(usize) -> Option<&'a [Coefficient]> + Sync),
) -> Result<Vec<ChannelFit<S>>, SysidError> {
    let settings = &recipe.settings;
    let gap = leakage_gap(prepared);
    let parts: Vec<Partialled<S>> = channels
        .par_iter()
        .map(|&k| {
            partial_out(
                prepared,
                (x, x_theta),
                x_fit,
                (fit_on, theta_rows, known(k)),
                k,
                recipe.effects_of(k),
                settings,
            )
        })
        .collect::<Result<_, _>>()?;
    let shared: Vec<usize> = parts
        .iter()
        .enumerate()
        .filter(|(_, p)| matches!(p, Partialled::Shared { .. }))
        .map(|(k, _)| k)
        .collect();
    // What the effects leave of each shared channel, on the selection rows.
    let mut y = Mat::<f64>::zeros(fit_on.len(), shared.len());
    for (c, &k) in shared.iter().enumerate() {
        let Partialled::Shared { z, theta, .. } = &parts[k] else {
            unreachable!("listed as shared")
        };
        let target = prepared.target(channels[k]);
        for (i, &row) in fit_on.iter().enumerate() {
            y[(i, c)] = adjusted(target, z, theta, row);
        }
    }
    let net = match shared.is_empty() {
        true => None,
        false => Some(
            fit_network(
                settings,
                x_fit.as_ref(),
                Mat::<f64>::zeros(fit_on.len(), 0).as_ref(),
                y.as_ref(),
                gap,
            )
            .map_err(|source| SysidError::Fit {
                channel: names(
                    prepared,
                    &shared.iter().map(|&k| channels[k]).collect::<Vec<_>>(),
                ),
                source,
            })?,
        ),
    };
    let mut out = Vec::with_capacity(channels.len());
    for (k, part) in parts.into_iter().enumerate() {
        out.push(match part {
            Partialled::Alone(f) => *f,
            Partialled::Shared {
                channel,
                effects,
                z,
                theta,
                coefficients,
            } => {
                let net = net
                    .as_ref()
                    .expect("a shared channel has the shared network");
                let c = shared.iter().position(|&s| s == k).expect("listed");
                let model = with_theta(net.output(c), &theta);
                ChannelFit {
                    channel,
                    effects,
                    z,
                    width: model.widths().get(0),
                    model,
                    coefficients,
                }
            }
        });
    }
    Ok(out)
}

/// Channel `k`'s effects checked on the selection rows and partialled out
/// (θ by cross-fitting on `theta_rows` of the raw windows `x_theta`), or,
/// when they cannot be cross-fitted, the channel fitted alone.
fn partial_out<S: Sensor>(
    prepared: &Prepared<S>,
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    x_fit: &Mat<f64>,
    (fit_on, theta_rows, known): (&[usize], &[usize], Option<&[Coefficient]>),
    k: usize,
    effects: &[S::Effect],
    settings: &FitSettings,
) -> Result<Partialled<S>, SysidError> {
    let effects = effects.to_vec();
    let z = prepared.effect_matrix(k, &effects)?;
    if effects.is_empty() {
        return Ok(Partialled::Shared {
            channel: k,
            effects,
            z,
            theta: Vec::new(),
            coefficients: Vec::new(),
        });
    }
    check_effects(
        prepared,
        k,
        &effects,
        gather(z.as_ref(), fit_on).as_ref(),
        fit_on,
    )?;
    if let Some(known) = known.filter(|c| c.len() == effects.len()) {
        // A model's own estimate (for its mirror): taken as it is.
        return Ok(Partialled::Shared {
            channel: k,
            theta: known.iter().map(|c| c.value).collect(),
            coefficients: known.to_vec(),
            effects,
            z,
        });
    }
    let y = prepared.target(k);
    let gap = leakage_gap(prepared);
    let hac = cross_fitted_theta(x_theta, &z, y, theta_rows, settings, gap).map_err(|source| {
        SysidError::Fit {
            channel: name(prepared, k),
            source,
        }
    })?;
    match hac {
        Some(f) => {
            let units: Vec<String> = effects.iter().map(Effect::unit).collect();
            let coefficients = coefficients(&units, Some(&f), &f.coef);
            Ok(Partialled::Shared {
                channel: k,
                effects,
                z,
                theta: f.coef,
                coefficients,
            })
        }
        None => fit_channel(
            prepared,
            (x, x_theta),
            x_fit,
            (fit_on, theta_rows, None),
            k,
            &effects,
            settings,
        )
        .map(|f| Partialled::Alone(Box::new(f))),
    }
}

/// `target − z θ` on row `row` (the target itself without effects).
fn adjusted(target: &[f64], z: &Mat<f64>, theta: &[f64], row: usize) -> f64 {
    target[row]
        - theta
            .iter()
            .enumerate()
            .map(|(j, t)| z[(row, j)] * t)
            .sum::<f64>()
}

/// A network of one output with fixed effect coefficients θ added.
fn with_theta(model: rbf::RbfModel, theta: &[f64]) -> rbf::RbfModel {
    match theta.is_empty() {
        true => model,
        false => model.with_linear(Mat::from_fn(theta.len(), 1, |j, _| theta[j]).as_ref()),
    }
}

/// The names of channels `channels`, for an error of their shared fit.
fn names<S: Sensor>(prepared: &Prepared<S>, channels: &[usize]) -> String {
    channels
        .iter()
        .map(|&k| name(prepared, k))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The final weights of channels that share centres, solved again on every
/// training row by one row-block QR with a column per channel (the kernel
/// columns computed once for all): what [`super::channel::refit_weights`]
/// does for one channel. Channels fitted alone are refitted alone.
pub(super) fn refit_weights_shared<S: Sensor>(
    prepared: &Prepared<S>,
    x: MatRef<'_, f64>,
    train: &[usize],
    fits: Vec<ChannelFit<S>>,
    settings: &FitSettings,
) -> Result<Vec<ChannelFit<S>>, SysidError> {
    // The channels of the shared selection: those whose centres and width
    // are the first partialled channel's (a channel fitted alone has its own).
    let shares = |f: &ChannelFit<S>, g: &ChannelFit<S>| {
        f.width == g.width && f.model.centres() == g.model.centres()
    };
    let Some(lead) = fits
        .iter()
        .position(|f| f.effects.is_empty() || f.theta_fixed())
    else {
        return fits
            .into_iter()
            .map(|f| super::channel::refit_weights(prepared, x, train, f, settings))
            .collect();
    };
    let members: Vec<usize> = (0..fits.len())
        .filter(|&k| {
            let f = &fits[k];
            (f.effects.is_empty() || f.theta_fixed()) && shares(f, &fits[lead])
        })
        .collect();
    let fail = |source| SysidError::Fit {
        channel: names(
            prepared,
            &members.iter().map(|&k| fits[k].channel).collect::<Vec<_>>(),
        ),
        source,
    };
    let params = RbfParams::new()
        .kernel(settings.kernel)
        .centres(CentreSelection::Given(fits[lead].model.centres()))
        .width(WidthRule::Fixed(fits[lead].width))
        .ridge(settings.ridge)
        .seed(settings.seed)
        .parallelism(Par::Seq)
        .check()
        .map_err(|e| fail(e.into()))?;
    let thetas: Vec<Vec<f64>> = members
        .iter()
        .map(|&k| {
            let t = fits[k].model.linear_coefficients();
            (0..t.nrows()).map(|j| t[(j, 0)]).collect()
        })
        .collect();
    let (n, d, q) = (train.len(), x.ncols(), members.len());
    let targets: Vec<&[f64]> = members
        .iter()
        .map(|&k| prepared.target(fits[k].channel))
        .collect();
    let model = params
        .fit_given_streaming(n, d, 0, q, |start, mut xb, _, mut yb| {
            for i in 0..xb.nrows() {
                let row = train[start + i];
                for j in 0..d {
                    xb[(i, j)] = x[(row, j)];
                }
                for (c, &k) in members.iter().enumerate() {
                    yb[(i, c)] = adjusted(targets[c], &fits[k].z, &thetas[c], row);
                }
            }
        })
        .map_err(fail)?;
    let mut out = Vec::with_capacity(fits.len());
    for (k, f) in fits.into_iter().enumerate() {
        match members.iter().position(|&m| m == k) {
            Some(c) => out.push(ChannelFit {
                model: with_theta(model.output(c), &thetas[c]),
                ..f
            }),
            None => out.push(super::channel::refit_weights(
                prepared, x, train, f, settings,
            )?),
        }
    }
    Ok(out)
}
