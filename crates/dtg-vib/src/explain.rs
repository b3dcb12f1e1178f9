//! The diagnosis loop in one call: fit, diagnose, add every suggested effect
//! to its channel, refit, and repeat until nothing new is suggested.
//!
//! Each round is what a user would do by hand with `dtg-vib diagnose` and
//! `dtg-vib fit --add-effect CHANNEL=ID`, and gives the same answer: the
//! refit of round k is `fit` with the options of round k − 1 plus the
//! additions, and its diagnosis is `diagnose` of that model.

use crate::diagnose::{DiagnoseOptions, Diagnosis, diagnose_records};
use crate::effects::ChannelEffect;
use crate::error::DtgVibError;
use crate::fit::{FitOptions, FitStage, fit_records};
use crate::model::CompensationModel;
use nav_sensors::calibration::Calibration;
use nav_sensors::geometry::Channel;
use nav_sensors::record::Record;
use serde::Serialize;

/// An effect a round added, with the evidence for it.
#[derive(Debug, Clone, Serialize)]
pub struct Added {
    /// The channel.
    pub channel: Channel,
    /// The effect id.
    pub effect: String,
    /// Its coefficient on the cross-fitted residual, in `unit`.
    pub coef: f64,
    /// The coefficient's standard error, in `unit`.
    pub se: f64,
    /// 95% confidence interval of `coef`.
    pub ci95: [f64; 2],
    /// Unit of `coef`.
    pub unit: String,
    /// p-value given the effects picked before it.
    pub p: f64,
    /// Share of what was left that it explains (conditional ERR).
    pub err: f64,
    /// Candidates it cannot be told apart from on this record.
    pub alternatives: Vec<String>,
    /// With alternatives: the combination this record identifies and the
    /// run that would separate the group, as `diagnose --json` gives it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation: Option<crate::diagnose::Separation>,
    /// Diagnosed on several records: the candidates it was collinear with
    /// on some record alone, and the records that told them apart.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub record_separations: Vec<crate::diagnose::RecordSeparation>,
}

/// One channel's validation rms after a round's fit.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ChannelRms {
    /// The channel.
    pub channel: Channel,
    /// Validation rms, deg/h.
    pub val_rms: f64,
}

/// One round: the fit it made, what its diagnosis suggested (added in the next round).
#[derive(Debug, Clone, Serialize)]
pub struct Round {
    /// Effects added to this round's fit (empty for the first).
    pub added: Vec<Added>,
    /// Validation rms of every channel after this round's fit.
    pub channels: Vec<ChannelRms>,
    /// This round's diagnosis (not serialised: `dtg-vib diagnose --json` has it).
    #[serde(skip)]
    pub diagnosis: Diagnosis,
}

/// The loop's outcome.
#[derive(Debug, Clone)]
pub struct Explanation {
    /// Rounds in order; the last one's diagnosis suggested nothing new (or
    /// the round limit was reached).
    pub rounds: Vec<Round>,
    /// The final model (the last round's fit).
    pub model: CompensationModel,
    /// The options that fit the final model (the first ones plus every addition).
    pub options: FitOptions,
    /// Whether the loop stopped because nothing new was suggested (false: the round limit).
    pub converged: bool,
}

/// Progress of the loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExplainStage {
    /// Fitting round `n` (1-based).
    Fitting(usize),
    /// Round `n`'s fit of this channel finished (channels finish in any order).
    ChannelFitted(usize, Channel),
    /// Diagnosing round `n`.
    Diagnosing(usize),
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

/// [`explain`] on several records fitted together ([`fit_records`]) and
/// diagnosed together ([`diagnose_records`]): candidates are ranked on all
/// of them, so a pair one record cannot tell apart is named when another
/// record excites it differently. One record gives exactly [`explain`].
pub fn explain_records(
    records: &[(String, &Record)],
    calibration: Option<&Calibration>,
    options: &FitOptions,
    diagnose_options: &DiagnoseOptions,
    max_rounds: usize,
    progress: &(dyn Fn(ExplainStage) + Sync),
) -> Result<Explanation, DtgVibError> {
    let max_rounds = max_rounds.max(1);
    let mut options = options.clone();
    let mut rounds: Vec<Round> = Vec::new();
    let mut added: Vec<Added> = Vec::new();
    loop {
        let n = rounds.len() + 1;
        progress(ExplainStage::Fitting(n));
        let (model, _) = fit_records(records, calibration, &options, &|s: FitStage| {
            if let FitStage::ChannelDone(ch) = s {
                progress(ExplainStage::ChannelFitted(n, ch));
            }
        })?;
        progress(ExplainStage::Diagnosing(n));
        let diagnosis = diagnose_records(&model, records, diagnose_options)?;
        let next = suggestions(&diagnosis, &options);
        let channels = model
            .channels()
            .iter()
            .map(|c| ChannelRms {
                channel: c.channel(),
                val_rms: c.scores().val_rms,
            })
            .collect();
        rounds.push(Round {
            added: std::mem::take(&mut added),
            channels,
            diagnosis,
        });
        let converged = next.is_empty();
        if converged || rounds.len() >= max_rounds {
            return Ok(Explanation {
                rounds,
                model,
                options,
                converged,
            });
        }
        for a in &next {
            options.add.push(ChannelEffect {
                channel: a.channel,
                effect: a.effect.parse()?,
            });
        }
        added = next;
    }
}

/// The suggestions of a diagnosis that the options do not have yet.
fn suggestions(d: &Diagnosis, options: &FitOptions) -> Vec<Added> {
    let mut out = Vec::new();
    for c in &d.channels {
        let have: Vec<String> = options
            .effects_of(c.channel)
            .iter()
            .map(|e| e.id())
            .collect();
        for id in c.suggested.iter().filter(|id| !have.contains(id)) {
            if let Some(k) = c.candidates.iter().find(|k| &k.effect == id) {
                out.push(Added {
                    channel: c.channel,
                    effect: id.clone(),
                    coef: k.coef,
                    se: k.coef_se,
                    ci95: k.coef_ci95,
                    unit: k.unit.clone(),
                    p: k.p_value.unwrap_or(f64::NAN),
                    err: k.conditional_err.unwrap_or(k.err),
                    alternatives: k.alternatives.clone(),
                    separation: k.separation.clone(),
                    record_separations: k.record_separations.clone(),
                });
            }
        }
    }
    out
}
