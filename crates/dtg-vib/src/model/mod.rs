//! The fitted compensation model of the paper's unit: the loop's model
//! ([`sysid::Model`]) of the [`PaperUnit`] — per channel, physical effects
//! (linear) plus an RBF network on the acceleration window, with everything
//! needed to prepare new data the same way (calibration, filter, window,
//! rate reference) — read by channel and saved as versioned JSON.

mod persist;

pub use persist::FORMAT_VERSION;
pub use sysid::{CentreMethod, ChannelScores, FitSettings, INTERVAL_TOLERANCE, Recipe};

use crate::effects::Effect;
use crate::error::DtgVibError;
use crate::paper_unit::{PaperUnit, borrowed, named_signals};
use crate::pipeline::{Prepared, Preprocess};
use crate::split::Holdout;
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;

/// One gyro channel's model: its effects, network, scores and intervals.
pub type ChannelModel = sysid::ChannelModel<Channel, Effect>;

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
#[derive(Debug, Clone, PartialEq)]
pub struct CompensationModel {
    inner: sysid::Model<PaperUnit>,
    /// The loop's pre-processing with the unit's rate reference, as files
    /// and the command line say it.
    preprocess: Preprocess,
}

impl CompensationModel {
    /// The paper unit's model of a loop's model.
    pub fn of(inner: sysid::Model<PaperUnit>) -> Self {
        let preprocess = Preprocess::of(inner.preprocess(), inner.sensor().rate_reference);
        Self { inner, preprocess }
    }

    /// The loop's model.
    pub fn inner(&self) -> &sysid::Model<PaperUnit> {
        &self.inner
    }

    /// How data are prepared.
    pub fn preprocess(&self) -> &Preprocess {
        &self.preprocess
    }

    /// The ground calibration the model was fitted after, if any.
    pub fn calibration(&self) -> Option<&Calibration> {
        self.inner.sensor().calibration.as_ref()
    }

    /// The sample interval the model was fitted at, s.
    pub fn dt_s(&self) -> f64 {
        self.inner.dt_s()
    }

    /// How the networks were chosen.
    pub fn fit_settings(&self) -> &FitSettings {
        self.inner.settings()
    }

    /// The recipe the model was fitted with (its pre-processing, split,
    /// each channel's effects and network settings; the rate reference is
    /// the unit's), to fit it again the same way.
    pub fn recipe(&self) -> Recipe<Effect> {
        self.inner.recipe()
    }

    /// The split used at fit time.
    pub fn split(&self) -> Holdout {
        self.inner.split()
    }

    /// The channel models, in X, X1, Y, Y1, Z, Z1 order.
    pub fn channels(&self) -> &[ChannelModel] {
        self.inner.channels()
    }

    /// One channel's model.
    pub fn channel(&self, channel: Channel) -> &ChannelModel {
        self.inner.channel(channel.index())
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
        let signals = named_signals(records)?;
        let inner = self.inner.prepare_many(&borrowed(&signals))?;
        Prepared::of(inner, self.preprocess.clone())
    }

    /// Predicted error of every channel on every row, deg/h, in X, X1, Y, Y1, Z, Z1 order.
    pub fn predict(&self, prepared: &Prepared) -> Result<[Vec<f64>; 6], DtgVibError> {
        let mut out = self.inner.predict(prepared.inner())?.into_iter();
        Ok(std::array::from_fn(|_| out.next().unwrap_or_default()))
    }

    /// What compensation subtracts from each unfiltered output, deg/h, in
    /// X, X1, Y, Y1, Z, Z1 order: [`CompensationModel::predict`], its network
    /// part faded outside the training range, with the
    /// effects unfiltered (θ·z, [`sysid::Model::effects_above_band`]); the
    /// onboard evaluator computes the same.
    pub fn compensation(&self, prepared: &Prepared) -> Result<[Vec<f64>; 6], DtgVibError> {
        let above = self.inner.effects_above_band(prepared.inner())?;
        // The network part faded outside the training range, as compensate fades it.
        let predicted = self.inner.predict_faded(prepared.inner())?.predicted;
        Ok(std::array::from_fn(|k| {
            predicted[k]
                .iter()
                .zip(&above[k])
                .map(|(p, a)| p + a)
                .collect()
        }))
    }

    /// Of several records, the one that only validated (`--validate-on`).
    pub fn validated_on(&self) -> Option<&str> {
        self.inner.validated_on()
    }

    /// Where the training windows sat, for `check`'s extrapolation measure.
    pub fn operating_points(&self) -> Option<&sysid::operating::OperatingPoints> {
        self.inner.operating_points()
    }

    /// The records fitted together (empty for a model of one record).
    pub fn records(&self) -> &[String] {
        self.inner.records()
    }

    /// Training and validation rows of prepared data, as at fit time
    /// ([`sysid::Model::rows`]).
    pub fn rows(&self, prepared: &Prepared) -> Result<(Vec<usize>, Vec<usize>), DtgVibError> {
        Ok(self.inner.rows(prepared.inner())?)
    }
}
