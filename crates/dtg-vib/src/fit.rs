//! Fitting the six channel models of the paper's unit: the loop's fit
//! ([`sysid::fit`]) of the [`PaperUnit`], told in the command line's words
//! (effects of every channel, additions to one channel, the rate reference
//! and the calibration).

use crate::effects::{ChannelEffect, Effect};
use crate::error::DtgVibError;
use crate::model::CompensationModel;
use crate::pipeline::{Prepared, Preprocess};
use crate::split::Holdout;
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;
use sysid::Signals;

pub use sysid::fit::{
    Candidate, ChoiceReport, MAX_SELECTION_ROWS, MIN_BLOCK_ROWS, ModelChoice, RecordScore,
    selection_stride,
};
pub use sysid::{CentreMethod, FitSettings, Recipe};

/// Which stage of a fit is running, for progress display.
pub type FitStage = sysid::FitStage<Channel>;

/// Everything a fit can be told: the recipe in the command line's words
/// (effects of every channel, additions to one channel) and, of several
/// records, the one that only validates.
///
/// ```
/// let o = dtg_vib::fit::FitOptions::default();
/// assert_eq!(o.settings.max_centres, 60);
/// assert!(o.effects.is_empty());
/// // Input and smoother chosen by validation under the Allan constraint.
/// assert_eq!(o.settings.choice, Some(dtg_vib::fit::ModelChoice::default()));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Pre-processing (filter, window, rate reference).
    pub preprocess: Preprocess,
    /// Effects of every channel's linear part.
    pub effects: Vec<Effect>,
    /// Effects added to one channel each.
    pub add: Vec<ChannelEffect>,
    /// Training/validation split (within each record of several).
    pub split: Holdout,
    /// Of several records, the one that only validates (the others only
    /// train); `None`: [`FitOptions::split`] within each record.
    pub validate_on: Option<String>,
    /// How the networks are chosen (what the model keeps).
    pub settings: FitSettings,
}

impl Default for FitOptions {
    /// The command line's defaults: the loop's, with the network input and
    /// prediction smoother chosen (`fit --input auto --smoother auto`).
    fn default() -> Self {
        Self {
            preprocess: Preprocess::default(),
            effects: Vec::new(),
            add: Vec::new(),
            split: Holdout::default(),
            validate_on: None,
            settings: FitSettings {
                choice: Some(ModelChoice::default()),
                ..FitSettings::default()
            },
        }
    }
}

impl FitOptions {
    /// The recipe these options describe: each channel's effects resolved
    /// (the common ones, then its additions, each once).
    ///
    /// ```
    /// use dtg_vib::fit::FitOptions;
    /// let o = FitOptions {
    ///     effects: vec!["g_I".parse().unwrap()],
    ///     add: vec!["Y1=gg_IS".parse().unwrap()],
    ///     ..FitOptions::default()
    /// };
    /// let r = o.recipe();
    /// assert_eq!(r.effects_of(0).len(), 1); // X
    /// assert_eq!(r.effects_of(3)[1].id(), "gg_IS"); // Y1
    /// ```
    pub fn recipe(&self) -> Recipe<Effect> {
        Recipe {
            preprocess: self.preprocess.sysid(),
            split: self.split,
            effects: Channel::ALL.iter().map(|&c| self.effects_of(c)).collect(),
            settings: self.settings.clone(),
        }
    }

    /// The loop's options.
    pub fn sysid(&self) -> sysid::FitOptions<Effect> {
        sysid::FitOptions {
            recipe: self.recipe(),
            validate_on: self.validate_on.clone(),
        }
    }

    /// The effects of one channel: the common ones, then its additions.
    pub fn effects_of(&self, channel: Channel) -> Vec<Effect> {
        let mut e = self.effects.clone();
        for a in self.add.iter().filter(|a| a.channel == channel) {
            if !e.contains(&a.effect) {
                e.push(a.effect.clone());
            }
        }
        e
    }
}

/// Fits the six channel models on a record.
///
/// ```no_run
/// use dtg_vib::fit::{fit, FitOptions};
/// let rec = nav_sensors::record::Record::read_csv("record.csv")?;
/// let model = fit(&rec, None, &FitOptions::default(), &|_| {})?;
/// println!("{}", model.channel(nav_sensors::geometry::Channel::Z).scores().val_rms);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit(
    record: &Record,
    calibration: Option<&Calibration>,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<CompensationModel, DtgVibError> {
    options.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new(record, calibration, &options.preprocess)?;
    fit_prepared(&prepared, options, progress)
}

/// [`fit`] on data already prepared (with `options.preprocess`, after the
/// calibration the model is to keep: both come from `prepared`).
pub fn fit_prepared(
    prepared: &Prepared,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<CompensationModel, DtgVibError> {
    let model = sysid::fit_prepared(prepared.inner(), &options.sysid(), progress)?;
    Ok(CompensationModel::of(model))
}

/// [`fit`] on several records, each prepared on its own (filters and
/// windows never cross a boundary) and named for errors and scores.
///
/// ```no_run
/// use dtg_vib::fit::{fit_records, FitOptions};
/// use nav_sensors::record::Record;
/// let (x, z) = (Record::read_csv("x.csv")?, Record::read_csv("z.csv")?);
/// let recs = [("x.csv".to_string(), &x), ("z.csv".to_string(), &z)];
/// let (model, prepared) = fit_records(&recs, None, &FitOptions::default(), &|_| {})?;
/// let per_record = dtg_vib::fit::record_scores(&model, &prepared)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn fit_records(
    records: &[(String, &Record)],
    calibration: Option<&Calibration>,
    options: &FitOptions,
    progress: &(dyn Fn(FitStage) + Sync),
) -> Result<(CompensationModel, Prepared), DtgVibError> {
    options.settings.check()?;
    progress(FitStage::Preparing);
    let prepared = Prepared::new_many(records, calibration, &options.preprocess)?;
    let mut model = sysid::fit_prepared(prepared.inner(), &options.sysid(), progress)?;
    if records.len() > 1 {
        model = model.with_records(records.iter().map(|(n, _)| n.clone()).collect());
    }
    let model = CompensationModel::of(model);
    // The records as the model reads them: its chosen input may not be
    // the one they were prepared with.
    let input = model.preprocess().input;
    let prepared = match prepared.preprocess().input == input {
        true => prepared,
        false => Prepared::of(
            prepared.inner().with_input(input)?,
            model.preprocess().clone(),
        )?,
    };
    Ok((model, prepared))
}

/// The window's signals chosen from the training records, each calibrated
/// (`fit --window-signals auto`): the accelerometer axes whose vibration is
/// significant in some record ([`sysid::window::signal_choice`]).
///
/// ```
/// let z = nav_sensors::sim::simulate(&nav_sensors::sim::Scenario::paper_z_random())?;
/// let c = dtg_vib::fit::choose_window_signals(&[("z".into(), &z.record)], Some(&z.calibration))?;
/// assert_eq!(c.taken, ["az"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn choose_window_signals(
    records: &[(String, &Record)],
    calibration: Option<&Calibration>,
) -> Result<sysid::window::signal_choice::WindowSignalsChoice, DtgVibError> {
    use sysid::Sensor;
    let unit = crate::paper_unit::PaperUnit {
        calibration: None,
        rate_reference: Default::default(),
    };
    // Only the accelerometers are read: calibrating them alone, as the full
    // calibration does, spares the gyro model's two passes over every row
    // (about 3 s on a 1M-row record).
    let names = unit.operating_signals();
    let accels = records
        .iter()
        .map(|(n, r)| {
            let accel = match calibration {
                Some(c) => {
                    let accel = c.compensate_accel(r);
                    crate::paper_unit::check_calibrated_accel(
                        r.t(),
                        &accel.each_ref().map(|a| &a[..]),
                    )
                    .map_err(|e| {
                        sysid::SysidError::Sensor(Box::new(e)).in_record(n, records.len())
                    })?;
                    accel
                }
                None => Axis::ALL.map(|a| r.accel(a).to_vec()),
            };
            let columns = names.iter().cloned().zip(accel).collect();
            Ok((n.clone(), Signals::new(r.t().to_vec(), columns)?))
        })
        .collect::<Result<Vec<(String, Signals)>, sysid::SysidError>>()?;
    let borrowed: Vec<(String, &Signals)> = accels.iter().map(|(n, s)| (n.clone(), s)).collect();
    Ok(sysid::window::signal_choice::choose_among(
        &names,
        &borrowed,
        unit.operating_scale(),
        &unit.wording().operating_unit,
    )
    .map_err(sysid::SysidError::from)?)
}

/// Each channel's validation rms on each record of `prepared`, for the
/// validation rows the model was fitted with (X, X1, Y, Y1, Z, Z1 order); a
/// record without validation rows (it only trained) is left out.
pub fn record_scores(
    model: &CompensationModel,
    prepared: &Prepared,
) -> Result<[Vec<RecordScore>; 6], DtgVibError> {
    Ok(six(sysid::fit::record_scores(
        model.inner(),
        prepared.inner(),
    )?))
}

/// Leave one record out (`fit --cv records`): each record validated, whole,
/// by a model fitted on the others; each channel's rms per record.
pub fn leave_one_record_out(
    prepared: &Prepared,
    options: &FitOptions,
) -> Result<[Vec<RecordScore>; 6], DtgVibError> {
    Ok(six(sysid::fit::leave_one_record_out(
        prepared.inner(),
        &options.sysid(),
    )?))
}

/// Per-channel results of the six channels, in order.
fn six<T: Default>(v: Vec<T>) -> [T; 6] {
    let mut v = v.into_iter();
    std::array::from_fn(|_| v.next().unwrap_or_default())
}

/// The model's mirror ([`sysid::fit::mirror`]).
pub fn mirror(
    model: &CompensationModel,
    prepared: &Prepared,
) -> Result<CompensationModel, DtgVibError> {
    Ok(CompensationModel::of(sysid::fit::mirror(
        model.inner(),
        prepared.inner(),
    )?))
}
