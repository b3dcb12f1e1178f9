//! The model and its mirror as one out-of-sample predictor: each half
//! predicts the rows the other was fitted on, so every analysed row has a
//! residual from a model that did not see it, and a candidate column has
//! each half's function space projected out the same way.

use crate::error::SysidError;
use crate::model::ChannelModelOf;
use crate::prepared::Prepared;
use crate::sensor::Sensor;
use faer::Mat;

/// One half of a cross-fit: a channel model, its predictions, the rows it
/// was fitted on and the rows it predicts out of sample.
pub(super) struct Half<'a, S: Sensor> {
    pub(super) model: &'a ChannelModelOf<S>,
    pub(super) predicted: &'a [f64],
    pub(super) fit_rows: &'a [usize],
    pub(super) test_rows: &'a [usize],
}

/// The model and its mirror: between them every analysed row is predicted
/// by a model that did not see it.
pub(super) struct CrossFit<'a, S: Sensor> {
    pub(super) x: &'a Mat<f64>,
    /// The fit's ridge on network weights.
    pub(super) ridge: f64,
    /// The channel both halves model.
    pub(super) channel: usize,
    pub(super) halves: [Half<'a, S>; 2],
}

impl<S: Sensor> CrossFit<'_, S> {
    /// The analysed rows, in time order.
    pub(super) fn rows(&self) -> Vec<usize> {
        let mut r: Vec<usize> = self
            .halves
            .iter()
            .flat_map(|h| h.test_rows.iter().copied())
            .collect();
        r.sort_unstable();
        r
    }

    /// Out-of-sample residual `y − ŷ` on [`CrossFit::rows`].
    pub(super) fn residual(&self, y: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; y.len()];
        for h in &self.halves {
            for &r in h.test_rows {
                out[r] = y[r] - h.predicted[r];
            }
        }
        self.rows().iter().map(|&r| out[r]).collect()
    }

    /// Each half's network part on its test rows (its prediction less its
    /// bias and effects), on [`CrossFit::rows`].
    pub(super) fn network_part(&self, prepared: &Prepared<S>) -> Result<Vec<f64>, SysidError> {
        let mut out = vec![0.0; prepared.rows()];
        for h in &self.halves {
            let z = prepared.effect_matrix(self.channel, h.model.effects())?;
            let theta = h.model.effect_coefficients();
            let b = h.model.bias();
            for &r in h.test_rows {
                let zt: f64 = theta.iter().enumerate().map(|(j, t)| z[(r, j)] * t).sum();
                out[r] = h.predicted[r] - b - zt;
            }
        }
        Ok(self.rows().iter().map(|&r| out[r]).collect())
    }

    /// `columns` (rows × m, all prepared rows) with each half's function space
    /// (bias, the model's effects, its network basis) fitted on its fitting
    /// rows and projected out of its test rows; on [`CrossFit::rows`].
    pub(super) fn partial_out(
        &self,
        prepared: &Prepared<S>,
        columns: &Mat<f64>,
    ) -> Result<Mat<f64>, SysidError> {
        let m = columns.ncols();
        let mut out = Mat::<f64>::zeros(columns.nrows(), m);
        for h in &self.halves {
            let z = prepared.effect_matrix(self.channel, h.model.effects())?;
            let p = z.ncols();
            let basis = |rows: &[usize]| {
                let xr = Mat::from_fn(rows.len(), self.x.ncols(), |i, j| self.x[(rows[i], j)]);
                let f = h.model.rbf().features(xr.as_ref());
                // [bias, effects, network]: the unpenalised columns first.
                Mat::from_fn(rows.len(), f.ncols() + p, |i, j| match j {
                    0 => f[(i, 0)],
                    j if j <= p => z[(rows[i], j - 1)],
                    j => f[(i, j - p)],
                })
            };
            let pick = |rows: &[usize]| Mat::from_fn(rows.len(), m, |i, j| columns[(rows[i], j)]);
            let r = crate::inference::residualise(
                basis(h.fit_rows).as_ref(),
                pick(h.fit_rows).as_ref(),
                basis(h.test_rows).as_ref(),
                pick(h.test_rows).as_ref(),
                1 + p,
                self.ridge,
            )
            .map_err(|e| SysidError::Fit {
                channel: h.model.channel().to_string(),
                source: e.into(),
            })?;
            for (i, &row) in h.test_rows.iter().enumerate() {
                for j in 0..m {
                    out[(row, j)] = r[(i, j)];
                }
            }
        }
        let rows = self.rows();
        Ok(Mat::from_fn(rows.len(), m, |i, j| out[(rows[i], j)]))
    }
}
