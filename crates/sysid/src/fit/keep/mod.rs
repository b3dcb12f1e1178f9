//! Each channel keeps its network only as far as it removes variation.
//!
//! A network fitted to a channel that holds little but noise, or that
//! cannot see what moves the channel on some of its records, predicts
//! structure that is not there: on the campaign's x and y runs the
//! three-run model's networks of Y, Y1 and Z1 read a_z alone, and what they
//! predict from a_z's 1% transverse vibration there (the shape of two
//! Gaussians between rest and the z run's levels) runs against what the x
//! or y vibration does to those channels, which they cannot see: they added
//! 0.4–0.8% to the channels' spread on the very runs they were fitted on
//! (docs/campaign.md §6). So after the fit (and the choice of input and
//! smoother), each channel's network gets a share t ∈ [0, 1] of its output
//! (its weights scaled by t, the bias keeping the training mean; the model
//! file keeps the centres, so every reader — compensate, check, the onboard
//! tables, the C export — reads it as before):
//! - 0 where its validation rms is not below what the bias and effects
//!   alone leave (the bias-only rms for a channel without effects);
//! - on each record's validation rows, where the compensated output varies
//!   more about its own mean than what the bias and effects alone leave,
//!   beyond the 68% interval of that spread ratio (its sampling spread,
//!   Newey–West over the rows: a ratio of 1.0001 is noise), the share that
//!   varies least there, cov(before, network)/var(network) (the spread is a
//!   convex quadratic in t, so records that gained keep gaining);
//! - lowered further where a channel's or a residue's bias instability
//!   would rise on a record ([`bias_instability`]).
//!
//! The spread ratio's interval is the one the ADEV bound of the choice uses
//! ([`ADEV_CONFIDENCE`]).

mod bias_instability;
mod series;

use super::input_choice::{ADEV_CONFIDENCE, MIN_ADEV_ROWS};
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
    let (mut model, shrunk, raised) = keep_networks(model, p, train, val)?;
    if shrunk.is_empty() && raised.is_empty() {
        return Ok(model);
    }
    if !shrunk.is_empty() {
        super::input_choice::rescore(&mut model, p, train, val)?;
    }
    // A fit with a fixed input and smoother has no choice to report; what
    // the keep step did is still the model's to say, so it gets a report
    // of that one candidate (judged by rms only).
    let mut report = model.choice_or_fixed();
    report.bias_instability_raised = raised;
    report.networks_shrunk = shrunk
        .iter()
        .map(|d| {
            let name = model.channels()[d.channel].channel();
            match d.share {
                0.0 => format!("{name} to zero: {}", d.reason),
                t => format!("{name} × {t:.3}: {}", d.reason),
            }
        })
        .collect();
    model.set_choice(report);
    Ok(model)
}

/// A channel whose network keeps less than all of its output, and why.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shrunk {
    /// The channel's index.
    pub(super) channel: usize,
    /// The share of its network's output it keeps, in [0, 1).
    pub(super) share: f64,
    /// What lowered it: the record (or `validation rows`) where it added
    /// variation and the ratio there, or the series whose bias instability
    /// it raised.
    pub(super) reason: String,
}

/// The model after the keep step, its shrunk channels and the bias
/// instabilities left raised.
type Kept<S> = (Model<S>, Vec<Shrunk>, Vec<String>);

/// The model with each channel's network scaled to the share it keeps
/// (see the module), the channels scaled, and the bias instabilities left
/// raised ([`bias_instability::Held::raised`]).
pub(super) fn keep_networks<S: Sensor>(
    model: Model<S>,
    prepared: &Prepared<S>,
    train: &[usize],
    val: &[usize],
) -> Result<Kept<S>, SysidError> {
    let predicted = model.predict(prepared)?;
    let records = prepared.record_rows();
    let n = model.channels().len();
    let mut shares = vec![1.0; n];
    let mut why: Vec<Vec<String>> = vec![Vec::new(); n];
    for (k, c) in model.channels().iter().enumerate() {
        let y = prepared.target(k);
        let s = crate::model::score(y, &predicted[k], train, val);
        // Before: what the bias and effects leave, so an effect that adds
        // variation is not laid at the network's door.
        let z = prepared.effect_matrix(k, c.effects())?;
        let theta = c.effect_coefficients();
        let effects = |r: usize| (0..theta.len()).map(|j| z[(r, j)] * theta[j]).sum::<f64>();
        // The validation rms the bias and effects alone leave (the bias-only
        // rms for a channel without effects; with effects, the bias-only rms
        // holds the effects too, and every network would pass it).
        let left: Vec<f64> = y.iter().enumerate().map(|(r, y)| y - effects(r)).collect();
        let without = crate::model::score(&left, &vec![0.0; left.len()], train, val);
        if s.val_rms >= without.val_rms_bias_only {
            shares[k] = 0.0;
            why[k].push(match theta.is_empty() {
                true => format!(
                    "validation rms {:.4} not below the bias-only {:.4}",
                    s.val_rms, s.val_rms_bias_only
                ),
                false => format!(
                    "validation rms {:.4} not below the {:.4} the bias and effects alone leave",
                    s.val_rms, without.val_rms_bias_only
                ),
            });
            continue;
        }
        for (name, range) in &records {
            let rows: Vec<usize> = val.iter().copied().filter(|r| range.contains(r)).collect();
            if rows.len() < MIN_ADEV_ROWS {
                continue;
            }
            let before: Vec<f64> = rows.iter().map(|&r| y[r] - effects(r)).collect();
            let after: Vec<f64> = rows.iter().map(|&r| y[r] - predicted[k][r]).collect();
            if let Some(j) = spread_beyond_interval(&before, &after) {
                shares[k] = f64::min(shares[k], j.share);
                let at = if name.is_empty() { "the record" } else { name };
                why[k].push(format!(
                    "spread after {:.4}× before on {at}'s validation rows (68% interval {:.4}–{:.4})",
                    j.ratio, j.low, j.high
                ));
            }
        }
    }
    let held = bias_instability::hold(&model, prepared, &predicted, (train, val), &mut shares)?;
    for (k, reason) in held.lowered {
        if !why[k].contains(&reason) {
            why[k].push(reason);
        }
    }
    let shrunk: Vec<Shrunk> = (0..n)
        .filter(|&k| shares[k] < 1.0)
        .map(|k| Shrunk {
            channel: k,
            share: shares[k],
            reason: why[k].join("; "),
        })
        .collect();
    if shrunk.is_empty() {
        return Ok((model, shrunk, held.raised));
    }
    let length = model.preprocess().window.length();
    let rest = match shrunk.iter().any(|d| d.share > 0.0) {
        true => crate::operating::fade::rest_rows(prepared, length, train)?,
        false => Vec::new(),
    };
    let mut parts = model.into_parts();
    for d in &shrunk {
        let k = d.channel;
        parts.channels[k] = scaled_network(
            prepared,
            &parts.channels[k],
            k,
            train,
            &parts.settings,
            d.share,
        )?;
        // The network at rest, where a record that starts outside holds it.
        let at_rest = match d.share {
            0.0 => 0.0,
            _ => crate::model::network_means::<S>(
                std::slice::from_ref(&parts.channels[k]),
                prepared.window_view(k),
                &rest,
            )[0],
        };
        if let Some(range) = parts
            .operating_points
            .as_mut()
            .and_then(|o| o.range.as_mut())
        {
            range.network_mean[k] = at_rest;
        }
    }
    let model = Model::from_parts(parts).map_err(|reason| SysidError::InvalidOption {
        name: "fitted model",
        value: reason,
        reason: "shrinking a network gave an inconsistent model (a bug: please report it)",
    })?;
    Ok((model, shrunk, held.raised))
}

/// A spread ratio beyond its interval, and the share that varies least.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Spread {
    /// Spread after / spread before (each about its own mean).
    ratio: f64,
    /// Its 68% interval ([`ADEV_CONFIDENCE`]).
    low: f64,
    high: f64,
    /// cov(before, network part)/var(network part), in [0, 1]: the share of
    /// the network with the least spread after on these rows.
    share: f64,
}

/// The spread of `after` against `before` (the same rows, `after` = `before`
/// − the network part) when above 1 beyond its 68% interval, else `None`.
///
/// ratio² − 1 = mean(d)/var(before) with dᵢ = q̃ᵢ² − 2·b̃ᵢq̃ᵢ (q the network
/// part, b before, each less its mean), so the interval is the one of a
/// mean: Newey–West over the rows (a network's prediction is smooth, its
/// products correlated over many rows), Student's t on its equivalent
/// degrees of freedom.
fn spread_beyond_interval(before: &[f64], after: &[f64]) -> Option<Spread> {
    let n = before.len().max(1) as f64;
    let q: Vec<f64> = before.iter().zip(after).map(|(b, a)| b - a).collect();
    let (mb, mq) = (before.iter().sum::<f64>() / n, q.iter().sum::<f64>() / n);
    let vb = before.iter().map(|b| (b - mb).powi(2)).sum::<f64>() / n;
    let vq = q.iter().map(|q| (q - mq).powi(2)).sum::<f64>() / n;
    let cov = before
        .iter()
        .zip(&q)
        .map(|(b, q)| (b - mb) * (q - mq))
        .sum::<f64>()
        / n;
    let d: Vec<f64> = before
        .iter()
        .zip(&q)
        .map(|(b, q)| (q - mq).powi(2) - 2.0 * (b - mb) * (q - mq))
        .collect();
    let mean_d = vq - 2.0 * cov;
    if !(vb > 0.0 && mean_d > 0.0) {
        return None;
    }
    let ones = vec![1.0; d.len()];
    let [lo, hi] = crate::inference::hac_regression(&d, &[&ones])
        .map_or([mean_d, mean_d], |f| f.interval(0, ADEV_CONFIDENCE));
    let ratio = |v: f64| (1.0 + v / vb).max(0.0).sqrt();
    (lo > 0.0).then(|| Spread {
        ratio: ratio(mean_d),
        low: ratio(lo),
        high: ratio(hi),
        share: if vq > 0.0 {
            (cov / vq).clamp(0.0, 1.0)
        } else {
            0.0
        },
    })
}

/// Channel `k`'s model with its network's output scaled by `share` about
/// the bias: weights solved again on the training rows against
/// `share`·network + (1 − `share`)·(the training rows' mean of what the
/// effects leave), on the same centres and width (at 0 they are zero to
/// rounding); effects and their coefficients as they were.
fn scaled_network<S: Sensor>(
    prepared: &Prepared<S>,
    c: &crate::model::ChannelModelOf<S>,
    k: usize,
    train: &[usize],
    settings: &crate::recipe::FitSettings,
    share: f64,
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
    let x = prepared.window_view(k);
    let d = x.ncols();
    let network = c.rbf();
    let rbf = params
        .fit_given_streaming(train.len(), d, 0, 1, |start, mut xb, _, mut yb| {
            for i in 0..xb.nrows() {
                let row = train[start + i];
                for j in 0..d {
                    xb[(i, j)] = x[(row, j)];
                }
                yb[(i, 0)] = bias;
            }
            if share > 0.0 {
                let none = Mat::<f64>::zeros(xb.nrows(), network.n_linear());
                let net = network.predict_with_linear(xb.as_ref(), none.as_ref());
                for i in 0..xb.nrows() {
                    yb[(i, 0)] = share * net[(i, 0)] + (1.0 - share) * bias;
                }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded, roughly normal sequence.
    fn noise(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed;
        let mut u = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        (0..n).map(|_| (0..12).map(|_| u()).sum()).collect()
    }

    /// A network that adds a hundredth of the noise's spread, unrelated to
    /// it, raises the spread ratio by 5e-5: noise, and it stays. One that
    /// adds its own pattern beyond the interval gets cov/var.
    #[test]
    fn a_ratio_within_its_interval_stays_and_one_beyond_it_is_shrunk() {
        let b = noise(3000, 1);
        let q = noise(3000, 3);
        let small: Vec<f64> = b.iter().zip(&q).map(|(b, q)| b - 0.01 * q).collect();
        let sd = |v: &[f64]| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            v.iter().map(|x| (x - m).powi(2)).sum::<f64>().sqrt()
        };
        assert!(sd(&small) > sd(&b), "the case needs a ratio above 1");
        assert_eq!(spread_beyond_interval(&b, &small), None);
        // After = before − (0.2·before + 0.8·q), each of unit variance: the
        // spread ratio is √(0.64 + 0.64) = 1.13, and the least-spread share
        // is cov/var = 0.2/0.68 = 0.29.
        let part: Vec<f64> = b.iter().zip(&q).map(|(b, q)| 0.2 * b + 0.8 * q).collect();
        let after: Vec<f64> = b.iter().zip(&part).map(|(b, p)| b - p).collect();
        let s = spread_beyond_interval(&b, &after).expect("beyond its interval");
        assert!(
            s.ratio > 1.0 && s.low > 1.0 && s.low <= s.ratio && s.ratio <= s.high,
            "{s:?}"
        );
        assert!((s.ratio - 1.13).abs() < 0.03, "{s:?}");
        assert!((s.share - 0.294).abs() < 0.03, "{s:?}");
    }
}
