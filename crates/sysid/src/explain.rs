//! The diagnosis loop in one call: fit, diagnose, add every suggested effect
//! to its channel, refit, and repeat until nothing new is suggested.
//!
//! Each round is what a user would do by hand with a diagnosis and a fit
//! with the suggested effects added, and gives the same answer: the refit
//! of round k is a fit with the options of round k − 1 plus the additions,
//! and its diagnosis is [`diagnose_records`] of that model.
//!
//! This is the loop layer: it fits the models the diagnosis reads (the
//! model's mirror, a longer window) and hands the diagnosis their
//! predictions; the diagnosis fits no model itself (it states a
//! suggestion's coefficient with the fit's estimator, [`crate::diagnose`]).

use crate::diagnose::{DiagnoseOptions, Diagnosis, RecordSeparation, diagnose_prepared};
use crate::error::SysidError;
use crate::fit::{FitStage, fit_records, mirror, refit_with_window};
use crate::model::Model;
use crate::recipe::FitOptions;
use crate::sensor::{Effect, Sensor, Separation};
use crate::signals::Signals;
use serde::Serialize;

/// Diagnoses a fitted model on the records it was fitted on (named as at
/// the fit; the validation rows of the model's split are used): each record
/// prepared on its own, the mirror fitted ([`mirror`]) and the diagnosis
/// read from both ([`diagnose_prepared`]). Where a residual stays
/// correlated beyond the model's window and `options.try_settings` is on,
/// the recipe is refitted with a three times longer window and the
/// diagnosis told what it gained ([`Diagnosis::note_window_trial`]); a
/// record too short for it says nothing about it.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let rec = line_record(3000, 2.0, 5);
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let records = [("r".to_string(), &rec)];
/// let (model, _) = sysid::fit_records(&Line, &records, &options, &|_| {})?;
/// let d = sysid::explain::diagnose_records(&model, &records, &Default::default())?;
/// // The slope the model lacks is what it suggests.
/// assert_eq!(d.channels[0].suggested, ["u"]);
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn diagnose_records<S: Sensor>(
    model: &Model<S>,
    records: &[(String, &Signals)],
    options: &DiagnoseOptions,
) -> Result<Diagnosis<S::Channel, S::Axis>, SysidError> {
    let mut diagnosis = diagnose_untried(model, records, options)?;
    try_longer_window(&mut diagnosis, model, records, options);
    Ok(diagnosis)
}

/// [`diagnose_records`] without the longer window's trial.
fn diagnose_untried<S: Sensor>(
    model: &Model<S>,
    records: &[(String, &Signals)],
    options: &DiagnoseOptions,
) -> Result<Diagnosis<S::Channel, S::Axis>, SysidError> {
    let prepared = model.prepare_many(records)?;
    let mirror = mirror(model, &prepared)?;
    diagnose_prepared(model, &prepared, &mirror, options)
}

/// Where a residual stays correlated beyond the model's window and
/// `options.try_settings` is on: the recipe refitted with a three times
/// longer window, and the diagnosis told what it gained.
fn try_longer_window<S: Sensor>(
    diagnosis: &mut Diagnosis<S::Channel, S::Axis>,
    model: &Model<S>,
    records: &[(String, &Signals)],
    options: &DiagnoseOptions,
) {
    if options.try_settings && !diagnosis.slow_channels().is_empty() {
        let longer = model.preprocess().window.length() * 3;
        if let Ok(trial) = refit_with_window(model, records, longer) {
            diagnosis.note_window_trial(longer, &trial);
        }
    }
}

/// An effect a round added, with the evidence for it.
#[derive(Debug, Clone, Serialize)]
pub struct Added<C, A = String> {
    /// The channel.
    pub channel: C,
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
    /// run that would separate the group, as the diagnosis gives it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation: Option<Separation<A>>,
    /// Diagnosed on several records: the candidates it was collinear with
    /// on some record alone, and the records that told them apart.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub record_separations: Vec<RecordSeparation>,
    /// What the suggestion rests on that its p-value does not say, as the
    /// diagnosis gives it; absent when none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub caveats: Vec<String>,
}

/// One channel's validation rms after a round's fit.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ChannelRms<C> {
    /// The channel.
    pub channel: C,
    /// Validation rms, in the target's unit.
    pub val_rms: f64,
}

/// One round: the fit it made, what its diagnosis suggested (added in the next round).
#[derive(Debug, Clone, Serialize)]
pub struct Round<C, A = String> {
    /// Effects added to this round's fit (empty for the first).
    pub added: Vec<Added<C, A>>,
    /// Validation rms of every channel after this round's fit.
    pub channels: Vec<ChannelRms<C>>,
    /// This round's diagnosis (not serialised: a diagnosis has its own
    /// JSON); only the last round's holds the longer window's trial.
    #[serde(skip)]
    pub diagnosis: Diagnosis<C, A>,
}

/// The loop's outcome.
#[derive(Debug, Clone)]
pub struct Explanation<S: Sensor> {
    /// Rounds in order; the last one's diagnosis suggested nothing new (or
    /// the round limit was reached).
    pub rounds: Vec<Round<S::Channel, S::Axis>>,
    /// The final model (the last round's fit).
    pub model: Model<S>,
    /// The options that fit the final model (the first ones plus every addition).
    pub options: FitOptions<S::Effect>,
    /// Whether the loop stopped because nothing new was suggested (false: the round limit).
    pub converged: bool,
}

/// Progress of the loop, for a channel type `C`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExplainStage<C> {
    /// Fitting round `n` (1-based).
    Fitting(usize),
    /// Round `n`'s fit of this channel finished (channels finish in any order).
    ChannelFitted(usize, C),
    /// Diagnosing round `n`.
    Diagnosing(usize),
}

/// Runs the loop on `records` fitted together ([`fit_records`]) and
/// diagnosed together ([`diagnose_records`]) for at most `max_rounds` fits
/// (at least 1): candidates are ranked on all of them, so a pair one
/// record cannot tell apart is named when another record excites it
/// differently.
///
/// ```
/// # use sysid::example::{Line, line_record};
/// let rec = line_record(3000, 2.0, 5);
/// let mut options = sysid::FitOptions::new(1);
/// options.recipe.preprocess = Line::preprocess();
/// options.recipe.settings.max_centres = 5;
/// let e = sysid::explain::explain(&Line, &[("r".into(), &rec)], &options, &Default::default(), 3, &|_| {})?;
/// assert_eq!(e.rounds[1].added[0].effect, "u"); // the slope the first model lacked
/// let slope = &e.model.channel(0).coefficients().unwrap()[0];
/// assert!(slope.covers(2.0), "{slope:?}");
/// assert!(e.converged);
/// # Ok::<(), sysid::SysidError>(())
/// ```
pub fn explain<S: Sensor>(
    sensor: &S,
    records: &[(String, &Signals)],
    options: &FitOptions<S::Effect>,
    diagnose_options: &DiagnoseOptions,
    max_rounds: usize,
    progress: &(dyn Fn(ExplainStage<S::Channel>) + Sync),
) -> Result<Explanation<S>, SysidError> {
    let max_rounds = max_rounds.max(1);
    let mut options = options.clone();
    let mut rounds: Vec<Round<S::Channel, S::Axis>> = Vec::new();
    let mut added: Vec<Added<S::Channel, S::Axis>> = Vec::new();
    loop {
        let n = rounds.len() + 1;
        progress(ExplainStage::Fitting(n));
        let (model, _) = fit_records(sensor, records, &options, &|s: FitStage<_>| {
            if let FitStage::ChannelDone(ch) = s {
                progress(ExplainStage::ChannelFitted(n, ch));
            }
        })?;
        progress(ExplainStage::Diagnosing(n));
        // The longer window's trial only adds a finding, which no later
        // round reads: it is made for the last round's diagnosis alone.
        let mut diagnosis = diagnose_untried(&model, records, diagnose_options)?;
        let next = suggestions(&diagnosis, &options);
        if next.is_empty() || rounds.len() + 1 >= max_rounds {
            try_longer_window(&mut diagnosis, &model, records, diagnose_options);
        }
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
        for (k, a) in &next {
            let effect = sensor
                .parse_effect(*k, &a.effect)
                .map_err(SysidError::Sensor)?;
            if !options.recipe.effects[*k].contains(&effect) {
                options.recipe.effects[*k].push(effect);
            }
        }
        added = next.into_iter().map(|(_, a)| a).collect();
    }
}

/// The suggestions of a diagnosis that the options do not have yet, with
/// their channels' positions.
fn suggestions<C: Clone, A: Clone, E: Effect>(
    d: &Diagnosis<C, A>,
    options: &FitOptions<E>,
) -> Vec<(usize, Added<C, A>)> {
    let mut out = Vec::new();
    for (k, c) in d.channels.iter().enumerate() {
        let have: Vec<String> = options
            .recipe
            .effects_of(k)
            .iter()
            .map(Effect::id)
            .collect();
        for id in c.suggested.iter().filter(|id| !have.contains(id)) {
            if let Some(cand) = c.candidates.iter().find(|cand| &cand.effect == id) {
                out.push((
                    k,
                    Added {
                        channel: c.channel.clone(),
                        effect: id.clone(),
                        coef: cand.coef,
                        se: cand.coef_se,
                        ci95: cand.coef_ci95,
                        unit: cand.unit.clone(),
                        p: cand.p_value.unwrap_or(f64::NAN),
                        err: cand.conditional_err.unwrap_or(cand.err),
                        alternatives: cand.alternatives.clone(),
                        separation: cand.separation.clone(),
                        record_separations: cand.record_separations.clone(),
                        caveats: cand.caveats.clone(),
                    },
                ));
            }
        }
    }
    out
}
