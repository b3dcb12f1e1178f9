//! The plug-in: what a sensor model tells the loop. The loop knows records
//! of named signals, windows, linear effects and networks; a [`Sensor`]
//! knows which columns are its outputs and what they should read (the
//! targets), how a raw record is calibrated, which physical effects could
//! be missing and how to compute their regressors, and which experiment
//! tells two look-alike effects apart.

use crate::signals::Signals;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::fmt::{Debug, Display};

/// An error a plug-in reports: its own typed error, boxed, shown as it is
/// (the loop adds where it happened, never rewords it).
pub type SensorError = Box<dyn std::error::Error + Send + Sync>;

/// A physical effect a channel model can hold: a term linear in its
/// coefficient. Named by a stable id in files, flags and JSON.
pub trait Effect:
    Clone + PartialEq + Debug + Display + Serialize + DeserializeOwned + Send + Sync + 'static
{
    /// The stable id (`g_I`, `col:temp`, `hyst`).
    fn id(&self) -> String;
    /// The unit of its coefficient: the target's unit per regressor unit.
    fn unit(&self) -> String;
    /// What it is physically, in a phrase.
    fn description(&self) -> String;
}

/// An effect known only by its id, unit and description: for a plug-in
/// whose effects need no type of their own, and for examples.
///
/// ```
/// use sysid::{Effect, Named};
/// let t = Named::new("col:temp", "kPa/°C", "thermal drift");
/// assert_eq!((t.id(), t.to_string()), ("col:temp".to_string(), "col:temp".to_string()));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Named {
    /// The id.
    pub id: String,
    /// The coefficient's unit.
    pub unit: String,
    /// What it is.
    pub description: String,
}

impl Named {
    /// An effect of this id, unit and description.
    pub fn new(id: &str, unit: &str, description: &str) -> Self {
        Self {
            id: id.into(),
            unit: unit.into(),
            description: description.into(),
        }
    }
}

impl Display for Named {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.id)
    }
}

impl Effect for Named {
    fn id(&self) -> String {
        self.id.clone()
    }
    fn unit(&self) -> String {
        self.unit.clone()
    }
    fn description(&self) -> String {
        self.description.clone()
    }
}

/// A candidate effect of a channel on a record: one the record excites, or
/// one it does not, with why (the diagnosis says so instead of ranking it).
#[derive(Debug, Clone, PartialEq)]
pub enum Candidacy<E> {
    /// The record excites it: rank it.
    Excited(E),
    /// The record does not excite it.
    NotExcited {
        /// The effect.
        effect: E,
        /// Why, in a phrase a report can show.
        reason: String,
    },
}

/// The words a sensor's numbers are said in, for the loop's findings and
/// files.
#[derive(Debug, Clone, PartialEq)]
pub struct Wording {
    /// Unit of the targets, residuals and predicted errors (`deg/h`).
    pub target_unit: String,
    /// Unit of the operating signals (`g`).
    pub operating_unit: String,
    /// The operating signals' spread as a quantity (`vibration`): names an
    /// operating point's last coordinate (`vibration_g_rms`).
    pub spread: String,
    /// What the operating signals are after pre-processing, as a finding
    /// says it (`low-passed specific force`).
    pub operating_noun: String,
    /// What a residual whose mean follows one operating signal suggests (`a
    /// g- or g²-sensitive term along it may be missing`).
    pub regime_hint: String,
    /// What a residual correlated beyond the model's window suggests (`a
    /// temperature or a drift: add its column as col:NAME`).
    pub slow_hint: String,
}

/// The operating signals' means and variances over the rows a diagnosis
/// reads (pre-processed), for [`Sensor::separation`].
#[derive(Debug, Clone, PartialEq)]
pub struct OperatingStats {
    /// The signals ([`Sensor::operating_signals`]).
    pub names: Vec<String>,
    /// Their means.
    pub means: Vec<f64>,
    /// Their variances about those means.
    pub variances: Vec<f64>,
}

/// How a group of candidates a record cannot tell apart responds along
/// one input: the linear and quadratic parts of its regressor's change
/// (r(x₀ + a) = r(x₀) + linear·a + quadratic·a²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Response {
    /// Coefficient of a.
    pub linear: f64,
    /// Coefficient of a².
    pub quadratic: f64,
}

/// What separates a group of candidates one record cannot tell apart: the
/// combination of their coefficients the record measures, and the run that
/// would split them (along an axis `A` of the sensor's, [`Sensor::Axis`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Separation<A = String> {
    /// The group, the suggested (representative) candidate first.
    pub effects: Vec<String>,
    /// The record measures c(first) + Σ κ·c(other): each other member's κ.
    pub combination: Vec<(String, f64)>,
    /// The axis along which a run would separate them (`x`, `y`, `z` for
    /// an inertial unit), if one would.
    pub axis: Option<A>,
    /// Each member's response along that input, if it has one.
    pub responses: Vec<Option<Response>>,
    /// The advice, in a sentence.
    pub advice: String,
}

/// A sensor model plugged into the loop.
///
/// The loop asks it for the channels and what they should read, for the
/// calibration of a raw record, for the candidate effects of a channel and
/// their regressors, and for the experiment that separates candidates it
/// cannot tell apart. Channels are identified by their position in
/// [`Sensor::channels`]; a channel value names it (its `Display` is the
/// name flags, JSON keys and reports use).
///
/// A sensor whose output follows a reference pressure plus a thermal drift
/// (a transducer in a thermal chamber), with one candidate effect:
///
/// ```
/// use sysid::{Candidacy, Effect, OperatingStats, Sensor, SensorError, Separation, Signals, Wording};
///
/// #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
/// struct Thermal; // the drift with temperature
/// impl std::fmt::Display for Thermal {
///     fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result { f.write_str("temp") }
/// }
/// impl Effect for Thermal {
///     fn id(&self) -> String { "temp".into() }
///     fn unit(&self) -> String { "kPa/°C".into() }
///     fn description(&self) -> String { "thermal drift".into() }
/// }
///
/// #[derive(Clone)]
/// struct Transducer;
/// impl Sensor for Transducer {
///     type Channel = String;
///     type Effect = Thermal;
///     type Axis = String;
///     fn channels(&self) -> Vec<String> { vec!["p".into()] }
///     fn wording(&self) -> Wording {
///         Wording { target_unit: "kPa".into(), operating_unit: "kPa".into(), spread: "swing".into(),
///             operating_noun: "reference pressure".into(), regime_hint: "a pressure term may be missing".into(),
///             slow_hint: "a drift".into() }
///     }
///     fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError> { Ok(raw.clone()) }
///     fn targets(&self, rec: &Signals) -> Result<Vec<Vec<f64>>, SensorError> {
///         let (p, r) = (rec.column("p").ok_or("no p")?, rec.column("ref").ok_or("no ref")?);
///         Ok(vec![p.iter().zip(r).map(|(p, r)| p - r).collect()])
///     }
///     fn operating_signals(&self) -> Vec<String> { vec!["ref".into()] }
///     fn operating_scale(&self) -> f64 { 0.1 }
///     fn extra_columns(&self, _: &Signals) -> Vec<String> { vec!["temp".into()] }
///     fn candidates(&self, _: &Signals, _: &[usize], _: usize) -> Vec<Candidacy<Thermal>> {
///         vec![Candidacy::Excited(Thermal)]
///     }
///     fn parse_effect(&self, _: usize, id: &str) -> Result<Thermal, SensorError> {
///         if id == "temp" { Ok(Thermal) } else { Err(format!("unknown effect {id}").into()) }
///     }
///     fn regressors(&self, rec: &Signals, _: usize, e: &[Thermal]) -> Result<Vec<Vec<f64>>, SensorError> {
///         Ok(e.iter().map(|_| rec.column("temp").unwrap_or(&[]).to_vec()).collect())
///     }
///     fn separation(&self, _: usize, g: &[Thermal], k: &[f64], _: &OperatingStats) -> Separation {
///         Separation { effects: g.iter().map(Effect::id).collect(), combination: vec![],
///             axis: None, responses: vec![None; g.len()], advice: format!("{k:?}") }
///     }
/// }
///
/// // A sinusoidal reference and a slow temperature ramp; the output drifts 0.3 kPa/°C.
/// let n = 3000;
/// let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.1).collect();
/// let reference: Vec<f64> = t.iter().map(|t| 100.0 + 5.0 * (0.7 * t).sin()).collect();
/// let temp: Vec<f64> = t.iter().map(|t| 20.0 + 10.0 * (t / 300.0)).collect();
/// let p: Vec<f64> = (0..n).map(|i| reference[i] + 0.3 * temp[i] + 0.01 * (i as f64 * 1.3).sin()).collect();
/// let rec = Signals::new(t, vec![("p".into(), p), ("ref".into(), reference), ("temp".into(), temp)])?;
///
/// let mut options = sysid::FitOptions::<Thermal>::new(1);
/// options.recipe.preprocess = sysid::Preprocess { filter: None, window: sysid::WindowSpec::new(vec!["ref".into()], 5)?, ..Default::default() };
/// options.recipe.effects[0] = vec![Thermal];
/// options.recipe.settings.max_centres = 5;
/// let (model, _) = sysid::fit_records(&Transducer, &[("r".into(), &rec)], &options, &|_| {})?;
/// let c = &model.channel(0).coefficients().unwrap()[0];
/// assert!(c.covers(0.3), "{c:?}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub trait Sensor: Clone + Send + Sync {
    /// A channel: what one model is fitted to.
    type Channel: Clone
        + PartialEq
        + Debug
        + Display
        + Serialize
        + DeserializeOwned
        + Send
        + Sync
        + 'static;
    /// A physical effect of a channel.
    type Effect: Effect;
    /// An axis along which a test can be run, as [`Separation`] advice
    /// names it (an inertial unit's x, y, z; `String` will do).
    type Axis: Clone + PartialEq + Debug + Serialize + Send + Sync + 'static;

    /// The channels, in order: a model has one per channel, and a channel
    /// is its position here.
    fn channels(&self) -> Vec<Self::Channel>;

    /// The units and nouns the loop's findings use.
    fn wording(&self) -> Wording;

    /// A raw record as the error model wants it: compensated for the ground
    /// calibration, in the model's units. Its columns are those of the raw
    /// record.
    fn calibrate(&self, raw: &Signals) -> Result<Signals, SensorError>;

    /// Per channel, in [`Sensor::channels`] order, the error the models
    /// learn: each output less what it should read (a known reference),
    /// unfiltered, on a calibrated record.
    fn targets(&self, calibrated: &Signals) -> Result<Vec<Vec<f64>>, SensorError>;

    /// The signals that place a window in the space of test conditions
    /// (its operating point): their means and spread over the window. The
    /// residual's regimes and its nonlinear tests are taken along each.
    fn operating_signals(&self) -> Vec<String>;

    /// The operating signals of channel `channel`: those its own
    /// vibration input is (an inertial unit of several IMUs: its gyro's
    /// IMU's accelerometers). A window may read any channel's. The shared
    /// [`Sensor::operating_signals`] by default.
    fn operating_signals_of(&self, channel: usize) -> Vec<String> {
        let _ = channel;
        self.operating_signals()
    }

    /// Every signal a window may read ([`every_operating_signal`]) in the
    /// sensor's order: when channels read different signals, the window's
    /// list of them all follows it (an inertial unit: the order of its
    /// accelerometers in its file). [`every_operating_signal`] by default.
    fn signal_order(&self) -> Vec<String> {
        every_operating_signal(self)
    }

    /// The smallest spread an operating point's coordinate is divided by,
    /// in the operating signals' unit: a coordinate the training windows
    /// held constant measures a change of this size as one unit, not as
    /// infinitely many (an inertial unit: 0.05 g, a 3° tilt of gravity).
    fn operating_scale(&self) -> f64;

    /// The columns of a record that are not the sensor's own (a
    /// temperature): the residual is tested against each, and records fitted
    /// together must share them.
    fn extra_columns(&self, record: &Signals) -> Vec<String>;

    /// Every candidate effect of channel `channel` on a calibrated record,
    /// judged on its `samples`: those they excite, and those they do not.
    fn candidates(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        channel: usize,
    ) -> Vec<Candidacy<Self::Effect>>;

    /// Refuses effects a fit cannot estimate from `samples` of a calibrated
    /// record (they are not excited there), saying why and what to do.
    /// Everything by default.
    fn check_excited(
        &self,
        calibrated: &Signals,
        samples: &[usize],
        channel: usize,
        effects: &[Self::Effect],
    ) -> Result<(), SensorError> {
        let _ = (calibrated, samples, channel, effects);
        Ok(())
    }

    /// An effect of channel `channel` by its id (the loop adds a suggested
    /// effect by the id the diagnosis names).
    fn parse_effect(&self, channel: usize, id: &str) -> Result<Self::Effect, SensorError>;

    /// The regressors of `effects` of channel `channel` on a calibrated
    /// record: one column per effect, each as long as the record,
    /// unfiltered (the loop filters them as it filters the targets).
    fn regressors(
        &self,
        calibrated: &Signals,
        channel: usize,
        effects: &[Self::Effect],
    ) -> Result<Vec<Vec<f64>>, SensorError>;

    /// What separates `group` (the suggested candidate first), which the
    /// rows cannot tell apart: the record measures c(group[0]) + Σ
    /// `kappa[i]`·c(group[i + 1]); `operating` holds the operating signals'
    /// means and variances on those rows.
    fn separation(
        &self,
        channel: usize,
        group: &[Self::Effect],
        kappa: &[f64],
        operating: &OperatingStats,
    ) -> Separation<Self::Axis>;

    /// What a suggestion of `effect` on channel `channel` rests on that its
    /// p-value does not say: each a sentence the diagnosis prints beside it
    /// (in the terminal, the JSON's `caveats` and the report). `records`
    /// holds each diagnosed record (calibrated) with the samples analysed.
    /// None by default.
    fn caveats(
        &self,
        records: &[(&Signals, Vec<usize>)],
        channel: usize,
        effect: &Self::Effect,
    ) -> Vec<String> {
        let _ = (records, channel, effect);
        Vec::new()
    }

    /// Named linear combinations of the channels' targets that are read as
    /// series of their own (an inertial unit's parity residues): each a name
    /// and one weight per channel, in [`Sensor::channels`] order. The fit's
    /// keep step holds each of them, as it holds each channel, to a bias
    /// instability no higher after compensation than before. None by
    /// default.
    fn residues(&self) -> Vec<(String, Vec<f64>)> {
        Vec::new()
    }

    /// What the records can observe of each family of effects, one line
    /// per family (`sf: …`): what the target's reference lets a fit tell
    /// apart and what it cannot (an inertial unit fitted in parity sees
    /// only the differences between its gyros). The diagnosis states them
    /// (its JSON's `observable`). None by default.
    fn observable(&self) -> Vec<String> {
        Vec::new()
    }
}

/// Every operating signal of `sensor`, once each: the shared ones
/// ([`Sensor::operating_signals`]), then each channel's others
/// ([`Sensor::operating_signals_of`]) in channel order: what a window may
/// read besides a record's extra columns.
pub fn every_operating_signal<S: Sensor>(sensor: &S) -> Vec<String> {
    let lists: Vec<Vec<String>> = std::iter::once(sensor.operating_signals())
        .chain((0..sensor.channels().len()).map(|k| sensor.operating_signals_of(k)))
        .collect();
    crate::window::union(&lists)
}
