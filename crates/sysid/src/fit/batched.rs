//! Every channel's own network, their cross-validations reading one store
//! of candidate kernel columns.
//!
//! A sensor's channels read the same input windows and differ only in their
//! targets, so each channel's blocked cross-validation worked out the same
//! candidate centres, widths and kernel columns for every width and fold
//! (on the demo, a fifth of a network fit's time, six times over). Here
//! each channel's effects are dealt with first (θ given, or cross-fitted,
//! as a channel fit does; a channel that needs the joint fit is fitted
//! alone), then the networks of all channels are chosen together by
//! [`rbf::grid_search_each_with_linear`], which computes those columns once
//! per width and fold. Each channel still gets its own selection, bit for
//! bit the one [`fit_channel`] makes (the tests below and the demo's
//! outputs check it): unlike [`super::shared`], nothing is chosen jointly.

use super::channel::{ChannelFit, check_effects, fit_channel, gather, name};
use super::memo::channel_fits::{self as memo, Records};
use super::network::{Chosen, best_of, fit_chosen, params, size_ladder};
use super::partial::{Rows, Theta, adjusted, theta_of};
use crate::error::SysidError;
use crate::inference::Coefficient;
use crate::prepared::Prepared;
use crate::recipe::{FitSettings, Recipe};
use crate::sensor::{Effect, Sensor};
use crate::split::leakage_gap;
use faer::{Mat, MatRef};
use rayon::prelude::*;
use rbf::{Grid, Sizes, Split, WidthRule};

/// A channel before its network: its fit (remembered, or fitted alone), or
/// what its network is fitted to.
enum Before<S: Sensor> {
    Done(Box<ChannelFit<S>>),
    Network(Box<Pending<S>>),
}

/// A channel whose network is still to be chosen.
struct Pending<S: Sensor> {
    key: Option<memo::Key>,
    effects: Vec<S::Effect>,
    z: Mat<f64>,
    /// The target (less Zθ) on the training rows.
    y: Mat<f64>,
    theta: Option<Theta>,
}

/// The channels `channels` of `recipe` (those that read the windows `x`)
/// fitted as [`memo::recall`] fits them, on the windows `x_train` (rows
/// `train` of `x`), effects' coefficients on `theta_rows` of `x_theta` (or
/// `known(k)`), in the order of `channels`.
#[allow(clippy::too_many_arguments)]
pub(super) fn fit_channels<'a, S: Sensor>(
    records: Option<Records>,
    (prepared, channels): (&Prepared<S>, &[usize]),
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    x_train: &Mat<f64>,
    (train, theta_rows): (&[usize], &[usize]),
    recipe: &Recipe<S::Effect>,
    known: &(dyn Fn(usize) -> Option<&'a [Coefficient]> + Sync),
) -> Result<Vec<ChannelFit<S>>, SysidError> {
    let settings = &recipe.settings;
    let before: Vec<Before<S>> = channels
        .par_iter()
        .map(|&k| {
            let rows = (train, theta_rows, known(k));
            let effects = recipe.effects_of(k);
            let (key, found) = memo::recall(records, prepared, rows, k, effects, settings)?;
            if let Some(f) = found {
                return Ok(Before::Done(Box::new(f)));
            }
            let effects = effects.to_vec();
            let z = prepared.effect_matrix(k, &effects)?;
            let y = prepared.target(k);
            let z_train = gather(z.as_ref(), train);
            let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
            check_effects(prepared, k, &effects, z_train.as_ref(), train)?;
            if effects.is_empty() {
                return Ok(Before::Network(Box::new(Pending {
                    key,
                    effects,
                    z,
                    y: y_train,
                    theta: None,
                })));
            }
            let gap = leakage_gap(prepared);
            let rows = Rows {
                train,
                theta: theta_rows,
                known: known(k),
            };
            let theta =
                theta_of(x_theta, &z, y, rows, effects.len(), settings, gap).map_err(|source| {
                    SysidError::Fit {
                        channel: name(prepared, k),
                        source,
                    }
                })?;
            let Some(t) = theta.values() else {
                // The joint fit: the channel alone, as before.
                let f = fit_channel(
                    prepared,
                    (x, x_theta),
                    x_train,
                    (train, theta_rows, known(k)),
                    k,
                    &effects,
                    settings,
                )?;
                memo::remember(key, &f);
                return Ok(Before::Done(Box::new(f)));
            };
            Ok(Before::Network(Box::new(Pending {
                key,
                effects,
                y: adjusted(&y_train, &z_train, t),
                z,
                theta: Some(theta),
            })))
        })
        .collect::<Result<_, SysidError>>()?;
    let pending: Vec<usize> = (0..before.len())
        .filter(|&k| matches!(before[k], Before::Network(_)))
        .collect();
    let mut y = Mat::<f64>::zeros(train.len(), pending.len());
    for (c, &k) in pending.iter().enumerate() {
        if let Before::Network(p) = &before[k] {
            y.as_mut().col_mut(c).copy_from(p.y.col(0));
        }
    }
    let networks = fit_networks(
        settings,
        x_train.as_ref(),
        y.as_ref(),
        leakage_gap(prepared),
    );
    finish(prepared, channels, before, networks)
}

/// Each channel's fit: the one remembered or fitted alone, or its pending
/// effects with the network fitted for it (`networks`, one per pending
/// channel in order), each remembered.
fn finish<S: Sensor>(
    prepared: &Prepared<S>,
    channels: &[usize],
    before: Vec<Before<S>>,
    networks: Vec<Result<rbf::RbfModel, rbf::RbfError>>,
) -> Result<Vec<ChannelFit<S>>, SysidError> {
    let mut networks = networks.into_iter();
    let mut out = Vec::with_capacity(before.len());
    for (&k, b) in channels.iter().zip(before) {
        out.push(match b {
            Before::Done(f) => *f,
            Before::Network(p) => {
                let Pending {
                    key,
                    effects,
                    z,
                    theta,
                    ..
                } = *p;
                let net = networks
                    .next()
                    .expect("a network for every pending channel")
                    .map_err(|source| SysidError::Fit {
                        channel: name(prepared, k),
                        source,
                    })?;
                let (model, coefficients) = match theta {
                    None => (net, Vec::new()),
                    Some(t) => {
                        let units: Vec<String> = effects.iter().map(Effect::unit).collect();
                        t.with_network(net, &units)
                    }
                };
                let f = ChannelFit {
                    channel: k,
                    effects,
                    z,
                    width: model.widths().get(0),
                    model,
                    coefficients,
                };
                memo::remember(key, &f);
                f
            }
        });
    }
    Ok(out)
}

/// [`super::network::fit_network`] of each column of `y` on the windows `x`
/// (no forced columns), the candidates' kernel columns of each width and
/// fold computed once for all of them.
pub(super) fn fit_networks(
    settings: &FitSettings,
    x: MatRef<'_, f64>,
    y: MatRef<'_, f64>,
    gap: usize,
) -> Vec<Result<rbf::RbfModel, rbf::RbfError>> {
    let q = y.ncols();
    let z = Mat::<f64>::zeros(x.nrows(), 0);
    let max_k = settings.max_centres.min(x.nrows() / 2).max(1);
    let split = Split::Blocked {
        k: settings.inner_folds,
        gap,
    };
    // One grid per width, in parallel, as one channel's fit runs them.
    let reports: Vec<Result<Vec<rbf::GridReport>, rbf::RbfError>> = settings
        .width_scales
        .par_iter()
        .map(|&scale| {
            let w = WidthRule::MedianPairwise { scale };
            let grid = Grid {
                widths: vec![w.clone()],
                sizes: Sizes::Centres(size_ladder(max_k)),
                ridges: vec![],
            };
            let p = params(settings, max_k, w)?;
            rbf::grid_search_each_with_linear(&p, x, z.as_ref(), y, &split, &grid)
        })
        .collect();
    // Per target: every width's points in width-major order, or the first
    // width's error (as one channel's fit reports it).
    let mut per_target: Vec<Result<Vec<rbf::GridPoint>, rbf::RbfError>> =
        (0..q).map(|_| Ok(Vec::new())).collect();
    for r in reports {
        match r {
            Ok(each) => {
                for (t, rep) in each.into_iter().enumerate() {
                    if let Ok(points) = &mut per_target[t] {
                        points.extend(rep.points);
                    }
                }
            }
            Err(e) => {
                // The first channel reported (in channel order) gets the
                // error itself, the others what it says.
                let reason = e.to_string();
                let mut e = Some(e);
                for slot in per_target.iter_mut().filter(|s| s.is_ok()) {
                    *slot = Err(e.take().unwrap_or_else(|| rbf::RbfError::FoldFailed {
                        reason: reason.clone(),
                    }));
                }
            }
        }
    }
    per_target
        .into_par_iter()
        .enumerate()
        .map(|(t, points)| {
            let chosen: Chosen = best_of(points?, 1, max_k)?;
            fit_chosen(settings, &chosen, x, z.as_ref(), y.subcols(t, 1))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::example::{Line, Slope, line_record};

    /// Each channel's network chosen with the others (one store of candidate
    /// columns per width and fold) is the one it gets alone, bit for bit.
    #[test]
    fn networks_chosen_together_are_each_channels_own() {
        let rec = line_record(3000, 1.5, 3);
        let mut recipe = crate::Recipe::new(1);
        recipe.preprocess = Line::preprocess();
        recipe.effects[0] = vec![Slope];
        recipe.settings.max_centres = 12;
        let prepared = Prepared::new(&Line, &rec, &recipe.preprocess).unwrap();
        let x = prepared.window_view(0);
        let rows: Vec<usize> = (0..prepared.rows()).step_by(2).collect();
        let xt = gather(x, &rows);
        let target = prepared.target(0);
        let y = Mat::from_fn(rows.len(), 3, |i, t| {
            target[rows[i]] * (1.0 + t as f64) + (t as f64) * xt[(i, 0)].powi(2)
        });
        let gap = leakage_gap(&prepared);
        let together = fit_networks(&recipe.settings, xt.as_ref(), y.as_ref(), gap);
        let none = Mat::<f64>::zeros(rows.len(), 0);
        for (t, got) in together.into_iter().enumerate() {
            let alone = super::super::network::fit_network(
                &recipe.settings,
                xt.as_ref(),
                none.as_ref(),
                y.as_ref().subcols(t, 1),
                gap,
            )
            .unwrap();
            let got = got.unwrap();
            assert_eq!(
                format!("{got:?}"),
                format!("{alone:?}"),
                "target {t}: the model differs"
            );
        }
    }
}
