//! A model's prediction with its network part faded outside its training
//! range ([`crate::operating::fade`] holds the fade's weights and hold).

use super::{ChannelModelOf, Model};
use crate::error::SysidError;
use crate::operating::fade::{Weights, held_series, weights};
use crate::prepared::Prepared;
use crate::sensor::Sensor;
use faer::{Mat, MatRef};

/// A model's prediction with its network part faded, and without.
#[derive(Debug, Clone, PartialEq)]
pub struct Faded {
    /// What compensation subtracts: the network part faded outside the range.
    pub predicted: Vec<Vec<f64>>,
    /// The model as fitted, not faded ([`Model::predict`]).
    pub unfaded: Vec<Vec<f64>>,
    /// The weights (`None` for a model without a training range; then
    /// `predicted` is `unfaded`).
    pub weights: Option<Weights>,
}

impl<S: Sensor> Model<S> {
    /// The fade weights of the model on prepared data (each record of
    /// several restarts the smoother); `None` for a model without a
    /// training range (fitted by an older version: it never fades).
    pub fn fade_weights(&self, prepared: &Prepared<S>) -> Result<Option<Weights>, SysidError> {
        let Some(range) = self.operating_points().and_then(|o| o.range.as_ref()) else {
            return Ok(None);
        };
        range.check(&self.sensor().operating_signals(), self.channels().len())?;
        weights(range, prepared, self.dt_s()).map(Some)
    }

    /// Each channel's network part on every row: the RBF sum without bias
    /// and effects, in the target's unit.
    pub fn network_parts(&self, prepared: &Prepared<S>) -> Vec<Vec<f64>> {
        let mut parts = vec![Vec::new(); self.channels().len()];
        for (members, view) in prepared.window_groups() {
            let windows = Mat::from_fn(view.nrows(), view.ncols(), |i, j| view[(i, j)]);
            for k in members {
                let c = self.channel(k);
                let z = Mat::<f64>::zeros(windows.nrows(), c.rbf().n_linear());
                let b = c.bias();
                parts[k] = c
                    .predict_with(&windows, &z)
                    .into_iter()
                    .map(|v| v - b)
                    .collect();
            }
        }
        parts
    }

    /// Predicts every channel on every row, with the network part faded
    /// outside the training range: what `compensate` and `check` subtract.
    ///
    /// ```
    /// # use sysid::example::{Line, line_record};
    /// let mut options = sysid::FitOptions::new(1);
    /// options.recipe.preprocess = Line::preprocess();
    /// options.recipe.settings.max_centres = 5;
    /// let model = sysid::fit(&Line, &line_record(3000, 2.0, 1), &options, &|_| {})?;
    /// let own = model.prepare(&line_record(3000, 2.0, 1))?;
    /// let f = model.predict_faded(&own)?;
    /// assert_eq!(f.predicted, f.unfaded); // its own record: inside, to the bit
    /// # Ok::<(), sysid::SysidError>(())
    /// ```
    pub fn predict_faded(&self, prepared: &Prepared<S>) -> Result<Faded, SysidError> {
        let unfaded = self.predict(prepared)?;
        let weights = self.fade_weights(prepared)?;
        let predicted = match (
            &weights,
            self.operating_points().and_then(|o| o.range.as_ref()),
        ) {
            (Some(w), Some(range)) if w.weight.iter().any(|&v| v < 1.0) => {
                let parts: Vec<std::ops::Range<usize>> =
                    prepared.record_rows().into_iter().map(|(_, r)| r).collect();
                let net = self.network_parts(prepared);
                let alpha = range.fade.alpha(self.dt_s());
                let held: Vec<Vec<f64>> = net
                    .iter()
                    .zip(&range.network_mean)
                    .map(|(r, &c)| {
                        parts
                            .iter()
                            .flat_map(|rows| {
                                held_series(&r[rows.clone()], c, &w.weight[rows.clone()], alpha)
                            })
                            .collect()
                    })
                    .collect();
                // The fade holds the network's own output, before the
                // prediction smoother: a zero-phase smoother run over the
                // unfaded network would carry what it extrapolates outside
                // the range into the held value (onboard and the C export
                // fade first too).
                let smooth = |v: &[f64]| -> Result<Vec<f64>, SysidError> {
                    match &self.preprocess().smoother {
                        Some(s) => crate::smoother::smooth_by_record(
                            s,
                            v,
                            &parts,
                            self.dt_s(),
                            self.preprocess().causal,
                        ),
                        None => Ok(v.to_vec()),
                    }
                };
                unfaded
                    .iter()
                    .zip(net.iter().zip(&held))
                    .map(|(p, (r, h))| {
                        let (r, h) = (smooth(r)?, smooth(h)?);
                        Ok(p.iter()
                            .zip(r.iter().zip(&h))
                            .map(|(p, (r, h))| p - (r - h))
                            .collect())
                    })
                    .collect::<Result<Vec<Vec<f64>>, SysidError>>()?
            }
            _ => unfaded.clone(),
        };
        Ok(Faded {
            predicted,
            unfaded,
            weights,
        })
    }
}

/// The network means over rows `rows` of every channel, for
/// [`TrainingRange::network_mean`](crate::operating::range::TrainingRange::network_mean)
/// (at most 20,000 rows, evenly strided).
pub(crate) fn network_means<S: Sensor>(
    model_channels: &[ChannelModelOf<S>],
    windows: MatRef<'_, f64>,
    rows: &[usize],
) -> Vec<f64> {
    let step = rows.len().div_ceil(20_000).max(1);
    let rows: Vec<usize> = rows.iter().step_by(step).copied().collect();
    let x = Mat::from_fn(rows.len(), windows.ncols(), |i, j| windows[(rows[i], j)]);
    model_channels
        .iter()
        .map(|c| {
            let z = Mat::<f64>::zeros(x.nrows(), c.rbf().n_linear());
            let b = c.bias();
            let v = c.predict_with(&x, &z);
            v.iter().map(|v| v - b).sum::<f64>() / v.len().max(1) as f64
        })
        .collect()
}

/// [`network_means`] of every channel (`model_channels[k]`: channel k's),
/// each on its own windows.
pub(crate) fn channel_network_means<S: Sensor>(
    model_channels: &[ChannelModelOf<S>],
    prepared: &Prepared<S>,
    rows: &[usize],
) -> Vec<f64> {
    let mut means = vec![0.0; model_channels.len()];
    for (members, windows) in prepared.window_groups() {
        let own: Vec<ChannelModelOf<S>> =
            members.iter().map(|&k| model_channels[k].clone()).collect();
        for (&k, m) in members.iter().zip(network_means::<S>(&own, windows, rows)) {
            means[k] = m;
        }
    }
    means
}
