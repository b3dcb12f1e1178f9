//! The fitted compensation model: per channel, physical effects (linear) plus
//! an RBF network on the acceleration window, with everything needed to
//! prepare new data the same way (calibration, filter, window, rate
//! reference). Saved as versioned JSON.

mod persist;
mod settings;

pub use persist::FORMAT_VERSION;
pub use settings::{CentreMethod, FitSettings, Recipe};

use crate::effects::Effect;
use crate::error::DtgVibError;
use crate::inference::Coefficient;
use crate::pipeline::{Prepared, Preprocess};
use crate::split::Holdout;
use faer::Mat;
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use rbf::RbfModel;
use serde::{Deserialize, Serialize};

/// How well a channel model did, deg/h.
///
/// `fit_percent` is 100·(1 − ‖y − ŷ‖/‖y − ȳ‖), as MATLAB's `compare`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ChannelScores {
    /// Training rows.
    pub n_train: usize,
    /// Validation rows.
    pub n_val: usize,
    /// RMS of the residual on training rows, deg/h.
    pub train_rms: f64,
    /// RMS of the residual on validation rows, deg/h.
    pub val_rms: f64,
    /// RMS on validation rows of what a bias-only model leaves (the target
    /// minus its training mean), deg/h: the "before" of this channel.
    pub val_rms_bias_only: f64,
    /// Fit percentage on training rows.
    pub train_fit_percent: f64,
    /// Fit percentage on validation rows.
    pub val_fit_percent: f64,
}

/// One gyro channel's model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelModel {
    channel: Channel,
    effects: Vec<Effect>,
    /// Kernel width chosen by cross-validation, in window units (g).
    width: f64,
    rbf: RbfModel,
    scores: ChannelScores,
    /// Each effect's coefficient with its standard error and interval, in the
    /// order of `effects` (empty in files written before they were estimated).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    coefficients: Vec<Coefficient>,
}

impl ChannelModel {
    pub(crate) fn new(
        channel: Channel,
        effects: Vec<Effect>,
        width: f64,
        rbf: RbfModel,
        scores: ChannelScores,
    ) -> Self {
        Self {
            channel,
            effects,
            width,
            rbf,
            scores,
            coefficients: Vec::new(),
        }
    }

    pub(crate) fn with_coefficients(mut self, coefficients: Vec<Coefficient>) -> Self {
        self.coefficients = coefficients;
        self
    }

    /// Each effect's coefficient with its standard error and 95% interval, in
    /// the order of [`ChannelModel::effects`]; `None` for a model file that
    /// predates them.
    pub fn coefficients(&self) -> Option<&[Coefficient]> {
        (self.coefficients.len() == self.effects.len() && !self.effects.is_empty())
            .then_some(self.coefficients.as_slice())
    }

    /// The channel.
    pub fn channel(&self) -> Channel {
        self.channel
    }

    /// The physical effects of the linear part (the bias is always there).
    pub fn effects(&self) -> &[Effect] {
        &self.effects
    }

    /// Estimated effect coefficients, in each effect's unit, in the order of
    /// [`ChannelModel::effects`].
    pub fn effect_coefficients(&self) -> Vec<f64> {
        let th = self.rbf.linear_coefficients();
        (0..th.nrows()).map(|i| th[(i, 0)]).collect()
    }

    /// The bias λ0, deg/h.
    pub fn bias(&self) -> f64 {
        self.rbf.bias().map_or(0.0, |b| b[0])
    }

    /// The RBF network.
    pub fn rbf(&self) -> &RbfModel {
        &self.rbf
    }

    /// Number of RBF centres.
    pub fn n_centres(&self) -> usize {
        self.rbf.n_centres()
    }

    /// The Gaussian width β chosen by cross-validation, in window units (g).
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Scores at fit time.
    pub fn scores(&self) -> &ChannelScores {
        &self.scores
    }

    /// Predicted error on every row of prepared data, deg/h.
    pub fn predict(
        &self,
        prepared: &Prepared,
        windows: &Mat<f64>,
    ) -> Result<Vec<f64>, DtgVibError> {
        let z = prepared.effect_matrix(self.channel, &self.effects)?;
        let y = self.rbf.predict_with_linear(windows.as_ref(), z.as_ref());
        Ok((0..y.nrows()).map(|i| y[(i, 0)]).collect())
    }
}

/// The six channel models and how their data were prepared.
///
/// ```no_run
/// use dtg_vib::model::CompensationModel;
/// let model = CompensationModel::load("model.json")?;
/// let rec = nav_sensors::record::Record::read_csv("record.csv")?;
/// let prepared = model.prepare(&rec)?;
/// let errors = model.predict(&prepared)?; // six series of predicted error, deg/h
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompensationModel {
    pub(crate) preprocess: Preprocess,
    pub(crate) calibration: Option<Calibration>,
    pub(crate) dt_s: f64,
    pub(crate) split: Holdout,
    pub(crate) channels: Vec<ChannelModel>,
    /// How the networks were chosen (absent in older files: the defaults).
    #[serde(default)]
    pub(crate) fit: FitSettings,
    /// The records fitted together, when there were several.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub(crate) records: Vec<String>,
    /// Of several records, the one that only validated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) validated_on: Option<String>,
    /// Where the training windows sat (absent in older files: `check` then
    /// cannot say what is outside).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) operating_points: Option<crate::operating::OperatingPoints>,
}

/// Relative tolerance on a record's sample interval against the model's.
pub const INTERVAL_TOLERANCE: f64 = 1e-3;

impl CompensationModel {
    /// What a model file must agree with before anything runs on it: a
    /// hand-edited window or effect list would otherwise meet the networks'
    /// shapes only deep inside a prediction.
    pub(crate) fn check_consistency(&self) -> Result<(), String> {
        if !(self.dt_s.is_finite() && self.dt_s > 0.0) {
            return Err(format!("sample interval {} s is not positive", self.dt_s));
        }
        let w = &self.preprocess.window;
        if w.length() == 0 || w.signals().is_empty() {
            return Err("the window needs at least one sample of one signal".into());
        }
        let dim = w.length() * w.signals().len();
        for c in &self.channels {
            let ch = c.channel();
            c.rbf
                .check_consistency()
                .map_err(|e| format!("channel {ch}: {e}"))?;
            if c.rbf.dim() != dim {
                return Err(format!(
                    "channel {ch}: the network takes {} inputs but the window gives {} samples × {} signals = {dim}",
                    c.rbf.dim(),
                    w.length(),
                    w.signals().len()
                ));
            }
            if c.rbf.n_linear() != c.effects.len() {
                return Err(format!(
                    "channel {ch}: {} effect coefficients for {} effects",
                    c.rbf.n_linear(),
                    c.effects.len()
                ));
            }
            if c.rbf.n_outputs() != 1 {
                return Err(format!(
                    "channel {ch}: the network has {} outputs, not 1",
                    c.rbf.n_outputs()
                ));
            }
        }
        Ok(())
    }

    /// How data are prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The ground calibration the model was fitted after, if any.
    pub fn calibration(&self) -> Option<&Calibration> {
        self.calibration.as_ref()
    }

    /// The sample interval the model was fitted at, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// How the networks were chosen.
    pub fn fit_settings(&self) -> &FitSettings {
        &self.fit
    }

    /// The recipe the model was fitted with (its pre-processing, split,
    /// each channel's effects and network settings), to fit it again the
    /// same way.
    pub fn recipe(&self) -> Recipe {
        Recipe {
            preprocess: self.preprocess.clone(),
            split: self.split,
            effects: std::array::from_fn(|k| self.channels[k].effects.clone()),
            settings: self.fit.clone(),
        }
    }

    /// The split used at fit time.
    pub fn split(&self) -> Holdout {
        self.split
    }

    /// The channel models, in X, X1, Y, Y1, Z, Z1 order.
    pub fn channels(&self) -> &[ChannelModel] {
        &self.channels
    }

    /// One channel's model.
    pub fn channel(&self, channel: Channel) -> &ChannelModel {
        &self.channels[channel.index()]
    }

    /// Prepares a record as the training data were, checking it can be: same
    /// sample interval, and every column the effects and windows need.
    pub fn prepare(&self, record: &Record) -> Result<Prepared, DtgVibError> {
        self.prepare_many(&[(String::new(), record)])
    }

    /// [`CompensationModel::prepare`] for several records, each prepared on
    /// its own and named (by its file) for errors and per-record results, as
    /// [`Prepared::new_many`] lays them end to end. One record gives exactly
    /// [`CompensationModel::prepare`].
    pub fn prepare_many(&self, records: &[(String, &Record)]) -> Result<Prepared, DtgVibError> {
        for (name, record) in records {
            let dt = record.dt();
            if ((dt - self.dt_s) / self.dt_s).abs() > INTERVAL_TOLERANCE {
                let e = DtgVibError::SampleInterval {
                    record_dt_s: dt,
                    model_dt_s: self.dt_s,
                };
                return Err(match records.len() {
                    1 => e,
                    _ => DtgVibError::InRecord {
                        record: name.clone(),
                        source: Box::new(e),
                    },
                });
            }
        }
        let prepared = Prepared::new_many(records, self.calibration.as_ref(), &self.preprocess)?;
        for c in &self.channels {
            // Fails early, naming the missing column, for a model fitted on other columns.
            crate::effects::EffectColumns::new(prepared.calibrated())
                .evaluate(c.channel, &c.effects)?;
        }
        Ok(prepared)
    }

    /// Predicted error of every channel on every row, deg/h, in X, X1, Y, Y1, Z, Z1 order.
    pub fn predict(&self, prepared: &Prepared) -> Result<[Vec<f64>; 6], DtgVibError> {
        let w = prepared.window_matrix();
        let mut out: [Vec<f64>; 6] = Default::default();
        for c in &self.channels {
            out[c.channel.index()] = c.predict(prepared, &w)?;
        }
        Ok(out)
    }

    /// Of several records, the one that only validated (`--validate-on`).
    pub fn validated_on(&self) -> Option<&str> {
        self.validated_on.as_deref()
    }

    /// Where the training windows sat, for `check`'s extrapolation measure.
    pub fn operating_points(&self) -> Option<&crate::operating::OperatingPoints> {
        self.operating_points.as_ref()
    }

    /// The records fitted together (empty for a model of one record).
    pub fn records(&self) -> &[String] {
        &self.records
    }

    /// Training and validation rows of prepared data, as at fit time: the
    /// model's split within each record, or, for a model validated on one
    /// whole record (`--split by-record --validate-on`) and data that hold
    /// that record among others, every other record training and that one
    /// validating.
    pub fn rows(&self, prepared: &Prepared) -> Result<(Vec<usize>, Vec<usize>), DtgVibError> {
        match &self.validated_on {
            Some(name)
                if prepared.record_rows().len() > 1
                    && prepared.record_rows().iter().any(|(n, _)| n == name) =>
            {
                crate::split::by_record_rows(prepared, name)
            }
            _ => crate::split::split_rows(prepared, self.split),
        }
    }
}
