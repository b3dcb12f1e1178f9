//! The diagnosis loop of the paper's unit in one call: fit, diagnose, add
//! every suggested effect to its channel, refit, and repeat until nothing
//! new is suggested ([`sysid::explain`] with the [`PaperUnit`]).
//!
//! Each round is what a user would do by hand with `dtg-vib diagnose` and
//! `dtg-vib fit --add-effect CHANNEL=ID`, and gives the same answer: the
//! refit of round k is `fit` with the options of round k − 1 plus the
//! additions, and its diagnosis is `diagnose` of that model.
//!
//! This is the loop layer: it fits what the diagnosis asks for (the model's
//! mirror, a longer window) and hands the diagnosis the predictions, so the
//! diagnosis only reads.

use crate::diagnose::{DiagnoseOptions, Diagnosis};
use crate::error::DtgVibError;
use crate::fit::FitOptions;
use crate::model::CompensationModel;
use crate::paper_unit::{PaperUnit, borrowed, named_signals};
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::{Axis, Channel};
use nav_sensors::record::Record;

/// Progress of the loop.
pub type ExplainStage = sysid::explain::ExplainStage<Channel>;

/// An effect a round added, with the evidence for it.
pub type Added = sysid::explain::Added<Channel, Axis>;

/// One channel's validation rms after a round's fit.
pub type ChannelRms = sysid::explain::ChannelRms<Channel>;

/// One round: the fit it made, what its diagnosis suggested (added in the next round).
pub type Round = sysid::explain::Round<Channel, Axis>;

/// The loop's outcome.
#[derive(Debug, Clone)]
pub struct Explanation {
    /// Rounds in order; the last one's diagnosis suggested nothing new (or
    /// the round limit was reached).
    pub rounds: Vec<Round>,
    /// The final model (the last round's fit).
    pub model: CompensationModel,
    /// Whether the loop stopped because nothing new was suggested (false: the round limit).
    pub converged: bool,
}

/// Diagnoses a fitted model on a record (normally the one it was fitted on:
/// the validation rows of the model's split are used).
///
/// ```no_run
/// let model = dtg_vib::model::CompensationModel::load("model.json")?;
/// let rec = nav_sensors::record::Record::read_csv("record.csv")?;
/// let d = dtg_vib::explain::diagnose(&model, &rec, &Default::default())?;
/// for c in &d.channels { println!("{}: {:?}", c.channel, c.suggested); }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn diagnose(
    model: &CompensationModel,
    record: &Record,
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    diagnose_records(model, &[(String::new(), record)], options)
}

/// Diagnoses a fitted model on several records at once (normally those it
/// was fitted on, named by their files as at the fit): the mirror fitted
/// and the diagnosis read from both, a longer window tried where the
/// residual stays slow ([`sysid::explain::diagnose_records`]). One record
/// gives exactly [`diagnose`].
///
/// ```no_run
/// use dtg_vib::explain::diagnose_records;
/// use dtg_vib::model::CompensationModel;
/// use nav_sensors::record::Record;
/// let model = CompensationModel::load("xyz.json")?;
/// let (x, z) = (Record::read_csv("x.csv")?, Record::read_csv("z.csv")?);
/// let recs = [("x.csv".to_string(), &x), ("z.csv".to_string(), &z)];
/// let d = diagnose_records(&model, &recs, &Default::default())?;
/// for c in &d.channels { println!("{}: {:?}", c.channel, c.suggested); }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn diagnose_records(
    model: &CompensationModel,
    records: &[(String, &Record)],
    options: &DiagnoseOptions,
) -> Result<Diagnosis, DtgVibError> {
    let signals = named_signals(records)?;
    Ok(sysid::explain::diagnose_records(
        model.inner(),
        &borrowed(&signals),
        options,
    )?)
}

/// Runs the loop for at most `max_rounds` fits (at least 1).
///
/// ```no_run
/// use dtg_vib::explain::explain;
/// let rec = nav_sensors::record::Record::read_csv("record.csv")?;
/// let e = explain(&rec, None, &Default::default(), &Default::default(), 5, &|_| {})?;
/// for (k, r) in e.rounds.iter().enumerate() {
///     for a in &r.added { println!("round {k}: {}={} ({:.3} {})", a.channel, a.effect, a.coef, a.unit); }
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn explain(
    record: &Record,
    calibration: Option<&Calibration>,
    options: &FitOptions,
    diagnose_options: &DiagnoseOptions,
    max_rounds: usize,
    progress: &(dyn Fn(ExplainStage) + Sync),
) -> Result<Explanation, DtgVibError> {
    explain_records(
        &[(String::new(), record)],
        calibration,
        options,
        diagnose_options,
        max_rounds,
        progress,
    )
}

/// [`explain`] on several records fitted together and diagnosed together
/// ([`sysid::explain::explain`]): candidates are ranked on all of them, so a
/// pair one record cannot tell apart is named when another record excites
/// it differently. One record gives exactly [`explain`].
pub fn explain_records(
    records: &[(String, &Record)],
    calibration: Option<&Calibration>,
    options: &FitOptions,
    diagnose_options: &DiagnoseOptions,
    max_rounds: usize,
    progress: &(dyn Fn(ExplainStage) + Sync),
) -> Result<Explanation, DtgVibError> {
    options.preprocess.rate_reference.check()?;
    let unit = PaperUnit {
        calibration: calibration.cloned(),
        rate_reference: options.preprocess.rate_reference,
    };
    let signals = named_signals(records)?;
    let e = sysid::explain::explain(
        &unit,
        &borrowed(&signals),
        &options.sysid(),
        diagnose_options,
        max_rounds,
        progress,
    )?;
    Ok(Explanation {
        rounds: e.rounds,
        model: CompensationModel::of(e.model),
        converged: e.converged,
    })
}
