//! One channel's fit: the checks its effects must pass on the training
//! rows, the network and coefficients, the final weights on every training
//! row of a subsampled fit, and the scores.

use super::network::fit_network;
use super::partial::fit_partially_linear;
use crate::error::SysidError;
use crate::inference::Coefficient;
use crate::model::{ChannelModel, ChannelModelOf, score};
use crate::prepared::Prepared;
use crate::recipe::FitSettings;
use crate::sensor::{Effect, Sensor};
use crate::split::leakage_gap;
use faer::{Mat, MatRef, Par};
use rbf::{CentreSelection, ParamGuard, RbfParams, Split, WidthRule};

/// One channel's fitted network and effect coefficients, not yet scored.
#[derive(Debug, Clone)]
pub(super) struct ChannelFit<S: Sensor> {
    pub(super) channel: usize,
    pub(super) effects: Vec<S::Effect>,
    /// The effects' columns on every row (worked out once per channel).
    pub(super) z: Mat<f64>,
    pub(super) width: f64,
    pub(super) model: rbf::RbfModel,
    pub(super) coefficients: Vec<Coefficient>,
}

impl<S: Sensor> ChannelFit<S> {
    /// True when the effects' coefficients were estimated (by partialling
    /// out) and stay fixed in the network's refit; as
    /// [`ChannelModel::coefficients`] tells.
    pub(super) fn theta_fixed(&self) -> bool {
        self.coefficients.len() == self.effects.len() && !self.effects.is_empty()
    }
}

/// The channel's name, for errors.
pub(super) fn name<S: Sensor>(prepared: &Prepared<S>, channel: usize) -> String {
    prepared
        .sensor()
        .channels()
        .get(channel)
        .map_or_else(|| channel.to_string(), ToString::to_string)
}

/// The channel model of a fit, scored on the training and validation rows
/// from its predictions `yhat` on every row.
pub(super) fn scored<S: Sensor>(
    prepared: &Prepared<S>,
    train: &[usize],
    val: &[usize],
    f: ChannelFit<S>,
    yhat: &[f64],
) -> Result<ChannelModelOf<S>, SysidError> {
    let y = prepared.target(f.channel);
    let scores = score(y, yhat, train, val);
    let channel = prepared.sensor().channels()[f.channel].clone();
    Ok(ChannelModel::new(
        channel,
        f.effects,
        f.width,
        f.model,
        scores,
        f.coefficients,
    ))
}

/// Every fit's predictions on the rows of `x` (the kernels computed once
/// for fits that share centres).
#[cfg(test)]
pub(super) fn predictions<S: Sensor>(fits: &[ChannelFit<S>], x: MatRef<'_, f64>) -> Vec<Vec<f64>> {
    let networks: Vec<&rbf::RbfModel> = fits.iter().map(|f| &f.model).collect();
    with_effects(fits, crate::model::network_outputs(&networks, x))
}

/// [`predictions`] of every channel's fit (`fits[k]`: channel k's), each
/// on its own windows.
pub(super) fn channel_predictions<S: Sensor>(
    prepared: &Prepared<S>,
    fits: &[ChannelFit<S>],
) -> Vec<Vec<f64>> {
    let networks: Vec<&rbf::RbfModel> = fits.iter().map(|f| &f.model).collect();
    with_effects(
        fits,
        crate::model::channel_network_outputs(prepared, &networks),
    )
}

/// Network outputs `out` (one per fit) with each fit's effects added.
fn with_effects<S: Sensor>(fits: &[ChannelFit<S>], mut out: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    for (y, f) in out.iter_mut().zip(fits) {
        let t = f.model.linear_coefficients();
        let theta: Vec<f64> = (0..t.nrows()).map(|j| t[(j, 0)]).collect();
        crate::model::add_effects(y, &f.z, &theta);
    }
    out
}

/// A channel fit whose centres and width were chosen on a subsample, with
/// its bias, effect coefficients and weights solved again on every training
/// row by a row-block QR ([`rbf::RbfValidParams::fit_given_streaming`]: the
/// rows are copied from the prepared windows block by block, so neither the
/// training windows nor their n × (1 + effects + K) design are ever held).
pub(super) fn refit_weights<S: Sensor>(
    prepared: &Prepared<S>,
    x: MatRef<'_, f64>,
    train: &[usize],
    f: ChannelFit<S>,
    settings: &FitSettings,
) -> Result<ChannelFit<S>, SysidError> {
    let z = &f.z;
    let y = prepared.target(f.channel);
    let fail = |source| SysidError::Fit {
        channel: name(prepared, f.channel),
        source,
    };
    let params = RbfParams::new()
        .kernel(settings.kernel)
        .centres(CentreSelection::Given(f.model.centres()))
        .width(WidthRule::Fixed(f.width))
        .ridge(settings.ridge)
        .seed(settings.seed)
        .parallelism(Par::Seq)
        .check()
        .map_err(|e| fail(e.into()))?;
    // Effect coefficients estimated by partialling out stay as they are
    // (with their intervals); the network is solved on what they leave.
    let theta = f
        .theta_fixed()
        .then(|| f.model.linear_coefficients().to_owned());
    let r = if theta.is_some() { 0 } else { z.ncols() };
    let (n, d) = (train.len(), x.ncols());
    let model = params
        .fit_given_streaming(n, d, r, 1, |start, mut xb, mut zb, mut yb| {
            for i in 0..xb.nrows() {
                let row = train[start + i];
                for j in 0..d {
                    xb[(i, j)] = x[(row, j)];
                }
                for j in 0..r {
                    zb[(i, j)] = z[(row, j)];
                }
                yb[(i, 0)] = match &theta {
                    Some(t) => {
                        y[row] - (0..t.nrows()).map(|j| z[(row, j)] * t[(j, 0)]).sum::<f64>()
                    }
                    None => y[row],
                };
            }
        })
        .map_err(fail)?;
    let model = match &theta {
        Some(t) => model.with_linear(t.as_ref()),
        None => model,
    };
    Ok(ChannelFit { model, ..f })
}

/// Windows that are all the same point leave the network nothing to tell
/// apart, and the library's width rule would say "use a fixed width", which
/// no flag here sets: say which signals do not vary instead.
pub(super) fn windows_vary(
    x: MatRef<'_, f64>,
    train: &[usize],
    signals: &[String],
) -> Result<(), SysidError> {
    let Some(&first) = train.first() else {
        return Ok(());
    };
    let same = (0..x.ncols()).all(|j| {
        let v = x[(first, j)];
        train.iter().all(|&i| x[(i, j)] == v)
    });
    if same {
        return Err(SysidError::WindowsConstant {
            signals: signals.to_vec(),
        });
    }
    Ok(())
}

/// The inner cross-validation keeps its blocked folds a leakage gap apart;
/// on a short record the gap can leave a fold no training rows, which the
/// library reports as "fold 1 of 226 samples has 0 training rows" without
/// the settings behind it: say them here, before any channel is fitted.
pub(super) fn inner_folds_fit<S: Sensor>(
    prepared: &Prepared<S>,
    n_train: usize,
    folds: usize,
) -> Result<(), SysidError> {
    let gap = leakage_gap(prepared);
    match (Split::Blocked { k: folds, gap }).folds(n_train) {
        Ok(_) => Ok(()),
        Err(_) => Err(SysidError::InnerFoldsEmpty {
            folds,
            n_train,
            gap,
            window: prepared.first_sample() + 1,
            filter_memory: prepared.filter_memory(),
        }),
    }
}

/// Refuses effects the training rows cannot estimate: not excited there
/// (the sensor says why), constant (the bias absorbs them), or a
/// combination of the bias and the effects before them.
pub(super) fn check_effects<S: Sensor>(
    prepared: &Prepared<S>,
    channel: usize,
    effects: &[S::Effect],
    z_train: MatRef<'_, f64>,
    train: &[usize],
) -> Result<(), SysidError> {
    let first = prepared.first_sample();
    let samples: Vec<usize> = train.iter().map(|&r| first + r).collect();
    prepared
        .sensor()
        .check_excited(prepared.calibrated(), &samples, channel, effects)
        .map_err(SysidError::Sensor)?;
    // A constant effect (a temperature column held by a thermal chamber, say)
    // would surface as an anonymous collinear forced column deep in OLS: name it.
    for (j, effect) in effects.iter().enumerate() {
        let col = (0..z_train.nrows()).map(|i| z_train[(i, j)]);
        let (lo, hi) = col.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        if hi - lo <= 1e-12 * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE) {
            return Err(SysidError::EffectConstant {
                channel: name(prepared, channel),
                effect: effect.id(),
                value: lo,
            });
        }
    }
    if let Some((j, kept)) = first_collinear_effect(z_train) {
        return Err(SysidError::EffectsCollinear {
            channel: name(prepared, channel),
            effect: effects[j].id(),
            earlier: effects[..j].iter().map(Effect::id).collect(),
            kept,
        });
    }
    Ok(())
}

/// One channel's network and effects, chosen and fitted on the windows
/// `x_train` (rows `train` of the prepared windows `x`); the effects'
/// coefficients estimated on rows `theta_rows` of the raw windows `x_theta`.
pub(super) fn fit_channel<S: Sensor>(
    prepared: &Prepared<S>,
    (x, x_theta): (MatRef<'_, f64>, MatRef<'_, f64>),
    x_train: &Mat<f64>,
    (train, theta_rows, known): (&[usize], &[usize], Option<&[Coefficient]>),
    channel: usize,
    effects: &[S::Effect],
    settings: &FitSettings,
) -> Result<ChannelFit<S>, SysidError> {
    let effects = effects.to_vec();
    let z = prepared.effect_matrix(channel, &effects)?;
    let y = prepared.target(channel);
    let z_train = gather(z.as_ref(), train);
    let y_train = Mat::from_fn(train.len(), 1, |i, _| y[train[i]]);
    let fail = |source| SysidError::Fit {
        channel: name(prepared, channel),
        source,
    };
    check_effects(prepared, channel, &effects, z_train.as_ref(), train)?;
    let gap = leakage_gap(prepared);
    let (model, coefficients) = if effects.is_empty() {
        let net = fit_network(
            settings,
            x_train.as_ref(),
            z_train.as_ref(),
            y_train.as_ref(),
            gap,
        )
        .map_err(fail)?;
        (net, Vec::new())
    } else {
        let units: Vec<String> = effects.iter().map(Effect::unit).collect();
        let rows = super::partial::Rows {
            train,
            theta: theta_rows,
            known,
        };
        fit_partially_linear((x, x_theta), &z, y, rows, &units, settings, gap).map_err(fail)?
    };
    let width = model.widths().get(0);
    Ok(ChannelFit {
        channel,
        effects,
        z,
        width,
        model,
        coefficients,
    })
}

/// Share of a column's variation (energy about its mean) that an effect must
/// keep once the bias and the effects before it are projected out. Stricter
/// than the OLS engine's own 1e-12, so a cross-validation fold on fewer rows
/// does not meet the collinearity first.
const EFFECT_COLLINEARITY_TOL: f64 = 1e-9;

/// The first effect column (and the share of its variation it keeps) that is
/// (nearly) a combination of the bias and the columns before it: modified
/// Gram–Schmidt on the centred columns, in order.
fn first_collinear_effect(z: MatRef<'_, f64>) -> Option<(usize, f64)> {
    let n = z.nrows();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for j in 0..z.ncols() {
        let mean = (0..n).map(|i| z[(i, j)]).sum::<f64>() / n.max(1) as f64;
        let mut v: Vec<f64> = (0..n).map(|i| z[(i, j)] - mean).collect();
        let orig: f64 = v.iter().map(|x| x * x).sum();
        for q in &basis {
            let c: f64 = q.iter().zip(&v).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(q).for_each(|(x, a)| *x -= c * a);
        }
        let kept: f64 = v.iter().map(|x| x * x).sum();
        if kept.is_nan() || kept <= EFFECT_COLLINEARITY_TOL * orig {
            return Some((j, if orig > 0.0 { kept / orig } else { 0.0 }));
        }
        let norm = kept.sqrt();
        basis.push(v.into_iter().map(|x| x / norm).collect());
    }
    None
}

/// Rows `rows` of `m`.
pub(super) fn gather(m: MatRef<'_, f64>, rows: &[usize]) -> Mat<f64> {
    Mat::from_fn(rows.len(), m.ncols(), |i, j| m[(rows[i], j)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::example::{Line, Slope, line_record};
    use crate::split::split_rows;

    /// The row-block solve of a large record's final weights gives the
    /// weights the whole-matrix QR gives on the same rows and centres, with
    /// and without effects (partialled out: θ kept, the network refitted).
    #[test]
    fn streamed_final_weights_equal_the_whole_matrix_solve() {
        let rec = line_record(3000, 1.5, 3);
        for effects in [vec![], vec![Slope]] {
            let mut recipe = crate::Recipe::new(1);
            recipe.preprocess = Line::preprocess();
            recipe.effects[0] = effects;
            recipe.settings.max_centres = 12;
            recipe.settings.width_scales = vec![1.0];
            let prepared = Prepared::new(&Line, &rec, &recipe.preprocess).unwrap();
            let (train, val) = split_rows(&prepared, recipe.split).unwrap();
            let options = crate::recipe::FitOptions {
                recipe: recipe.clone(),
                validate_on: None,
            };
            let model = super::super::fit_prepared(&prepared, &options, &|_| {}).unwrap();
            let m = model.channel(0);
            let f = ChannelFit::<Line> {
                channel: 0,
                effects: m.effects().to_vec(),
                z: prepared.effect_matrix(0, m.effects()).unwrap(),
                width: m.width(),
                model: m.rbf().clone(),
                coefficients: m.coefficients().map(<[_]>::to_vec).unwrap_or_default(),
            };
            let x = prepared.window_view(0);
            let f = refit_weights(&prepared, x, &train, f, &recipe.settings).unwrap();
            let yhat = predictions(std::slice::from_ref(&f), x);
            let again = scored(&prepared, &train, &val, f, &yhat[0]).unwrap();
            let (a, b) = (m.rbf(), again.rbf());
            assert_eq!(a.centres(), b.centres());
            assert_eq!(a.linear_coefficients(), b.linear_coefficients());
            let scale = a.weights().norm_max();
            assert!(
                (a.weights() - b.weights()).norm_max() <= 1e-7 * scale,
                "weights {:?} against {:?}",
                a.weights(),
                b.weights()
            );
            let (sa, sb) = (m.scores(), again.scores());
            assert!((sa.val_rms - sb.val_rms).abs() <= 1e-9 * sa.val_rms);
            assert_eq!((sa.n_train, sa.n_val), (sb.n_train, sb.n_val));
        }
    }
}
