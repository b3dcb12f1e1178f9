//! The fitted model: per channel, a bias, the physical effects (linear in
//! their coefficients, with intervals) and an RBF network over the input
//! windows; with the sensor and recipe it was fitted with, so new records
//! are prepared exactly as the training records were.

pub(crate) mod choice_report;
mod fade;

pub use fade::Faded;
pub(crate) use fade::{channel_network_means, network_means};

use crate::error::SysidError;
use crate::inference::Coefficient;
use crate::operating::OperatingPoints;
use crate::prepared::Prepared;
use crate::preprocess::Preprocess;
use crate::recipe::{FitSettings, Recipe};
use crate::sensor::Sensor;
pub use crate::signals::INTERVAL_TOLERANCE;
use crate::signals::Signals;
use crate::split::{Holdout, by_record_rows, split_rows};
use crate::window::signal_choice::WindowSignalsChoice;
use choice_report::{Candidate, ChoiceReport};
use faer::{Mat, MatRef};
use rayon::prelude::*;
use rbf::RbfModel;
use serde::{Deserialize, Serialize};

/// How well a channel model did, in the target's unit.
///
/// `fit_percent` is 100·(1 − ‖y − ŷ‖/‖y − ȳ‖), as MATLAB's `compare`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ChannelScores {
    /// Training rows.
    pub n_train: usize,
    /// Validation rows.
    pub n_val: usize,
    /// RMS of the residual on training rows.
    pub train_rms: f64,
    /// RMS of the residual on validation rows.
    pub val_rms: f64,
    /// RMS on validation rows of what a bias-only model leaves (the target
    /// minus its training mean): the "before" of this channel.
    pub val_rms_bias_only: f64,
    /// Fit percentage on training rows.
    pub train_fit_percent: f64,
    /// Fit percentage on validation rows.
    pub val_fit_percent: f64,
}

/// Scores of a prediction `yhat` of `y` on training and validation rows
/// (each side has rows: a split keeps at least [`crate::split::MIN_ROWS`]).
///
/// ```
/// let y = [1.0, 2.0, 3.0, 4.0];
/// let s = sysid::score(&y, &y, &[0, 1], &[2, 3]);
/// assert_eq!((s.val_rms, s.val_fit_percent), (0.0, 100.0));
/// ```
pub fn score(y: &[f64], yhat: &[f64], train: &[usize], val: &[usize]) -> ChannelScores {
    let rms = |v: Vec<f64>| stats::rms(&v);
    let mean = |rows: &[usize]| rows.iter().map(|&i| y[i]).sum::<f64>() / rows.len() as f64;
    let fit = |rows: &[usize]| {
        let m = mean(rows);
        let num = rms(rows.iter().map(|&i| y[i] - yhat[i]).collect());
        let den = rms(rows.iter().map(|&i| y[i] - m).collect());
        100.0 * (1.0 - num / den)
    };
    let train_mean = mean(train);
    ChannelScores {
        n_train: train.len(),
        n_val: val.len(),
        train_rms: rms(train.iter().map(|&i| y[i] - yhat[i]).collect()),
        val_rms: rms(val.iter().map(|&i| y[i] - yhat[i]).collect()),
        val_rms_bias_only: rms(val.iter().map(|&i| y[i] - train_mean).collect()),
        train_fit_percent: fit(train),
        val_fit_percent: fit(val),
    }
}

/// One channel's model: its effects and network, generic over the
/// sensor's channel `C` and effect `E` types.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelModel<C, E> {
    channel: C,
    effects: Vec<E>,
    /// Kernel width chosen by cross-validation, in window units.
    width: f64,
    rbf: RbfModel,
    scores: ChannelScores,
    /// Each effect's coefficient with its standard error and interval, in the
    /// order of `effects` (empty in files written before they were estimated).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    coefficients: Vec<Coefficient>,
}

impl<C: Clone, E> ChannelModel<C, E> {
    pub(crate) fn new(
        channel: C,
        effects: Vec<E>,
        width: f64,
        rbf: RbfModel,
        scores: ChannelScores,
        coefficients: Vec<Coefficient>,
    ) -> Self {
        Self {
            channel,
            effects,
            width,
            rbf,
            scores,
            coefficients,
        }
    }

    /// Each effect's coefficient with its standard error and 95% interval, in
    /// the order of [`ChannelModel::effects`]; `None` for a model that
    /// predates them.
    pub fn coefficients(&self) -> Option<&[Coefficient]> {
        (self.coefficients.len() == self.effects.len() && !self.effects.is_empty())
            .then_some(self.coefficients.as_slice())
    }

    /// The channel.
    pub fn channel(&self) -> C {
        self.channel.clone()
    }

    /// The physical effects of the linear part (the bias is always there).
    pub fn effects(&self) -> &[E] {
        &self.effects
    }

    /// The same model with each effect as `f` makes it: for a plug-in whose
    /// effect, read back from a file by its id alone, takes what only the
    /// sensor knows (a column's unit). `f` must keep the id.
    pub fn map_effects(mut self, f: impl Fn(E) -> E) -> Self {
        self.effects = self.effects.into_iter().map(f).collect();
        self
    }

    /// Estimated effect coefficients, in each effect's unit, in the order of
    /// [`ChannelModel::effects`].
    pub fn effect_coefficients(&self) -> Vec<f64> {
        let th = self.rbf.linear_coefficients();
        (0..th.nrows()).map(|i| th[(i, 0)]).collect()
    }

    /// The bias λ0, in the target's unit.
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

    /// The Gaussian width β chosen by cross-validation, in window units.
    pub fn width(&self) -> f64 {
        self.width
    }

    /// Scores at fit time.
    pub fn scores(&self) -> &ChannelScores {
        &self.scores
    }

    pub(crate) fn set_scores(&mut self, scores: ChannelScores) {
        self.scores = scores;
    }

    /// Predicted error on the rows of `windows` (rows × window dimension)
    /// with the effects' regressors `z` (rows × effects).
    pub fn predict_with(&self, windows: &Mat<f64>, z: &Mat<f64>) -> Vec<f64> {
        let y = self.rbf.predict_with_linear(windows.as_ref(), z.as_ref());
        (0..y.nrows()).map(|i| y[(i, 0)]).collect()
    }
}

/// Each channel's network output ([`network_outputs`]) on its own
/// windows: `networks[k]` is channel k's, and the channels of a group that
/// read the same windows are computed together.
pub(crate) fn channel_network_outputs<S: Sensor>(
    prepared: &Prepared<S>,
    networks: &[&RbfModel],
) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::new(); networks.len()];
    for (members, x) in prepared.window_groups() {
        let nets: Vec<&RbfModel> = members.iter().map(|&k| networks[k]).collect();
        for (&k, y) in members.iter().zip(network_outputs(&nets, x)) {
            out[k] = y;
        }
    }
    out
}

/// Each network's output (bias, tail and kernels; without the effects'
/// linear part) on the rows of `x`: the kernel columns computed once for
/// networks that share centres and width (a shared centre selection), else
/// each network on its own.
pub(crate) fn network_outputs(networks: &[&RbfModel], x: MatRef<'_, f64>) -> Vec<Vec<f64>> {
    if networks.len() > 1
        && let Some(all) = RbfModel::stacked(networks)
    {
        let y = all.predict(x);
        return (0..y.ncols())
            .map(|o| (0..y.nrows()).map(|i| y[(i, o)]).collect())
            .collect();
    }
    networks
        .par_iter()
        .map(|m| {
            let y = m.predict_with_linear(x, Mat::<f64>::zeros(x.nrows(), m.n_linear()).as_ref());
            (0..y.nrows()).map(|i| y[(i, 0)]).collect()
        })
        .collect()
}

/// `y += z θ`, row by row (nothing without effects).
pub(crate) fn add_effects(y: &mut [f64], z: &Mat<f64>, theta: &[f64]) {
    if theta.is_empty() {
        return;
    }
    for (i, v) in y.iter_mut().enumerate() {
        *v += theta
            .iter()
            .enumerate()
            .map(|(j, t)| z[(i, j)] * t)
            .sum::<f64>();
    }
}

/// A channel model of sensor `S`.
pub type ChannelModelOf<S> = ChannelModel<<S as Sensor>::Channel, <S as Sensor>::Effect>;

/// Everything a model is, for [`Model::from_parts`] (a file reader) and
/// [`Model::into_parts`].
#[derive(Debug, Clone)]
pub struct ModelParts<S: Sensor> {
    /// The sensor (with its calibration) the records were read by.
    pub sensor: S,
    /// How records are prepared.
    pub preprocess: Preprocess,
    /// The sample interval fitted at, s: the records' mean, which the
    /// filters were designed at.
    pub dt_s: f64,
    /// The records' median sample interval, s, which a record is compared
    /// by (absent: `dt_s`, as in files written before it was stored).
    pub median_dt_s: Option<f64>,
    /// The split within each record.
    pub split: Holdout,
    /// One model per channel, in the sensor's channel order.
    pub channels: Vec<ChannelModelOf<S>>,
    /// How the networks were chosen.
    pub settings: FitSettings,
    /// The records fitted together, when there were several.
    pub records: Vec<String>,
    /// Of several records, the one that only validated.
    pub validated_on: Option<String>,
    /// Where the training windows sat (absent: the transfer check cannot
    /// say what is outside).
    pub operating_points: Option<OperatingPoints>,
    /// The fit's choice of input and smoother, with every candidate's
    /// figures (absent: the recipe's were taken as they were).
    pub choice: Option<ChoiceReport>,
}

/// The channel models of a sensor and how their data were prepared.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let rec = line_record(2000, 0.5, 1);
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let (model, _) = sysid::fit_records(&Line, &[("r".into(), &rec)], &options, &|_| {})?;
/// let prepared = model.prepare(&rec)?;
/// let predicted = model.predict(&prepared)?; // one series per channel
/// assert_eq!(predicted[0].len(), prepared.rows());
/// # Ok::<(), sysid::SysidError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Model<S: Sensor> {
    sensor: S,
    preprocess: Preprocess,
    dt_s: f64,
    median_dt_s: f64,
    split: Holdout,
    channels: Vec<ChannelModelOf<S>>,
    settings: FitSettings,
    records: Vec<String>,
    validated_on: Option<String>,
    operating_points: Option<OperatingPoints>,
    choice: Option<ChoiceReport>,
}

impl<S: Sensor> Model<S> {
    /// A model from its parts, checked for what they must agree on (a
    /// hand-edited window or effect list would otherwise meet the networks'
    /// shapes only deep inside a prediction): the reason, if they do not.
    pub fn from_parts(parts: ModelParts<S>) -> Result<Self, String> {
        let m = Self {
            sensor: parts.sensor,
            preprocess: parts.preprocess,
            dt_s: parts.dt_s,
            median_dt_s: parts.median_dt_s.unwrap_or(parts.dt_s),
            split: parts.split,
            channels: parts.channels,
            settings: parts.settings,
            records: parts.records,
            validated_on: parts.validated_on,
            operating_points: parts.operating_points,
            choice: parts.choice,
        };
        m.check_consistency()?;
        Ok(m)
    }

    /// The model's parts.
    pub fn into_parts(self) -> ModelParts<S> {
        ModelParts {
            sensor: self.sensor,
            preprocess: self.preprocess,
            dt_s: self.dt_s,
            median_dt_s: Some(self.median_dt_s),
            split: self.split,
            channels: self.channels,
            settings: self.settings,
            records: self.records,
            validated_on: self.validated_on,
            operating_points: self.operating_points,
            choice: self.choice,
        }
    }

    fn check_consistency(&self) -> Result<(), String> {
        for dt in [self.dt_s, self.median_dt_s] {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(format!("sample interval {dt} s is not positive"));
            }
        }
        let w = &self.preprocess.window;
        if w.length() == 0 || w.signals().is_empty() {
            return Err("the window needs at least one sample of one signal".into());
        }
        if let Some(lists) = w.channel_lists().filter(|&l| l != self.channels.len()) {
            return Err(format!(
                "the window names the signals of {lists} channels, not of each of the model's {}",
                self.channels.len()
            ));
        }
        for (k, c) in self.channels.iter().enumerate() {
            let ch = &c.channel;
            let own = w.of_channel(k);
            let dim = self.preprocess.input.dim(&own);
            c.rbf
                .check_consistency()
                .map_err(|e| format!("channel {ch}: {e}"))?;
            if c.rbf.dim() != dim {
                return Err(format!(
                    "channel {ch}: the network takes {} inputs but the {} input of a window of {} samples × {} signals gives {dim}",
                    c.rbf.dim(),
                    self.preprocess.input,
                    w.length(),
                    own.signals().len()
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

    /// The sensor (with its calibration) the model reads records by.
    pub fn sensor(&self) -> &S {
        &self.sensor
    }

    /// How data are prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The sample interval the model was fitted at, s.
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// The median sample interval of the records fitted, s: a record is
    /// prepared for the model when its own median agrees with it within
    /// [`INTERVAL_TOLERANCE`] (a log's dropped samples lengthen its mean
    /// interval, not its median, so two logs of one rate agree).
    pub fn median_dt_s(&self) -> f64 {
        self.median_dt_s
    }

    /// How the networks were chosen.
    pub fn settings(&self) -> &FitSettings {
        &self.settings
    }

    /// The recipe the model was fitted with (its pre-processing, split,
    /// each channel's effects and network settings), to fit it again the
    /// same way.
    pub fn recipe(&self) -> Recipe<S::Effect> {
        Recipe {
            preprocess: self.preprocess.clone(),
            split: self.split,
            effects: self.channels.iter().map(|c| c.effects.clone()).collect(),
            settings: self.settings.clone(),
        }
    }

    /// The split used at fit time.
    pub fn split(&self) -> Holdout {
        self.split
    }

    /// The channel models, in the sensor's channel order.
    pub fn channels(&self) -> &[ChannelModelOf<S>] {
        &self.channels
    }

    /// Channel `channel`'s model.
    pub fn channel(&self, channel: usize) -> &ChannelModelOf<S> {
        &self.channels[channel]
    }

    /// Of several records, the one that only validated.
    pub fn validated_on(&self) -> Option<&str> {
        self.validated_on.as_deref()
    }

    /// What the fit chose among its candidates' inputs and smoothers, and
    /// each candidate's validation rms and worst Allan-deviation ratio.
    pub fn choice(&self) -> Option<&ChoiceReport> {
        self.choice.as_ref()
    }

    pub(crate) fn set_choice(&mut self, report: ChoiceReport) {
        self.choice = Some(report);
    }

    /// The fit's choice report, or for a fit that chose nothing the report
    /// of its one candidate: the model's input and smoother with its
    /// validation rms, no run judged by ADEV.
    pub(crate) fn choice_or_fixed(&self) -> ChoiceReport {
        self.choice.clone().unwrap_or_else(|| ChoiceReport {
            candidates: vec![Candidate::unjudged(
                self.preprocess.input,
                self.preprocess.smoother,
                self.channels.iter().map(|c| c.scores.val_rms).collect(),
            )],
            chosen: 0,
            adev_runs: 0,
            networks_shrunk: Vec::new(),
            input_sample: None,
            bias_instability_raised: Vec::new(),
            window_signals: Vec::new(),
        })
    }

    /// The model with the choice of its window's signals in its choice
    /// report (a report of its one candidate when it chose nothing else),
    /// so that the model file and `fit --json` say what was measured.
    pub fn with_window_signals(mut self, choices: Vec<WindowSignalsChoice>) -> Self {
        let mut report = self.choice_or_fixed();
        report.window_signals = choices;
        self.set_choice(report);
        self
    }

    pub(crate) fn set_smoother(&mut self, smoother: Option<crate::smoother::Smoother>) {
        self.preprocess.smoother = smoother;
    }

    pub(crate) fn channels_mut(&mut self) -> &mut [ChannelModelOf<S>] {
        &mut self.channels
    }

    pub(crate) fn set_validated_on(&mut self, name: Option<String>) {
        self.validated_on = name;
    }

    /// Where the training windows sat, for the transfer check.
    pub fn operating_points(&self) -> Option<&OperatingPoints> {
        self.operating_points.as_ref()
    }

    /// The records fitted together (empty for a model of one record).
    pub fn records(&self) -> &[String] {
        &self.records
    }

    pub(crate) fn set_records(&mut self, records: Vec<String>) {
        self.records = records;
    }

    /// The model with the names of the records it was fitted on (for a
    /// caller that prepared them itself; [`crate::fit_records`] names them).
    pub fn with_records(mut self, records: Vec<String>) -> Self {
        self.records = records;
        self
    }

    /// Prepares a record as the training data were, checking it can be: same
    /// sample interval, and every column the effects and windows need.
    pub fn prepare(&self, record: &Signals) -> Result<Prepared<S>, SysidError> {
        self.prepare_many(&[(String::new(), record)])
    }

    /// [`Model::prepare`] for several records, each prepared on its own and
    /// named (by its file) for errors and per-record results, as
    /// [`Prepared::new_many`] lays them end to end. One record gives exactly
    /// [`Model::prepare`].
    pub fn prepare_many(&self, records: &[(String, &Signals)]) -> Result<Prepared<S>, SysidError> {
        for (name, record) in records {
            let dt = record.median_dt();
            if ((dt - self.median_dt_s) / self.median_dt_s).abs() > INTERVAL_TOLERANCE {
                let e = SysidError::SampleInterval {
                    record_dt_s: dt,
                    model_dt_s: self.median_dt_s,
                };
                return Err(e.in_record(name, records.len()));
            }
        }
        let prepared = Prepared::new_many(&self.sensor, records, &self.preprocess)?;
        for (k, c) in self.channels.iter().enumerate() {
            // Fails early, naming what is missing, for a model fitted on other columns.
            self.sensor
                .regressors(prepared.calibrated(), k, &c.effects)
                .map_err(SysidError::Sensor)?;
        }
        Ok(prepared)
    }

    /// Predicted error of every channel on every row, in the sensor's
    /// channel order.
    pub fn predict(&self, prepared: &Prepared<S>) -> Result<Vec<Vec<f64>>, SysidError> {
        // Views of the windows, not copies (400 MB for a 1M-row record of
        // 50-sample windows).
        let records: Vec<_> = prepared.record_rows().into_iter().map(|(_, r)| r).collect();
        let rbfs: Vec<&RbfModel> = self.channels.iter().map(|c| &c.rbf).collect();
        let networks = channel_network_outputs(prepared, &rbfs);
        self.channels
            .par_iter()
            .zip(networks)
            .enumerate()
            .map(|(k, (c, mut y))| {
                let z = prepared.effect_matrix(k, &c.effects)?;
                add_effects(&mut y, &z, &c.effect_coefficients());
                crate::smoother::smoothed(
                    self.preprocess.smoother.as_ref(),
                    self.preprocess.causal,
                    self.dt_s,
                    &records,
                    (c.bias(), &c.effect_coefficients()),
                    &z,
                    y,
                )
            })
            .collect()
    }

    /// Per channel and row, the effects' part above the filter's band,
    /// θ·(z − z_filtered): what compensation adds to [`Model::predict`] to
    /// subtract the effects unfiltered from the unfiltered output. The
    /// coefficients were estimated with the same filter on both sides
    /// (filtered target on filtered regressors), so the unfiltered θ·z is
    /// the effect itself; subtracting θ·z_filtered left its part above the
    /// cut-off in the output (Y1 of `triaxial_hidden`: 0.906 deg/h above the
    /// noise floor against 0.150 without the filter). Zero for a channel
    /// without effects.
    pub fn effects_above_band(&self, prepared: &Prepared<S>) -> Result<Vec<Vec<f64>>, SysidError> {
        self.channels
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let theta = c.effect_coefficients();
                if theta.is_empty() {
                    return Ok(vec![0.0; prepared.rows()]);
                }
                let raw = prepared.effect_matrix_unfiltered(k, &c.effects)?;
                let low = prepared.effect_matrix(k, &c.effects)?;
                Ok((0..prepared.rows())
                    .map(|i| {
                        theta
                            .iter()
                            .enumerate()
                            .map(|(j, t)| t * (raw[(i, j)] - low[(i, j)]))
                            .sum()
                    })
                    .collect())
            })
            .collect()
    }

    /// Training and validation rows of prepared data, as at fit time: the
    /// model's split within each record, or, for a model validated on one
    /// whole record (`--split by-record --validate-on`) and data that hold
    /// that record among others, every other record training and that one
    /// validating.
    pub fn rows(&self, prepared: &Prepared<S>) -> Result<(Vec<usize>, Vec<usize>), SysidError> {
        match &self.validated_on {
            Some(name)
                if prepared.record_rows().len() > 1
                    && prepared.record_rows().iter().any(|(n, _)| n == name) =>
            {
                by_record_rows(prepared, name)
            }
            _ => split_rows(prepared, self.split),
        }
    }
}
